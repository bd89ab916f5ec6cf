#include "msh_check.hpp"

#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <map>
#include <set>
#include <stdexcept>
#include <unordered_set>
#include <vector>

namespace alphaflex::msh_check {
namespace {

/// Thrown with "line N: what" by the parser below; turned into the returned message.
struct Bad : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Nodes per element and dimension of gmsh's element types (gmsh's GmshDefines.h, MSH format
/// documentation); a type not listed is refused, since gmsh would not know its node count either.
bool element_type(long long type, int& nodes, int& dim) {
  static const std::map<long long, std::pair<int, int>> table = {
      {1, {2, 1}},   {2, {3, 2}},   {3, {4, 2}},   {4, {4, 3}},   {5, {8, 3}},   {6, {6, 3}},   {7, {5, 3}},
      {8, {3, 1}},   {9, {6, 2}},   {10, {9, 2}},  {11, {10, 3}}, {12, {27, 3}}, {13, {18, 3}}, {14, {14, 3}},
      {15, {1, 0}},  {16, {8, 2}},  {17, {20, 3}}, {18, {15, 3}}, {19, {13, 3}}, {20, {9, 2}},  {21, {10, 2}},
      {22, {12, 2}}, {23, {15, 2}}, {24, {15, 2}}, {25, {21, 2}}, {26, {4, 1}},  {27, {5, 1}},  {28, {6, 1}},
      {29, {20, 3}}, {30, {35, 3}}, {31, {56, 3}}, {92, {64, 3}}, {93, {125, 3}}};
  const auto it = table.find(type);
  if (it == table.end()) return false;
  nodes = it->second.first;
  dim = it->second.second;
  return true;
}

/// Whitespace-separated tokens of the file, with their line numbers, read on demand.
class Tokens {
 public:
  explicit Tokens(const std::string& text) : s_(text) {}

  [[noreturn]] void fail(const std::string& what) const { throw Bad("line " + std::to_string(line_) + ": " + what); }

  bool at_end() {
    skip();
    return pos_ >= s_.size();
  }
  std::string word(const char* what) {
    skip();
    if (pos_ >= s_.size()) fail(std::string("the file ends where ") + what + " was expected");
    const size_t b = pos_;
    while (pos_ < s_.size() && !blank(s_[pos_])) ++pos_;
    return s_.substr(b, pos_ - b);
  }
  long long integer(const char* what, long long lo, long long hi) {
    const std::string w = word(what);
    errno = 0;
    char* end = nullptr;
    const long long v = std::strtoll(w.c_str(), &end, 10);
    if (end == w.c_str() || *end != '\0' || errno == ERANGE)
      fail(std::string("expected ") + what + " (an integer), found '" + w.substr(0, 40) + "'");
    if (v < lo || v > hi)
      fail(std::string(what) + " " + w + " is outside [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    return v;
  }
  double real(const char* what) {
    const std::string w = word(what);
    char* end = nullptr;
    const double v = std::strtod(w.c_str(), &end);
    if (end == w.c_str() || *end != '\0') fail(std::string("expected ") + what + " (a number), found '" + w.substr(0, 40) + "'");
    if (!std::isfinite(v)) fail(std::string(what) + " is '" + w.substr(0, 40) + "': expected a finite number");
    return v;
  }
  /// A count of items that take at least `tokens_each` tokens each: no more than the rest of the
  /// file could hold (two bytes a token), so that no count makes anyone allocate or loop for long.
  long long count(const char* what, long long tokens_each) {
    const long long n = integer(what, 0, LLONG_MAX);
    skip();
    const long long room = static_cast<long long>(s_.size() - pos_) / 2 / tokens_each + 1;
    if (n > room)
      fail(std::string(what) + " " + std::to_string(n) + " is more than the rest of the file can hold (at most " +
           std::to_string(room) + "): the file is cut short, or the count is wrong");
    return n;
  }
  /// The rest of the current line (a physical name).
  std::string rest_of_line() {
    while (pos_ < s_.size() && (s_[pos_] == ' ' || s_[pos_] == '\t')) ++pos_;
    const size_t b = pos_;
    while (pos_ < s_.size() && s_[pos_] != '\n') ++pos_;
    std::string r = s_.substr(b, pos_ - b);
    while (!r.empty() && (r.back() == '\r' || r.back() == ' ')) r.pop_back();
    return r;
  }
  void expect(const std::string& marker) {
    const std::string w = word(marker.c_str());
    if (w != marker) fail("expected " + marker + ", found '" + w.substr(0, 40) + "'");
  }
  int line() const { return line_; }

 private:
  static bool blank(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }
  void skip() {
    while (pos_ < s_.size() && blank(s_[pos_])) {
      if (s_[pos_] == '\n') ++line_;
      ++pos_;
    }
  }
  const std::string& s_;
  size_t pos_ = 0;
  int line_ = 1;
};

constexpr long long kTagMax = INT_MAX;  // gmsh keeps entity, physical and element types as int

class Checker {
 public:
  explicit Checker(const std::string& text) : t_(text) {}

