#include "alphaflex/io/scene_modes.hpp"

#include <fstream>
#include <iterator>

#include "alphaflex/io/scene.hpp"
#include "scene_reader.hpp"

namespace alphaflex {

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
  scene_detail::Reader rd(path);
  for (const std::string& o : overrides) {
    const size_t eq = o.find('='), dot = o.find('.');
    if (eq == std::string::npos || dot == std::string::npos || dot > eq) continue;
    const std::string section = o.substr(0, dot), key = o.substr(dot + 1, eq - dot - 1);
    if ((section != "modes" && section != "parameters") || key.find('.') != std::string::npos) continue;
    if (!root[section]) root[section] = YAML::Node(YAML::NodeType::Map);
    YAML::Node section_node = root[section];
    section_node[key] = YAML::Load(o.substr(eq + 1));
    rd.add_override(section_node[key], o);
  }
  rd.read_parameters(root["parameters"]);
  ModalOptions opt;
  const YAML::Node m = root["modes"];
  if (!m) return opt;
  rd.keys(m, "modes", {"count", "below", "shift", "rotating_frame", "campbell"});
  if (m["count"]) opt.count = rd.integer(m["count"], "modes.count", 1, 100000);
  if (m["below"]) opt.below = rd.positive(m["below"], "modes.below", "frequency (Hz)");
  if (m["shift"]) opt.shift = rd.non_negative(m["shift"], "modes.shift", "frequency (Hz)");
  if (m["rotating_frame"]) opt.rotating_frame = rd.text(m["rotating_frame"], "modes.rotating_frame");
  if (const YAML::Node c = m["campbell"]) {
    rd.keys(c, "modes.campbell", {"driver", "speeds"});
    opt.campbell_driver = rd.text(rd.need(c, "driver", "modes.campbell"), "modes.campbell.driver");
    const YAML::Node sp = rd.need(c, "speeds", "modes.campbell");
    if (!sp.IsSequence() || sp.size() == 0)
      rd.fail(sp, "modes.campbell.speeds", "expected a list of speeds (rad/s), e.g. [0, 50, 100]");
    for (size_t i = 0; i < sp.size(); ++i)
      opt.campbell_speeds.push_back(
          rd.non_negative(sp[i], "modes.campbell.speeds[" + std::to_string(i) + "]", "speed (rad/s)"));
    if (opt.shift > 0.0) rd.fail(m["shift"], "modes.shift", "not with modes.campbell (the rotating frame's problem is gyroscopic)");
  }
  return opt;
}

}  // namespace alphaflex
