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
       input::Range::non_negative(), "frequency (Hz)"}}};
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
  return opt;
}

}  // namespace alphaflex
