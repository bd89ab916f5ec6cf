#pragma once
// Meshes read before, kept by content (docs/performance.md, "Start-up of a small run"). Reading a
// mesh loads the gmsh module and its ~70 libraries: on a 10-element beam that is ~0.3 s of CPU in
// the dynamic loader (perf: do_lookup_x), against ~1 ms of meshing. A .geo meshed (or a .msh read)
// with the same bytes, the same MeshOptions, the same gmsh version and the same reader module gives
// the same MeshData, so a later run takes it from here and does not load gmsh at all.
#include <filesystem>
#include <optional>
#include <string>

#include "alphaflex/mesh/gmsh_reader.hpp"

namespace alphaflex {

class MeshCache {
 public:
  /// The cache directory from the environment: $ALPHAFLEX_MESH_CACHE (a directory; "off" or "0"
  /// turns the cache off), else $XDG_CACHE_HOME/alphaflex/meshes, else $HOME/.cache/alphaflex/meshes;
  /// off if none of them is set. `reader` identifies what produced the meshes (gmsh version, reader
  /// module): an entry made by another reader is never used.
  static MeshCache from_environment(const std::string& reader);
  MeshCache(std::filesystem::path dir, std::string reader);

  bool enabled() const { return !dir_.empty(); }
  /// Everything a read of `path` with `options` depends on: the reader, the extension, the options
  /// and the file's bytes. Empty (not cached) if the cache is off, the file cannot be read, is larger
  /// than 4 MB, or is a .geo that may read other files or its environment (Include, Merge,
  /// ShapeFromFile, GetEnv, SystemCall, ...: its bytes alone do not determine the mesh).
  std::string key(const std::string& path, const MeshOptions& options) const;
  /// The mesh stored under `key`, its `file` set to `path`; nothing if absent or unreadable.
  std::optional<MeshData> find(const std::string& key, const std::string& path) const;
  /// Stores `mesh` under `key` (write to a temporary file, then rename: concurrent runs never see a
  /// partial entry). Best effort: a directory that cannot be written only costs the next run a read.
  void store(const std::string& key, const MeshData& mesh) const;
  /// The file an entry of `key` lives in (its name is a hash of the key; the key itself is stored in
  /// the file and compared in full on every look-up, so a hash collision is a miss, never a wrong mesh).
  std::filesystem::path entry_path(const std::string& key) const;

 private:
  std::filesystem::path dir_;
  std::string reader_;
};

}  // namespace alphaflex
