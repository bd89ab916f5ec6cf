#include "alphaflex/study/strain_energy.hpp"

#include <algorithm>

namespace alphaflex::study {

std::vector<FlexiblePart> flexible_parts(const Model& model) {
  std::vector<FlexiblePart> parts;
  const auto& els = model.elements();
  for (size_t i = 0; i < els.size(); ++i) {
    const char* kind = els[i]->structure();  // elements that store strain
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
      sum += e.elastic_energy(gather(s.q, model.confs_of(e.nodes())));
    }
    w.push_back(sum);
  }
  return w;
}

}  // namespace alphaflex::study
