// The full mesh of a reduced body for the results and sensors (reduced_body.hpp, second part;
// model/mesh_reconstruction.hpp; docs/theory/reduced_bodies.md, "Reconstruction").
#include <stdexcept>
#include <string>

#include "alphaflex/elements/reduced_body.hpp"

namespace alphaflex {

void ReducedBody::attach_reconstruction(std::shared_ptr<const MeshReconstruction> mesh) {
  if (mesh && mesh->elastic() != m_.elastic())
    throw std::invalid_argument("reduced body '" + name() + "': the mesh's basis has " + std::to_string(mesh->elastic()) +
                                " columns for " + std::to_string(m_.elastic()) + " elastic coordinates");
  mesh_ = std::move(mesh);
}

std::vector<CellField> ReducedBody::cell_fields() const {
  if (!mesh_) return {};
  const int np = static_cast<int>(mesh_->points()), ne = static_cast<int>(mesh_->elements().size());
  std::vector<CellField> fields{{"point_position", 3 * np}, {"point_displacement", 3 * np}};
  for (const CellField& f : mesh_->cell_fields()) fields.push_back({f.name, f.components * ne});
  return fields;
}

void ReducedBody::output(const LocalState& s, Eigen::VectorXd& values) const {
  if (!mesh_) {
    values.resize(0);
    return;
  }
  const LocalState p = mesh_->state(s);
  const Eigen::Index np = static_cast<Eigen::Index>(mesh_->points());
  const Eigen::Index ne = static_cast<Eigen::Index>(mesh_->elements().size());
  std::vector<CellField> fields = mesh_->cell_fields();
  Eigen::Index width = 0;
  for (const CellField& f : fields) width += f.components;
  values.resize(6 * np + width * ne);
  for (Eigen::Index a = 0; a < np; ++a) {
    values.segment<3>(3 * a) = p.q.segment<3>(7 * a);
    values.segment<3>(3 * np + 3 * a) = p.q.segment<3>(7 * a) - mesh_->point(static_cast<size_t>(a)).initial;
  }
  // Each element's own recovery (a beam's section forces and strains) at the rebuilt poses.
  const std::vector<Eigen::VectorXd> cells = mesh_->element_outputs(s);
  for (Eigen::Index k = 0; k < ne; ++k) {
    const Eigen::VectorXd& cell = cells[static_cast<size_t>(k)];
    Eigen::Index at = 6 * np, c = 0;
    for (const CellField& f : fields) {
      for (int j = 0; j < f.components; ++j, ++c)
        values[at + k * f.components + j] = c < cell.size() ? cell[c] : 0.0;
      at += f.components * ne;
    }
  }
}

}  // namespace alphaflex
