#pragma once
// Private to the mesh module: a structural check of an MSH file before gmsh reads it.
//
// Why: gmsh 4.8.4's MSH readers trust the file. A node tag out of the header's range, an element
// naming a node that does not exist or a count larger than the file make it read out of bounds
// (a segmentation fault in GModel::getMeshVertexByTag, found by tests/fuzz), allocate without
// bound, or loop over garbage; no error reaches its logger first. So every .msh is parsed here
// first, as the format specifies it, and gmsh only ever sees a file whose sections, counts, tags
// and references agree. ASCII MSH 4.1 and 2.2 are read (what gmsh writes, and what meshes/ holds);
// binary files cannot be checked this way and are refused with how to save them as ASCII.
#include <string>

namespace alphaflex::msh_check {

/// Empty if `text` (the whole file) is a well-formed ASCII MSH 4.1 or 2.2 mesh, else what is
/// wrong, starting with its line: "line 17: $Nodes: node tag 9 is outside [1, 8] (the header's
/// minNodeTag and maxNodeTag)". Coordinates must be finite.
std::string structure_error(const std::string& text);

}  // namespace alphaflex::msh_check
