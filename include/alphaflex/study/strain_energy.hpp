#pragma once
// Strain energy of each flexible part of a model — what a user needs to decide which parts may be
// made rigid ("model no more than a scene needs"). A part is a block of elements of a structure
// (Element::structure(): beams, shells) in the scene: its elements are named NAME[0], NAME[1], ...
// (docs/input.md), and its energy is the sum of the elements' Element::elastic_energy, e.g.
// W = (L0/2) εᵀ C ε for a beam element (planar_beam.hpp, geometrically_exact_beam.hpp) and
// ½ (s − s0)ᵀ C_e (s − s0) for a shell element (shell.hpp).
#include <string>
#include <vector>

#include "alphaflex/model/model.hpp"

namespace alphaflex::study {

struct FlexiblePart {
  std::string name;          ///< the block name (beams[NAME] or shells[NAME])
  std::string kind;          ///< its elements' Element::structure(): "beam", "shell"
  std::vector<int> elements; ///< indices into Model::elements()
};

/// The blocks of elements with a structure (beams, shells) of a model, in the order their first
/// element appears.
std::vector<FlexiblePart> flexible_parts(const Model& model);

/// Strain energy (J) of each part at state s, in the order of `parts`.
std::vector<double> strain_energies(const Model& model, const std::vector<FlexiblePart>& parts,
                                    const MechanicalState& s);

}  // namespace alphaflex::study
