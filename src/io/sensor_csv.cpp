#include "sensor_csv.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <unistd.h>

namespace alphaflex::io_detail {

SensorCsv::SensorCsv(std::string path, const std::vector<std::string>& sensors) : path_(std::move(path)), header_("t") {
  for (const auto& s : sensors) header_ += "," + s;
}

SensorCsv::~SensorCsv() {
  if (file_) std::fclose(file_);
}

std::string SensorCsv::failure(const std::string& operation) const {
  std::string e = "cannot " + operation + ": " + path_;
  if (errno != 0) e += std::string(" (") + std::strerror(errno) + ")";
  return e;
}

std::string SensorCsv::create() {
  errno = 0;
  if (!(file_ = std::fopen(path_.c_str(), "w"))) return failure("create the sensor file");
  std::fprintf(file_, "%s\n", header_.c_str());
  return flush();
}

std::string SensorCsv::resume(long long rows, std::string& warning) {
  // The CSV up to the checkpoint's rows (header + rows), or a new one if it is gone.
  std::ifstream in(path_);
  std::vector<std::string> lines;
  for (std::string line; lines.size() < static_cast<size_t>(rows) + 1 && std::getline(in, line);) lines.push_back(line);
  in.close();
  if (lines.empty() || lines[0] != header_ || lines.size() != static_cast<size_t>(rows) + 1) {
    warning = path_ + " does not hold the " + std::to_string(rows) +
              " sensor rows of the checkpoint: it is started anew, from the restart time";
    lines.assign(1, header_);
  }
  errno = 0;
  if (!(file_ = std::fopen(path_.c_str(), "w"))) return failure("create the sensor file");
  for (const auto& l : lines) std::fprintf(file_, "%s\n", l.c_str());
  return flush();
}

void SensorCsv::row(double t, const std::vector<double>& values) {
  if (!file_) return;
  std::fprintf(file_, "%.17g", t);
  for (double v : values) std::fprintf(file_, ",%.17g", v);
  std::fprintf(file_, "\n");
}

std::string SensorCsv::flush() {
  if (!file_) return {};
  errno = 0;
  // A failed fprintf sets the stream's error flag, which stays set: ferror sees every failure since
  // the file was opened.
  if (std::fflush(file_) != 0 || std::ferror(file_)) return failure("write the sensor file");
  return {};
}

void SensorCsv::cut(long long rows) {
  if (!file_) return;
  std::fclose(file_);  // what stays buffered goes (or fails to go) now; the cut below decides
  file_ = nullptr;
  std::ifstream in(path_, std::ios::binary);
  long long offset = 0;
  std::string line;
  for (long long k = 0; k <= rows && std::getline(in, line); ++k) {
    if (in.eof()) break;  // a last line without its newline is a row cut off
    offset += static_cast<long long>(line.size()) + 1;
  }
  in.close();
  if (truncate(path_.c_str(), static_cast<off_t>(offset)) != 0) { /* the run has failed already: its message stands */ }
}

}  // namespace alphaflex::io_detail
