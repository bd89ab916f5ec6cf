// MeshData as a flat byte buffer: the rank that reads a mesh with gmsh sends it to the others
// (io/scene.cpp), so that gmsh runs once per run and every rank builds the same model.
#include <cstring>
#include <stdexcept>

#include "alphaflex/mesh/gmsh_reader.hpp"

namespace alphaflex {

const MeshLineBlock* MeshData::find_line_block(const std::string& name) const {
  for (const MeshLineBlock& b : line_blocks)
    if (b.name == name) return &b;
  return nullptr;
}

const MeshSurfaceBlock* MeshData::find_surface_block(const std::string& name) const {
  for (const MeshSurfaceBlock& b : surface_blocks)
    if (b.name == name) return &b;
  return nullptr;
}

namespace {

class Writer {
 public:
  template <class T>
  void pod(const T& v) {
    const char* p = reinterpret_cast<const char*>(&v);
    out.insert(out.end(), p, p + sizeof(T));
  }
  template <class T>
  void pods(const T* v, size_t n) {
    pod(n);
    const char* p = reinterpret_cast<const char*>(v);
    out.insert(out.end(), p, p + n * sizeof(T));
  }
  void text(const std::string& s) { pods(s.data(), s.size()); }
  std::vector<char> out;
};

class ByteReader {
 public:
  explicit ByteReader(const std::vector<char>& b) : b_(b) {}
  template <class T>
  T pod() {
    T v;
    take(&v, sizeof(T));
    return v;
  }
  template <class T>
  std::vector<T> pods() {
    std::vector<T> v(pod<size_t>());
    take(v.data(), v.size() * sizeof(T));
    return v;
  }
  std::string text() {
    const std::vector<char> c = pods<char>();
    return std::string(c.begin(), c.end());
  }

 private:
  void take(void* dst, size_t n) {
    if (pos_ + n > b_.size()) throw std::runtime_error("unpack(MeshData): truncated buffer");
    if (n) std::memcpy(dst, b_.data() + pos_, n);
    pos_ += n;
  }
  const std::vector<char>& b_;
  size_t pos_ = 0;
};

}  // namespace

std::vector<char> pack(const MeshData& m) {
  Writer w;
  w.text(m.file);
  w.pods(m.points.data(), m.points.size());
  w.pods(m.node_tags.data(), m.node_tags.size());
  w.pod(m.line_blocks.size());
  for (const auto& b : m.line_blocks) {
    w.text(b.name);
    w.pod(b.tag);
    w.pods(b.elements.data(), b.elements.size());
    w.pods(b.element_tags.data(), b.element_tags.size());
  }
  w.pod(m.named_points.size());
  for (const auto& [name, id] : m.named_points) {
    w.text(name);
    w.pod(id);
  }
  w.pod(m.point_groups.size());
  for (const auto& [name, ids] : m.point_groups) {
    w.text(name);
    w.pods(ids.data(), ids.size());
  }
  w.pod(m.parameters.size());
  for (const auto& [name, v] : m.parameters) {
    w.text(name);
    w.pod(v);
  }
  w.pod(m.warnings.size());
  for (const auto& s : m.warnings) w.text(s);
  w.pod(m.surface_blocks.size());
  for (const auto& b : m.surface_blocks) {
    w.text(b.name);
    w.pod(b.tag);
    w.pod(b.elements.size());
    for (const auto& e : b.elements) w.pods(e.data(), e.size());
    w.pods(b.element_tags.data(), b.element_tags.size());
  }
  return w.out;
}

MeshData unpack(const std::vector<char>& bytes) {
  ByteReader r(bytes);
  MeshData m;
  m.file = r.text();
  m.points = r.pods<Eigen::Vector3d>();
  m.node_tags = r.pods<std::size_t>();
  m.line_blocks.resize(r.pod<size_t>());
  for (auto& b : m.line_blocks) {
    b.name = r.text();
    b.tag = r.pod<int>();
    b.elements = r.pods<std::array<int, 2>>();
    b.element_tags = r.pods<std::size_t>();
  }
  for (size_t k = r.pod<size_t>(); k > 0; --k) {
    const std::string name = r.text();
    m.named_points[name] = r.pod<int>();
  }
  for (size_t k = r.pod<size_t>(); k > 0; --k) {
    const std::string name = r.text();
    m.point_groups[name] = r.pods<int>();
  }
  for (size_t k = r.pod<size_t>(); k > 0; --k) {
    const std::string name = r.text();
    m.parameters[name] = r.pod<double>();
  }
  m.warnings.resize(r.pod<size_t>());
  for (auto& s : m.warnings) s = r.text();
  m.surface_blocks.resize(r.pod<size_t>());
  for (auto& b : m.surface_blocks) {
    b.name = r.text();
    b.tag = r.pod<int>();
    b.elements.resize(r.pod<size_t>());
    for (auto& e : b.elements) e = r.pods<int>();
    b.element_tags = r.pods<std::size_t>();
  }
  return m;
}

}  // namespace alphaflex
