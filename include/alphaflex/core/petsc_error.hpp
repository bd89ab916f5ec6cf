#pragma once
// PETSc error codes as C++ exceptions, in one place. Functions that return a PetscErrorCode use
// PetscCall (PETSc's convention: its traceback names the call); C++ code that reports failure by
// exception — constructors, the integrators, the study — passes the code to check_petsc, so a
// failed PETSc call reads alike wherever it happens.
#include <petscsys.h>

namespace alphaflex {

/// Throws SolverError "PETSc error CODE (PETSc's text for CODE) in WHAT".
[[noreturn]] void throw_petsc_error(PetscErrorCode ierr, const char* what);

/// Throws SolverError naming `what` (the call or the phase) if a PETSc call failed (ierr ≠ 0).
inline void check_petsc(PetscErrorCode ierr, const char* what) {
  if (ierr) throw_petsc_error(ierr, what);
}

}  // namespace alphaflex
