#pragma once
// Private to the io module: the HDF5 rows of the results (io/results_writer.hpp describes the
// layout). One step group per output step with this rank's rows of every dataset, in part files
// NAME.h5.parts/part_KKKKKK.h5 (each with the topology) written under a temporary name and renamed
// when closed, and NAME.h5, the external links into the parts. Every HDF5 call is checked: the
// collective functions throw an OutputError on every rank if a call failed on one, the functions
// of rank 0 alone return what failed (the caller makes the ranks agree on it).
#include <optional>
#include <string>
#include <vector>

#include "alphaflex/model/model.hpp"
#include "alphaflex/partition/subdomain.hpp"
#include "hdf5_rows.hpp"
#include "results_layout.hpp"
#include "results_mesh.hpp"

namespace alphaflex::io_detail {

class ResultsParts {
 public:
  /// The parts of NAME in `parts_dir` (whose last path component is `parts_name`) and the link
  /// file `h5_path`, for the element grids `grids` of the global model. Collective.
  ResultsParts(const Subdomain& sub, const std::vector<ElementGrid>& grids, std::string parts_dir,
               std::string parts_name, std::string h5_path);
  ~ResultsParts();
  ResultsParts(const ResultsParts&) = delete;
  ResultsParts& operator=(const ResultsParts&) = delete;

  bool is_open() const { return part_ >= 0; }
  /// Bodies, links and flexible blocks of the model (results_layout.hpp), for the index.
  const NodeLayout& layout() const { return layout_; }
  /// Opens part k under its temporary name and writes the topology into it. Collective.
  void open(long long k);
  /// This rank's rows of the state `s` (local) as group `group` of the open part, at time s.t.
  /// Collective.
  void write_step(const MechanicalState& s, const std::string& group);
  /// Closes the open part k (collective: all of every rank's rows are on disk) and renames it
  /// into place (rank 0): the error, if any (the caller agrees on it).
  std::string close(long long k);
  /// After a failed write: the open part is closed without its data (discard_file) and removed
  /// (rank 0). Collective; nothing if no part is open.
  void discard();
  /// Rank 0: NAME.h5 with links to `steps`, written under a temporary name; publish_links()
  /// renames it over the old one (separately, so that the XDMF index is renamed with it).
  std::string write_links(const std::vector<OutputStep>& steps) const;
  std::string publish_links() const;
  /// Rank 0: the output steps of parts 0 … parts−1 (times and part numbers), for a restart; an
  /// error if one is missing or unreadable.
  std::string read_steps(long long parts, std::vector<OutputStep>& steps) const;
  /// Rank 0: removes the parts numbered `from` and above and unfinished ones (temporary names).
  void remove_from(long long from) const;

 private:
  void write_topology(H5Calls& h5, hid_t file) const;
  /// The 3 points of joint `con`'s link (location `at`) at state s, appended to `out`.
  void append_link(const Constraint& con, const Eigen::Vector3d& at, const MechanicalState& s,
                   std::vector<double>& out) const;
  std::string part_path(long long k) const { return parts_dir_ + "/" + part_file(k); }

  const Subdomain& sub_;
  const Model& model_;  ///< the local model
  const std::vector<ElementGrid>& grids_;
  std::string parts_dir_, parts_name_, h5_path_;
  hid_t transfer_ = -1;
  hid_t part_ = -1;  ///< the open part, −1 if none
  std::string open_path_;  ///< its path (temporary name)
  /// Bytes an output step adds to a part (the largest measured, first an estimate): the room
  /// asked of the file system before a step is written (hdf5_rows.hpp, room_for).
  unsigned long long step_bytes_ = 0;
  // This rank's rows: owned nodes, its joints, and per grid its elements and connectivity entries.
  Rows node_, joint_;
  NodeLayout layout_;
  Rows body_, link_;  ///< owned body nodes (when not every node is a body); 3 points per drawn link
  std::optional<ShapeRows> shapes_;  ///< the shapes of the owned bodies (made with layout_)
  std::optional<ReducedRows> reduced_;  ///< the rebuilt meshes of the owned reduced bodies (made with layout_)
  StateRows state_;
  std::vector<Rows> cells_, connectivity_;
  std::vector<std::vector<int>> local_elements_;  ///< per grid: local element indices, in row order
};

}  // namespace alphaflex::io_detail
