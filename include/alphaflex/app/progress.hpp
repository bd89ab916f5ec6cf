#pragma once
// Progress of a long run on rank 0 (issue 8, item 5): on a terminal one line rewritten in place at
// most `kTerminalInterval` s apart; otherwise (batch logs) a plain line every `interval` seconds of
// wall time. Simulated time, step, Newton iterations per step so far, wall time and the ETA from
// the mean wall time per simulated second. Nothing is printed by a reporter that is not active.
#include <cstdio>
#include <string>

namespace alphaflex {

class ProgressReporter {
 public:
  /// `active`: rank 0 and a verbose run; `interval` (s): plain lines apart (0: none); `t0`, `t_end`:
  /// the simulated interval; `total_steps`; `stream`: stderr (stdout keeps the summary); `what`:
  /// the name of the progressing quantity with its unit ("t", " s"; a static analysis: the load
  /// factor, "").
  ProgressReporter(bool active, double interval, double t0, double t_end, long total_steps, std::FILE* stream = stderr,
                   std::string what = "t", std::string unit = " s");
  ~ProgressReporter();
  ProgressReporter(const ProgressReporter&) = delete;
  ProgressReporter& operator=(const ProgressReporter&) = delete;

  /// After step `step` (1-based) reached time t with `newton_total` iterations so far (< 0: not
  /// known); variable steps: `rejected` steps so far (< 0: fixed steps) and the step size h.
  void update(long step, double t, long newton_total, long long rejected = -1, double h = 0.0);
  /// Clears a terminal line (before the summary).
  void finish();

  /// The line printed for a state (exposed for the tests).
  std::string line(long step, double t, long newton_total, double wall, long long rejected = -1, double h = 0.0) const;

 private:
  bool active_, terminal_;
  double interval_, t0_, t_end_, start_, last_ = 0.0;
  long total_;
  std::FILE* out_;
  std::string what_, unit_;
  bool dirty_ = false;
};

}  // namespace alphaflex
