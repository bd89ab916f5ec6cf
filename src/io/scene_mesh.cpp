// Beams from gmsh meshes (`mesh`, `beams`), spatial scenes only.
#include "scene_reader.hpp"

namespace alphaflex::scene_detail {

void read_mesh_and_beams(Reader& rd, const YAML::Node& root, Model&, const Eigen::Vector3d&) {
  for (const char* k : {"mesh", "beams"})
    if (root[k]) rd.fail(root[k], k, "reading beams from meshes is being wired in");
}

}  // namespace alphaflex::scene_detail
