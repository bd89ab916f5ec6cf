#pragma once
// Memory of this process and of the machine (issue 24, defect 3): what a rank uses and may still
// use, and the one message of every memory exhaustion — what was being allocated, how much, and
// what to do. Linux: /proc/self/status, /proc/meminfo, getrlimit(RLIMIT_AS).
#include <mpi.h>

#include <string>

namespace alphaflex {

struct MemoryStatus {
  double resident_mb = 0.0;       ///< VmRSS of this process
  double peak_resident_mb = 0.0;  ///< VmHWM (getrusage's maxrss)
  double address_space_mb = 0.0;  ///< VmSize: what RLIMIT_AS counts
  double available_mb = -1.0;     ///< MemAvailable of /proc/meminfo (−1: unknown)
  double limit_mb = -1.0;         ///< RLIMIT_AS (ulimit -v) of this process (−1: unlimited)
  /// What this process may still allocate: the smaller of MemAvailable and the address space left
  /// under RLIMIT_AS (−1 if neither is known).
  double room_mb() const;
};

MemoryStatus memory_status();

/// True if `bytes` more of address space can be mapped now (a PROT_NONE mapping made and given back
/// at once: nothing is touched). Only an address-space limit (RLIMIT_AS) makes it fail; it cannot
/// see a cgroup limit, whose excess the kernel ends with the OOM killer instead.
bool address_space_for(double bytes);

/// The message of a memory exhaustion: "out of memory on rank R while WHAT: NEED (this rank: …
/// resident, … of address space under the limit …; the machine: … available)", then what to do.
/// `bytes` ≤ 0: the size is not known.
std::string out_of_memory_message(const std::string& what, double bytes, int rank = -1);

/// Collective over `comm`: if `bytes` of address space are not free on some rank (address_space_for),
/// every rank throws MemoryError(out_of_memory_message(what, bytes)) — before an allocation that
/// would fail in a library that cannot report it (PETSc's hash tables, OpenBLAS' workspace), and so
/// that no rank goes on into a collective call alone.
void require_address_space(MPI_Comm comm, double bytes, const std::string& what);

}  // namespace alphaflex
