#include "alphaflex/app/progress.hpp"

#include <mpi.h>
#include <unistd.h>

#include <cmath>
#include <utility>

namespace alphaflex {

namespace {
constexpr double kTerminalInterval = 0.25;  // s between rewrites of a terminal line
}

ProgressReporter::ProgressReporter(bool active, double interval, double t0, double t_end, long total_steps, std::FILE* stream,
                                   std::string what, std::string unit)
    : active_(active), terminal_(active && ::isatty(::fileno(stream)) != 0), interval_(interval), t0_(t0),
      t_end_(t_end), start_(MPI_Wtime()), total_(total_steps), out_(stream), what_(std::move(what)), unit_(std::move(unit)) {
  last_ = start_;
  if (!terminal_ && !(interval_ > 0.0)) active_ = false;
}

ProgressReporter::~ProgressReporter() { finish(); }

std::string ProgressReporter::line(long step, double t, long newton_total, double wall, long long rejected, double h) const {
  const double done = t_end_ > t0_ ? (t - t0_) / (t_end_ - t0_) : 1.0;
  const double eta = done > 0.0 ? wall * (1.0 - done) / done : 0.0;
  char head[160], newton[64] = "", steps[96] = "", tail[96];
  if (total_ >= 0)
    std::snprintf(head, sizeof head, "progress: %s = %.6g%s (%.0f %%), step %ld of %ld", what_.c_str(), t, unit_.c_str(),
                  100.0 * done, step, total_);
  else
    std::snprintf(head, sizeof head, "progress: %s = %.6g%s (%.0f %%), step %ld", what_.c_str(), t, unit_.c_str(), 100.0 * done, step);
  if (rejected >= 0) std::snprintf(steps, sizeof steps, " (%lld rejected, h = %.3g s)", rejected, h);
  if (newton_total >= 0)
    std::snprintf(newton, sizeof newton, ", Newton %.2f per step",
                  step > 0 ? static_cast<double>(newton_total) / static_cast<double>(step) : 0.0);
  std::snprintf(tail, sizeof tail, ", wall %.1f s, ETA %.1f s", wall, eta);
  return std::string(head) + steps + newton + tail;
}

void ProgressReporter::update(long step, double t, long newton_total, long long rejected, double h) {
  if (!active_) return;
  const double now = MPI_Wtime();
  if (now - last_ < (terminal_ ? kTerminalInterval : interval_)) return;
  last_ = now;
  const std::string text = line(step, t, newton_total, now - start_, rejected, h);
  if (terminal_) {
    std::fprintf(out_, "\r%s\033[K", text.c_str());
    dirty_ = true;
  } else {
    std::fprintf(out_, "%s\n", text.c_str());
  }
  std::fflush(out_);
}

void ProgressReporter::finish() {
  if (dirty_) {
    std::fprintf(out_, "\r\033[K");
    std::fflush(out_);
    dirty_ = false;
  }
}

}  // namespace alphaflex