  void run() {
    t_.expect("$MeshFormat");
    const std::string version = t_.word("the MSH version");
    const long long file_type = t_.integer("the file type", 0, 1);
    const long long data_size = t_.integer("the data size", 0, 16);
    if (file_type != 0)
      t_.fail("a binary MSH file: alphaflex reads ASCII MSH only (binary files cannot be checked before gmsh reads "
              "them); save it as ASCII, e.g. gmsh FILE.msh -save -format msh41 -o ASCII.msh (Mesh.Binary = 0)");
    if (version == "4.1") v4_ = true;
    else if (version != "2.2")
      t_.fail("MSH version '" + version.substr(0, 20) + "': expected 4.1 or 2.2 (ASCII), as gmsh writes them");
    if (data_size != 8) t_.fail("data size " + std::to_string(data_size) + ": expected 8 (doubles)");
    t_.expect("$EndMeshFormat");
    while (!t_.at_end()) {
      const int line = t_.line();
      const std::string head = t_.word("a section");
      if (head.size() < 2 || head[0] != '$' || head.compare(0, 4, "$End") == 0)
        t_.fail("expected a section ($Nodes, $Elements, ...), found '" + head.substr(0, 40) + "'");
      const std::string name = head.substr(1);
      const bool known = name == "PhysicalNames" || name == "Entities" || name == "Nodes" || name == "Elements";
      if (known && !seen_.insert(name).second) t_.fail("section $" + name + " is given twice");
      if (name == "MeshFormat") t_.fail("section $MeshFormat is given twice");
      if (name == "PhysicalNames") physical_names();
      else if (name == "Entities" && v4_) entities();
      else if (name == "Nodes") nodes();
      else if (name == "Elements") elements();
      else {
        skip_section(name, line);
        continue;
      }
      t_.expect("$End" + name);
    }
    if (!seen_.count("Nodes")) t_.fail("no $Nodes section");
    if (!seen_.count("Elements")) t_.fail("no $Elements section");
  }

 private:
  void physical_names() {
    const long long n = t_.count("the number of physical names", 3);
    for (long long i = 0; i < n; ++i) {
      t_.integer("a physical group's dimension", 0, 3);
      t_.integer("a physical tag", 1, kTagMax);
      const std::string name = t_.rest_of_line();
      if (name.size() < 2 || name.front() != '"' || name.back() != '"')
        t_.fail("expected a physical name in double quotes, found '" + name.substr(0, 40) + "'");
    }
  }

