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
//
// What is drawn is asked of the elements (Element::structure, output_cell, cell_fields, output):
// the elements of a structure "beam" are the grid "beams" with datasets beam_<field>, and so on; the
// writer tests no element type. It composes three parts (private to src/io): the HDF5 rows of the
// part files and NAME.h5 (results_parts.hpp), the XDMF index (xdmf_index.hpp) and the sensor CSV
// (sensor_csv.hpp); it decides when to commit and makes the ranks agree on every outcome. A failed
// write is an OutputError on every rank (exit code 6), naming the file and the operation.
#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "alphaflex/model/model.hpp"
#include "alphaflex/partition/subdomain.hpp"

namespace alphaflex {

namespace io_detail {  // the parts of the writer (src/io)
struct ElementGrid;
struct OutputStep;
class ResultsParts;
class XdmfIndex;
class SensorCsv;
}  // namespace io_detail
class OutputLock;

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
  /// in `warnings()`). Collective; throws OutputError on every rank if a file cannot be written,
  /// InputError if the results of the checkpoint cannot be continued.
  /// `csv` false (output.sensors: off): no NAME.csv (csv_path() is empty).
  ResultsWriter(const Subdomain& subdomain, const std::string& outdir, const std::string& name, bool hdf5,
                double commit_interval = 1.0, const ResultsPosition* resume = nullptr, bool csv = true);
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
  /// The position of the last commit that succeeded.
  const ResultsPosition& committed() const { return committed_; }
  /// Called after every commit that succeeded (the run keeps the state it committed, for a
  /// checkpoint of it if a later write fails).
  void on_commit(std::function<void()> f) { on_commit_ = std::move(f); }
  /// After an OutputError (a full disk): the results are left as last committed — the open part
  /// and the temporary files removed, the CSV cut to the committed rows (no cut-off line) — and
  /// nothing more is written. Collective.
  void abandon();
  const std::vector<std::string>& warnings() const { return warnings_; }

  std::string h5_path() const { return h5_path_; }
  std::string xdmf_path() const { return xdmf_path_; }
  std::string csv_path() const { return csv_path_; }
  int fields_written() const;

 private:
  /// Rank 0: NAME.h5's links to the parts and the XDMF index, rewritten; the error, if any.
  std::string write_index() const;
  void resume_from(const ResultsPosition& at);

  const Subdomain& sub_;
  bool root_, hdf5_;
  double commit_interval_;
  std::string h5_path_, xdmf_path_, csv_path_, parts_dir_;
  long long parts_ = 0;  ///< parts committed; the open one is number parts_
  long long csv_rows_ = 0;
  std::chrono::steady_clock::time_point part_opened_ = std::chrono::steady_clock::now();
  double last_commit_cost_ = 0.0;  ///< s of wall time of the last commit (rank 0's)
  std::vector<io_detail::OutputStep> steps_, open_steps_;  ///< committed output steps; those of the open part
  std::vector<std::string> warnings_;
  ResultsPosition committed_;
  std::function<void()> on_commit_;
  /// NAME.lock in the output directory (rank 0): released last, after every file is closed.
  std::unique_ptr<OutputLock> lock_;
  std::unique_ptr<std::vector<io_detail::ElementGrid>> grids_;  ///< what the elements draw
  std::unique_ptr<io_detail::ResultsParts> parts_file_;         ///< HDF5 rows (if hdf5)
  std::unique_ptr<io_detail::XdmfIndex> xdmf_;                  ///< the index (if hdf5)
  std::unique_ptr<io_detail::SensorCsv> csv_;                   ///< the sensors (rank 0)
};

}  // namespace alphaflex
