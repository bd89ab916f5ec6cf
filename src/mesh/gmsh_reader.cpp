// gmsh → MeshData through the gmsh C++ API (Debian gmsh 4.8.4). Built as a module of its own
// (libalphaflex_gmsh.so, loaded by gmsh_loader.cpp only when a scene has a mesh): libgmsh pulls
// OpenCASCADE, FLTK and ~70 other libraries, three quarters of the process' start-up CPU
// (docs/performance.md, start-up).
//
// How gmsh 4.8.4 reports failures, and why errors are read from its logger instead of caught:
// with General.AbortOnError >= 2 (gmsh::initialize sets 2) every gmsh error (Msg::Error) throws a
// std::string holding the message, e.g. "'x.geo', line 2: Unknown variable 'x'" or "Could not read
// nodes". But an exception thrown from inside the .geo parser leaves its lexer in the middle of
// the failed file, and that survives gmsh::finalize: every later .geo read in the process then
// fails with "line 0: syntax error". So errors are not thrown (AbortOnError = 0): gmsh finishes
// each operation, the logger keeps every message ("Error: ...", "Warning: ..."), and each stage
// here checks it. Anything still thrown (std::string, std::exception, other) is converted too.
// A .msh is checked before gmsh reads it (msh_check.hpp: gmsh crashes on bad tags and counts).
// Silent failures checked here instead: opening a missing file does nothing; a .msh without a
// $MeshFormat header is parsed as a .geo script; a Physical group naming a curve or point that does
// not exist is dropped. State that survives gmsh::finalize: the ONELAB database (cleared before and
// after each read) and the parser's lexer (see above).
#include "alphaflex/mesh/gmsh_reader.hpp"

#include <gmsh.h>

#include <algorithm>
#include <cctype>
#include <climits>
#include <cmath>
#include <exception>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <optional>
#include <sstream>
#include <unordered_map>
#include <utility>

#include "alphaflex/core/error.hpp"
#include "msh_check.hpp"