  void entities() {
    if (seen_.count("Nodes")) t_.fail("$Entities must come before $Nodes");
    long long n[4];
    for (int d = 0; d < 4; ++d) n[d] = t_.count("a number of entities", 5);
    for (int d = 0; d < 4; ++d) {
      for (long long i = 0; i < n[d]; ++i) {
        const long long tag = t_.integer("an entity tag", 1, kTagMax);
        if (!entities_[d].insert(tag).second)
          t_.fail("entity " + std::to_string(tag) + " of dimension " + std::to_string(d) + " is given twice");
        for (int k = 0; k < (d == 0 ? 3 : 6); ++k) t_.real("a coordinate of the entity's box");
        const long long np = t_.count("a number of physical tags", 1);
        for (long long k = 0; k < np; ++k) t_.integer("a physical tag", -kTagMax, kTagMax);
        if (d == 0) continue;
        const long long nb = t_.count("a number of bounding entities", 1);
        for (long long k = 0; k < nb; ++k) {
          const long long b = t_.integer("a bounding entity's tag", -kTagMax, kTagMax);
          if (!entities_[d - 1].count(b < 0 ? -b : b))
            t_.fail("entity " + std::to_string(tag) + " of dimension " + std::to_string(d) + " is bounded by entity " +
                    std::to_string(b) + " of dimension " + std::to_string(d - 1) + ", which is not in $Entities");
        }
      }
    }
  }

  /// The entity (dim, tag) of a node or element block exists (when the file lists entities).
  void check_entity(long long dim, long long tag, const char* block) {
    if (!seen_.count("Entities")) return;
    if (!entities_[dim].count(tag))
      t_.fail(std::string(block) + " block of entity " + std::to_string(tag) + " (dimension " + std::to_string(dim) +
              "), which is not in $Entities");
  }

  void node(long long tag, long long lo, long long hi) {
    if (tag < lo || tag > hi)
      t_.fail("node tag " + std::to_string(tag) + " is outside [" + std::to_string(lo) + ", " + std::to_string(hi) +
              "] (the header's minNodeTag and maxNodeTag)");
    if (!nodes_.insert(tag).second) t_.fail("node " + std::to_string(tag) + " is given twice");
  }

  void nodes() {
    if (!v4_) {
      const long long n = t_.count("the number of nodes", 4);
      for (long long i = 0; i < n; ++i) {
        node(t_.integer("a node tag", 1, LLONG_MAX), 1, LLONG_MAX);
        for (int k = 0; k < 3; ++k) t_.real("a node coordinate");
      }
      return;
    }
    const long long blocks = t_.count("the number of node blocks", 4);
    const long long total = t_.count("the number of nodes", 4);
    const long long lo = t_.integer("the smallest node tag", 0, LLONG_MAX);
    const long long hi = t_.integer("the largest node tag", 0, LLONG_MAX);
    if (total > 0 && (lo < 1 || hi < lo)) t_.fail("node tags from " + std::to_string(lo) + " to " + std::to_string(hi) + ": expected 1 <= min <= max");
    long long sum = 0;
    for (long long b = 0; b < blocks; ++b) {
      const long long dim = t_.integer("a node block's entity dimension", 0, 3);
      const long long entity = t_.integer("a node block's entity tag", 1, kTagMax);
      const long long parametric = t_.integer("the parametric flag", 0, 1);
      const long long n = t_.count("the number of nodes in a block", 4);
      check_entity(dim, entity, "a node");
      if (parametric && dim == 3) t_.fail("parametric nodes on a volume (dimension 3) have no parameters");
      for (long long i = 0; i < n; ++i) node(t_.integer("a node tag", 1, LLONG_MAX), lo, hi);
      for (long long i = 0; i < n; ++i)
        for (long long k = 0; k < 3 + (parametric ? dim : 0); ++k) t_.real("a node coordinate");
      sum += n;
    }
    if (sum != total)
      t_.fail("the header counts " + std::to_string(total) + " nodes, the blocks hold " + std::to_string(sum));
  }

