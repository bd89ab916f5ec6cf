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

/// A beam or shell block with a `reduction` key (`block_nodes`: the mesh nodes of its elements in
/// mesh group `group`, built by `add_elements`): see read_reduced_beam_block_3d.
void read_reduced_block_3d(const Item& it, const std::vector<int>& block_nodes, const std::string& group,
                           const BlockElementsOf& add_elements);

/// The schema of `reduction` (registered with the spatial beams; shells use the same).
const Schema& reduction_schema();

/// A beam block with a `reduction` key: the block built on a scratch model and reduced there
/// (modal/superelement.hpp); the run's model gets the frame node (the first interface point), one
/// scalar node per elastic amplitude, one ReducedBody element named after the block, and a node
/// with a ReducedInterfaceTie (NAME:tie:POINT) at each other interface point.
void read_reduced_beam_block_3d(const Item& it, const MeshLineBlock& block, const BeamSection& section, const Eigen::Vector3d& orient);

}  // namespace alphaflex::scene_detail
