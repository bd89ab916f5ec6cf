#pragma once
// Deterministic mutations of scene files (YAML) and gmsh meshes (MSH text) for the fuzz test
// (tests/fuzz/fuzz_inputs.cpp). Every mutation is logged in words ("line 12: 'h: 1e-3' → ...") so
// that a failing case can be read without rerunning it, and every random choice comes from Rng, a
// fixed-seed generator whose sequence is the same on every platform and standard library (no
// std::uniform_*_distribution, whose results are implementation-defined).
#include <cstdint>
#include <string>
#include <vector>

namespace alphaflex::fuzz {

/// SplitMix64: small, fast, and fully specified.
class Rng {
 public:
  explicit Rng(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next();
  /// Uniform in [0, n) (n > 0; the modulo bias is irrelevant here).
  std::size_t below(std::size_t n) { return static_cast<std::size_t>(next() % n); }
  bool percent(int p) { return below(100) < static_cast<std::size_t>(p); }
  template <class T>
  const T& pick(const std::vector<T>& v) { return v[below(v.size())]; }

 private:
  std::uint64_t state_;
};

/// A stable 64-bit hash (FNV-1a) of text: case seeds derive from file names, not list positions,
/// so adding a seed file does not change the cases of the others.
std::uint64_t stable_hash(const std::string& text, std::uint64_t basis = 1469598103934665603ULL);

struct Mutation {
  std::string text;              ///< the mutated file
  std::vector<std::string> log;  ///< what was done, in order
};

/// `count` mutations of a scene file: lines deleted, duplicated, swapped or re-indented; numbers
/// replaced by edge values (0, -1, 1e308, nan, inf, huge integers, words); keys renamed; values
/// turned from scalars into lists or maps and back; deep nesting; the file cut short; random bytes.
Mutation mutate_scene(const std::string& text, Rng& rng, int count);

/// `count` mutations of an ASCII MSH file (4.1 or 2.2): the file cut short, a section removed,
/// counts (nodes, elements, entities, blocks) and tags (nodes, elements, entities, physical)
/// changed, coordinates made non-finite or huge, lines deleted, duplicated or swapped, random bytes.
Mutation mutate_msh(const std::string& text, Rng& rng, int count);

}  // namespace alphaflex::fuzz
