#pragma once
// Private to src/io: loads and sensors whose expressions name sensors (types/sensor_feedback_3d.cpp;
// elements/sensor_feedback.hpp, model/sensor_function.hpp). Forces are read before sensors, so
// what names sensors is recorded while the scene is read and completed once `sensors` is read.
#include "joint_coordinates.hpp"

namespace alphaflex::scene_detail {

/// Before the scene's items are read (io/scene.cpp): forgets what a previous read left.
void begin_sensor_feedback(const SceneBuilder& sb);
/// After `sensors` (io/scene.cpp): adds the pending motors, then the elements of the `expression`
/// and `integral` sensors, in list order (the element indices that sensors were given).
void resolve_sensor_feedback(SceneBuilder& sb);

/// A joint motor whose `key` (torque or force) names sensors: recorded, its element added by
/// resolve_sensor_feedback. False, with nothing done, if the expression names none.
bool read_feedback_motor(const Item& it, const JointCoordinateNode& psi, const char* key);
/// The element index a pending feedback motor named `name` will have (−1: none of that name);
/// for `force_output` sensors, read after the forces and before the motor exists.
int pending_motor_element(const Item& it, const std::string& name);

}  // namespace alphaflex::scene_detail
