// Every type a scene can name, registered in the manner of PETSc's TSRegisterAll: each line below
// names a function `void register_NAME(SceneTypes&)`, defined in the file of this folder that
// reads the type (NAME.cpp; joint_reaction.cpp holds both dimensions' joint_reaction), which adds
// the name, schema and constructor of its type (or small family of types) to the registries of
// its dimension; the list declares the functions itself. A new type is a new file and one line here (docs/architecture.md, worked example).
// The order of the lines is the order of the registries' "expected one of …" messages; every line
// ends with a backslash, so a line added anywhere (last too) is the only line changed.
//
// An explicit list rather than self-registration by static objects: the types live in a static
// library, whose linker drops objects that nothing references.
#include "common.hpp"

#define ALPHAFLEX_PLANAR_TYPES(X) \
  X(register_rigid_body_2d)       \
  X(register_particles_2d)        \
  X(register_revolute_2d)         \
  X(register_fixed_2d)            \
  X(register_line_joints_2d)      \
  X(register_spring_damper_2d)    \
  X(register_applied_loads_2d)    \
  X(register_angle_sensors_2d)    \
  X(register_point_sensors_2d)    \
  X(register_joint_reaction_2d)   \
  X(register_beams_2d)            \
  X(register_force_elements_2d)   \
  X(register_energy_sensors_2d)   \
  /* end of the planar types */

#define ALPHAFLEX_SPATIAL_TYPES(X) \
  X(register_rigid_body_3d)        \
  X(register_spatial_joints_3d)    \
  X(register_point_loads_3d)       \
  X(register_pressure_3d)          \
  X(register_edge_load_3d)         \
  X(register_point_sensors_3d)     \
  X(register_body_rotation_3d)     \
  X(register_joint_reaction_3d)    \
  X(register_element_output_3d)    \
  X(register_beams_3d)             \
  X(register_shells_3d)            \
  X(register_force_elements_3d)    \
  X(register_joint_stops_3d)       \
  X(register_sensor_feedback_3d)   \
  X(register_energy_sensors_3d)    \
  /* end of the spatial types */

namespace alphaflex::scene_detail {

#define ALPHAFLEX_DECLARE(function) void function(SceneTypes&);
ALPHAFLEX_PLANAR_TYPES(ALPHAFLEX_DECLARE)
ALPHAFLEX_SPATIAL_TYPES(ALPHAFLEX_DECLARE)
#undef ALPHAFLEX_DECLARE

#define ALPHAFLEX_REGISTER(function) function(t);

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
