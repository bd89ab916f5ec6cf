#include "alphaflex/core/memory.hpp"

#include <sys/mman.h>
#include <sys/resource.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <iomanip>
#include <sstream>

#include "alphaflex/core/error.hpp"

namespace alphaflex {
namespace {

/// The value (kB) of `key` in a /proc file of "Key:   value kB" lines; −1 if absent.
double proc_kb(const char* file, const char* key) {
  std::FILE* f = std::fopen(file, "r");
  if (!f) return -1.0;
  char line[256];
  double kb = -1.0;
  const size_t n = std::strlen(key);
  while (std::fgets(line, sizeof line, f))
    if (std::strncmp(line, key, n) == 0 && line[n] == ':') {
      kb = std::strtod(line + n + 1, nullptr);
      break;
    }
  std::fclose(f);
  return kb;
}

std::string mb(double x) {
  std::ostringstream os;
  os << std::fixed << std::setprecision(x < 10.0 ? 2 : 1) << x << " MB";
  return os.str();
}

}  // namespace

double MemoryStatus::room_mb() const {
  double room = available_mb;
  if (limit_mb >= 0.0) {
    const double left = limit_mb - address_space_mb;
    room = room < 0.0 ? left : std::min(room, left);
  }
  return room;
}

MemoryStatus memory_status() {
  MemoryStatus m;
  const double kb = 1.0 / 1024.0;
  m.resident_mb = std::max(0.0, proc_kb("/proc/self/status", "VmRSS") * kb);
  m.peak_resident_mb = std::max(0.0, proc_kb("/proc/self/status", "VmHWM") * kb);
  m.address_space_mb = std::max(0.0, proc_kb("/proc/self/status", "VmSize") * kb);
  const double avail = proc_kb("/proc/meminfo", "MemAvailable");
  m.available_mb = avail < 0.0 ? -1.0 : avail * kb;
  struct rlimit rl;
  if (getrlimit(RLIMIT_AS, &rl) == 0 && rl.rlim_cur != RLIM_INFINITY)
    m.limit_mb = static_cast<double>(rl.rlim_cur) / 1048576.0;
  return m;
}

bool address_space_for(double bytes) {
  if (!(bytes > 0.0)) return true;
  if (!std::isfinite(bytes) || bytes > 1e18) return false;
  const size_t n = static_cast<size_t>(bytes);
  void* p = mmap(nullptr, n, PROT_NONE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
  if (p == MAP_FAILED) return false;
  munmap(p, n);
  return true;
}

std::string out_of_memory_message(const std::string& what, double bytes, int rank) {
  const MemoryStatus m = memory_status();
  std::ostringstream os;
  os << "out of memory" << (rank >= 0 ? " on rank " + std::to_string(rank) : std::string()) << " while " << what;
  if (bytes > 0.0) os << ": " << mb(bytes / 1048576.0) << " could not be allocated";
  os << " (this process: " << mb(m.resident_mb) << " resident, " << mb(m.address_space_mb) << " of address space";
  if (m.limit_mb >= 0.0) os << " under its limit of " << mb(m.limit_mb) << " (ulimit -v)";
  if (m.available_mb >= 0.0) os << "; the machine: " << mb(m.available_mb) << " available";
  os << ").\n  What to do: fewer unknowns per rank — run on more ranks (mpirun -np N divides the matrix and "
        "MUMPS' factors among them) or a coarser model —, or give each rank more memory (a larger ulimit -v or "
        "job memory request); the run's memory estimate (printed before large runs, and in NAME.summary.json of a "
        "smaller run of the same model) tells how much a rank needs (docs/running.md, \"Memory exhaustion\")";
  return os.str();
}

void require_address_space(MPI_Comm comm, double bytes, const std::string& what) {
  int ok = address_space_for(bytes) ? 1 : 0, all = 1, rank = 0;
  MPI_Allreduce(&ok, &all, 1, MPI_INT, MPI_MIN, comm);
  if (all) return;
  // The lowest rank without room names itself; every rank throws the same text.
  MPI_Comm_rank(comm, &rank);
  int mine = ok ? (1 << 30) : rank, first = 0;
  MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, comm);
  std::string msg = rank == first ? out_of_memory_message(what, bytes, rank) : std::string();
  int len = static_cast<int>(msg.size());
  MPI_Bcast(&len, 1, MPI_INT, first, comm);
  msg.resize(static_cast<size_t>(len));
  MPI_Bcast(msg.data(), len, MPI_CHAR, first, comm);
  throw MemoryError(msg);
}

}  // namespace alphaflex
