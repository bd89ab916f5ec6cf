#include "alphaflex/io/results_writer.hpp"

#include <algorithm>
#include <filesystem>

#include "alphaflex/core/error.hpp"
#include "alphaflex/io/output_lock.hpp"
#include "hdf5_rows.hpp"
#include "results_mesh.hpp"
#include "results_parts.hpp"
#include "sensor_csv.hpp"
#include "xdmf_index.hpp"

namespace alphaflex {

using io_detail::agree;

namespace {

/// rank 0's decision on every rank.
bool root_decides(const Subdomain& sub, bool decision) {
  int d = decision ? 1 : 0;
  if (sub.size() > 1) MPI_Bcast(&d, 1, MPI_INT, 0, sub.comm());
  return d != 0;
}

}  // namespace

ResultsWriter::ResultsWriter(const Subdomain& sub, const std::string& outdir, const std::string& name, bool hdf5,
                             double commit_interval, const ResultsPosition* resume, bool csv)
    : sub_(sub), root_(sub.rank() == 0), hdf5_(hdf5), commit_interval_(commit_interval),
      grids_(std::make_unique<std::vector<io_detail::ElementGrid>>(io_detail::element_grids(sub.global_model()))) {
  namespace fs = std::filesystem;
  const Model& global = sub.global_model();
  const fs::path dir = fs::absolute(outdir);
  h5_path_ = (dir / (name + ".h5")).string();
  xdmf_path_ = (dir / (name + ".xdmf")).string();
  if (csv) csv_path_ = (dir / (name + ".csv")).string();
  const std::string parts_name = name + ".h5.parts";
  parts_dir_ = (dir / parts_name).string();
  // Rank 0 makes the directories and the CSV; the ranks agree before any collective file call.
  std::string err;
  if (root_) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) err = "cannot create the output directory " + dir.string() + " (" + ec.message() + ")";
    // One run at a time writes NAME's results here (io/output_lock.hpp), before any file is touched.
    if (err.empty()) {
      try {
        std::string note;
        lock_ = std::make_unique<OutputLock>(dir.string(), name, &note);
        if (!note.empty()) warnings_.push_back(note);
      } catch (const OutputError& e) {
        err = e.what();
      }
    }
    if (err.empty() && hdf5_) {
      fs::create_directories(parts_dir_, ec);
      if (ec) err = "cannot create the output directory " + parts_dir_ + " (" + ec.message() + ")";
    }
    std::vector<std::string> sensors;
    for (const auto& s : global.sensors()) sensors.push_back(s.name);
    if (csv) csv_ = std::make_unique<io_detail::SensorCsv>(csv_path_, sensors);
  }
  agree<OutputError>(sub, err);
  if (hdf5_) {
    parts_file_ = std::make_unique<io_detail::ResultsParts>(sub, *grids_, parts_dir_, parts_name, h5_path_);
    xdmf_ = std::make_unique<io_detail::XdmfIndex>(xdmf_path_, parts_name, global.nodes().size(),
                                                   global.constraints().size(), *grids_, parts_file_->layout());
  }
  if (resume) {
    resume_from(*resume);
    return;
  }
  if (root_) {
    if (csv_) err = csv_->create();
    // Parts of an earlier run in the same directory are not ours: remove them, and NAME.h5.
    if (err.empty() && hdf5_) {
      parts_file_->remove_from(0);
      std::error_code ec;
      fs::remove(h5_path_, ec);
      fs::remove(xdmf_path_, ec);
      err = parts_file_->write_links(steps_);
      if (err.empty()) err = parts_file_->publish_links();
    }
  }
  agree<OutputError>(sub, err);
  committed_ = position();
}

ResultsWriter::~ResultsWriter() = default;

void ResultsWriter::write_sensors(double t, const std::vector<double>& values) {
  ++csv_rows_;
  if (csv_) csv_->row(t, values);
}

void ResultsWriter::write_fields(const MechanicalState& s) {
  if (!hdf5_) return;
  if (!parts_file_->is_open()) {
    parts_file_->open(parts_);
    part_opened_ = std::chrono::steady_clock::now();
  }
  const std::string group = io_detail::group_name(steps_.size() + open_steps_.size());
  parts_file_->write_step(s, group);  // every rank throws the same OutputError if one write failed
  open_steps_.push_back({s.t, group, parts_});
  agree<OutputError>(sub_, csv_ ? csv_->flush() : std::string());
  // Commit when the part has been open long enough (rank 0's clock decides for all), and at once
  // the first output step: from then on there is always an index to open. The index and NAME.h5
  // grow with the steps, so a commit costs more as a run goes on: the interval also grows to ten
  // times the last commit's cost, which keeps commits under ~10 % of the run.
  const double open_for = std::chrono::duration<double>(std::chrono::steady_clock::now() - part_opened_).count();
  if (root_decides(sub_, open_for >= std::max(commit_interval_, 10.0 * last_commit_cost_) || parts_ == 0)) commit();
}

