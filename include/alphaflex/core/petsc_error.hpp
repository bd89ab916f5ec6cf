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

#include <string>

namespace alphaflex {

/// While alive, PETSc errors are recorded instead of printed (PETSc's default handler prints its
/// trace at the first failing call, whatever the caller then does with the code): the first error
/// raised (its code, e.g. PETSC_ERR_MEM, and PETSc's message, e.g. "Memory requested 1234567") is
/// kept for `check`. Pops its handler when destroyed. (PETSc 3.18 may return another number than
/// the code it raised, e.g. a line number after a failed PetscMalloc: the raised code is the one
/// the handler saw.)
class QuietPetscErrors {
 public:
  QuietPetscErrors();
  ~QuietPetscErrors();
  QuietPetscErrors(const QuietPetscErrors&) = delete;
  QuietPetscErrors& operator=(const QuietPetscErrors&) = delete;

  /// Nothing if ierr = 0. Otherwise throws: a MemoryError if PETSc ran out of memory (what was
  /// being done: `what`; how much: PETSc's "Memory requested"), else SolverError as check_petsc.
  void check(PetscErrorCode ierr, const char* what) const;
  /// The code PETSc raised first (0: none) and its message.
  PetscErrorCode raised() const { return raised_; }
  const std::string& message() const { return message_; }

 private:
  static PetscErrorCode record(MPI_Comm, int, const char*, const char*, PetscErrorCode, PetscErrorType, const char*, void*);
  PetscErrorCode raised_ = 0;
  std::string message_, function_;
};

}  // namespace alphaflex
