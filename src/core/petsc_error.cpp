#include "alphaflex/core/petsc_error.hpp"

#include <string>

#include "alphaflex/core/error.hpp"

namespace alphaflex {

void throw_petsc_error(PetscErrorCode ierr, const char* what) {
  std::string msg = "PETSc error " + std::to_string(static_cast<int>(ierr));
  const char* text = nullptr;
  // PETSc's one-line description of the code ("Out of memory", "Error in external library", ...).
  if (PetscErrorMessage(static_cast<int>(ierr), &text, nullptr) == 0 && text && *text) msg += " (" + std::string(text) + ")";
  throw SolverError(msg + " in " + what);
}

}  // namespace alphaflex
