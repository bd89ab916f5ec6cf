#pragma once
// How every rank ends a run, so that no rank is ever left hanging (design §8). Each rank brings
// its exit code (0, or the code of the error it caught) to one non-blocking all-gather on a
// communicator of its own (a duplicate made at start-up, so that it cannot match a collective call
// another rank is stuck in):
//  - every rank arrives within `timeout` seconds: the error was collective (the ranks agreed on it,
//    as they do for bad scenes, Newton and factorization failures) or there was none; the lowest
//    failing rank prints its message and every rank returns the largest code;
//  - some rank does not arrive: it waits in a collective call that a failing rank has left (an
//    error that only one rank saw); the failing ranks print their message with their rank number
//    and abort the job (MPI_Abort with their code), which ends every rank at once. A rank that
//    arrives with code 0 and is not joined in time aborts too (code 5: "a rank did not finish").
#include <mpi.h>

#include <exception>
#include <string>

namespace alphaflex {

int end_run(MPI_Comm exit_comm, int code, const std::string& message, double timeout);

/// Inside a run, where objects whose destructors are collective (parallel HDF5 file, MUMPS, PETSc
/// matrices) are alive: a rank that caught an error checks that every rank caught one in the same
/// round (within `timeout` s). If so it returns, and the caller rethrows: the objects are destroyed
/// on every rank alike. If not, the error was this rank's only: it prints the message with its
/// rank and aborts the job before any collective destructor could wait for ranks that never come.
void fail_together(MPI_Comm exit_comm, int code, const std::string& message, double timeout);

/// The exit code of an error: 1 bad input, 3 solver failure, 5 interrupted, 6 output not written,
/// 4 anything else.
int exit_code_of(const std::exception& e);

}  // namespace alphaflex
