#pragma once
// Private to the io module: which nodes the results draw as bodies, the links that make a
// mechanism visible, and the flexible blocks whose elastic displacement they write (issue 21).
//  - bodies: the nodes that are no node of a drawn element (rigid bodies, particles) — mesh nodes
//    are drawn by their beams and shells, not as dots on top of them;
//  - links: per joint that holds a body, the polyline body 1's centre → the joint → body 2's
//    centre (a ground or mesh side is the joint itself), so that a rigid mechanism shows its links
//    without a shape;
//  - shapes: the bodies' shapes, a surface that moves with them (results_shapes.hpp);
//  - blocks: the beam and shell blocks (element name up to '['), each with its best-fit rigid
//    motion removed in `elastic_displacement`.
#include <string>
#include <vector>

#include "alphaflex/partition/subdomain.hpp"
#include "results_mesh.hpp"
#include "results_reduced.hpp"
#include "results_shapes.hpp"

namespace alphaflex::io_detail {

struct NodeLayout {
  std::vector<int> bodies;       ///< global ids of the body nodes, increasing
  std::vector<int> body_row;     ///< global node → its row among the bodies, −1 if none
  std::vector<int> links;        ///< global ids of the joints drawn as links, increasing
  std::vector<int> link_row;     ///< global joint → its row among the links, −1 if none
  std::vector<int> node_block;   ///< global node → its flexible block, −1 if none
  std::vector<std::string> blocks;  ///< names of the flexible blocks
  ShapeLayout shapes;               ///< the bodies' shapes (results_shapes.hpp)
  ReducedLayout reduced;            ///< the reduced bodies' rebuilt meshes (results_reduced.hpp)
  /// Every node is a body (no drawn element): the bodies grid reads the node datasets themselves.
  bool all_bodies() const { return bodies.size() == body_row.size(); }
};

NodeLayout node_layout(const Model& global, const std::vector<ElementGrid>& grids);

/// The displacement of each owned node of a flexible block relative to the block's best-fit rigid
/// motion (3 values per owned node, zero outside blocks), from the owned nodes' positions `pos`
/// and displacements `disp` (reference position = pos − disp). The rigid motion (c, R) minimizes
/// Σ |x_i − c − R (X_i − c_X)|² over the block's nodes: c is the centroid of the current positions
/// and R the rotation of the polar decomposition of H = Σ (X_i − c_X)(x_i − c)ᵀ, through its SVD
/// with the reflection removed (Kabsch 1976, Acta Cryst. A32:922; the same R as Horn's quaternion
/// solution, J. Opt. Soc. Am. A 4:629, 1987). Equal weights per node. Collective (the sums over a
/// block's nodes are all-reduced over the ranks).
std::vector<double> elastic_displacements(const Subdomain& sub, const NodeLayout& layout, const std::vector<double>& pos,
                                          const std::vector<double>& disp);

}  // namespace alphaflex::io_detail
