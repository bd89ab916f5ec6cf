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
  values.resize(mesh_->output_size());
  for (Eigen::Index a = 0; a < np; ++a) {
    values.segment<3>(3 * a) = p.q.segment<3>(7 * a);
    values.segment<3>(3 * np + 3 * a) = p.q.segment<3>(7 * a) - mesh_->point(static_cast<size_t>(a)).initial;
  }
  // Each element's own recovery (a beam's section forces and strains) at the rebuilt poses, in the
  // layout of MeshReconstruction::output_index (missing values 0).
  const std::vector<Eigen::VectorXd> cells = mesh_->element_outputs(s);
  Eigen::Index width = 0;
  for (const CellField& f : mesh_->cell_fields()) width += f.components;
  for (size_t k = 0; k < cells.size(); ++k)
    for (int c = 0; c < width; ++c) values[mesh_->output_index(k, c)] = c < cells[k].size() ? cells[k][c] : 0.0;
}

}  // namespace alphaflex
