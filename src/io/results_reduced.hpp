#pragma once
// Private to the io module: the reduced bodies' rebuilt meshes and their modal coordinates in the
// results (issue 19; model/mesh_reconstruction.hpp; docs/output.md, "Reduced bodies").
//  - a grid `reduced_<structure>s` per kind of rebuilt mesh (reduced_beams, reduced_shells): the
//    meshes of the reduced bodies of that kind, body k of the grid at points rows point_offset[k]
//    … of `reduced_<structure>_points` (also _displacement, _velocity, _quaternion, _axis2,
//    _axis3), its cells rows cell_offset[k] … of the cell fields `reduced_<structure>_<field>`
//    (the block's elements' own results: a beam's section forces and strains, a shell's
//    resultants), its connectivity entries connectivity_offset[k] … of
//    /topology/reduced_<structure>_connectivity (point rows);
//  - `modal_coordinates` and `modal_velocities`: ξ and ξ̇ of every reduced body of any kind, rows
//    modal_offset[b] … (dataset /topology/modal_offsets; the bodies' names in the attribute
//    `modal_bodies` of /topology, one per line, in model order).
// The rank that owns a reduced body's element writes all its rows, so the files are the same on
// any number of ranks.
#include <string>
#include <vector>

#include "alphaflex/partition/subdomain.hpp"
#include "hdf5_rows.hpp"

namespace alphaflex::io_detail {

/// The rebuilt meshes of one kind (one grid).
struct ReducedGrid {
  std::string structure;          ///< the elements' ("beam", "shell")
  std::vector<CellField> fields;  ///< the first body's elements' (bodies with other fields write zeros)
  bool lines = true;              ///< only line cells: an XDMF Polyline topology of 2 point rows per cell
  std::vector<size_t> bodies;     ///< its bodies: rows of ReducedLayout::elements, increasing
  /// Per body k of the grid its first row; entry `bodies.size()` is the total.
  std::vector<unsigned long long> point_offset{0}, cell_offset{0}, connectivity_offset{0};
  unsigned long long points() const { return point_offset.back(); }
  unsigned long long cells() const { return cell_offset.back(); }
  unsigned long long connectivity_size() const { return connectivity_offset.back(); }
  std::string grid() const { return "reduced_" + structure + "s"; }
  std::string dataset(const std::string& what) const { return "reduced_" + structure + "_" + what; }
};

struct ReducedLayout {
  std::vector<int> elements;      ///< global ids of the elements with a rebuilt mesh, increasing
  std::vector<std::string> names; ///< their names
  /// Per body b its first modal row; entry `elements.size()` is the total (empty: no reduced body).
  std::vector<unsigned long long> modal_offset;
  std::vector<ReducedGrid> grids;  ///< one per kind, in the order of their first bodies
  bool empty() const { return elements.empty(); }
  unsigned long long modes() const { return empty() ? 0 : modal_offset.back(); }
  unsigned long long points() const {
    unsigned long long n = 0;
    for (const ReducedGrid& g : grids) n += g.points();
    return n;
  }
};

ReducedLayout reduced_layout(const Model& global);

/// This rank's rows: the reduced bodies whose element it owns.
class ReducedRows {
 public:
  ReducedRows(const Subdomain& sub, const ReducedLayout& layout);
  /// The connectivity and modal offsets (collective; nothing without reduced bodies).
  void write_topology(H5Calls& h5, hid_t topo, hid_t xfer) const;
  /// The rebuilt meshes and modal coordinates at the local state s (collective).
  void write_step(H5Calls& h5, hid_t group, const MechanicalState& s, hid_t xfer) const;

 private:
  /// A reduced body this rank writes: its row b, its grid g, its place k in the grid, its local element.
  struct Mine {
    size_t b, g, k;
    int element;
  };
  const Subdomain& sub_;
  const ReducedLayout& layout_;
  std::vector<Mine> mine_;  ///< increasing in b
  std::vector<Rows> points_, cells_, connectivity_;  ///< per grid
  Rows modal_;
};

}  // namespace alphaflex::io_detail
