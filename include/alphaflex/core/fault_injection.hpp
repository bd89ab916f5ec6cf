#pragma once
// Faults injected on purpose, for the tests of error handling under MPI (tests/cli): the PETSc
// option
//     -af_inject_fault WHAT:RANK[:COUNT]
// makes fault_injected(WHAT) true on rank RANK of PETSC_COMM_WORLD at its COUNT-th call (default
// 1; `*`: at every call), and false everywhere else. The places that ask are named in docs/running.md: "input" (a bad
// value found on one rank only), "newton" (a NaN in one rank's Newton correction), "output" (a
// failed HDF5 write on one rank), "singular" (a zero row in one rank's part of the iteration
// matrix), "internal" (an unexpected exception on one rank), "disk_full" (the COUNT-th checked
// HDF5 call of the rank fails with ENOSPC, as on a full disk), "index" (the XDMF index cannot be
// written, ENOSPC), "no_room_check" (the results do not ask the file system for room before a step,
// so that a full disk fails inside HDF5: the path of a disk filled by another process). Without the option nothing changes and
// the check costs one comparison.
namespace alphaflex {

bool fault_injected(const char* what);

}  // namespace alphaflex
