#pragma once
// Error types of alphaflex. Every error that reaches the user says where (file, key, entity) and
// what was expected; the application maps each type to a non-zero exit code on all MPI ranks.
#include <stdexcept>
#include <string>

namespace alphaflex {

/// Bad user input: a scene key, a value, a reference to something that does not exist.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A numerical failure the user can act on: Newton did not converge, a singular iteration matrix.
class SolverError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Results or a checkpoint that cannot be written (a full or vanished file system, no permission):
/// the message names the file, the operation and errno's text when there is one. Exit code 6: the
/// input was good and the computation may have been too, so neither 1 nor 3.
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// An element that cannot be evaluated in the configuration reached (a spring whose two points
/// coincide). During a run a solver failure like any other; during the consistent start at t = 0
/// the configuration is the scene's own (projected onto its joints), so run_simulation reports it
/// as an InputError naming the scene file.
class ConfigurationError : public SolverError {
 public:
  using SolverError::SolverError;
};

/// The operating system refused memory (an address-space limit such as `ulimit -v`, or no memory
/// left): a failed PETSc allocation (PETSC_ERR_MEM), MUMPS' INFOG(1) = −13, a std::bad_alloc of
/// alphaflex, or a check before an allocation that would not fit. A solver failure (exit code 3,
/// as MUMPS' workspace failure): the input was good, the machine too small for it on these ranks.
/// The message says what was being allocated, how much, and what to do.
class MemoryError : public SolverError {
 public:
  using SolverError::SolverError;
};

/// Not an error: the run stopped on request (a stop signal) after writing a checkpoint and its
/// results; the message says how to restart. Exit code 5.
class Interrupted : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace alphaflex
