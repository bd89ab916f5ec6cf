#pragma once
// Concurrent runs of a study (`alphaflex study --ranks-per-run k` under mpirun -np N): the N ranks
// split into N/k groups (MPI_Comm_split), each group runs its share of the independent simulations
// on its own communicator (every PETSc object of a run is created on it), and the outcomes — rows,
// final states, or the error a run threw — are gathered on every rank afterwards, so that no group
// waits in a collective call for a group that failed.
#include <mpi.h>

#include <string>
#include <vector>

#include "alphaflex/model/state.hpp"
#include "alphaflex/study/study.hpp"

namespace alphaflex::study {

/// Scenes up to this many unknowns (coordinates + multipliers) run one per rank by default: a
/// factorization of that size gains little from a second rank (MUMPS' parallel efficiency on the
/// small fronts of a mechanism), while independent runs scale with the ranks (docs/performance.md).
constexpr int kSmallSceneUnknowns = 20000;

/// The default ranks per run: 1 for a small scene, all ranks (one run at a time) otherwise.
int default_ranks_per_run(int unknowns, int ranks);

/// Why `k` ranks per run is not possible on `ranks` ranks ("" when it is): k must be ≥ 1, at most
/// the number of ranks, and divide it.
std::string ranks_per_run_problem(int k, int ranks);

/// Returns when every rank of `comm` has called it; waits asleep (a non-blocking barrier tested
/// every millisecond), so that a rank that is done leaves the core to the ranks still working.
void wait_asleep(MPI_Comm comm);

/// The groups of ranks of a communicator, `k` ranks each (k divides its size; checked by the caller).
class RunGroups {
 public:
  RunGroups(MPI_Comm comm, int ranks_per_run);
  ~RunGroups();
  RunGroups(const RunGroups&) = delete;
  RunGroups& operator=(const RunGroups&) = delete;

  MPI_Comm group_comm() const { return group_; }
  int group() const { return group_index_; }
  int groups() const { return groups_; }
  bool leads_group() const { return group_rank_ == 0; }

  /// True when every rank is on one node: then the groups take their runs one at a time from a
  /// counter in shared memory (next_task), so that a group that finishes early, or starts late,
  /// takes more; else each group runs the share assign() gives it.
  bool shares_a_counter() const { return counter_ != nullptr; }
  /// The next position in the common list of runs (group leaders only; atomic fetch-and-add on
  /// the shared counter: each position is handed out once).
  long next_task() const;
  /// `value` of the group's leader on every rank of the group (waited for asleep, like
  /// wait_for_all, while the leader runs something else).
  long from_leader(long value) const;

  /// A group for each task, by longest processing time first (Graham 1969): tasks in decreasing
  /// estimated cost, each to the group with the least work so far. Deterministic: every rank gets
  /// the same answer.
  std::vector<int> assign(const std::vector<double>& cost) const;

  /// Returns when every rank has called it; waits asleep, not polling (see the definition).
  void wait_for_all() const;

  /// Every rank's byte string, on every rank (in rank order of the whole communicator), once every
  /// rank has come (wait_for_all).
  std::vector<std::string> allgather(const std::string& mine) const;

 private:
  MPI_Comm comm_, group_ = MPI_COMM_NULL;
  MPI_Win window_ = MPI_WIN_NULL;  ///< the shared counter's memory (rank 0's)
  long* counter_ = nullptr;
  int group_index_ = 0, groups_ = 1, group_rank_ = 0;
};

/// What one run of a concurrent study sends to every rank.
struct RunOutcome {
  int task = -1;
  StudyRow row;                      ///< errors not yet measured
  std::vector<std::string> sensor_names;
  std::vector<double> final_sensors;
  MechanicalState final_state;
  /// Fidelity runs: the output times, each sensor's history at them (sensor_names order) and the
  /// strain energy per flexible part.
  std::vector<double> times;
  std::vector<std::vector<double>> histories;
  std::vector<EnergyRow> energy;
  /// The run's time history for the study's charts (NAME_history.csv; oscillation and blow_up):
  /// its output times and, at each, the values the mode keeps.
  std::vector<double> history_t;
  std::vector<std::vector<double>> history;
  int error_code = 0;                ///< exit code of an exception other than a failed run (exit_agreement.hpp)
  std::string error;                 ///< its message
};

std::string pack(const std::vector<RunOutcome>& outcomes);
std::vector<RunOutcome> unpack(const std::string& bytes);

/// Throws the error of an outcome as the type its exit code stands for (1 InputError, 3
/// SolverError, 6 OutputError, else std::runtime_error).
[[noreturn]] void rethrow(const RunOutcome& o);

}  // namespace alphaflex::study