void ResultsWriter::commit() {
  std::string err = csv_ ? csv_->flush() : std::string();
  if (!hdf5_ || !parts_file_->is_open()) {
    agree<OutputError>(sub_, err);
    return;
  }
  const auto started = std::chrono::steady_clock::now();
  // Close (collective: all of every rank's rows are on disk), then rename into place, link the new
  // steps from NAME.h5 and rewrite the index (rank 0): each is a new file renamed over the old one,
  // so a kill at any moment leaves complete files and an index of complete steps.
  const std::string closed = parts_file_->close(parts_);
  if (err.empty()) err = closed;
  steps_.insert(steps_.end(), open_steps_.begin(), open_steps_.end());
  open_steps_.clear();
  ++parts_;
  if (err.empty()) err = write_index();
  agree<OutputError>(sub_, err);
  last_commit_cost_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  committed_ = position();
  if (on_commit_) on_commit_();
}

void ResultsWriter::abandon() {
  // The open part and the temporary files of a commit that did not happen go (their space is what
  // a checkpoint may need now); the CSV is cut to the committed rows; NAME.h5 and the index are the
  // last committed ones, untouched.
  if (parts_file_) parts_file_->discard();
  if (root_) {
    if (parts_file_) parts_file_->remove_from(committed_.parts);  // a part closed by the failed commit
    std::error_code ec;
    std::filesystem::remove(h5_path_ + ".tmp", ec);
    if (xdmf_) xdmf_->discard();
    if (csv_) csv_->cut(committed_.csv_rows);
  }
  csv_.reset();
}

void ResultsWriter::finish() { commit(); }

ResultsPosition ResultsWriter::position() const {
  ResultsPosition p;
  p.csv_rows = csv_rows_;
  p.steps = static_cast<long long>(steps_.size());
  p.parts = parts_;
  return p;
}

int ResultsWriter::fields_written() const { return static_cast<int>(steps_.size() + open_steps_.size()); }

std::string ResultsWriter::write_index() const {
  if (!root_) return {};
  // NAME.h5 and the index are written in full first, then renamed one right after the other: a
  // kill or a full disk while they are written leaves both as they were, so ParaView (the index)
  // and scripts (NAME.h5) see the same steps (issue 24: the index had lagged a commit behind).
  std::string err = parts_file_->write_links(steps_);
  if (err.empty()) err = xdmf_->write(steps_);
  if (err.empty()) err = parts_file_->publish_links();
  if (err.empty()) err = xdmf_->publish();
  if (!err.empty()) {
    std::error_code ec;
    std::filesystem::remove(h5_path_ + ".tmp", ec);
    xdmf_->discard();
  }
  return err;
}

void ResultsWriter::resume_from(const ResultsPosition& at) {
  namespace fs = std::filesystem;
  std::string err;
  if (root_) {
    std::string warning;
    if (csv_) err = csv_->resume(at.csv_rows, warning);
    if (!warning.empty()) warnings_.push_back(warning);
  }
  csv_rows_ = at.csv_rows;
  agree<OutputError>(sub_, err);
  if (!hdf5_) return;
  // The parts up to the checkpoint's, and their steps (rank 0 reads them; all need them).
  std::vector<io_detail::OutputStep> steps;
  if (root_) {
    err = parts_file_->read_steps(at.parts, steps);
    if (err.empty() && static_cast<long long>(steps.size()) != at.steps)
      err = "restart: the parts in " + parts_dir_ + " hold " + std::to_string(steps.size()) + " output steps, the checkpoint " +
            std::to_string(at.steps) + "; restart into a new output directory (-o)";
    // Later parts (and an unfinished one) belong to the part of the run after the checkpoint.
    parts_file_->remove_from(at.parts);
  }
  // A fresh output directory: the results continue from the restart, numbered after the checkpoint's.
  const bool fresh =
      root_decides(sub_, root_ && at.parts > 0 && !fs::exists(parts_dir_ + "/" + io_detail::part_file(0)));
  if (fresh) {
    err.clear();
    steps.clear();
    if (root_) warnings_.push_back(parts_dir_ + " does not hold the checkpoint's results: the HDF5 output starts anew at the restart time");
  }
  agree<InputError>(sub_, err);  // the output directory given does not continue the checkpoint's run
  unsigned long long n = steps.size();
  if (sub_.size() > 1) MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG_LONG, 0, sub_.comm());
  std::vector<double> times(n);
  std::vector<long long> parts_of(n);
  for (size_t k = 0; k < steps.size(); ++k) {
    times[k] = steps[k].time;
    parts_of[k] = steps[k].part;
  }
  if (sub_.size() > 1 && n > 0) {
    MPI_Bcast(times.data(), static_cast<int>(n), MPI_DOUBLE, 0, sub_.comm());
    MPI_Bcast(parts_of.data(), static_cast<int>(n), MPI_LONG_LONG, 0, sub_.comm());
  }
  for (size_t k = 0; k < n; ++k) steps_.push_back({times[k], io_detail::group_name(k), parts_of[k]});
  // In a fresh directory the HDF5 results start at the restart: steps and parts numbered from 0.
  parts_ = fresh ? 0 : at.parts;
  agree<OutputError>(sub_, write_index());
  committed_ = position();
}

}  // namespace alphaflex
