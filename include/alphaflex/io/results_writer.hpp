#pragma once
// Results for ParaView and for scripts: an HDF5 file with one group per output step and an XDMF
// index (temporal collections "bodies" and "joints" as polyvertex grids with node frames (axes and
// quaternion), "beams" as line segments in the deformed configuration with section forces and
// strains as cell data, and "shells" as triangles and quadrilaterals (one XDMF Mixed topology) in
// the deformed configuration with stress resultants and von Mises stresses as cell data;
// Precision="8" doubles),
// plus the sensors as CSV (header row, first column t, 17 significant digits).
//
// Crash-safe layout. The output steps go to part files OUTDIR/NAME.h5.parts/part_KKKKKK.h5, each
// holding the topology and the step groups written since the previous commit. A part is written
// under a temporary name and renamed when it is complete (a commit); only then do NAME.h5 (external
// links /topology and /step_NNNNNN to the parts, so scripts read one file) and the XDMF index
// (rewritten to a temporary file and renamed) refer to it. A run killed at any moment (SIGKILL)
// therefore leaves an index whose every step is in a complete file: ParaView opens the run up to the
// last commit. A part is committed at the first output step after it has been open for
// `output.commit_interval` s of wall time (0: every output step) and for ten times as long as the
// last commit took (the index grows with the steps: commits stay under ~10 % of the run), and
// always at the first output step, at a checkpoint, at the end, after a failure and on a signal.
//
// In parallel every rank writes the rows it owns (its nodes, elements and joints, at their places
// in model order) with collective MPI-IO writes of parallel HDF5, so the files have the same layout
// and order whatever the number of ranks; rank 0 writes the CSV, NAME.h5 and the XDMF index.
#include <chrono>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "alphaflex/model/model.hpp"
#include "alphaflex/partition/subdomain.hpp"

namespace alphaflex {

/// Where a restart picks up the results of the run it continues (from its checkpoint): the
/// sensor rows, output steps and parts that were complete at the checkpoint.
struct ResultsPosition {
  long long csv_rows = 0;  ///< CSV rows after the header (one per step, t = 0 included)
  long long steps = 0;     ///< output steps (HDF5 groups) committed
  long long parts = 0;     ///< part files committed
};

class ResultsWriter {
 public:
  /// Creates OUTDIR/NAME.csv (rank 0) and, if `hdf5`, NAME.h5 and the directory of its parts.
  /// With `resume`, continues the results of a run from a checkpoint instead: the CSV is cut
  /// after the checkpoint's rows, parts after its last one are removed, NAME.h5 and the index are
  /// rebuilt from the parts that remain (files that are missing are started anew, with a warning
  /// in `warnings()`). Collective; throws InputError on every rank if any part failed.
  ResultsWriter(const Subdomain& subdomain, const std::string& outdir, const std::string& name, bool hdf5,
                double commit_interval = 1.0, const ResultsPosition* resume = nullptr);
  ~ResultsWriter();
  ResultsWriter(const ResultsWriter&) = delete;
  ResultsWriter& operator=(const ResultsWriter&) = delete;

  /// One CSV row (rank 0): time and the sensor values in scene order (the same on every rank).
  void write_sensors(double t, const std::vector<double>& values);
  /// This rank's part of the state `s` (its subdomain's local state) to HDF5, one group per call,
  /// into the open part; commits the part when it is due. Collective.
  void write_fields(const MechanicalState& s);
  /// Makes everything written so far complete on disk and listed in NAME.h5 and the index.
  /// Collective.
  void commit();
  /// Commits and flushes the CSV (called at the end, also after a failure). Collective.
  void finish();

  /// What has been committed (for a checkpoint, after commit()).
  ResultsPosition position() const;
  const std::vector<std::string>& warnings() const { return warnings_; }

  std::string h5_path() const { return h5_path_; }
  std::string xdmf_path() const { return xdmf_path_; }
  std::string csv_path() const { return csv_path_; }
  int fields_written() const { return static_cast<int>(times_.size() + open_times_.size()); }

 private:
  void open_part();
  void write_topology(long long file);
  void write_xdmf() const;
  void write_links();
  /// Rank 0: NAME.h5's links to the parts and the XDMF index, rewritten; the error, if any (no throw).
  std::string write_index();
  void resume_from(const ResultsPosition& at);

  const Subdomain& sub_;
  const Model& model_;   ///< the local model (this rank's subdomain)
  const Model& global_;  ///< the whole model: names, counts and layouts
  bool root_, hdf5_;
  double commit_interval_;
  std::string name_, dir_, h5_path_, xdmf_path_, csv_path_, parts_dir_, parts_name_;
  long long transfer_ = -1;               ///< hid_t of the (collective) transfer list
  long long part_ = -1;                   ///< hid_t of the open part, −1 if none
  long long parts_ = 0;                   ///< parts committed; the open one is number parts_
  std::string error_;  ///< the first failed HDF5 call of the current output step, on this rank
  std::FILE* csv_ = nullptr;
  long long csv_rows_ = 0;
  std::chrono::steady_clock::time_point part_opened_ = std::chrono::steady_clock::now();
  double last_commit_cost_ = 0.0;  ///< s of wall time of the last commit (rank 0's)
  // Committed output steps: time, group name, part index; and those of the open part.
  std::vector<double> times_, open_times_;
  std::vector<std::string> groups_, open_groups_;
  std::vector<long long> group_part_;
  std::vector<std::string> warnings_;
  std::vector<int> beams_;                 ///< global elements drawn as beam segments
  std::vector<std::string> beam_fields_;   ///< their result fields (cell data)
  std::vector<int> shells_;                ///< global elements drawn as shell triangles and quadrilaterals
  std::vector<std::string> shell_fields_;  ///< their result fields (cell data)
  size_t shell_topology_size_ = 0;         ///< length of /topology/shell_connectivity (Mixed)
  // This rank's rows: owned nodes, its joints, its beams and shells, and its part of the shell
  // connectivity (the state vectors' rows are io_detail::StateRows).
  struct RowsImpl;
  std::unique_ptr<RowsImpl> rows_;
  std::vector<int> local_beams_, local_shells_;  ///< local element indices, in row order
};

}  // namespace alphaflex
