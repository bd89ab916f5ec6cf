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
  rd.keys(m, "modes", {"count", "below", "shift"});
  if (m["count"]) opt.count = rd.integer(m["count"], "modes.count", 1, 100000);
  if (m["below"]) opt.below = rd.positive(m["below"], "modes.below", "frequency (Hz)");
  if (m["shift"]) opt.shift = rd.non_negative(m["shift"], "modes.shift", "frequency (Hz)");
  return opt;
}

}  // namespace alphaflex
