#include "alphaflex/app/exit_agreement.hpp"

#include <algorithm>
#include <chrono>
#include <iostream>
#include <thread>
#include <vector>

#include "alphaflex/core/error.hpp"

namespace alphaflex {
namespace {

/// Every rank's code, or false if not every rank came within `timeout` seconds.
bool gather_codes(MPI_Comm comm, int code, double timeout, std::vector<int>& codes) {
  int size = 1;
  MPI_Comm_size(comm, &size);
  codes.assign(static_cast<size_t>(size), 0);
  MPI_Request req;
  MPI_Iallgather(&code, 1, MPI_INT, codes.data(), 1, MPI_INT, comm, &req);
  const auto start = std::chrono::steady_clock::now();
  for (int done = 0;;) {
    MPI_Test(&req, &done, MPI_STATUS_IGNORE);
    if (done) return true;
    if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > timeout) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

}  // namespace

int exit_code_of(const std::exception& e) {
  if (dynamic_cast<const InputError*>(&e)) return 1;
  if (dynamic_cast<const SolverError*>(&e)) return 3;
  if (dynamic_cast<const Interrupted*>(&e)) return 5;
  if (dynamic_cast<const OutputError*>(&e)) return 6;
  return 4;
}

void fail_together(MPI_Comm comm, int code, const std::string& message, double timeout) {
  if (comm == MPI_COMM_NULL) return;
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::vector<int> codes;
  const bool all_came = gather_codes(comm, code, timeout, codes);
  const bool all_failed = all_came && std::all_of(codes.begin(), codes.end(), [](int c) { return c != 0; });
  if (all_failed) return;
  std::cerr << "alphaflex: error on rank " << rank << " (the other ranks did not reach the same error; ending the job): "
            << message << std::endl;
  MPI_Abort(MPI_COMM_WORLD, code);
}

int end_run(MPI_Comm comm, int code, const std::string& message, double timeout) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  std::vector<int> codes;
  if (!gather_codes(comm, code, timeout, codes)) {
    // Another rank is stuck in a collective call: only aborting the job ends it.
    if (code != 0)
      std::cerr << "alphaflex: error on rank " << rank << " (the other ranks did not reach the same error; ending the job): "
                << message << std::endl;
    else
      std::cerr << "alphaflex: rank " << rank << " finished but another rank did not within " << timeout
                << " s; ending the job" << std::endl;
    MPI_Abort(MPI_COMM_WORLD, code != 0 ? code : 5);
  }
  int first = -1, worst = 0;
  for (int r = 0; r < size; ++r) {
    if (codes[static_cast<size_t>(r)] != 0 && first < 0) first = r;
    worst = std::max(worst, codes[static_cast<size_t>(r)]);
  }
  if (first == rank && code != 0) std::cerr << (code == 5 ? "alphaflex: " : "alphaflex: error: ") << message << std::endl;
  return worst;
}

}  // namespace alphaflex
