#include "alphaflex/mesh/mesh_cache.hpp"

#include <unistd.h>

#include <cctype>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>
#include <system_error>

namespace alphaflex {

namespace {

// Bump when the entry layout or MeshData's pack() changes.
constexpr const char* kMagic = "alphaflex mesh cache 1\n";
constexpr std::uintmax_t kMaxSourceBytes = 4u << 20;

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

/// gmsh's .geo commands and functions through which a script reads other files, the environment
/// or the clock (gmsh reference manual, "Gmsh scripting language"): with any of them, even in a
/// comment, the script's bytes do not determine its mesh, and it is not cached.
bool reads_outside(const std::string& text) {
  static const std::set<std::string> words = {
      "Include", "Merge", "MergeWithBoundingBox", "ShapeFromFile", "Open", "OpenProject", "GetEnv",
      "GetString", "GetNumber", "SystemCall", "NonBlockingSystemCall", "OnelabRun", "Exists", "FileExists",
      "Today", "Rand", "Plugin"};
  std::string word;
  for (size_t i = 0; i <= text.size(); ++i) {
    const char c = i < text.size() ? text[i] : ' ';
    if (std::isalnum(static_cast<unsigned char>(c)) || c == '_') {
      word += c;
    } else if (!word.empty()) {
      if (words.count(word)) return true;
      word.clear();
    }
  }
  return false;
}

std::string key_hex_float(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%a", v);
  return buf;
}

/// FNV-1a, 64 bits: only the entry's file name (the key is compared in full).
std::uint64_t fnv1a(const std::string& s) {
  std::uint64_t h = 14695981039346656037ull;
  for (unsigned char c : s) h = (h ^ c) * 1099511628211ull;
  return h;
}

bool read_file(const std::filesystem::path& p, std::string& out) {
  std::ifstream in(p, std::ios::binary);
  if (!in) return false;
  out.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  return !in.bad();
}

}  // namespace

MeshCache MeshCache::from_environment(const std::string& reader) {
  std::filesystem::path dir;
  if (const char* e = std::getenv("ALPHAFLEX_MESH_CACHE"); e && *e) {
    const std::string v = e;
    if (v != "off" && v != "0") dir = v;
  } else if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) {
    dir = std::filesystem::path(x) / "alphaflex" / "meshes";
  } else if (const char* h = std::getenv("HOME"); h && *h) {
    dir = std::filesystem::path(h) / ".cache" / "alphaflex" / "meshes";
  }
  return MeshCache(dir, reader);
}

MeshCache::MeshCache(std::filesystem::path dir, std::string reader) : dir_(std::move(dir)), reader_(std::move(reader)) {}

std::string MeshCache::key(const std::string& path, const MeshOptions& options) const {
  if (!enabled() || reader_.empty()) return {};
  const std::string ext = lower_extension(path);
  if (ext != ".geo" && ext != ".msh") return {};
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return {};
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec || size > kMaxSourceBytes) return {};
  std::string bytes;
  if (!read_file(path, bytes)) return {};
  if (ext == ".geo" && reads_outside(bytes)) return {};
  std::ostringstream k;
  k << "reader " << reader_ << "\nextension " << ext << "\nelements_per_curve " << options.elements_per_curve
    << "\nelement_size " << key_hex_float(options.element_size) << "\nparameters " << options.parameters.size() << "\n";
  for (const auto& [name, value] : options.parameters) k << name.size() << ' ' << name << ' ' << key_hex_float(value) << "\n";
  k << "bytes " << bytes.size() << "\n" << bytes;
  return k.str();
}

std::filesystem::path MeshCache::entry_path(const std::string& key) const {
  char name[40];
  std::snprintf(name, sizeof name, "%016llx.mesh", static_cast<unsigned long long>(fnv1a(key)));
  return dir_ / name;
}

std::optional<MeshData> MeshCache::find(const std::string& key, const std::string& path) const {
  if (key.empty()) return std::nullopt;
  std::string entry;
  if (!read_file(entry_path(key), entry)) return std::nullopt;
  // magic, key length (decimal) and newline, key, then pack(MeshData).
  const std::string magic = kMagic;
  if (entry.compare(0, magic.size(), magic) != 0) return std::nullopt;
  size_t pos = magic.size();
  const size_t nl = entry.find('\n', pos);
  if (nl == std::string::npos) return std::nullopt;
  const std::string length = entry.substr(pos, nl - pos);
  if (length != std::to_string(key.size())) return std::nullopt;
  pos = nl + 1;
  if (entry.size() < pos + key.size() || entry.compare(pos, key.size(), key) != 0) return std::nullopt;
  pos += key.size();
  try {
    MeshData mesh = unpack(std::vector<char>(entry.begin() + static_cast<std::ptrdiff_t>(pos), entry.end()));
    mesh.file = path;
    return mesh;
  } catch (const std::exception&) {
    return std::nullopt;  // a truncated or foreign entry: read the mesh again
  }
}

void MeshCache::store(const std::string& key, const MeshData& mesh) const {
  if (key.empty()) return;
  std::error_code ec;
  std::filesystem::create_directories(dir_, ec);
  if (ec) return;
  const std::filesystem::path final_path = entry_path(key);
  const std::filesystem::path tmp = final_path.string() + ".tmp" + std::to_string(::getpid());
  {
    std::ofstream out(tmp, std::ios::binary);
    if (!out) return;
    const std::vector<char> bytes = pack(mesh);
    out << kMagic << key.size() << "\n" << key;
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (!out) {
      out.close();
      std::filesystem::remove(tmp, ec);
      return;
    }
  }
  std::filesystem::rename(tmp, final_path, ec);
  if (ec) std::filesystem::remove(tmp, ec);
}

}  // namespace alphaflex
