#pragma once
// gmsh meshes → MeshData: node coordinates, named line blocks (2-node segments), named surface
// blocks (3-node triangles and 4-node quadrilaterals, consistently oriented) and named points.
// Upstream of the model: this module knows nothing of nodes' kinds, elements or PETSc. It reads a
// .msh as is, or opens a .geo and meshes it (in 2D if it has physical surfaces, else in 1D) with the
// gmsh C++ API (libgmsh). Conventions for
// .geo parameters and physical groups: meshes/README.md.
#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "alphaflex/mesh/surface_mesh.hpp"

namespace alphaflex {

/// How a .geo is meshed. Every option is refused for a .msh (read as is, never re-meshed).
struct MeshOptions {
  /// > 0: every curve of the .geo is meshed with this many elements (transfinite, uniform),
  /// overriding the .geo's own sizes and Transfinite constraints. Excludes element_size.
  int elements_per_curve = 0;
  /// > 0 (m): Mesh.MeshSizeMax for the .geo. Curves whose number of elements the .geo fixes
  /// (Transfinite Curve) cannot honour it: that is an error, not a silent override.
  double element_size = 0.0;
  /// Values of the .geo's ONELAB parameters, set before parsing: the key is the full ONELAB name
  /// given in `DefineConstant[ n = {16, Name "n"} ];` (here "n"). A name the .geo does not
  /// define this way is an error listing the names it does define.
  std::map<std::string, double> parameters;
};

/// A physical group of dimension 1, as 2-node segments (3-node lines are split at their mid node).
struct MeshLineBlock {
  std::string name;                            ///< physical name, or "line_<tag>" if unnamed
  int tag = 0;                                 ///< gmsh physical tag
  std::vector<std::array<int, 2>> elements;    ///< local node ids, in gmsh element order
  std::vector<std::size_t> element_tags;       ///< gmsh tag of the element each segment comes from
};

/// A physical group of dimension 2: 3-node triangles and 4-node quadrilaterals, mixed.
struct MeshSurfaceBlock {
  std::string name;                            ///< physical name, or "surface_<tag>" if unnamed
  int tag = 0;                                 ///< gmsh physical tag
  /// Local node ids (3 or 4), counter-clockwise about the element normal; the normals of elements
  /// sharing an edge agree (read_mesh reverses elements that disagreed with their neighbours).
  std::vector<std::vector<int>> elements;
  std::vector<std::size_t> element_tags;       ///< gmsh tag of each element
};

struct MeshData {
  std::string file;                           ///< the path as given to read_mesh
  std::vector<Eigen::Vector3d> points;        ///< node coordinates (m), index = local node id
  std::vector<std::size_t> node_tags;         ///< gmsh tag of each local node (for messages)
  std::vector<MeshLineBlock> line_blocks;     ///< physical groups of dimension 1, by physical tag
  std::map<std::string, int> named_points;    ///< physical groups of dimension 0 with one node → local node id
  /// Physical groups of dimension 0 with several nodes (supports, hinge points): local node ids
  /// in gmsh node order. They name groups (a joint or load at each node), not single bodies.
  std::map<std::string, std::vector<int>> point_groups;
  /// The .geo's ONELAB number parameters (DefineConstant with a Name) and the values it was
  /// meshed with: defaults and MeshOptions::parameters. Empty for a .msh.
  std::map<std::string, double> parameters;
  /// gmsh's warnings while reading and meshing ("Warning: " removed), for the caller to print.
  std::vector<std::string> warnings;
  std::vector<MeshSurfaceBlock> surface_blocks;  ///< physical groups of dimension 2, by physical tag

  /// The line block named `name`, or nullptr.
  const MeshLineBlock* find_line_block(const std::string& name) const;
  /// The surface block named `name`, or nullptr.
  const MeshSurfaceBlock* find_surface_block(const std::string& name) const;
};

/// Reads a .msh, or opens a .geo and meshes it. Throws InputError, whose message starts
/// with `context` (e.g. "scene.yaml:12: mesh.file") and names the file and what was expected, for
/// every failure: missing or unreadable file, unknown extension, gmsh's own errors, options that
/// do not fit the file, unknown parameters, no physical groups, unsupported element types
/// (second-order surface elements among them), named points that are not exactly one node,
/// empty point groups, duplicate group names, a surface block whose elements cannot be oriented consistently
/// (non-orientable, like a Möbius strip). Elements reversed to agree with their neighbours are
/// reported in `warnings`. A point group of one node is a named point, of several a point group.
///
/// Local node ids are compact (only nodes of the returned groups) and deterministic: in order of
/// first use by the line blocks (by physical tag, gmsh element order), then by the surface blocks
/// (the same), then the named points' nodes (by physical tag). Each call runs its own gmsh session
/// (initialize ... finalize), so gmsh must not be used elsewhere in the process at the same time; concurrent calls from
/// threads are serialized. It writes no file of its own, so every MPI rank may read the same file
/// at once (gmsh's first initialize in a process makes FLTK rewrite its preference file, with the
/// same content on every rank: meshes/README.md).
MeshData read_mesh(const std::string& path, const MeshOptions& options, const std::string& context);

/// The surface elements (3-node triangles, 4-node quadrilaterals) of every surface of a .stl or
/// .msh (a body's shape), points in the file's units, in order of first use. InputError (starting
/// with `context`, naming the file) if the file is missing, of another kind, invalid, or has no
/// surface elements or others than these. Each call is a gmsh session of its own, as read_mesh.
SurfaceMesh read_surface_mesh(const std::string& path, const std::string& context);

/// MeshData as bytes and back (one rank reads the mesh with gmsh and sends it to the others).
std::vector<char> pack(const MeshData& mesh);
MeshData unpack(const std::vector<char>& bytes);

}  // namespace alphaflex