  void element(long long tag, long long type, long long block_dim) {
    int nn = 0, dim = 0;
    if (!element_type(type, nn, dim)) t_.fail("element " + std::to_string(tag) + " has unknown type " + std::to_string(type));
    if (block_dim >= 0 && dim != block_dim)
      t_.fail("element " + std::to_string(tag) + " of type " + std::to_string(type) + " (dimension " + std::to_string(dim) +
              ") is in a block of dimension " + std::to_string(block_dim));
    if (!elements_.insert(tag).second) t_.fail("element " + std::to_string(tag) + " is given twice");
  }

  void element_nodes(long long tag, long long type) {
    int nn = 0, dim = 0;
    element_type(type, nn, dim);
    for (int k = 0; k < nn; ++k) {
      const long long n = t_.integer("a node of an element", 1, LLONG_MAX);
      if (!nodes_.count(n))
        t_.fail("element " + std::to_string(tag) + " uses node " + std::to_string(n) + ", which is not in $Nodes");
    }
  }

  void elements() {
    if (!seen_.count("Nodes")) t_.fail("$Elements must come after $Nodes");
    if (!v4_) {
      const long long n = t_.count("the number of elements", 4);
      for (long long i = 0; i < n; ++i) {
        const long long tag = t_.integer("an element tag", 1, LLONG_MAX);
        const long long type = t_.integer("an element type", 1, kTagMax);
        element(tag, type, -1);
        const long long ntags = t_.integer("the number of an element's tags", 0, 64);
        for (long long k = 0; k < ntags; ++k) t_.integer("an element's physical or entity tag", -kTagMax, kTagMax);
        element_nodes(tag, type);
      }
      return;
    }
    const long long blocks = t_.count("the number of element blocks", 4);
    const long long total = t_.count("the number of elements", 2);
    const long long lo = t_.integer("the smallest element tag", 0, LLONG_MAX);
    const long long hi = t_.integer("the largest element tag", 0, LLONG_MAX);
    long long sum = 0;
    for (long long b = 0; b < blocks; ++b) {
      const long long dim = t_.integer("an element block's entity dimension", 0, 3);
      const long long entity = t_.integer("an element block's entity tag", 1, kTagMax);
      const long long type = t_.integer("an element type", 1, kTagMax);
      const long long n = t_.count("the number of elements in a block", 2);
      check_entity(dim, entity, "an element");
      int nn = 0, tdim = 0;
      if (!element_type(type, nn, tdim)) t_.fail("element block of unknown type " + std::to_string(type));
      for (long long i = 0; i < n; ++i) {
        const long long tag = t_.integer("an element tag", 1, LLONG_MAX);
        if (tag < lo || tag > hi)
          t_.fail("element tag " + std::to_string(tag) + " is outside [" + std::to_string(lo) + ", " + std::to_string(hi) +
                  "] (the header's minElementTag and maxElementTag)");
        element(tag, type, dim);
        element_nodes(tag, type);
      }
      sum += n;
    }
    if (sum != total)
      t_.fail("the header counts " + std::to_string(total) + " elements, the blocks hold " + std::to_string(sum));
  }

  /// A section alphaflex does not use ($Periodic, $NodeData, ...): skipped, with its end marker.
  void skip_section(const std::string& name, int line) {
    for (;;) {
      if (t_.at_end()) throw Bad("line " + std::to_string(line) + ": section $" + name + " has no $End" + name);
      const std::string w = t_.word("a section's end");
      if (w == "$End" + name) return;
      if (w.size() > 1 && w[0] == '$' && w.compare(0, 4, "$End") != 0)
        t_.fail("section $" + name + " ends without $End" + name + " (found '" + w.substr(0, 40) + "')");
    }
  }

  Tokens t_;
  bool v4_ = false;
  std::set<std::string> seen_;
  std::set<long long> entities_[4];
  std::unordered_set<long long> nodes_, elements_;
};

}  // namespace

std::string structure_error(const std::string& text) {
  try {
    Checker(text).run();
  } catch (const Bad& e) {
    return e.what();
  }
  return {};
}

}  // namespace alphaflex::msh_check
