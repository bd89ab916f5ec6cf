#pragma once
// Private to the io module: the XDMF index of the results (NAME.xdmf, io/results_writer.hpp), for
// ParaView. Temporal collections "bodies" (polyvertex, one per body node: results_layout.hpp),
// "links" (a polyline body → joint → body per joint that holds a body), "shapes" (the bodies'
// shapes, a Mixed surface whose points move with them: results_shapes.hpp), one per element grid
// (results_mesh.hpp: line segments or a Mixed topology of faces, the node positions of each step
// as points, the elements' fields as cell data) and "joints" (polyvertex, one per joint); every
// step refers to the part file that holds it. Rewritten whole at every commit: written to a
// temporary file and renamed, so a reader never sees half an index.
#include <string>
#include <vector>

#include "results_layout.hpp"
#include "results_mesh.hpp"

namespace alphaflex::io_detail {

class XdmfIndex {
 public:
  /// The index `path` of parts in the directory `parts_name` (relative to it), for `nodes` nodes,
  /// `joints` joints and the element grids `grids`.
  XdmfIndex(std::string path, std::string parts_name, size_t nodes, size_t joints, const std::vector<ElementGrid>& grids,
            const NodeLayout& layout);
  /// The index of `steps`, written under a temporary name (NAME.xdmf.tmp); publish() renames it
  /// over the index. The error, if any (the caller agrees on it).
  std::string write(const std::vector<OutputStep>& steps) const;
  std::string publish() const;
  /// Removes a temporary index left by a failed commit.
  void discard() const;
  const std::string& path() const { return path_; }

 private:
  std::string path_, parts_name_;
  size_t nodes_, joints_;
  const std::vector<ElementGrid>& grids_;
  const NodeLayout& layout_;
};

}  // namespace alphaflex::io_detail
