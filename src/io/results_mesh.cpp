#include "results_mesh.hpp"

#include <algorithm>
#include <cstdio>

namespace alphaflex::io_detail {

unsigned long long cell_size(CellShape shape, bool lines) {
  const unsigned long long corners = shape == CellShape::line ? 2 : shape == CellShape::triangle ? 3 : 4;
  if (lines) return corners;
  return corners + (shape == CellShape::line ? 2 : 1);  // type code (and a polyline's node count)
}

int xdmf_cell_type(CellShape shape) {
  switch (shape) {
    case CellShape::line: return 2;
    case CellShape::triangle: return 4;
    case CellShape::quadrilateral: return 5;
    case CellShape::none: break;
  }
  return 0;
}

std::vector<ElementGrid> element_grids(const Model& global) {
  std::vector<ElementGrid> grids;
  const auto& els = global.elements();
  for (size_t e = 0; e < els.size(); ++e) {
    const Element& el = *els[e];
    const char* structure = el.structure();
    const CellShape shape = el.output_cell().shape;
    if (!structure || shape == CellShape::none) continue;
    auto g = std::find_if(grids.begin(), grids.end(), [&](const ElementGrid& x) { return x.structure == structure; });
    if (g == grids.end()) {
      grids.push_back({});
      g = grids.end() - 1;
      g->structure = structure;
      g->fields = el.cell_fields();
    }
    if (el.cell_fields() != g->fields) continue;  // another set of fields than its grid's: not drawn
    g->elements.push_back(static_cast<int>(e));
    g->shapes.push_back(shape);
    g->lines = g->lines && shape == CellShape::line;
  }
  for (ElementGrid& g : grids) {
    for (CellShape shape : g.shapes) {
      g.offset.push_back(g.connectivity_size);
      g.connectivity_size += cell_size(shape, g.lines);
    }
  }
  std::stable_partition(grids.begin(), grids.end(), [](const ElementGrid& g) { return g.lines; });
  return grids;
}

std::string part_file(long long k) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "part_%06lld.h5", k);
  return buf;
}

std::string group_name(size_t k) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "step_%06zu", k);
  return buf;
}

}  // namespace alphaflex::io_detail
