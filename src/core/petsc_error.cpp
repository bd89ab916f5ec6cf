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

#include <cstdlib>
#include <cstring>

#include "alphaflex/core/memory.hpp"

namespace alphaflex {

QuietPetscErrors::QuietPetscErrors() { PetscPushErrorHandler(&QuietPetscErrors::record, this); }

QuietPetscErrors::~QuietPetscErrors() { PetscPopErrorHandler(); }

PetscErrorCode QuietPetscErrors::record(MPI_Comm, int, const char* fun, const char*, PetscErrorCode n, PetscErrorType p,
                                        const char* mess, void* ctx) {
  auto* self = static_cast<QuietPetscErrors*>(ctx);
  if (p == PETSC_ERROR_INITIAL && self->raised_ == 0) {
    self->raised_ = n;
    self->message_ = mess ? mess : "";
    self->function_ = fun ? fun : "";
  }
  return n;
}

void QuietPetscErrors::check(PetscErrorCode ierr, const char* what) const {
  if (!ierr && !raised_) return;
  // Out of memory: the code PETSc raises for it, or (PETSc 3.18 passes other numbers from a failed
  // PetscMallocA) an error raised by its allocator itself.
  const bool memory = raised_ == PETSC_ERR_MEM || function_.rfind("PetscMalloc", 0) == 0 ||
                      function_.rfind("PetscTrMalloc", 0) == 0 || function_.rfind("PetscRealloc", 0) == 0;
  if (memory) {
    // PetscMallocAlign's message: "Memory requested N" (bytes).
    double bytes = 0.0;
    const char* r = std::strstr(message_.c_str(), "Memory requested");
    if (r) bytes = std::strtod(r + std::strlen("Memory requested"), nullptr);
    int rank = 0;
    MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
    throw MemoryError(out_of_memory_message(std::string(what) + (function_.empty() ? "" : " (in PETSc's " + function_ + ")"),
                                            bytes, rank));
  }
  throw_petsc_error(raised_ ? raised_ : ierr, (std::string(what) + (message_.empty() ? "" : ": " + message_)).c_str());
}

}  // namespace alphaflex
