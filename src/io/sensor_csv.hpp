#pragma once
// Private to the io module: the sensors of a run as CSV (NAME.csv, io/results_writer.hpp): a
// header row "t,<sensor names>", then one row per step with 17 significant digits, so the values
// read back exactly. Written by rank 0 alone; the functions return what failed (errno's text
// included) and the caller makes the ranks agree on it.
#include <cstdio>
#include <string>
#include <vector>

namespace alphaflex::io_detail {

class SensorCsv {
 public:
  SensorCsv(std::string path, const std::vector<std::string>& sensors);
  ~SensorCsv();
  SensorCsv(const SensorCsv&) = delete;
  SensorCsv& operator=(const SensorCsv&) = delete;

  /// A new file with the header row.
  std::string create();
  /// The file of a run that goes on from `rows` rows: cut after them, or started anew (with the
  /// header only, and a warning in `warning`) if it does not hold them.
  std::string resume(long long rows, std::string& warning);
  /// One row: time and the sensor values in scene order.
  void row(double t, const std::vector<double>& values);
  /// Everything written so far to the file system; the error, if a write failed.
  std::string flush();
  /// After a failed write: the file cut after `rows` rows (what was committed with the HDF5
  /// results; a row cut off by a full disk goes too) and closed. Needs no space: truncate(2).
  void cut(long long rows);
  const std::string& path() const { return path_; }

 private:
  std::string failure(const std::string& operation) const;
  std::string path_, header_;
  std::FILE* file_ = nullptr;
};

}  // namespace alphaflex::io_detail
