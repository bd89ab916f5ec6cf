#pragma once
// Private to src/io/types: the beam block's elements built on any model (types/beams_3d.cpp), and
// the reduced beam block (types/reduced_beams_3d.cpp, key `reduction`, docs/theory/reduced_bodies.md).
#include <functional>

#include "common.hpp"

namespace alphaflex::scene_detail {

/// The model node of mesh node `m` with the initial pose `q0` of the first element that reaches it.
using BlockNodeOf = std::function<int(int m, const Eigen::VectorXd& q0)>;

/// Adds the beam elements of `block` to `model` (named ITEM[e], in mesh order), their nodes given by
/// `node_of`; returns their indices in model.elements().
std::vector<int> add_beam_elements(const Item& it, const MeshLineBlock& block, const BeamSection& section, const Eigen::Vector3d& orient,
                                   Model& model, const BlockNodeOf& node_of);

/// The schema of `reduction` (registered with the spatial beams).
const Schema& reduction_schema();

/// A beam block with a `reduction` key: the block built on a scratch model and reduced there
/// (modal/superelement.hpp); the run's model gets the frame node (the first interface point), one
/// scalar node per elastic amplitude, one ReducedBody element named after the block, and a node
/// with a ReducedInterfaceTie (NAME:tie:POINT) at each other interface point.
void read_reduced_beam_block_3d(const Item& it, const MeshLineBlock& block, const BeamSection& section, const Eigen::Vector3d& orient);

}  // namespace alphaflex::scene_detail
