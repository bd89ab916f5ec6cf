// `beam_output` and `shell_output` (spatial): a result field of one element of a beam or shell
// block (elements NAME[k], in mesh order).
#include "common.hpp"
#include "reduced_mesh_3d.hpp"

namespace alphaflex::scene_detail {
namespace {

void read_element_output(const Item& it, Sensor& sn, bool beam) {
  Reader& rd = it.rd;
  const char* block = beam ? "beam" : "shell";
  sn.kind = Sensor::Kind::ElementOutput;
  const std::string bn = it.keys.text(block);
  const int idx = it.keys.integer("element");
  if (read_reduced_element_output(it, sn, bn, idx)) return;  // recovered from the modes (a reduced beam or shell block)
  const std::string ename = bn + "[" + std::to_string(idx) + "]";
  const auto& elements = it.model.elements();
  for (size_t e = 0; e < elements.size(); ++e)
    if (elements[e]->name() == ename && !elements[e]->output_names().empty()) sn.element = static_cast<int>(e);
  if (sn.element < 0)
    rd.fail(it.node["element"], it.at("element"), std::string(block) + " '" + bn + "' has no element " + std::to_string(idx) +
                                                      (beam ? " (elements are numbered from 0 along the mesh)"
                                                            : " (elements are numbered from 0 in the mesh group's order)"));
  sn.component = rd.choice(it.keys.node("component"), it.at("component"), elements[static_cast<size_t>(sn.element)]->output_names());
}

}  // namespace

void register_element_output_3d(SceneTypes& t) {
  for (const bool beam : {true, false}) {
    const char* block = beam ? "beam" : "shell";
    t.sensors.add(std::string(block) + "_output", type_schema(std::string("sensors.3d.") + block + "_output",
                  std::string("`") + block + "_output`: a result of one element of a " + block + " block", {
        {block, KeyType::Text, "–", kRequired, std::string("the name of a `") + block + "s` block"},
        {"element", KeyType::Integer, "–", kRequired, beam ? "index from 0 along the mesh" : "index from 0 in the group's element order", Range::at_least(0)},
        {"component", KeyType::Text, "–", kRequired, beam ? "`N V2 V3 T M2 M3` (N, N·m) or `axial_strain shear_strain_2 shear_strain_3 twist curvature_2 curvature_3` (1, 1/m)"
                                                          : "a shell result: `n11 n22 n12` (N/m), `m11 m22 m12` (N·m/m), `q1 q2` (N/m), stresses (Pa)"}}),
        [beam](const Item& it, Sensor& sn) { read_element_output(it, sn, beam); });
  }
}

}  // namespace alphaflex::scene_detail
