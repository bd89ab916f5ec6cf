// Every type a scene can name, registered in the manner of PETSc's TSRegisterAll: each line below
// names a file of this folder, FILE.cpp, whose function `void register_FILE(SceneTypes&)` adds the
// name, schema and constructor of its type (or small family of types) to the registries of its
// dimension. A new type is a new file and one line here (docs/architecture.md, worked example).
// The order of the lines is the order of the registries' "expected one of …" messages.
//
// An explicit list rather than self-registration by static objects: the types live in a static
// library, whose linker drops objects that nothing references.
#include "common.hpp"

#define ALPHAFLEX_PLANAR_TYPES(X) \
  X(rigid_body_2d)                \
  X(particles_2d)                 \
  X(revolute_2d)                  \
  X(fixed_2d)                     \
  X(line_joints_2d)               \
  X(spring_damper_2d)             \
  X(applied_loads_2d)             \
  X(angle_sensors_2d)             \
  X(point_sensors_2d)             \
  X(joint_reaction_2d)            \
  X(beams_2d)

#define ALPHAFLEX_SPATIAL_TYPES(X) \
  X(rigid_body_3d)                 \
  X(spatial_joints_3d)             \
  X(point_loads_3d)                \
  X(pressure_3d)                   \
  X(edge_load_3d)                  \
  X(point_sensors_3d)              \
  X(body_rotation_3d)              \
  X(joint_reaction_3d)             \
  X(element_output_3d)             \
  X(beams_3d)                      \
  X(shells_3d)

namespace alphaflex::scene_detail {

#define ALPHAFLEX_DECLARE(file) void register_##file(SceneTypes&);
ALPHAFLEX_PLANAR_TYPES(ALPHAFLEX_DECLARE)
ALPHAFLEX_SPATIAL_TYPES(ALPHAFLEX_DECLARE)
#undef ALPHAFLEX_DECLARE

#define ALPHAFLEX_REGISTER(file) register_##file(t);

const SceneTypes& planar_types() {
  static const SceneTypes t = [] {
    SceneTypes t{{"body type", ""}, {"joint type", ""}, {"force type", ""}, {"sensor type", ""}, {"block", ""}, "", {}};
    ALPHAFLEX_PLANAR_TYPES(ALPHAFLEX_REGISTER)
    return t;
  }();
  return t;
}

const SceneTypes& spatial_types() {
  static const SceneTypes t = [] {
    SceneTypes t{{"body type", " for dimension 3"}, {"joint type", ""}, {"load type", " for dimension 3"},
                 {"sensor type", " for dimension 3"}, {"block", " for dimension 3"}, "; beams come from `beams`", {}};
    ALPHAFLEX_SPATIAL_TYPES(ALPHAFLEX_REGISTER)
    return t;
  }();
  return t;
}

#undef ALPHAFLEX_REGISTER

}  // namespace alphaflex::scene_detail
