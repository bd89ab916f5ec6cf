#include "alphaflex/model/node.hpp"

namespace alphaflex {

const char* to_string(NodeKind kind) {
  switch (kind) {
    case NodeKind::RigidBody2D: return "rigid_body";
    case NodeKind::Particle2D: return "particle";
    case NodeKind::LineParticle2D: return "line_particle";
  }
  return "?";
}

int Node::dofs_of(NodeKind kind) {
  switch (kind) {
    case NodeKind::RigidBody2D: return 3;
    case NodeKind::Particle2D: return 2;
    case NodeKind::LineParticle2D: return 1;
  }
  return 0;
}

const char* coordinate_name(NodeKind kind, int k) {
  static const char* planar[] = {"x", "y", "theta"};
  return kind == NodeKind::LineParticle2D ? "s" : planar[k];
}

}  // namespace alphaflex
