// `shape` of a rigid body: what the results draw (a box, cylinder, sphere or surface mesh file in
// the body frame; model/body_shape.hpp). Read for the planar and the spatial `rigid_body`.
#include "body_shape.hpp"

#include <algorithm>
#include <filesystem>

namespace alphaflex::scene_detail {

namespace {

enum ShapeType { kBox, kCylinder, kSphere, kMesh };
const char* const kShapeNames[] = {"box", "cylinder", "sphere", "mesh"};

}  // namespace

Key shape_key() {
  return {"shape", KeyType::Map, "m, rad", "none (the body is drawn as its links)",
          "what the results draw, fixed to the body: `{type: box|cylinder|sphere|mesh, ...}` (table `bodies.shape`); "
          "no effect on the dynamics"};
}

const Schema& shape_schema() {
  static const Schema s{"bodies.shape", {
      {"type", KeyType::Choice, "–", kRequired, "the surface drawn", {}, "", "", {"box", "cylinder", "sphere", "mesh"}},
      {"size", KeyType::Vec3, "m", "required for a box", "box: edge lengths [a, b, c] along the body axes x, y, z, each > 0"},
      {"radius", KeyType::Number, "m", "required for a cylinder, sphere", "cylinder, sphere: radius", Range::positive(), "radius (m)"},
      {"length", KeyType::Number, "m", "required for a cylinder", "cylinder: length along its axis", Range::positive(), "length (m)"},
      {"axis", KeyType::Choice, "–", "z", "cylinder: the body axis it lies along", {}, "", "", {"x", "y", "z"}},
      {"file", KeyType::Text, "–", "required for a mesh", "mesh: a surface mesh (.stl, or .msh with triangles or quadrilaterals), relative to the scene file's directory, read with gmsh"},
      {"scale", KeyType::Number, "–", "1", "mesh: factor from the file's length unit to metres (0.001 for a file in mm)", Range::positive(), "scale factor"},
      {"position", KeyType::Vec3, "m", "[0, 0, 0]", "the shape's centre (a mesh: the file's origin) in the body frame"},
      {"orientation", KeyType::Map, "rad", "identity", "the shape's rotation in the body frame: a rotation vector or {axis, angle}", {}, "", "rotation"}}};
  return s;
}

void read_body_shape(const Item& it, int node) {
  if (!it.keys.has("shape")) return;
  Reader& rd = it.rd;
  const YAML::Node n = it.keys.node("shape");
  const std::string path = it.at("shape");
  if (!n.IsMap()) rd.fail(n, path, "expected a map {type: box|cylinder|sphere|mesh, ...}");
  const Section s(rd, n, path, shape_schema());
  const int type = s.choice("type");
  // The keys of each type: any other size key is a mistake (a box's radius is never used).
  const std::vector<std::vector<std::string>> own = {{"size"}, {"radius", "length", "axis"}, {"radius"}, {"file", "scale"}};
  const std::vector<std::string>& mine = own[static_cast<size_t>(type)];
  std::string listed;
  for (const std::string& k : mine) listed += k + ", ";
  for (const char* key : {"size", "radius", "length", "axis", "file", "scale"}) {
    const bool allowed = std::find(mine.begin(), mine.end(), key) != mine.end();
    const bool optional = std::string(key) == "axis" || std::string(key) == "scale";
    if (s.has(key) && !allowed)
      rd.fail(s.node(key), s.key_path(key), std::string("not a key of a ") + kShapeNames[type] + " shape (its keys: " + listed +
                                                "position, orientation)");
    if (!s.has(key) && allowed && !optional)
      rd.fail(n, s.key_path(key), std::string("missing (required for a ") + kShapeNames[type] + " shape)");
  }
  BodyShape shape;
  shape.node = node;
  shape.what = kShapeNames[type];
  double scale = 1.0;
  switch (type) {
    case kBox: {
      const Eigen::Vector3d size = s.vec3("size");
      if (!(size.minCoeff() > 0.0))
        rd.fail(s.node("size"), s.key_path("size"), "expected edge lengths > 0 (m), got [" + std::to_string(size[0]) + ", " +
                                                        std::to_string(size[1]) + ", " + std::to_string(size[2]) + "]");
      shape.surface = box_surface(size);
      break;
    }
    case kCylinder:
      shape.surface = cylinder_surface(s.number("radius"), s.number("length"), s.choice("axis", 2));
      break;
    case kSphere:
      shape.surface = sphere_surface(s.number("radius"));
      break;
    case kMesh: {
      const std::string given = s.text("file");
      std::filesystem::path file(given);
      if (file.is_relative()) file = std::filesystem::path(rd.file()).parent_path() / file;
      // Every rank reads the file (gmsh writes nothing: mesh/gmsh_reader.hpp); the same file
      // gives the same surface on each.
      shape.surface = read_surface_mesh(file.string(), rd.where(s.node("file"), s.key_path("file")));
      shape.what = "mesh " + given;
      scale = s.number("scale", 1.0);
      break;
    }
  }
  const Eigen::Matrix3d R = s.has("orientation") ? read_orientation(rd, s.node("orientation"), s.key_path("orientation"))
                                                 : Eigen::Matrix3d::Identity();
  place_surface(shape.surface, scale, R, s.vec3("position"));
  it.model.add_shape(std::move(shape));
}

}  // namespace alphaflex::scene_detail
