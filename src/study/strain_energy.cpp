#include "alphaflex/study/strain_energy.hpp"

#include "alphaflex/elements/geometrically_exact_beam.hpp"
#include "alphaflex/elements/planar_beam.hpp"
#include "alphaflex/elements/shell.hpp"

#include <algorithm>

namespace alphaflex::study {
namespace {

const char* flexible_kind(const Element& e) {
  if (dynamic_cast<const PlanarBeam*>(&e) || dynamic_cast<const GeometricallyExactBeam*>(&e)) return "beam";
  if (dynamic_cast<const ReissnerMindlinShell*>(&e)) return "shell";
  return nullptr;
}

double elastic_energy(const Element& e, const Eigen::VectorXd& q) {
  if (const auto* b = dynamic_cast<const PlanarBeam*>(&e)) return b->elastic_energy(q);
  if (const auto* b = dynamic_cast<const GeometricallyExactBeam*>(&e)) return b->elastic_energy(q);
  if (const auto* s = dynamic_cast<const ReissnerMindlinShell*>(&e)) return s->elastic_energy(q);
  return 0.0;
}

}  // namespace

std::vector<FlexiblePart> flexible_parts(const Model& model) {
  std::vector<FlexiblePart> parts;
  const auto& els = model.elements();
  for (size_t i = 0; i < els.size(); ++i) {
    const char* kind = flexible_kind(*els[i]);
    if (!kind) continue;
    const std::string& n = els[i]->name();
    const std::string block = n.substr(0, n.find('['));  // NAME[k] → NAME
    auto it = std::find_if(parts.begin(), parts.end(), [&](const FlexiblePart& p) { return p.name == block; });
    if (it == parts.end()) {
      parts.push_back({block, kind, {}});
      it = parts.end() - 1;
    }
    it->elements.push_back(static_cast<int>(i));
  }
  return parts;
}

std::vector<double> strain_energies(const Model& model, const std::vector<FlexiblePart>& parts,
                                    const MechanicalState& s) {
  std::vector<double> w;
  for (const auto& p : parts) {
    double sum = 0.0;
    for (int i : p.elements) {
      const Element& e = *model.elements()[static_cast<size_t>(i)];
      sum += elastic_energy(e, gather(s.q, model.confs_of(e.nodes())));
    }
    w.push_back(sum);
  }
  return w;
}

}  // namespace alphaflex::study
