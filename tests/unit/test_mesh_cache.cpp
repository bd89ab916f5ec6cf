// mesh/mesh_cache.hpp: meshes read before, kept by content so that a later run does not load gmsh
// (docs/performance.md, "Start-up of a small run"). Checked: a hit returns what gmsh read, bit for
// bit (pack bytes); read_mesh takes a stored entry instead of reading (an entry planted with a moved
// node comes back moved); any change of the bytes, the options or the reader is a miss; a .geo that
// may read other files is never cached; a damaged entry is ignored and rewritten; failures are
// never cached. The other unit tests run with the cache off (tests/unit/main.cpp).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "alphaflex/mesh/gmsh_reader.hpp"
#include "alphaflex/mesh/mesh_cache.hpp"
#include "test_support.hpp"

namespace alphaflex {
namespace {

namespace fs = std::filesystem;

std::string slurp(const std::string& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/// The cache in a directory of this test, set for read_mesh through ALPHAFLEX_MESH_CACHE and put
/// back to "off" (the unit tests' setting) at the end.
struct CacheDir : testing::TestOutputDir {
  explicit CacheDir(const std::string& name) : TestOutputDir("mesh_cache_" + name) {
    ::setenv("ALPHAFLEX_MESH_CACHE", file("cache").c_str(), 1);
  }
  ~CacheDir() { ::setenv("ALPHAFLEX_MESH_CACHE", "off", 1); }
  std::string copy_of_spinup_beam() const {
    return write("beam.geo", slurp(std::string(ALPHAFLEX_SOURCE_DIR) + "/meshes/spinup_beam.geo"));
  }
};

MeshOptions with_n(double n) {
  MeshOptions o;
  o.parameters["n"] = n;
  return o;
}

TEST(MeshCache, HitIsWhatGmshReadAndReadMeshUsesIt) {
  CacheDir dir("hit");
  const std::string geo = dir.copy_of_spinup_beam();
  const MeshData first = read_mesh(geo, with_n(4), "ctx");  // gmsh; stored
  ASSERT_EQ(first.points.size(), 5u);
  const MeshCache cache(dir.file("cache"), "");
  const MeshCache env = MeshCache::from_environment("x");
  EXPECT_TRUE(env.enabled());
  // The entry exists under the key read_mesh used; it unpacks to the same bytes.
  size_t entries = 0;
  for (const auto& e : fs::directory_iterator(dir.file("cache"))) entries += e.path().extension() == ".mesh";
  EXPECT_EQ(entries, 1u);
  const MeshData second = read_mesh(geo, with_n(4), "ctx");
  EXPECT_EQ(pack(second), pack(first));
  // read_mesh takes the entry and does not read the file: plant a moved node under every entry.
  MeshData moved = first;
  moved.points[4].x() += 1.0;
  for (const auto& e : fs::directory_iterator(dir.file("cache"))) {
    const std::string text = slurp(e.path().string());
    const std::string header = "alphaflex mesh cache 1\n";
    const size_t nl = text.find('\n', header.size());
    const size_t key_size = std::stoul(text.substr(header.size(), nl - header.size()));
    const std::string key = text.substr(nl + 1, key_size);
    MeshCache(dir.file("cache"), "unused").store(key, moved);  // store() takes the key as given
  }
  EXPECT_DOUBLE_EQ(read_mesh(geo, with_n(4), "ctx").points[4].x(), first.points[4].x() + 1.0);
  // A path of another name with the same bytes is the same mesh; its `file` is the path given.
  const std::string other = dir.write("other.geo", slurp(geo));
  const MeshData again = read_mesh(other, with_n(4), "ctx");
  EXPECT_EQ(again.file, other);
  EXPECT_DOUBLE_EQ(again.points[4].x(), first.points[4].x() + 1.0);
}

TEST(MeshCache, KeyChangesWithBytesOptionsAndReader) {
  CacheDir dir("key");
  const std::string geo = dir.copy_of_spinup_beam();
  const MeshCache a(dir.file("cache"), "reader A"), b(dir.file("cache"), "reader B");
  const std::string k = a.key(geo, with_n(4));
  ASSERT_FALSE(k.empty());
  EXPECT_EQ(a.key(geo, with_n(4)), k);
  EXPECT_NE(a.key(geo, with_n(5)), k);
  EXPECT_NE(a.key(geo, with_n(4.000000000000001)), k);  // options compared exactly (hex floats)
  MeshOptions size = with_n(4);
  size.element_size = 0.5;
  EXPECT_NE(a.key(geo, size), k);
  MeshOptions per_curve = with_n(4);
  per_curve.elements_per_curve = 4;
  EXPECT_NE(a.key(geo, per_curve), k);
  EXPECT_NE(b.key(geo, with_n(4)), k);
  std::ofstream(geo, std::ios::app) << "// a comment\n";
  EXPECT_NE(a.key(geo, with_n(4)), k);
  // A miss, then a fresh read: the mesh of n = 5 is not the stored one of n = 4.
  EXPECT_EQ(read_mesh(geo, with_n(4), "ctx").points.size(), 5u);
  EXPECT_EQ(read_mesh(geo, with_n(5), "ctx").points.size(), 6u);
  // Off, or no reader (the module not found): no key, nothing stored or found.
  EXPECT_TRUE(MeshCache("", "reader A").key(geo, with_n(4)).empty());
  EXPECT_TRUE(MeshCache(dir.file("cache"), "").key(geo, with_n(4)).empty());
  ::setenv("ALPHAFLEX_MESH_CACHE", "off", 1);
  EXPECT_FALSE(MeshCache::from_environment("x").enabled());
}

TEST(MeshCache, GeoReadingOtherFilesIsNotCached) {
  CacheDir dir("include");
  const MeshCache cache(dir.file("cache"), "reader");
  dir.write("points.geo", "Point(1) = {0, 0, 0};\nPoint(2) = {1, 0, 0};\n");
  for (const std::string& line : {"Include \"points.geo\";", "Merge \"points.geo\";", "x = GetEnv(\"HOME\");",
                                  "SystemCall \"true\";", "v() = ShapeFromFile(\"a.step\");"}) {
    const std::string geo = dir.write("with.geo", line + std::string("\nLine(1) = {1, 2};\n"));
    EXPECT_TRUE(cache.key(geo, MeshOptions{}).empty()) << line;
  }
  const std::string plain = dir.write("plain.geo", "Point(1) = {0, 0, 0};\nPoint(2) = {1, 0, 0};\nLine(1) = {1, 2};\n");
  EXPECT_FALSE(cache.key(plain, MeshOptions{}).empty());
  EXPECT_TRUE(cache.key(dir.file("missing.geo"), MeshOptions{}).empty());
  EXPECT_TRUE(cache.key(dir.write("beam.txt", "x"), MeshOptions{}).empty());
}

TEST(MeshCache, DamagedEntryIsIgnoredAndFailuresAreNotCached) {
  CacheDir dir("damaged");
  const std::string geo = dir.copy_of_spinup_beam();
  const MeshData first = read_mesh(geo, with_n(3), "ctx");
  for (const auto& e : fs::directory_iterator(dir.file("cache"))) {
    const std::string text = slurp(e.path().string());
    std::ofstream(e.path(), std::ios::binary) << text.substr(0, text.size() - 7);  // truncated
  }
  EXPECT_EQ(pack(read_mesh(geo, with_n(3), "ctx")), pack(first));  // read again by gmsh, rewritten
  const MeshCache cache(dir.file("cache"), "r");
  const std::string key = cache.key(geo, with_n(3));
  cache.store(key, first);
  ASSERT_TRUE(cache.find(key, geo).has_value());
  EXPECT_EQ(pack(*cache.find(key, geo)), pack(first));
  EXPECT_FALSE(cache.find(key + " ", geo).has_value());
  // A parameter out of the .geo's range: a gmsh error every time, and no entry for it.
  const size_t before = std::distance(fs::directory_iterator(dir.file("cache")), fs::directory_iterator());
  for (int k = 0; k < 2; ++k)
    EXPECT_NE(testing::input_error_of([&] { read_mesh(geo, with_n(0), "ctx"); }).find("parameter n = 0"),
              std::string::npos);
  EXPECT_EQ(static_cast<size_t>(std::distance(fs::directory_iterator(dir.file("cache")), fs::directory_iterator())),
            before);
}

}  // namespace
}  // namespace alphaflex
