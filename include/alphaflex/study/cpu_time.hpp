#pragma once
// CPU time of this process (all its threads), the cost measure of every study: generalized-α runs,
// the SUNDIALS IDA peer (in process) and SciPy's Radau (its own process, time.process_time()) are
// all timed the same way. Wall time would charge a run for the other jobs of a shared machine.
#include <ctime>

namespace alphaflex::study {

/// Seconds of CPU time used by this process so far (CLOCK_PROCESS_CPUTIME_ID).
inline double process_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

}  // namespace alphaflex::study
