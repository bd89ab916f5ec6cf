#include "alphaflex/io/scene_modes.hpp"

#include <fstream>
#include <iterator>

#include "alphaflex/io/scene.hpp"
#include "scene_reader.hpp"

namespace alphaflex {

const input::Schema& scene_detail::modes_schema() {
  static const input::Schema s{"modes", {
      {"count", input::KeyType::Integer, "–", "10, or every degree of freedom if fewer",
       "how many modes: the lowest ones, or the nearest `shift`; at most the degrees of freedom (coordinates − joint equations), else exit 1 naming both numbers. Rigid-body modes count as modes",
       input::Range::closed(1, 100000)},
      {"below", input::KeyType::Number, "Hz", "none",
       "if given: report only the modes whose (natural) frequency is below it; a warning says when all `count` modes are below (there may be more: raise `count`)",
       input::Range::positive(), "frequency (Hz)"},
      {"shift", input::KeyType::Number, "Hz", "none (the lowest modes)",
       "the frequency the modes are sought around (shift-and-invert at ω² = (2π·shift)²); undamped problems only: a damped or gyroscopic scene (C ≠ 0) refuses it",
       input::Range::non_negative(), "frequency (Hz)"},
      {"rotating_frame", input::KeyType::Text, "–", "none (inertial frame)",
       "linearize in the reference frame turning with the first body of this joint (3D spatial joint, e.g. a driven revolute at a hub) at the state's angular velocity of that body relative to the second (rad/s): Coriolis 2MΩ̂ and centrifugal softening MΩ̂Ω̂ = −Ω²M_⊥ on the translations, the tension of the state in K (docs/theory/modes.md). For a structure turning as a whole in steady rotation (a checkpoint of a spin-up: `--restart`); the frequencies are those seen in the rotating frame. Not a joint of the scene: exit 1",
       {}, "", "joint name"},
      {"campbell", input::KeyType::Map, "–", "none",
       "a Campbell diagram instead of one analysis (keys: `modes.campbell`): at each speed the steady rotation is constructed directly (Newton on the relative equilibrium, docs/modes.md) from the state chosen as above, and its `count` lowest modes are computed in the rotating frame. Writes OUTDIR/NAME_campbell.csv (`speed_rad_s, speed_hz, mode, kind, frequency_hz, natural_frequency_hz, damping_ratio, whirl, dominant_part`) and the chart NAME_campbell.png (scripts/campbell_plot.py); no mode shapes. Not with `shift`"}}};
  return s;
}

/// modes.campbell: the driver joint and the speeds of the diagram.
const input::Schema& scene_detail::campbell_schema() {
  static const input::Schema s{"modes.campbell", {
      {"driver", input::KeyType::Text, "–", input::kRequired,
       "name of a revolute joint: the structure turns about its axis (a3 of its first marker, through that marker's point)",
       {}, "", "joint name"},
      {"speeds", input::KeyType::List, "rad/s", input::kRequired,
       "the speeds of the diagram, a non-empty list of numbers ≥ 0", {}, "", "[Ω1, Ω2, ...]"}}};
  return s;
}

ModalOptions read_modal_options(const std::string& path, const std::vector<std::string>& overrides, MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::string text;
  if (rank == 0) {
    std::ifstream in(path, std::ios::binary);
    text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  text = broadcast_text(text, comm);
  // read_scene has read the same file before and reported what is wrong with it as a scene.
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw InputError(path + ":" + std::to_string(e.mark.line + 1) + ": not valid YAML: " + e.msg);
  }
  // The same overrides as read_scene's, through the same function (read_scene accepted them).
  scene_detail::Reader rd(path);
  for (const std::string& o : overrides) rd.add_override(input::apply_override(root, o, "--set", path), o);
  rd.read_parameters(root["parameters"]);
  ModalOptions opt;
  const input::Section m(rd, root["modes"], "modes", scene_detail::modes_schema());
  opt.count = m.integer("count", opt.count);
  if (m.has("below")) opt.below = m.number("below");
  if (m.has("shift")) opt.shift = m.number("shift");
  if (m.has("rotating_frame")) opt.rotating_frame = m.text("rotating_frame");
  if (m.has("campbell")) {
    const input::Section c(rd, m.node("campbell"), m.key_path("campbell"), scene_detail::campbell_schema());
    opt.campbell_driver = c.text("driver");
    const YAML::Node sp = c.node("speeds");
    if (!sp.IsSequence() || sp.size() == 0)
      rd.fail(sp, c.key_path("speeds"), "expected a list of speeds (rad/s), e.g. [0, 50, 100]");
    for (size_t i = 0; i < sp.size(); ++i)
      opt.campbell_speeds.push_back(
          rd.non_negative(sp[i], c.key_path("speeds") + "[" + std::to_string(i) + "]", "speed (rad/s)"));
    if (opt.shift > 0.0) rd.fail(m.node("shift"), "modes.shift", "not with modes.campbell (the rotating frame's problem is gyroscopic)");
  }
  return opt;
}

}  // namespace alphaflex
