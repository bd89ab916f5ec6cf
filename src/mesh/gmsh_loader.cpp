// read_mesh: loads the gmsh reader module (gmsh_reader.cpp, built as libalphaflex_gmsh.so and
// linked against libgmsh) on the first call, so that only scenes with a mesh pay for loading
// gmsh and the ~70 libraries it pulls in (OpenCASCADE, FLTK, ...): loading them all at start-up
// was three quarters of the start-up CPU of every run (docs/performance.md, start-up;
// docs/architecture.md, mesh module).
#include <dlfcn.h>

#include <cstdlib>
#include <mutex>
#include <stdexcept>
#include <string>

#include "alphaflex/mesh/gmsh_reader.hpp"

namespace alphaflex {

namespace {

using ReadMeshEntry = void (*)(const std::string&, const MeshOptions&, const std::string&, MeshData&);

// The module is looked for where the build put it (ALPHAFLEX_GMSH_MODULE, set by CMakeLists.txt),
// unless ALPHAFLEX_GMSH_MODULE is set in the environment (a relocated build). Loaded once and kept
// until the process ends: gmsh keeps static state that must not be unloaded.
ReadMeshEntry load_reader() {
  static ReadMeshEntry entry = nullptr;
  static std::string failure;
  static std::once_flag once;
  std::call_once(once, [] {
    const char* env = std::getenv("ALPHAFLEX_GMSH_MODULE");
    const std::string path = env && *env ? env : ALPHAFLEX_GMSH_MODULE;
    // RTLD_LAZY: gmsh's ~70 libraries bind their functions on first call, as they did when linked
    // to the executable; RTLD_NOW would resolve every PLT entry of OpenCASCADE and FLTK up front.
    void* handle = dlopen(path.c_str(), RTLD_LAZY | RTLD_LOCAL);
    if (!handle) {
      failure = "cannot load the gmsh reader module: " + std::string(dlerror());
      return;
    }
    entry = reinterpret_cast<ReadMeshEntry>(dlsym(handle, "alphaflex_gmsh_read_mesh"));
    if (!entry) failure = "the gmsh reader module " + path + " has no alphaflex_gmsh_read_mesh: " + dlerror();
  });
  if (!entry) throw std::runtime_error(failure);
  return entry;
}

}  // namespace

MeshData read_mesh(const std::string& path, const MeshOptions& options, const std::string& context) {
  MeshData mesh;
  load_reader()(path, options, context, mesh);
  return mesh;
}

}  // namespace alphaflex
