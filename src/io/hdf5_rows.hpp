#pragma once
// Private to the io module: the rows of an HDF5 dataset that one rank writes (its owned nodes,
// elements, joints, coordinates and multipliers, at their places in model order), and collective
// writes of them. Shared by the results writer and the checkpoints, so that both files have the
// same layout on any number of ranks.
#include <hdf5.h>

#include <string>
#include <vector>

#include "alphaflex/partition/subdomain.hpp"

#include "alphaflex/core/error.hpp"

namespace alphaflex::io_detail {

/// The same outcome of a file operation on every rank: an InputError with the first failing
/// rank's message, so that no rank goes on into a collective call alone.
inline void agree(const Subdomain& sub, const std::string& local_error) {
  const std::string error = sub.first_error(local_error);
  if (!error.empty()) throw InputError(error);
}

/// Rows of a dataset that this rank writes: intervals [start, start + count) of its first
/// dimension (sorted, disjoint), out of `total` rows.
struct Rows {
  std::vector<unsigned long long> start, count;
  unsigned long long total = 0, mine = 0;
  /// Appends rows [first, first + n); intervals that touch are merged.
  void add(unsigned long long first, unsigned long long n);
  /// All rows (on rank 0) or none (elsewhere): for data that rank 0 alone holds.
  static Rows all_on_root(unsigned long long total, bool root);
};

/// The rows of the state vectors in model order that this rank owns: q (configuration numbers),
/// v, q̈ and a (node unknowns), λ (multipliers). Local vectors hold them first, in this order.
struct StateRows {
  Rows conf, dof, mult;
  explicit StateRows(const Subdomain& sub);
};

/// Creates dataset `name` of `rows.total` × `cols` values in `loc` and writes this rank's rows
/// (`rows.mine` × `cols` values, in row order) with the transfer list `xfer`. Collective. Returns
/// an empty string, or what failed (the caller makes the ranks agree on it).
std::string write_rows(hid_t loc, const char* name, const Rows& rows, int cols, const double* data, hid_t xfer);
std::string write_int_rows(hid_t loc, const char* name, const Rows& rows, const int* data, hid_t xfer);
std::string write_long_rows(hid_t loc, const char* name, const Rows& rows, const long long* data, hid_t xfer);

/// The whole of a dataset as doubles / integers (every rank reads all of it); false if missing.
bool read_all(hid_t loc, const char* name, std::vector<double>& out);
bool read_all(hid_t loc, const char* name, std::vector<long long>& out);

/// A scalar attribute of an object (written by every rank with the same value: collective).
void write_attribute(hid_t loc, const char* name, double value);
void write_attribute(hid_t loc, const char* name, long long value);
void write_attribute(hid_t loc, const char* name, const std::string& value);
bool read_attribute(hid_t loc, const char* name, double& value);
bool read_attribute(hid_t loc, const char* name, long long& value);
bool read_attribute(hid_t loc, const char* name, std::string& value);

/// File access for `comm`: MPI-IO when it has more than one rank, HDF5's default otherwise.
hid_t file_access(MPI_Comm comm);
/// A transfer list: collective MPI-IO when `comm` has more than one rank.
hid_t transfer_list(MPI_Comm comm);

}  // namespace alphaflex::io_detail
