// read_mesh: loads the gmsh reader module (gmsh_reader.cpp, built as libalphaflex_gmsh.so and
// linked against libgmsh) on the first call, so that only scenes with a mesh pay for loading
// gmsh and the ~70 libraries it pulls in (OpenCASCADE, FLTK, ...): loading them all at start-up
// was three quarters of the start-up CPU of every run (docs/performance.md, start-up;
// docs/architecture.md, mesh module).
#include <dlfcn.h>
#include <gmsh.h>  // GMSH_API_VERSION only: nothing of libgmsh is called from here
#include <sys/stat.h>

#include <cstdlib>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>

#include "alphaflex/core/error.hpp"
#include "alphaflex/core/memory.hpp"
#include "alphaflex/mesh/gmsh_reader.hpp"
#include "alphaflex/mesh/mesh_cache.hpp"

namespace alphaflex {

namespace {

using ReadMeshEntry = void (*)(const std::string&, const MeshOptions&, const std::string&, MeshData&);
using ReadSurfaceEntry = void (*)(const std::string&, const std::string&, SurfaceMesh&);

// The module is looked for where the build put it (ALPHAFLEX_GMSH_MODULE, set by CMakeLists.txt),
// unless ALPHAFLEX_GMSH_MODULE is set in the environment (a relocated build). Loaded once and kept
// until the process ends: gmsh keeps static state that must not be unloaded.
std::string module_path() {
  const char* env = std::getenv("ALPHAFLEX_GMSH_MODULE");
  return env && *env ? env : ALPHAFLEX_GMSH_MODULE;
}

/// What the meshes in the cache were read with: gmsh's API version and the reader module (its size
/// and modification time, so a rebuilt reader never takes an older one's meshes). Empty (no cache)
/// if the module cannot be found.
std::string reader_identity() {
  struct stat st {};
  const std::string path = module_path();
  if (::stat(path.c_str(), &st) != 0) return {};
  return std::string("gmsh ") + GMSH_API_VERSION + ", module " + path + " " + std::to_string(st.st_size) + " " +
         std::to_string(st.st_mtim.tv_sec) + "." + std::to_string(st.st_mtim.tv_nsec);
}

void* load_module() {
  static void* module = nullptr;
  static std::string failure;
  static std::once_flag once;
  std::call_once(once, [] {
    const std::string path = module_path();
    // RTLD_LAZY: gmsh's ~70 libraries bind their functions on first call, as they did when linked
    // to the executable; RTLD_NOW would resolve every PLT entry of OpenCASCADE and FLTK up front.
    module = dlopen(path.c_str(), RTLD_LAZY | RTLD_LOCAL);
    if (!module) failure = "cannot load the gmsh reader module: " + std::string(dlerror());
  });
  // The loader could not map the module's segments (gmsh's ~70 libraries): an address-space limit
  // (ulimit -v) too small for them, i.e. memory exhaustion (exit 3), not a bug.
  if (!module && (failure.find("failed to map segment") != std::string::npos ||
                  failure.find("Cannot allocate memory") != std::string::npos))
    throw MemoryError(out_of_memory_message("loading the gmsh module to read the mesh (" + failure + ")", 0.0));
  if (!module) throw std::runtime_error(failure);
  return module;
}

/// The module's function `name` (its entry points have C linkage).
template <class Entry>
Entry entry_point(const char* name) {
  void* f = dlsym(load_module(), name);
  if (!f) throw std::runtime_error(std::string("the gmsh reader module has no ") + name + ": " + dlerror());
  return reinterpret_cast<Entry>(f);
}

}  // namespace

MeshData read_mesh(const std::string& path, const MeshOptions& options, const std::string& context) {
  // A mesh read before with the same bytes and options comes from the cache: gmsh is not loaded
  // (docs/performance.md, start-up). Failures are never cached: a bad file goes to gmsh every time.
  const MeshCache cache = MeshCache::from_environment(reader_identity());
  const std::string key = cache.key(path, options);
  if (std::optional<MeshData> hit = cache.find(key, path)) return std::move(*hit);
  MeshData mesh;
  static const ReadMeshEntry entry = entry_point<ReadMeshEntry>("alphaflex_gmsh_read_mesh");
  entry(path, options, context, mesh);
  cache.store(key, mesh);
  return mesh;
}

SurfaceMesh read_surface_mesh(const std::string& path, const std::string& context) {
  SurfaceMesh surface;
  static const ReadSurfaceEntry entry = entry_point<ReadSurfaceEntry>("alphaflex_gmsh_read_surface");
  entry(path, context, surface);
  return surface;
}

}  // namespace alphaflex
