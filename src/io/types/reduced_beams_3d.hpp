#pragma once
// Private to src/io/types: the beam block's elements built on any model (types/beams_3d.cpp), and
// the reduced beam block (types/reduced_beams_3d.cpp, key `reduction`, docs/theory/reduced_bodies.md).
#include <algorithm>
#include <functional>

#include "common.hpp"

namespace alphaflex::scene_detail {

/// The model node of mesh node `m` with the initial pose `q0` of the first element that reaches it.
using BlockNodeOf = std::function<int(int m, const Eigen::VectorXd& q0)>;

/// Adds the beam elements of `block` to `model` (named ITEM[e], in mesh order), their nodes given by
/// `node_of`; returns their indices in model.elements().
std::vector<int> add_beam_elements(const Item& it, const MeshLineBlock& block, const BeamSection& section, const Eigen::Vector3d& orient,
                                   Model& model, const BlockNodeOf& node_of);

/// Adds a block's elements to `model` with their nodes given by a BlockNodeOf; returns their indices.
using BlockElementsOf = std::function<std::vector<int>(Model& model, const BlockNodeOf& node_of)>;

/// The mesh nodes of a block's elements (each once, sorted).
template <class Elements>
std::vector<int> mesh_nodes_of(const Elements& elements) {
  std::vector<int> m;
  for (const auto& e : elements) m.insert(m.end(), e.begin(), e.end());
  std::sort(m.begin(), m.end());
  m.erase(std::unique(m.begin(), m.end()), m.end());
  return m;
}

/// One block's part of a reduced body: the mesh nodes of its elements (each once, sorted), its mesh
/// group (for messages) and the builder of its elements on any model.
struct BlockPart {
  std::vector<int> nodes;
  std::string group;
  BlockElementsOf add_elements;
};
/// The part of a block item of the list being read (`beams`: types/beams_3d.cpp beam_part,
/// `shells`: types/shells_3d.cpp); it takes the item's mesh group (one block per group).
using BlockPartOf = std::function<BlockPart(const Item&)>;

/// A beam or shell block with a `reduction` key, with the further blocks of its list that
/// `reduction.blocks` names (each built by `part_of` with its own section): all their elements are
/// built on a scratch model and reduced there as one body (modal/superelement.hpp); the run's model
/// gets the frame node (the first interface point), one scalar node per elastic amplitude, one
/// ReducedBody element named after the block, and a node with a ReducedInterfaceTie
/// (NAME:tie:POINT) at each other interface point.
void read_reduced_block_3d(const Item& it, const BlockPartOf& part_of);

/// The schema of `reduction` (registered with the spatial beams; shells use the same).
const Schema& reduction_schema();

/// The part of a spatial beam block (its group, section and orientation).
BlockPart beam_part(const Item& it);

}  // namespace alphaflex::scene_detail
