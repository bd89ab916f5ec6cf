#pragma once
// The superelements of a scene's reduced blocks kept beside its results (issue 19; docs/results.md,
// "Superelements"): OUTDIR/NAME.superelements.h5. Reducing a block — its Craig–Bampton basis
// (SLEPc), its inertia invariants, with `geometric_stiffness` the T and Q tensors by differences of
// the block's own nonlinear elements — costs 0.7–1.6 s of CPU on a 10³-unknown link, more than the
// run; it depends only on the block (its elements, nodes and frames, sections and materials) and
// the `reduction` keys. So a reduced block (modal/superelement.hpp, ReducedBlock: everything the
// reduced body and the rebuilt mesh need) is stored once under a key of all that, and a later run
// with the same key reads it: the same bits, so the same results to the last bit.
//
// The file: one group per block, in it one group per key (its digest), each field of ReducedBlock a
// dataset with Fletcher32 checksums and the metadata in HDF5's checksummed format (as the
// checkpoints, io/checkpoint.hpp). Up to kEntriesPerBlock keys of a block are kept, the newest
// first, so that the rungs of a study (2, 4, 8 … modes of one block) share one file. A file that
// cannot be read (cut off, a flipped byte) costs a recomputation and a warning naming it, never the
// run. Written by rank 0 under a temporary name and renamed (mesh/mesh_cache.hpp's pattern):
// a concurrent run never sees a partial file. Under MPI rank 0 reads and sends the entry to the
// others, so every rank builds the same body from the same bits (as when every rank reduces).
#include <mpi.h>

#include <functional>
#include <string>
#include <vector>

#include "alphaflex/modal/superelement.hpp"

namespace alphaflex {

class Model;

/// What a reduced block depends on: `settings` (text: the block's scene keys, its reduction keys,
/// its interface points), the scratch model's nodes (kinds, initial poses: coordinates and frames),
/// its elements (types, names, nodes), the block's linear K and M (they carry every section and
/// material constant, also ones given through parameters or --set), the cache's format version and
/// the layout of ReducedBlock. Its digest (128 bits) names the entry; the text is stored with it and
/// compared in full.
class SuperelementKey {
 public:
  SuperelementKey(const std::string& settings, const Model& scratch, const std::vector<int>& elements, const BlockMatrices& block);
  const std::string& digest() const { return digest_; }  ///< 32 hexadecimal digits
  const std::string& text() const { return text_; }
  size_t nodes() const { return nodes_; }                ///< the block's nodes (a read entry must have as many points)

 private:
  std::string text_, digest_;
  size_t nodes_ = 0;
};

class SuperelementCache {
 public:
  static constexpr int kEntriesPerBlock = 8;
  /// The cache in the file `path` ("": off: every block is reduced), on the ranks of `comm`.
  SuperelementCache(std::string path, MPI_Comm comm);
  bool enabled() const { return !path_.empty(); }
  const std::string& path() const { return path_; }

  /// The reduced block `block` of key `key`: read from the file (rank 0, sent to all), else
  /// `reduce()` (on every rank, as without a cache; its exceptions pass through), kept for
  /// finish(). Collective over the communicator.
  ReducedBlock find_or_reduce(const std::string& block, const SuperelementKey& key, const std::function<ReducedBlock()>& reduce);
  /// Writes the file if a block was reduced (rank 0; temporary file and rename), with the entries of
  /// this run and up to kEntriesPerBlock − 1 older keys of each block. Best effort: a file that
  /// cannot be written is a warning (the next run reduces again).
  void finish();

  /// Per block, where its superelement came from ("rod: read from F", "rod: computed in 1.2 s CPU,
  /// written to F"), for the run's summary.
  const std::vector<std::string>& notes() const { return notes_; }
  /// Files that could not be read or written, named.
  const std::vector<std::string>& warnings() const { return warnings_; }

 private:
  struct Entry {
    std::string block, digest, text;
    ReducedBlock rb;
  };
  std::string path_;
  MPI_Comm comm_;
  int rank_ = 0;
  std::vector<Entry> computed_;
  std::vector<std::pair<std::string, std::string>> read_;  // (block, digest) read in this run
  std::vector<std::string> notes_, warnings_;
};

/// The cache's byte form of a ReducedBlock and back (what rank 0 sends; tests): every field of the
/// block. `unpack` throws std::invalid_argument if the bytes are not one.
std::string pack_reduced_block(const ReducedBlock& rb);
ReducedBlock unpack_reduced_block(const std::string& bytes);

}  // namespace alphaflex
