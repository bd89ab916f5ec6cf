#pragma once
// Private to the io module: what the results draw, asked of the elements (Element::structure,
// output_cell, cell_fields) — the results writer tests no element type. Shared by the HDF5 part
// files (results_parts.hpp) and the XDMF index (xdmf_index.hpp), and the names they share.
#include <string>
#include <vector>

#include "alphaflex/model/model.hpp"

namespace alphaflex::io_detail {

/// The elements of one structure (Element::structure(), e.g. "beam") drawn as one XDMF grid:
/// grid "beams", cell data "beam_<field>", connectivity /topology/beam_connectivity.
struct ElementGrid {
  std::string structure;
  std::vector<CellField> fields;  ///< shared by its elements (the first element's; others are not drawn)
  std::vector<int> elements;      ///< global element indices, model order (= row order)
  std::vector<CellShape> shapes;  ///< their cells
  std::vector<unsigned long long> offset;  ///< start of each element's cell in the connectivity
  unsigned long long connectivity_size = 0;
  /// Only line segments: an XDMF Polyline topology of two node ids per cell (else Mixed: per cell
  /// its XDMF cell type, then its node ids).
  bool lines = true;

  std::string grid() const { return structure + "s"; }
  std::string dataset(const CellField& f) const { return structure + "_" + f.name; }
  std::string connectivity() const { return structure + "_connectivity"; }
};

/// The grids of a model's elements: grids of line segments first, then the others, each in the
/// order of its first element.
std::vector<ElementGrid> element_grids(const Model& global);

/// The connectivity entries of element e's cell (its Mixed type code first unless the grid is of
/// lines), with the node ids given by `node_id` (local node → global node id).
template <class NodeId>
void append_cell(const ElementGrid& grid, const Element& e, NodeId node_id, std::vector<int>& out);

/// The number of connectivity entries of a cell of this shape.
unsigned long long cell_size(CellShape shape, bool lines);
/// XDMF's Mixed-topology type code of a cell shape (2 polyline, 4 triangle, 5 quadrilateral).
int xdmf_cell_type(CellShape shape);

/// File and group names of the results: part_KKKKKK.h5, step_NNNNNN.
std::string part_file(long long k);
std::string group_name(size_t k);

/// A committed output step: its time, its group and the part file that holds it.
struct OutputStep {
  double time = 0.0;
  std::string group;
  long long part = 0;
};

template <class NodeId>
void append_cell(const ElementGrid& grid, const Element& e, NodeId node_id, std::vector<int>& out) {
  const OutputCell cell = e.output_cell();
  if (!grid.lines) {
    out.push_back(xdmf_cell_type(cell.shape));
    if (cell.shape == CellShape::line) out.push_back(2);  // a Mixed polyline gives its node count
  }
  for (int c : cell.corners) out.push_back(node_id(e.nodes()[static_cast<size_t>(c)]));
}

}  // namespace alphaflex::io_detail
