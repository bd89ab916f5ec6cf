#pragma once
// Stop signals: what batch systems send before a job's wall-time limit. SIGTERM, SIGINT and
// SIGUSR1 ask a run to stop after the step it is computing: it writes a checkpoint and its results
// and exits with code 5, saying how to restart (docs/running.md). Under mpirun, Open MPI forwards
// SIGUSR1 to every rank and leaves them running, while on SIGTERM it kills the ranks after a short
// grace period: a batch system should be told to send SIGUSR1 (Slurm: --signal=B:USR1@300). A
// second SIGINT or SIGTERM ends the process at once (the usual meaning of pressing Ctrl-C twice).
namespace alphaflex {

/// Installs the handlers (once per process; the command does, tests need not).
void install_stop_signals();
/// The stop signal received so far on this rank, or 0.
int stop_signal();
/// Its name ("SIGTERM", …) for messages.
const char* signal_name(int sig);

}  // namespace alphaflex