namespace alphaflex {

namespace {

// gmsh is one global state: one session at a time in this process.
std::mutex gmsh_mutex;

constexpr int kLine2 = 1;  // gmsh element type: 2-node line
constexpr int kLine3 = 8;  // 3-node line (second order): nodes [end, end, mid]
constexpr int kTriangle3 = 2;
constexpr int kQuadrangle4 = 3;

std::string number(double v) {
  std::ostringstream s;
  s.precision(15);
  s << v;
  return s.str();
}

std::string join(const std::vector<std::string>& items, const std::string& sep = ", ") {
  std::string out;
  for (size_t i = 0; i < items.size(); ++i) out += (i ? sep : "") + items[i];
  return out;
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

/// One gmsh session: initialize with no configuration files and a silent terminal, errors thrown,
/// an empty ONELAB database and the logger on; finalize (quietly) in every case.
class GmshSession {
 public:
  GmshSession() {
    gmsh::initialize(0, nullptr, /*readConfigFiles=*/false);
    try {
      gmsh::option::setNumber("General.Terminal", 0);
      gmsh::option::setNumber("General.AbortOnError", 0);  // errors go to the logger only
      gmsh::onelab::clear();  // the database outlives gmsh::finalize (values of a previous read)
      gmsh::logger::start();
    } catch (...) {
      shut_down();
      throw;
    }
  }
  ~GmshSession() { shut_down(); }
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;

  /// Logged messages starting with `level` (e.g. "Error: "), with that prefix removed.
  static std::vector<std::string> logged(const std::string& level) {
    std::vector<std::string> out;
    try {
      std::vector<std::string> log;
      gmsh::logger::get(log);
      for (const std::string& line : log)
        if (line.compare(0, level.size(), level) == 0) out.push_back(line.substr(level.size()));
    } catch (...) {
    }
    return out;
  }

 private:
  static void shut_down() noexcept {
    try { gmsh::logger::stop(); } catch (...) {}
    try { gmsh::onelab::clear(); } catch (...) {}
    try { gmsh::finalize(); } catch (...) {}
  }
};

class Reader {
 public:
  Reader(std::string path, const MeshOptions& options, const std::string& context)
      : path_(std::move(path)), options_(options) {
    prefix_ = (context.empty() ? "" : context + ": ") + "mesh '" + path_ + "': ";
  }

  MeshData read() {
    check_file_and_options();
    std::lock_guard<std::mutex> lock(gmsh_mutex);
    std::optional<GmshSession> session;
    try {
      stage_ = "starting gmsh";
      session.emplace();
      check_gmsh();
      MeshData mesh;
      mesh.file = path_;
      if (is_geo_) {
        stage_ = "reading the .geo (expected a valid gmsh geometry script)";
        for (const auto& [name, value] : options_.parameters) gmsh::onelab::setNumber(name, {value});
        gmsh::open(path_);
        check_gmsh();
        mesh.parameters = check_parameters();
        stage_ = "meshing the .geo";
        mesh_geo();
        check_gmsh();
      } else {
        stage_ = "reading the .msh (expected a valid gmsh MSH file)";
        gmsh::open(path_);
        check_gmsh();
      }
      stage_ = "reading the mesh's physical groups";
      extract(mesh);
      check_gmsh();
      const std::vector<std::string> logged = GmshSession::logged("Warning: ");
      mesh.warnings.insert(mesh.warnings.begin(), logged.begin(), logged.end());
      return mesh;
    } catch (const InputError&) {
      throw;
    } catch (const std::string& message) {
      fail_gmsh({message});
    } catch (const std::exception& e) {
      fail_gmsh({e.what()});
    } catch (...) {
      std::string last;
      try { gmsh::logger::getLastError(last); } catch (...) {}
      fail_gmsh({last.empty() ? "unknown gmsh failure" : last});
    }
  }

 private:
  [[noreturn]] void fail(const std::string& what) const { throw InputError(prefix_ + what); }

  /// Fails with the errors gmsh logged so far, if any.
  void check_gmsh() const {
    const std::vector<std::string> errors = GmshSession::logged("Error: ");
    if (!errors.empty()) fail_gmsh({});
  }

  /// A gmsh failure: `first` (a thrown message), then the errors gmsh logged, the first ones
  /// (the cause; later ones are often its consequences).
  [[noreturn]] void fail_gmsh(std::vector<std::string> first) const {
    std::vector<std::string> errors = std::move(first);
    for (const std::string& e : GmshSession::logged("Error: "))
      if (std::find(errors.begin(), errors.end(), e) == errors.end()) errors.push_back(e);
    constexpr size_t kShown = 3;
    std::string text = "gmsh failed while " + stage_ + ": ";
    for (size_t i = 0; i < errors.size() && i < kShown; ++i) text += (i ? "; " : "") + errors[i];
    if (errors.size() > kShown) text += " (and " + std::to_string(errors.size() - kShown) + " more)";
    if (errors.empty()) text += "unknown error";
    fail(text);
  }

  void check_file_and_options() {
    namespace fs = std::filesystem;
    const std::string ext = lower(fs::path(path_).extension().string());
    if (ext != ".geo" && ext != ".msh")
      fail("expected a gmsh file ending in .geo (geometry, meshed here) or .msh (mesh, read as is)");
    is_geo_ = ext == ".geo";

    std::error_code ec;
    if (!fs::exists(path_, ec)) fail("file not found");
    if (!fs::is_regular_file(path_, ec)) fail("not a regular file");
    std::ifstream in(path_, std::ios::binary);
    if (!in) fail("cannot be opened for reading");
    if (!is_geo_) {
      // gmsh parses a .msh without this header as a .geo script; never run one by mistake.
      std::string word;
      in >> word;
      if (word != "$MeshFormat")
        fail("not a gmsh MSH file: expected it to start with $MeshFormat" +
             (word.empty() ? std::string(" (the file is empty)") : ", found '" + word.substr(0, 40) + "'"));
      // gmsh trusts a .msh: a bad tag or count crashes it (msh_check.hpp). Checked here first.
      in.seekg(0);
      const std::string text(std::istreambuf_iterator<char>(in), {});
      const std::string bad = msh_check::structure_error(text);
      if (!bad.empty()) fail("not a valid MSH file (checked before gmsh reads it): " + bad);
    }

    if (options_.elements_per_curve < 0)
      fail("elements_per_curve = " + std::to_string(options_.elements_per_curve) + ": expected a number > 0, or 0 for the .geo's own sizes");
    if (options_.elements_per_curve == INT_MAX) fail("elements_per_curve is too large");
    if (!std::isfinite(options_.element_size) || options_.element_size < 0)
      fail("element_size = " + number(options_.element_size) + ": expected a length > 0 (m), or 0 for the .geo's own sizes");
    for (const auto& [name, value] : options_.parameters) {
      if (name.empty()) fail("a parameter has an empty name");
      if (!std::isfinite(value)) fail("parameter '" + name + "' = " + number(value) + ": expected a finite number");
    }
    if (!is_geo_) {
      std::vector<std::string> given;
      if (options_.elements_per_curve > 0) given.push_back("elements_per_curve");
      if (options_.element_size > 0) given.push_back("element_size");
      if (!options_.parameters.empty()) given.push_back("parameters");
      if (!given.empty())
        fail(join(given) + ": only for a .geo; a .msh is read as is, never re-meshed (use the .geo, "
             "or mesh it again with gmsh)");
    } else if (options_.elements_per_curve > 0 && options_.element_size > 0) {
      fail("elements_per_curve and element_size exclude each other: give one");
    }
  }

  /// The .geo's ONELAB number parameters after gmsh::open, checked against options_.parameters:
  /// a parameter the .geo defines gets a "clients" entry (Gmsh) in the database; one that only we
  /// set has none.
  std::map<std::string, double> check_parameters() const {
    std::vector<std::string> names;
    gmsh::onelab::getNames(names);
    std::map<std::string, double> defined;
    for (const std::string& name : names) {
      if (name.rfind("Gmsh/", 0) == 0 || name.rfind("ONELAB/", 0) == 0) continue;
      std::string json;
      gmsh::onelab::get(json, name);
      if (json.find("\"clients\"") == std::string::npos) continue;
      std::vector<double> value;
      gmsh::onelab::getNumber(name, value);
      if (value.size() == 1) defined[name] = value[0];
    }
    std::vector<std::string> unknown;
    for (const auto& [name, value] : options_.parameters)
      if (!defined.count(name)) unknown.push_back("'" + name + "'");
    if (!unknown.empty()) {
      std::vector<std::string> known;
      for (const auto& [name, value] : defined) known.push_back("'" + name + "'");
      fail("unknown parameter" + std::string(unknown.size() > 1 ? "s " : " ") + join(unknown) + ": " +
           (known.empty() ? std::string("the .geo defines no parameters")
                          : "the .geo defines " + join(known)) +
           " (a parameter is a DefineConstant with a Name, e.g. DefineConstant[ n = {16, Name \"n\"} ];"
           " see meshes/README.md)");
    }
    for (const auto& [name, value] : options_.parameters)
      if (defined.at(name) != value)
        fail("parameter '" + name + "' = " + number(value) + " was not taken: the .geo keeps " +
             number(defined.at(name)) + " (is it ReadOnly in its DefineConstant?)");
    return defined;
  }

  void mesh_geo() const {
    if (options_.elements_per_curve > 0) {
      gmsh::vectorpair curves;
      gmsh::model::getEntities(curves, 1);
      for (const auto& [dim, tag] : curves)
        gmsh::model::mesh::setTransfiniteCurve(tag, options_.elements_per_curve + 1);
    }
    if (options_.element_size > 0) gmsh::option::setNumber("Mesh.MeshSizeMax", options_.element_size);
    // In 2D only if there are physical surfaces (shells): beam-only geometries stay 1D.
    gmsh::vectorpair surfaces;
    gmsh::model::getPhysicalGroups(surfaces, 2);
    gmsh::model::mesh::generate(surfaces.empty() ? 1 : 2);
  }

  /// With element_size, every curve element (chord between its end nodes) must be no longer.
  void check_element_size(const std::unordered_map<std::size_t, Eigen::Vector3d>& coords) const {
    const double h = options_.element_size;
    gmsh::vectorpair curves;
    gmsh::model::getEntities(curves, 1);
    for (const auto& [dim, tag] : curves) {
      std::vector<int> types;
      std::vector<std::vector<std::size_t>> element_tags, node_tags;
      gmsh::model::mesh::getElements(types, element_tags, node_tags, 1, tag);
      for (size_t t = 0; t < types.size(); ++t) {
        if (types[t] != kLine2 && types[t] != kLine3) continue;
        const size_t per = types[t] == kLine2 ? 2 : 3;
        for (size_t e = 0; e < element_tags[t].size(); ++e) {
          const double length = (coords.at(node_tags[t][per * e + 1]) - coords.at(node_tags[t][per * e])).norm();
          if (length > h * (1 + 1e-6))
            fail("element_size = " + number(h) + " m was not honoured: curve " + std::to_string(tag) +
                 " has an element of length " + number(length) +
                 " m (the .geo fixes its number of elements, e.g. Transfinite Curve, or its sizes; "
                 "use elements_per_curve or the .geo's parameters instead)");
        }
      }
    }
  }

  struct Group {
    int dim;
    int tag;
    std::string name;
  };

  void extract(MeshData& mesh) {
    // Physical groups of dimension 0 and 1, by (dim, tag); names checked before anything else.
    gmsh::vectorpair physical;
    gmsh::model::getPhysicalGroups(physical);
    std::sort(physical.begin(), physical.end());
    std::vector<Group> groups;
    std::map<std::string, const char*> seen;
    std::vector<std::string> other_dims;
    for (const auto& [dim, tag] : physical) {
      if (dim > 2) {
        other_dims.push_back(std::to_string(dim));
        continue;
      }
      std::string name;
      gmsh::model::getPhysicalName(dim, tag, name);
      if (name.empty()) name = (dim == 2 ? "surface_" : dim == 1 ? "line_" : "point_") + std::to_string(tag);
      const char* kind = dim == 2 ? "surface (dimension 2)" : dim == 1 ? "line (dimension 1)" : "point (dimension 0)";
      if (seen.count(name))
        fail("two physical groups are named '" + name + "' (a " + seen[name] + " and a " + kind +
             ", tag " + std::to_string(tag) + "): expected unique names");
      seen[name] = kind;
      groups.push_back({dim, tag, name});
    }
    if (groups.empty())
      fail(std::string("no physical groups of dimension 0, 1 or 2") +
           (other_dims.empty() ? "" : " (volumes are not read)") +
           ": expected the beam curves in a Physical Curve(\"name\"), the shell surfaces in a "
           "Physical Surface(\"name\") and named points in a Physical Point(\"name\") (see meshes/README.md)");

    // Coordinates of every node (bulk, one call).
    std::unordered_map<std::size_t, Eigen::Vector3d> coords;
    {
      std::vector<std::size_t> tags;
      std::vector<double> xyz, parametric;
      gmsh::model::mesh::getNodes(tags, xyz, parametric, -1, -1, false, false);
      coords.reserve(tags.size());
      for (size_t i = 0; i < tags.size(); ++i) coords[tags[i]] = Eigen::Vector3d(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
    }
    if (is_geo_ && options_.element_size > 0) check_element_size(coords);

    std::unordered_map<std::size_t, int> local;  // gmsh node tag → local id
    auto local_id = [&](std::size_t gmsh_tag, const Group& g) {
      auto it = local.find(gmsh_tag);
      if (it != local.end()) return it->second;
      auto c = coords.find(gmsh_tag);
      if (c == coords.end())
        fail("physical group '" + g.name + "' uses node " + std::to_string(gmsh_tag) + ", which has no coordinates");
      // Lengths are formed from coordinate differences squared: beyond 1e150 m they overflow, and the
      // first symptom was far away (a section frame that is not a rotation; issue 24).
      if (!(c->second.cwiseAbs().maxCoeff() <= 1e150)) {
        std::ostringstream os;
        os.precision(6);
        os << "node " << gmsh_tag << " of physical group '" << g.name << "' is at (" << c->second.x() << ", " << c->second.y()
           << ", " << c->second.z() << "): expected coordinates of magnitude at most 1e150 m (squared lengths must stay finite)";
        fail(os.str());
      }
      const int id = static_cast<int>(mesh.points.size());
      local.emplace(gmsh_tag, id);
      mesh.points.push_back(c->second);
      mesh.node_tags.push_back(gmsh_tag);
      return id;
    };

    for (const Group& g : groups) {
      if (g.dim != 1) continue;
      MeshLineBlock block;
      block.name = g.name;
      block.tag = g.tag;
      std::map<std::pair<std::size_t, std::size_t>, std::size_t> segment_owner;  // duplicates
      auto add = [&](std::size_t a, std::size_t b, std::size_t element_tag) {
        const auto key = std::minmax(a, b);
        auto [it, fresh] = segment_owner.emplace(key, element_tag);
        if (!fresh && it->second != element_tag)
          fail("physical group '" + g.name + "': elements " + std::to_string(it->second) + " and " +
               std::to_string(element_tag) + " join the same gmsh nodes (" + std::to_string(a) + ", " +
               std::to_string(b) + "): expected each segment once (a MSH 2 file repeats the elements "
               "of a curve in several physical groups; save the mesh in MSH 4 format)");
        block.elements.push_back({local_id(a, g), local_id(b, g)});
        block.element_tags.push_back(element_tag);
      };
      std::vector<int> entities;
      gmsh::model::getEntitiesForPhysicalGroup(1, g.tag, entities);
      for (int entity : entities) {
        std::vector<int> types;
        std::vector<std::vector<std::size_t>> element_tags, node_tags;
        gmsh::model::mesh::getElements(types, element_tags, node_tags, 1, entity);
        for (size_t t = 0; t < types.size(); ++t) {
          const std::vector<std::size_t>& n = node_tags[t];
          if (types[t] == kLine2) {
            for (size_t e = 0; e < element_tags[t].size(); ++e) add(n[2 * e], n[2 * e + 1], element_tags[t][e]);
          } else if (types[t] == kLine3) {  // [end, end, mid] → (end, mid), (mid, end)
            for (size_t e = 0; e < element_tags[t].size(); ++e) {
              add(n[3 * e], n[3 * e + 2], element_tags[t][e]);
              add(n[3 * e + 2], n[3 * e + 1], element_tags[t][e]);
            }
          } else if (!element_tags[t].empty()) {
            std::string type_name;
            int edim = 0, order = 0, nodes = 0, primary = 0;
            std::vector<double> local_coords;
            gmsh::model::mesh::getElementProperties(types[t], type_name, edim, order, nodes, local_coords, primary);
            fail("physical group '" + g.name + "' (dimension 1) holds element " +
                 std::to_string(element_tags[t][0]) + " of type '" + type_name + "' (gmsh type " +
                 std::to_string(types[t]) + "): expected 2-node lines (type 1) or 3-node lines "
                 "(type 8; Mesh.ElementOrder 1 or 2)");
          }
        }
      }
      if (block.elements.empty())
        fail("physical group '" + g.name + "' (dimension 1) has no line elements: expected a "
             "meshed curve (does it name curves that exist?)");
      mesh.line_blocks.push_back(std::move(block));
    }

    for (const Group& g : groups) {
      if (g.dim != 2) continue;
      MeshSurfaceBlock block;
      block.name = g.name;
      block.tag = g.tag;
      std::vector<int> entities;
      gmsh::model::getEntitiesForPhysicalGroup(2, g.tag, entities);
      for (int entity : entities) {
        std::vector<int> types;
        std::vector<std::vector<std::size_t>> element_tags, node_tags;
        gmsh::model::mesh::getElements(types, element_tags, node_tags, 2, entity);
        for (size_t t = 0; t < types.size(); ++t) {
          if (element_tags[t].empty()) continue;
          if (types[t] != kTriangle3 && types[t] != kQuadrangle4) {
            std::string type_name;
            int edim = 0, order = 0, nodes = 0, primary = 0;
            std::vector<double> local_coords;
            gmsh::model::mesh::getElementProperties(types[t], type_name, edim, order, nodes, local_coords, primary);
            fail("physical group '" + g.name + "' (dimension 2) holds element " + std::to_string(element_tags[t][0]) +
                 " of type '" + type_name + "' (gmsh type " + std::to_string(types[t]) +
                 "): expected 3-node triangles (type 2) or 4-node quadrangles (type 3); shells are "
                 "first order (Mesh.ElementOrder 1)");
          }
          const size_t per = types[t] == kTriangle3 ? 3 : 4;
          for (size_t e = 0; e < element_tags[t].size(); ++e) {
            std::vector<int> el;
            for (size_t k = 0; k < per; ++k) el.push_back(local_id(node_tags[t][per * e + k], g));
            block.elements.push_back(el);
            block.element_tags.push_back(element_tags[t][e]);
          }
        }
      }
      if (block.elements.empty())
        fail("physical group '" + g.name + "' (dimension 2) has no surface elements: expected a "
             "meshed surface (does it name surfaces that exist?)");
      orient(block, mesh);
      mesh.surface_blocks.push_back(std::move(block));
    }

    for (const Group& g : groups) {
      if (g.dim != 0) continue;
      std::vector<std::size_t> tags;
      std::vector<double> xyz;
      gmsh::model::mesh::getNodesForPhysicalGroup(0, g.tag, tags, xyz);
      if (tags.empty())
        fail("physical point group '" + g.name + "' holds no node: expected the geometry points it names");
      if (tags.size() == 1) {
        mesh.named_points[g.name] = local_id(tags[0], g);
        continue;
      }
      std::vector<int>& ids = mesh.point_groups[g.name];
      for (std::size_t t : tags) ids.push_back(local_id(t, g));
    }
  }

  /// Makes the elements of a surface block agree in orientation: a breadth-first walk over each
  /// component connected through edges shared by exactly two elements, from its lowest-tag
  /// element, reversing elements that traverse a shared edge in the same direction as their
  /// neighbour. A contradiction (non-orientable surface) fails; reversals are reported.
  void orient(MeshSurfaceBlock& block, MeshData& mesh) const {
    const size_t ne = block.elements.size();
    std::map<std::pair<int, int>, std::vector<size_t>> edge_elements;
    for (size_t e = 0; e < ne; ++e) {
      const auto& el = block.elements[e];
      for (size_t k = 0; k < el.size(); ++k) edge_elements[std::minmax(el[k], el[(k + 1) % el.size()])].push_back(e);
    }
    // +1 if element e runs from a to b along its boundary, −1 if from b to a.
    auto direction = [&](size_t e, int a, int b) {
      const auto& el = block.elements[e];
      for (size_t k = 0; k < el.size(); ++k) {
        if (el[k] == a && el[(k + 1) % el.size()] == b) return 1;
        if (el[k] == b && el[(k + 1) % el.size()] == a) return -1;
      }
      return 0;
    };
    std::vector<size_t> order(ne);
    for (size_t e = 0; e < ne; ++e) order[e] = e;
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return block.element_tags[a] < block.element_tags[b]; });
    std::vector<int> flip(ne, 0);  // 0: not reached; +1 keep; −1 reverse
    size_t reversed = 0;
    for (size_t seed : order) {
      if (flip[seed] != 0) continue;
      flip[seed] = 1;
      std::vector<size_t> queue{seed};
      for (size_t qi = 0; qi < queue.size(); ++qi) {
        const size_t e = queue[qi];
        const auto& el = block.elements[e];
        for (size_t k = 0; k < el.size(); ++k) {
          const int a = el[k], b = el[(k + 1) % el.size()];
          const auto& sharing = edge_elements[std::minmax(a, b)];
          if (sharing.size() != 2) continue;
          const size_t o = sharing[0] == e ? sharing[1] : sharing[0];
          // Consistent: the neighbour runs the shared edge the other way (after both flips).
          const int want = -flip[e] * direction(e, a, b) * direction(o, a, b);
          if (flip[o] == 0) {
            flip[o] = want;
            queue.push_back(o);
          } else if (flip[o] != want) {
            fail("physical group '" + block.name + "' (dimension 2) cannot be oriented consistently: element " +
                 std::to_string(block.element_tags[o]) + " would need both normals (a non-orientable surface, "
                 "like a Moebius strip); split it into orientable groups");
          }
        }
      }
    }
    for (size_t e = 0; e < ne; ++e)
      if (flip[e] < 0) {
        std::reverse(block.elements[e].begin() + 1, block.elements[e].end());
        ++reversed;
      }
    if (reversed > 0)
      mesh.warnings.push_back("physical group '" + block.name + "': " + std::to_string(reversed) +
                              " element(s) reversed so that their normals agree with their neighbours'");
  }

  std::string path_;
  const MeshOptions& options_;
  std::string prefix_;
  std::string stage_;
  bool is_geo_ = false;
};

/// A body's surface mesh (io: `shape: {type: mesh}`): the 3-node triangles and 4-node
/// quadrilaterals of every surface of a .stl or .msh, physical groups or not (an STL has none).
SurfaceMesh read_surface(const std::string& path, const std::string& context) {
  namespace fs = std::filesystem;
  const std::string prefix = (context.empty() ? "" : context + ": ") + "surface mesh '" + path + "': ";
  auto fail = [&](const std::string& what) { throw InputError(prefix + what); };
  const std::string ext = lower(fs::path(path).extension().string());
  if (ext != ".stl" && ext != ".msh") fail("expected a surface mesh file ending in .stl or .msh");
  std::error_code ec;
  if (!fs::exists(path, ec)) fail("file not found");
  if (!fs::is_regular_file(path, ec)) fail("not a regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in) fail("cannot be opened for reading");
  if (ext == ".msh") {  // as Reader::check_file_and_options: never let gmsh parse a bad .msh
    const std::string text(std::istreambuf_iterator<char>(in), {});
    if (text.compare(0, 11, "$MeshFormat") != 0) fail("not a gmsh MSH file: expected it to start with $MeshFormat");
    const std::string bad = msh_check::structure_error(text);
    if (!bad.empty()) fail("not a valid MSH file (checked before gmsh reads it): " + bad);
  } else if (fs::file_size(path, ec) == 0) {
    fail("the file is empty");
  }
  std::lock_guard<std::mutex> lock(gmsh_mutex);
  GmshSession session;
  auto check = [&](const std::string& stage) {
    const std::vector<std::string> errors = GmshSession::logged("Error: ");
    if (!errors.empty()) fail("gmsh failed while " + stage + ": " + errors.front());
  };
  SurfaceMesh s;
  try {
    gmsh::open(path);
    check("reading the file");
    std::vector<int> types;
    std::vector<std::vector<std::size_t>> element_tags, node_tags;
    gmsh::model::mesh::getElements(types, element_tags, node_tags, 2, -1);
    std::unordered_map<std::size_t, int> index;  // gmsh node tag → point, in order of first use
    for (size_t t = 0; t < types.size(); ++t) {
      if (types[t] != kTriangle3 && types[t] != kQuadrangle4) {
        std::string type_name;
        int edim = 0, order = 0, nodes = 0, primary = 0;
        std::vector<double> local_coords;
        gmsh::model::mesh::getElementProperties(types[t], type_name, edim, order, nodes, local_coords, primary);
        fail("surface elements of type '" + type_name + "': expected 3-node triangles and 4-node quadrilaterals");
      }
      const size_t n = types[t] == kTriangle3 ? 3 : 4;
      for (size_t e = 0; e < element_tags[t].size(); ++e) {
        std::vector<int> face(n);
        for (size_t c = 0; c < n; ++c)
          face[c] = index.emplace(node_tags[t][n * e + c], static_cast<int>(index.size())).first->second;
        s.faces.push_back(face);
      }
    }
    if (s.faces.empty()) fail("no surface elements (expected 3-node triangles or 4-node quadrilaterals)");
    std::vector<std::size_t> tags;
    std::vector<double> xyz, parametric;
    gmsh::model::mesh::getNodes(tags, xyz, parametric, -1, -1, true, false);
    s.points.assign(index.size(), Eigen::Vector3d::Zero());
    for (size_t i = 0; i < tags.size(); ++i) {
      const auto at = index.find(tags[i]);
      if (at != index.end()) s.points[static_cast<size_t>(at->second)] = Eigen::Vector3d(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
    }
    check("reading the surface elements");
  } catch (const InputError&) {
    throw;
  } catch (const std::string& message) {
    fail("gmsh failed: " + message);
  } catch (const std::exception& e) {
    fail(std::string("gmsh failed: ") + e.what());
  }
  return s;
}

}  // namespace

}  // namespace alphaflex

// The entry point of the module (gmsh_loader.cpp loads it when a scene has a mesh): C linkage, so
// dlsym finds it by this name. Errors leave as C++ exceptions (InputError), which cross the module
// boundary like any shared object's (same compiler and libstdc++).
extern "C" __attribute__((visibility("default"))) void alphaflex_gmsh_read_mesh(
    const std::string& path, const alphaflex::MeshOptions& options, const std::string& context,
    alphaflex::MeshData& mesh) {
  mesh = alphaflex::Reader(path, options, context).read();
}

// The module's second entry point: a body's surface mesh (gmsh_loader.cpp, read_surface_mesh).
extern "C" __attribute__((visibility("default"))) void alphaflex_gmsh_read_surface(const std::string& path,
                                                                                   const std::string& context,
                                                                                   alphaflex::SurfaceMesh& surface) {
  surface = alphaflex::read_surface(path, context);
}
