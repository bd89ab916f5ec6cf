#include "xdmf_index.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "alphaflex/core/fault_injection.hpp"

namespace alphaflex::io_detail {

XdmfIndex::XdmfIndex(std::string path, std::string parts_name, size_t nodes, size_t joints,
                     const std::vector<ElementGrid>& grids, const NodeLayout& layout)
    : path_(std::move(path)), parts_name_(std::move(parts_name)), nodes_(nodes), joints_(joints), grids_(grids),
      layout_(layout) {}

namespace {

/// "cannot OPERATION: FILE (errno's text)".
std::string write_failure(const std::string& operation, const std::string& file) {
  std::string e = "cannot " + operation + ": " + file;
  if (errno != 0) e += std::string(" (") + std::strerror(errno) + ")";
  return e;
}

/// XDMF's attribute type of a field of `components` values per cell.
const char* attribute_type(int components) { return components == 1 ? "Scalar" : components == 3 ? "Vector" : "Matrix"; }

}  // namespace

std::string XdmfIndex::write(const std::vector<OutputStep>& steps) const {
  const size_t nn = nodes_, nj = joints_;
  // Every step refers to its own part: the part's topology and the step's group.
  auto in_part = [&](size_t s) { return parts_name_ + "/" + part_file(steps[s].part); };
  const std::string tmp = path_ + ".tmp";
  errno = 0;
  std::ofstream x(tmp);
  x.precision(17);
  x << "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n<Xdmf Version=\"2.0\">\n <Domain>\n";
  auto item = [&](size_t s, const std::string& set, size_t rows, int cols) {
    x << "      <DataItem Dimensions=\"" << rows;
    if (cols > 1) x << " " << cols;
    x << "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" << in_part(s) << ":/" << steps[s].group << "/" << set
      << "</DataItem>\n";
  };
  auto grid = [&](const char* name, size_t n, const char* topo, const char* geom,
                  std::initializer_list<std::pair<const char*, const char*>> attrs) {
    x << "  <Grid Name=\"" << name << "\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
    for (size_t s = 0; s < steps.size(); ++s) {
      x << "   <Grid Name=\"" << name << "\" GridType=\"Uniform\">\n    <Time Value=\"" << steps[s].time << "\"/>\n"
        << "    <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" << n << "\" NodesPerElement=\"1\">\n"
        << "      <DataItem Dimensions=\"" << n << "\" NumberType=\"Int\" Precision=\"4\" Format=\"HDF\">" << in_part(s)
        << ":/topology/" << topo << "</DataItem>\n    </Topology>\n    <Geometry GeometryType=\"XYZ\">\n";
      item(s, geom, n, 3);
      x << "    </Geometry>\n";
      for (const auto& [aname, set] : attrs) {
        const std::string name = set;
        auto ends = [&](const std::string& tail) {
          return name.size() >= tail.size() && name.compare(name.size() - tail.size(), tail.size(), tail) == 0;
        };
        const bool scalar = ends("_angle"), quaternion = ends("_quaternion");
        x << "    <Attribute Name=\"" << aname << "\" AttributeType=\""
          << (scalar ? "Scalar" : quaternion ? "Matrix" : "Vector") << "\" Center=\"Node\">\n";
        item(s, set, n, scalar ? 1 : quaternion ? 4 : 3);
        x << "    </Attribute>\n";
      }
      x << "   </Grid>\n";
    }
    x << "  </Grid>\n";
  };
  // Bodies only (results_layout.hpp): the node datasets when every node is a body, else the body
  // datasets; no grid when the model has no body.
  if (layout_.all_bodies())
    grid("bodies", nn, "nodes", "node_position",
         {{"displacement", "node_displacement"}, {"velocity", "node_velocity"}, {"acceleration", "node_acceleration"},
          {"angle", "node_angle"}, {"axis", "node_axis"}, {"axis2", "node_axis2"}, {"axis3", "node_axis3"},
          {"quaternion", "node_quaternion"}});
  else if (!layout_.bodies.empty())
    grid("bodies", layout_.bodies.size(), "bodies", "body_position",
         {{"displacement", "body_displacement"}, {"velocity", "body_velocity"}, {"acceleration", "body_acceleration"},
          {"angle", "body_angle"}, {"axis", "body_axis"}, {"axis2", "body_axis2"}, {"axis3", "body_axis3"},
          {"quaternion", "body_quaternion"}});
  if (!layout_.links.empty()) {
    // The links of the bodies: a polyline body 1 → joint → body 2 per joint (link_points).
    const size_t nl = layout_.links.size();
    x << "  <Grid Name=\"links\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
    for (size_t s = 0; s < steps.size(); ++s) {
      x << "   <Grid Name=\"links\" GridType=\"Uniform\">\n    <Time Value=\"" << steps[s].time << "\"/>\n"
        << "    <Topology TopologyType=\"Polyline\" NumberOfElements=\"" << nl << "\" NodesPerElement=\"3\">\n"
        << "      <DataItem Dimensions=\"" << nl << " 3\" NumberType=\"Int\" Precision=\"4\" Format=\"HDF\">" << in_part(s)
        << ":/topology/links</DataItem>\n    </Topology>\n    <Geometry GeometryType=\"XYZ\">\n";
      item(s, "link_points", 3 * nl, 3);
      x << "    </Geometry>\n   </Grid>\n";
    }
    x << "  </Grid>\n";
  }
  if (layout_.shapes.faces() > 0) {
    // The bodies' shapes (results_shapes.hpp): one surface of triangles and quadrilaterals whose
    // points move with their bodies.
    const ShapeLayout& sh = layout_.shapes;
    x << "  <Grid Name=\"shapes\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
    for (size_t s = 0; s < steps.size(); ++s) {
      x << "   <Grid Name=\"shapes\" GridType=\"Uniform\">\n    <Time Value=\"" << steps[s].time << "\"/>\n"
        << "    <Topology TopologyType=\"Mixed\" NumberOfElements=\"" << sh.faces() << "\">\n"
        << "      <DataItem Dimensions=\"" << sh.connectivity_size() << "\" NumberType=\"Int\" Precision=\"4\" Format=\"HDF\">"
        << in_part(s) << ":/topology/shapes</DataItem>\n    </Topology>\n    <Geometry GeometryType=\"XYZ\">\n";
      item(s, "shape_points", sh.points(), 3);
      x << "    </Geometry>\n";
      for (const char* f : {"displacement", "velocity"}) {
        x << "    <Attribute Name=\"" << f << "\" AttributeType=\"Vector\" Center=\"Node\">\n";
        item(s, std::string("shape_") + f, sh.points(), 3);
        x << "    </Attribute>\n";
      }
      x << "   </Grid>\n";
    }
    x << "  </Grid>\n";
  }
  // The reduced bodies' meshes rebuilt from their frames and modes (results_reduced.hpp), one grid
  // per kind, drawn like a beam or shell block: points, node data, the elements' results as cell
  // data; each body's modal coordinates as grid data of its kind's grid (ParaView: field data
  // `modal_coordinates_NAME`), a hyperslab of the step's modal_coordinates (start, stride, count of
  // the 1-D dataset of Σm values over all bodies).
  const ReducedLayout& rl = layout_.reduced;
  for (const ReducedGrid& r : rl.grids) {
    const std::string name = r.grid();
    x << "  <Grid Name=\"" << name << "\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
    for (size_t s = 0; s < steps.size(); ++s) {
      x << "   <Grid Name=\"" << name << "\" GridType=\"Uniform\">\n    <Time Value=\"" << steps[s].time << "\"/>\n";
      if (r.lines)
        x << "    <Topology TopologyType=\"Polyline\" NumberOfElements=\"" << r.cells() << "\" NodesPerElement=\"2\">\n"
          << "      <DataItem Dimensions=\"" << r.cells() << " 2\" NumberType=\"Int\" Precision=\"4\" Format=\"HDF\">";
      else
        x << "    <Topology TopologyType=\"Mixed\" NumberOfElements=\"" << r.cells() << "\">\n"
          << "      <DataItem Dimensions=\"" << r.connectivity_size() << "\" NumberType=\"Int\" Precision=\"4\" Format=\"HDF\">";
      x << in_part(s) << ":/topology/reduced_" << r.structure << "_connectivity</DataItem>\n    </Topology>\n"
        << "    <Geometry GeometryType=\"XYZ\">\n";
      item(s, r.dataset("points"), r.points(), 3);
      x << "    </Geometry>\n";
      for (const char* v : {"displacement", "velocity", "axis2", "axis3"}) {
        x << "    <Attribute Name=\"" << v << "\" AttributeType=\"Vector\" Center=\"Node\">\n";
        item(s, r.dataset(v), r.points(), 3);
        x << "    </Attribute>\n";
      }
      x << "    <Attribute Name=\"quaternion\" AttributeType=\"Matrix\" Center=\"Node\">\n";
      item(s, r.dataset("quaternion"), r.points(), 4);
      x << "    </Attribute>\n";
      for (const CellField& f : r.fields) {
        x << "    <Attribute Name=\"" << f.name << "\" AttributeType=\"" << attribute_type(f.components) << "\" Center=\"Cell\">\n";
        item(s, r.dataset(f.name), r.cells(), f.components);
        x << "    </Attribute>\n";
      }
      for (size_t b : r.bodies) {
        const unsigned long long first = rl.modal_offset[b], m = rl.modal_offset[b + 1] - first;
        if (m == 0) continue;
        x << "    <Attribute Name=\"modal_coordinates_" << rl.names[b] << "\" AttributeType=\"Scalar\" Center=\"Grid\">\n"
          << "     <DataItem ItemType=\"HyperSlab\" Dimensions=\"" << m << "\" Type=\"HyperSlab\">\n"
          << "      <DataItem Dimensions=\"3 1\" Format=\"XML\">" << first << " 1 " << m << "</DataItem>\n"
          << "      <DataItem Dimensions=\"" << rl.modes() << "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" << in_part(s)
          << ":/" << steps[s].group << "/modal_coordinates</DataItem>\n     </DataItem>\n    </Attribute>\n";
      }
      x << "   </Grid>\n";
    }
    x << "  </Grid>\n";
  }
  // An element grid per output step: its topology, the nodes' positions and motion as point data,
  // the elements' results as cell data. Line segments (beams) carry the node axes 2 and 3 (the
  // section axes), faces (shells) the accelerations.
  for (const ElementGrid& g : grids_) {
    if (g.elements.empty()) continue;
    const size_t nc = g.elements.size();
    const std::string name = g.grid();
    using Pairs = std::vector<std::pair<const char*, const char*>>;
    Pairs vectors = g.lines ? Pairs{{"displacement", "node_displacement"}, {"velocity", "node_velocity"},
                                    {"axis2", "node_axis2"}, {"axis3", "node_axis3"}}
                            : Pairs{{"displacement", "node_displacement"}, {"velocity", "node_velocity"},
                                    {"acceleration", "node_acceleration"}};
    // The displacement without the block's best-fit rigid motion (results_layout.hpp): Warp By
    // Vector on it magnifies the deformation of a moving part.
    if (!layout_.blocks.empty()) vectors.emplace_back("elastic_displacement", "node_elastic_displacement");
    x << "  <Grid Name=\"" << name << "\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
    for (size_t s = 0; s < steps.size(); ++s) {
      x << "   <Grid Name=\"" << name << "\" GridType=\"Uniform\">\n    <Time Value=\"" << steps[s].time << "\"/>\n";
      if (g.lines)
        x << "    <Topology TopologyType=\"Polyline\" NumberOfElements=\"" << nc << "\" NodesPerElement=\"2\">\n"
          << "      <DataItem Dimensions=\"" << nc << " 2\" NumberType=\"Int\" Precision=\"4\" Format=\"HDF\">";
      else
        x << "    <Topology TopologyType=\"Mixed\" NumberOfElements=\"" << nc << "\">\n"
          << "      <DataItem Dimensions=\"" << g.connectivity_size << "\" NumberType=\"Int\" Precision=\"4\" Format=\"HDF\">";
      x << in_part(s) << ":/topology/" << g.connectivity() << "</DataItem>\n    </Topology>\n"
        << "    <Geometry GeometryType=\"XYZ\">\n";
      item(s, "node_position", nn, 3);
      x << "    </Geometry>\n";
      for (const auto& [aname, set] : vectors) {
        x << "    <Attribute Name=\"" << aname << "\" AttributeType=\"Vector\" Center=\"Node\">\n";
        item(s, set, nn, 3);
        x << "    </Attribute>\n";
      }
      x << "    <Attribute Name=\"quaternion\" AttributeType=\"Matrix\" Center=\"Node\">\n";
      item(s, "node_quaternion", nn, 4);
      x << "    </Attribute>\n";
      for (const CellField& f : g.fields) {
        x << "    <Attribute Name=\"" << f.name << "\" AttributeType=\"" << attribute_type(f.components)
          << "\" Center=\"Cell\">\n";
        item(s, g.dataset(f), nc, f.components);
        x << "    </Attribute>\n";
      }
      x << "   </Grid>\n";
    }
    x << "  </Grid>\n";
  }
  if (nj > 0) grid("joints", nj, "joints", "joint_location", {{"force", "joint_force"}, {"moment", "joint_moment"}});
  x << " </Domain>\n</Xdmf>\n";
  x.close();
  if (fault_injected("index")) {  // tests (core/fault_injection.hpp): the index cannot be written, as on a full disk
    errno = ENOSPC;
    x.setstate(std::ios::badbit);
  }
  if (!x) {
    const std::string e = write_failure("write the XDMF index", tmp);
    discard();
    return e;
  }
  return {};
}

std::string XdmfIndex::publish() const {
  const std::string tmp = path_ + ".tmp";
  errno = 0;
  std::error_code ec;
  std::filesystem::rename(tmp, path_, ec);
  if (ec) return write_failure("rename to " + path_, tmp);
  return {};
}

void XdmfIndex::discard() const {
  std::error_code ec;
  std::filesystem::remove(path_ + ".tmp", ec);
}

}  // namespace alphaflex::io_detail
