#pragma once
// Private to the io module: the `shapes` grid of the results (issue 21), the bodies' shapes
// (model/body_shape.hpp) as one surface of triangles and quadrilaterals (an XDMF Mixed topology)
// that moves with the bodies. Shape k's points are rows point_offset[k] … of `shape_points`
// (x + R·X of its body at each output step), its faces entries connectivity_offset[k] … of
// /topology/shapes (per face its XDMF type code, 4 triangle or 5 quadrilateral, then its point
// rows). The rank that owns a body writes its shape's rows, as it writes the body's own rows in
// the bodies grid, so the files are the same on any number of ranks.
#include <optional>
#include <vector>

#include "alphaflex/partition/subdomain.hpp"
#include "hdf5_rows.hpp"

namespace alphaflex::io_detail {

/// Where each shape of the global model is in the shapes grid's datasets.
struct ShapeLayout {
  /// Per shape k, its first row; entry `shapes` is the total (empty: no shapes).
  std::vector<unsigned long long> point_offset, face_offset, connectivity_offset;
  unsigned long long points() const { return point_offset.empty() ? 0 : point_offset.back(); }
  unsigned long long faces() const { return face_offset.empty() ? 0 : face_offset.back(); }
  unsigned long long connectivity_size() const { return connectivity_offset.empty() ? 0 : connectivity_offset.back(); }
};

ShapeLayout shape_layout(const Model& global);

/// This rank's rows of the shapes grid: the shapes of the bodies it owns.
class ShapeRows {
 public:
  ShapeRows(const Subdomain& sub, const ShapeLayout& layout);
  /// /topology/shapes (collective; nothing if the model has no shapes).
  void write_topology(H5Calls& h5, hid_t topo, hid_t xfer) const;
  /// shape_points, shape_displacement (from the body's pose at t = 0) and shape_velocity at the
  /// local state s (collective; nothing if the model has no shapes).
  void write_step(H5Calls& h5, hid_t group, const MechanicalState& s, hid_t xfer) const;

 private:
  const Subdomain& sub_;
  const ShapeLayout& layout_;
  std::vector<std::pair<int, int>> mine_;  ///< (global shape, local node of its body), increasing
  Rows points_, connectivity_;
};

}  // namespace alphaflex::io_detail
