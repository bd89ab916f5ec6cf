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

/// The same outcome of a file operation on every rank: an `Error` (OutputError for what is
/// written, InputError for a file the user gave) with the first failing rank's message, so that no
/// rank goes on into a collective call alone.
template <class Error>
void agree(const Subdomain& sub, const std::string& local_error) {
  const std::string error = sub.first_error(local_error);
  if (!error.empty()) throw Error(error);
}

/// The HDF5 calls on one file, every one checked (HDF5's own error stack is not printed: from the
/// first H5Calls on, the process reports HDF5 failures through these messages only): each call's status (hid_t or herr_t, < 0 if it
/// failed) goes through operator(), which keeps the first failure as "cannot OPERATION: FILE" with
/// errno's text when the call left one (a full or vanished file system). The caller makes the
/// ranks agree on error() (collective calls fail on every rank or must be agreed on).
class H5Calls {
 public:
  explicit H5Calls(std::string file);
  template <class Status>
  Status operator()(Status status, const std::string& operation) {
    if (status < 0 || injected_disk_full()) fail(operation);
    clear_errno();
    return status;
  }
  /// Records a failure that is not an HDF5 status (e.g. a rename).
  void fail(const std::string& operation);
  const std::string& error() const { return error_; }
  const std::string& file() const { return file_; }
  /// The group that dataset operations are in, for messages ("/step_000003").
  std::string group;

 private:
  static void clear_errno();
  static bool injected_disk_full();
  std::string file_, error_;
};

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
/// (`rows.mine` × `cols` values, in row order) with the transfer list `xfer`. Collective. A failed
/// call is recorded in `h5` (the caller makes the ranks agree on it).
/// With `checksum`, the dataset is chunked with HDF5's Fletcher32 filter: a read of it fails
/// if a byte changed since it was written (checkpoints).
void write_rows(H5Calls& h5, hid_t loc, const char* name, const Rows& rows, int cols, const double* data, hid_t xfer,
                bool checksum = false);
void write_int_rows(H5Calls& h5, hid_t loc, const char* name, const Rows& rows, const int* data, hid_t xfer);
void write_long_rows(H5Calls& h5, hid_t loc, const char* name, const Rows& rows, const long long* data, hid_t xfer,
                     bool checksum = false);

/// The whole of a dataset as doubles / integers (every rank reads all of it); false if missing or
/// unreadable.
bool read_all(hid_t loc, const char* name, std::vector<double>& out);
bool read_all(hid_t loc, const char* name, std::vector<long long>& out);
/// The whole of dataset `where`/`name`, which must hold `expected` values: checked before anything
/// is allocated (a flipped byte in a dimension must not ask for 10^12 values). Empty, or what is
/// wrong, naming the dataset: missing, of another size, or unreadable (its checksum does not match).
std::string read_expected(hid_t loc, const std::string& where, const char* name, size_t expected, std::vector<double>& out);
std::string read_expected(hid_t loc, const std::string& where, const char* name, size_t expected, std::vector<long long>& out);

/// A scalar attribute of an object (written by every rank with the same value: collective).
void write_attribute(H5Calls& h5, hid_t loc, const char* name, double value);
void write_attribute(H5Calls& h5, hid_t loc, const char* name, long long value);
void write_attribute(H5Calls& h5, hid_t loc, const char* name, const std::string& value);
/// An attribute of an array of one double (the layout of the results' step times).
void write_attribute_array(H5Calls& h5, hid_t loc, const char* name, double value);
/// False if the attribute is missing or unreadable.
bool read_attribute(hid_t loc, const char* name, double& value);
bool read_attribute(hid_t loc, const char* name, long long& value);
bool read_attribute(hid_t loc, const char* name, std::string& value);

/// Closes a file after a failed write without a second failure. HDF5 writes the file's metadata
/// when it closes it; on a full disk that write fails too (cutting the file first does not help:
/// the metadata of a part with many steps is most of its size), which leaves the file half-closed
/// in HDF5's tables, and HDF5 closes it again when MPI_Finalize ends the library — and crashes
/// (issue 24, defect 1). So this process's descriptors of `path` are first replaced by an anonymous
/// memory file (memfd_create; the data goes nowhere), then the objects left open in the file and
/// the file are closed. Collective for a file opened with MPI-IO. The caller removes the file.
/// Errors are ignored: the write has failed already, and its message is the one to report.
void discard_file(hid_t file, const std::string& path);

/// Whether the file system of `path` (a file open in HDF5 as `file`) has room for what HDF5 holds
/// for it in memory (its end of allocation beyond the blocks on disk: metadata is written when the
/// file is flushed or closed) and `more` bytes: empty, or the OutputError's text for `operation`.
/// Why ask before writing: with MPI-IO, HDF5 writes a file's metadata in collective steps, and a
/// write that fails on one rank in the middle of them leaves the ranks in different collective
/// calls (a hang, seen on a full tmpfs); a failure found here is agreed on before any of them.
/// Another process can still fill the disk in between: then the write fails as before.
std::string room_for(const std::string& path, hid_t file, unsigned long long more, const std::string& operation);

/// File access for `comm`: MPI-IO when it has more than one rank, HDF5's default otherwise.
hid_t file_access(H5Calls& h5, MPI_Comm comm);
/// A transfer list: collective MPI-IO when `comm` has more than one rank.
hid_t transfer_list(H5Calls& h5, MPI_Comm comm);

}  // namespace alphaflex::io_detail
