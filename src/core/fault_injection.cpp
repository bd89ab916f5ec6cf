#include "alphaflex/core/fault_injection.hpp"

#include <petscsys.h>

#include <cstdlib>
#include <string>

namespace alphaflex {
namespace {

struct Fault {
  bool read = false, armed = false;
  std::string what;
  int rank = -1;
  long count = 1, calls = 0;
};

Fault& fault() {
  static Fault f;
  if (f.read) return f;
  f.read = true;
  PetscBool initialized = PETSC_FALSE;
  PetscInitialized(&initialized);
  if (!initialized) return f;
  char value[256] = "";
  PetscBool set = PETSC_FALSE;
  if (PetscOptionsGetString(nullptr, nullptr, "-af_inject_fault", value, sizeof value, &set) || !set) return f;
  const std::string v = value;
  const size_t a = v.find(':');
  if (a == std::string::npos) return f;
  const size_t b = v.find(':', a + 1);
  f.what = v.substr(0, a);
  f.rank = std::atoi(v.substr(a + 1, b == std::string::npos ? std::string::npos : b - a - 1).c_str());
  if (b != std::string::npos) f.count = v.substr(b + 1) == "*" ? -1 : std::atol(v.substr(b + 1).c_str());
  int me = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &me);
  f.armed = me == f.rank;
  return f;
}

}  // namespace

bool fault_injected(const char* what) {
  Fault& f = fault();
  if (!f.armed || f.what != what) return false;
  return ++f.calls == f.count || f.count < 0;
}

}  // namespace alphaflex
