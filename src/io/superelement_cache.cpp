#include "alphaflex/io/superelement_cache.hpp"

#include <hdf5.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <map>
#include <sstream>
#include <stdexcept>
#include <type_traits>

#include "alphaflex/io/scene.hpp"
#include "alphaflex/model/model.hpp"
#include "hdf5_rows.hpp"

namespace alphaflex {

namespace {

namespace fs = std::filesystem;
using io_detail::H5Calls;
using io_detail::Rows;

// Bump when the meaning of a stored field changes (not for a change of its C++ type: the layout
// signature below is part of every key).
constexpr const char* kCacheFormat = "alphaflex superelements";
constexpr long long kCacheVersion = 2;  // 2: the key has the evaluated reduction keys

// ---- ReducedBlock as a list of flat fields ------------------------------------------------------
//
// Every field is a shape (integers) and values (doubles): an Eigen matrix is its rows, columns and
// column-major values, a list its length and its items, an integer its value. One list of the
// fields below (fields()) serves writing, reading, the byte form and the layout signature, for any
// field types of these kinds: a field whose type changes (sym19 packs T and Q) needs no code here.

// A member added to one of these structs must be listed in fields(), or a block read from the cache
// would miss it: their sizes stop the build until it is (update the sizes with the list).
static_assert(sizeof(ReducedBodyMatrices) == sizeof(Eigen::MatrixXd) * 2 + sizeof(std::vector<Eigen::MatrixXd>) +
                                                 sizeof(std::vector<Eigen::Matrix3d>) + sizeof(SymmetricTensor) * 2,
              "ReducedBodyMatrices changed: list its new members in superelement_cache.cpp's fields()");
static_assert(sizeof(Superelement) == sizeof(std::vector<int>) + sizeof(Eigen::MatrixXd) * 3 + sizeof(Eigen::VectorXd),
              "Superelement changed: list its new members in superelement_cache.cpp's fields()");
static_assert(sizeof(ReducedBlock) == sizeof(int) * 2 + sizeof(Superelement) + sizeof(ReducedBodyMatrices) +
                                          sizeof(std::vector<Eigen::Vector3d>) + sizeof(std::vector<Eigen::Matrix3d>) +
                                          sizeof(std::vector<Eigen::MatrixXd>),
              "ReducedBlock changed: list its new members in superelement_cache.cpp's fields()");

template <class Block, class F>
void fields(Block& rb, F&& f) {
  f("frame_node", rb.frame_node);
  f("superelement.boundary", rb.superelement.boundary);
  f("superelement.T", rb.superelement.T);
  f("superelement.K", rb.superelement.K);
  f("superelement.M", rb.superelement.M);
  f("superelement.frequencies", rb.superelement.frequencies);
  f("matrices.M0", rb.matrices.M0);
  f("matrices.C", rb.matrices.C);
  f("matrices.M2", rb.matrices.M2);
  f("matrices.K", rb.matrices.K);
  f("matrices.T", rb.matrices.T);
  f("matrices.Q", rb.matrices.Q);
  f("positions", rb.positions);
  f("rotations", rb.rotations);
  f("shapes", rb.shapes);
}

struct Flat {
  std::vector<long long> shape;
  std::vector<double> data;
};

/// A cursor through a Flat, bounds-checked (a corrupt entry is an exception, never a wild read).
struct Cursor {
  const Flat& f;
  size_t s = 0, d = 0;
  long long next_shape() {
    if (s >= f.shape.size()) throw std::invalid_argument("shape too short");
    return f.shape[s++];
  }
  size_t left() const { return (f.shape.size() - s) + (f.data.size() - d); }
};

template <class T>
struct Codec;

template <>
struct Codec<int> {
  static std::string signature() { return "i"; }
  static void put(const int& v, Flat& f) { f.data.push_back(static_cast<double>(v)); }
  static void get(Cursor& c, int& v) {
    if (c.d >= c.f.data.size()) throw std::invalid_argument("values too short");
    const double x = c.f.data[c.d++];
    if (!(x >= -2147483648.0 && x <= 2147483647.0) || x != static_cast<double>(static_cast<long long>(x)))
      throw std::invalid_argument("not an integer");
    v = static_cast<int>(x);
  }
};

template <>
struct Codec<double> {
  static std::string signature() { return "d"; }
  static void put(const double& v, Flat& f) { f.data.push_back(v); }
  static void get(Cursor& c, double& v) {
    if (c.d >= c.f.data.size()) throw std::invalid_argument("values too short");
    v = c.f.data[c.d++];
  }
};

template <class S, int R, int C, int O, int MR, int MC>
struct Codec<Eigen::Matrix<S, R, C, O, MR, MC>> {
  static_assert(std::is_same_v<S, double>, "the cache stores doubles");
  using M = Eigen::Matrix<S, R, C, O, MR, MC>;
  static std::string signature() { return "M" + std::to_string(R) + "x" + std::to_string(C) + "o" + std::to_string(O); }
  static void put(const M& m, Flat& f) {
    f.shape.push_back(m.rows());
    f.shape.push_back(m.cols());
    for (Eigen::Index j = 0; j < m.cols(); ++j)
      for (Eigen::Index i = 0; i < m.rows(); ++i) f.data.push_back(m(i, j));
  }
  static void get(Cursor& c, M& m) {
    const long long rows = c.next_shape(), cols = c.next_shape();
    const size_t left = c.f.data.size() - c.d;
    if (rows < 0 || cols < 0 || (R != Eigen::Dynamic && rows != R) || (C != Eigen::Dynamic && cols != C) ||
        (cols > 0 && static_cast<unsigned long long>(rows) > left / static_cast<unsigned long long>(cols)))
      throw std::invalid_argument("a matrix of another size");
    m.resize(rows, cols);
    for (Eigen::Index j = 0; j < m.cols(); ++j)
      for (Eigen::Index i = 0; i < m.rows(); ++i) m(i, j) = c.f.data[c.d++];
  }
};

// A fully symmetric tensor (T, Q of geometric stiffness): shape (order, dim), values its unique
// entries in SymmetricTensor's storage order; (0, 0) and no values: empty.
template <>
struct Codec<SymmetricTensor> {
  static std::string signature() { return "S"; }
  static void put(const SymmetricTensor& t, Flat& f) {
    f.shape.push_back(t.order());
    f.shape.push_back(t.dim());
    f.data.insert(f.data.end(), t.values().begin(), t.values().end());
  }
  static void get(Cursor& c, SymmetricTensor& t) {
    const long long order = c.next_shape(), dim = c.next_shape();
    if (order == 0 && dim == 0) {
      t = SymmetricTensor();
      return;
    }
    if ((order != 3 && order != 4) || dim < 0) throw std::invalid_argument("a symmetric tensor of order 3 or 4 expected");
    // The count of unique entries, C(dim + order − 1, order), in floating point: a corrupt dim is
    // refused before anything is allocated.
    double count = 1.0;
    for (long long i = 0; i < order; ++i) count *= static_cast<double>(dim + i) / static_cast<double>(i + 1);
    if (count > static_cast<double>(c.f.data.size() - c.d)) throw std::invalid_argument("values too short");
    t = SymmetricTensor(static_cast<int>(order), static_cast<int>(dim), [&](int, int, int, int) { return c.f.data[c.d++]; });
  }
};

template <class T, class A>
struct Codec<std::vector<T, A>> {
  static std::string signature() { return "V(" + Codec<T>::signature() + ")"; }
  static void put(const std::vector<T, A>& v, Flat& f) {
    f.shape.push_back(static_cast<long long>(v.size()));
    for (const T& x : v) Codec<T>::put(x, f);
  }
  static void get(Cursor& c, std::vector<T, A>& v) {
    const long long n = c.next_shape();
    // Every item takes at least one shape entry or value: a count beyond them is corrupt (and is
    // not allocated).
    if (n < 0 || static_cast<unsigned long long>(n) > c.left()) throw std::invalid_argument("a list longer than its entry");
    v.clear();
    for (long long k = 0; k < n; ++k) {
      v.emplace_back();
      Codec<T>::get(c, v.back());
    }
  }
};

/// The names and types of the fields: part of every key, so that an entry of another layout is
/// never read as this one.
std::string layout_signature() {
  std::string s;
  ReducedBlock rb;
  fields(rb, [&](const char* name, auto& x) {
    s += std::string(name) + ":" + Codec<std::decay_t<decltype(x)>>::signature() + ";";
  });
  return s;
}

std::vector<std::pair<std::string, Flat>> flatten(const ReducedBlock& rb) {
  std::vector<std::pair<std::string, Flat>> out;
  fields(rb, [&](const char* name, const auto& x) {
    Flat f;
    Codec<std::decay_t<decltype(x)>>::put(x, f);
    out.emplace_back(name, std::move(f));
  });
  return out;
}

/// The block from its fields (in fields() order); throws std::invalid_argument naming the field
/// that does not fit.
ReducedBlock unflatten(const std::vector<std::pair<std::string, Flat>>& flat) {
  ReducedBlock rb;
  size_t k = 0;
  fields(rb, [&](const char* name, auto& x) {
    if (k >= flat.size() || flat[k].first != name) throw std::invalid_argument(std::string("field ") + name + " is missing");
    Cursor c{flat[k].second};
    try {
      Codec<std::decay_t<decltype(x)>>::get(c, x);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("field ") + name + ": " + e.what());
    }
    if (c.s != c.f.shape.size() || c.d != c.f.data.size()) throw std::invalid_argument(std::string("field ") + name + " has more values than its type");
    ++k;
  });
  return rb;
}

// ---- the key's digest ---------------------------------------------------------------------------

/// 128 bits from two 64-bit hashes of the bytes (FNV-1a, and a splitmix64-mixed sum): a name for
/// the entry, not a security measure (the key's text is compared in full as well).
class Digest {
 public:
  void add(const void* p, size_t n) {
    const auto* b = static_cast<const unsigned char*>(p);
    for (size_t i = 0; i < n; ++i) {
      a_ = (a_ ^ b[i]) * 1099511628211ull;
      b_ = mix(b_ + b[i] + 0x9E3779B97F4A7C15ull);
    }
    bytes_ += n;
  }
  void add(const std::string& s) {
    const unsigned long long n = s.size();
    add(&n, sizeof n);
    add(s.data(), s.size());
  }
  void add(Eigen::SparseMatrix<double> m) {
    m.makeCompressed();
    const long long dims[3] = {m.rows(), m.cols(), m.nonZeros()};
    add(dims, sizeof dims);
    add(m.outerIndexPtr(), sizeof(int) * static_cast<size_t>(m.outerSize() + 1));
    add(m.innerIndexPtr(), sizeof(int) * static_cast<size_t>(m.nonZeros()));
    add(m.valuePtr(), sizeof(double) * static_cast<size_t>(m.nonZeros()));
  }
  void add(const Eigen::MatrixXd& m) {
    const long long dims[2] = {m.rows(), m.cols()};
    add(dims, sizeof dims);
    add(m.data(), sizeof(double) * static_cast<size_t>(m.size()));
  }
  std::string hex() const {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%016llx%016llx", static_cast<unsigned long long>(a_ ^ bytes_),
                  static_cast<unsigned long long>(mix(b_)));
    return buf;
  }

 private:
  static std::uint64_t mix(std::uint64_t z) {
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  std::uint64_t a_ = 14695981039346656037ull, b_ = 0, bytes_ = 0;
};

std::string hex_float(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%a", v);
  return buf;
}

// ---- HDF5 ------------------------------------------------------------------------------------------

/// Names of the links in group `loc`.
std::vector<std::string> links(hid_t loc) {
  std::vector<std::string> names;
  auto collect = [](hid_t, const char* name, const H5L_info_t*, void* data) -> herr_t {
    static_cast<std::vector<std::string>*>(data)->push_back(name);
    return 0;
  };
  hsize_t idx = 0;
  if (H5Literate(loc, H5_INDEX_NAME, H5_ITER_INC, &idx, collect, &names) < 0) names.clear();
  return names;
}

/// The values of dataset `name` (at most `max_values`: a size read from a corrupt header must not
/// allocate more than the file holds); empty or what is wrong.
template <class T>
std::string read_bounded(hid_t loc, const std::string& where, const char* name, unsigned long long max_values, std::vector<T>& out) {
  if (H5Lexists(loc, name, H5P_DEFAULT) <= 0) return "the dataset " + where + "/" + name + " is missing";
  const hid_t d = H5Dopen2(loc, name, H5P_DEFAULT);
  if (d < 0) return "the dataset " + where + "/" + name + " cannot be opened (corrupted)";
  const hid_t space = H5Dget_space(d);
  const hssize_t n = space < 0 ? -1 : H5Sget_simple_extent_npoints(space);
  if (space >= 0) H5Sclose(space);
  H5Dclose(d);
  if (n < 0 || static_cast<unsigned long long>(n) > max_values)
    return "the dataset " + where + "/" + name + " has an impossible size (corrupted)";
  return io_detail::read_expected(loc, where, name, static_cast<size_t>(n), out);
}

/// Writes one entry (group `g`: the key's text and digest, the time, every field) with `h5`.
void write_entry(H5Calls& h5, hid_t g, const std::string& digest, const std::string& text, double written, const ReducedBlock& rb) {
  io_detail::write_attribute(h5, g, "key", digest);
  io_detail::write_attribute(h5, g, "key_text", text);
  io_detail::write_attribute(h5, g, "written", written);
  for (const auto& [name, f] : flatten(rb)) {
    const std::string shape = name + ".shape";
    io_detail::write_long_rows(h5, g, shape.c_str(), Rows::all_on_root(f.shape.size(), true), f.shape.data(), H5P_DEFAULT, true);
    io_detail::write_rows(h5, g, name.c_str(), Rows::all_on_root(f.data.size(), true), 1, f.data.data(), H5P_DEFAULT, true);
  }
}

/// Reads entry `block`/`digest` of the open file `f` (of `file_bytes` bytes): its packed bytes, or
/// "" and (if the entry is there but unreadable) what is wrong in `error`.
std::string read_entry(hid_t f, unsigned long long file_bytes, const std::string& block, const std::string& digest,
                       const std::string& text, std::string& error) {
  const std::string where = "/" + block + "/" + digest;
  if (H5Lexists(f, block.c_str(), H5P_DEFAULT) <= 0) return {};
  const hid_t bg = H5Gopen2(f, block.c_str(), H5P_DEFAULT);
  if (bg < 0) {
    error = "the group /" + block + " cannot be opened (corrupted)";
    return {};
  }
  std::string packed;
  if (H5Lexists(bg, digest.c_str(), H5P_DEFAULT) > 0) {
    const hid_t g = H5Gopen2(bg, digest.c_str(), H5P_DEFAULT);
    std::string stored;
    if (g < 0) {
      error = "the group " + where + " cannot be opened (corrupted)";
    } else if (!io_detail::read_attribute(g, "key_text", stored)) {
      error = "the attribute key_text of " + where + " cannot be read (corrupted)";
    } else if (stored == text) {  // else a digest collision: another block's entry, not used
      std::vector<std::pair<std::string, Flat>> flat;
      ReducedBlock shape_only;
      fields(shape_only, [&](const char* name, const auto&) {
        if (!error.empty()) return;
        Flat fl;
        const std::string s = std::string(name) + ".shape";
        error = read_bounded(g, where, s.c_str(), file_bytes / 8, fl.shape);
        if (error.empty()) error = read_bounded(g, where, name, file_bytes / 8, fl.data);
        flat.emplace_back(name, std::move(fl));
      });
      if (error.empty()) {
        try {
          packed = pack_reduced_block(unflatten(flat));
        } catch (const std::invalid_argument& e) {
          error = "the entry " + where + " does not hold a reduced block (" + e.what() + ")";
        }
      }
    }
    if (g >= 0) H5Gclose(g);
  }
  H5Gclose(bg);
  return error.empty() ? packed : std::string();
}

double cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

std::string seconds(double s) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", s);
  return buf;
}

}  // namespace

// ---- byte form ------------------------------------------------------------------------------------

std::string pack_reduced_block(const ReducedBlock& rb) {
  std::string out;
  auto put = [&](const void* p, size_t n) {
    if (n > 0) out.append(static_cast<const char*>(p), n);
  };
  for (const auto& [name, f] : flatten(rb)) {
    const unsigned long long ns = f.shape.size(), nd = f.data.size();
    put(&ns, sizeof ns);
    put(f.shape.data(), sizeof(long long) * ns);
    put(&nd, sizeof nd);
    put(f.data.data(), sizeof(double) * nd);
  }
  return out;
}

ReducedBlock unpack_reduced_block(const std::string& bytes) {
  size_t pos = 0;
  auto take = [&](void* p, size_t n) {
    if (n > bytes.size() - pos) throw std::invalid_argument("a reduced block's bytes are cut off");
    if (n == 0) return;  // an empty field: its data() may be null, which memcpy must not get
    std::memcpy(p, bytes.data() + pos, n);
    pos += n;
  };
  std::vector<std::pair<std::string, Flat>> flat;
  ReducedBlock names;
  fields(names, [&](const char* name, const auto&) {
    Flat f;
    unsigned long long ns = 0, nd = 0;
    take(&ns, sizeof ns);
    if (ns > (bytes.size() - pos) / sizeof(long long)) throw std::invalid_argument("a reduced block's bytes are cut off");
    f.shape.resize(ns);
    take(f.shape.data(), sizeof(long long) * ns);
    take(&nd, sizeof nd);
    if (nd > (bytes.size() - pos) / sizeof(double)) throw std::invalid_argument("a reduced block's bytes are cut off");
    f.data.resize(nd);
    take(f.data.data(), sizeof(double) * nd);
    flat.emplace_back(name, std::move(f));
  });
  if (pos != bytes.size()) throw std::invalid_argument("a reduced block's bytes go on after its last field");
  return unflatten(flat);
}

// ---- key ----------------------------------------------------------------------------------------------

SuperelementKey::SuperelementKey(const std::string& settings, const Model& scratch, const std::vector<int>& elements,
                                 const BlockMatrices& block)
    : nodes_(block.nodes.size()) {
  std::ostringstream t;
  t << kCacheFormat << " " << kCacheVersion << "\nlayout " << layout_signature() << "\n" << settings << "\nnodes " << scratch.nodes().size() << "\n";
  for (const Node& n : scratch.nodes()) {
    t << n.name << " " << to_string(n.kind);
    for (Eigen::Index i = 0; i < n.q0.size(); ++i) t << " " << hex_float(n.q0[i]);
    t << "\n";
  }
  t << "elements " << elements.size() << "\n";
  for (int e : elements) {
    const Element& el = *scratch.elements()[static_cast<size_t>(e)];
    t << el.type() << " " << el.name();
    for (int nd : el.nodes()) t << " " << nd;
    t << "\n";
  }
  t << "block nodes";
  for (int nd : block.nodes) t << " " << nd;
  t << "\n";
  text_ = t.str();
  Digest d;
  d.add(text_);
  d.add(block.K_sparse);  // the sections and materials, however they were given
  d.add(block.M_sparse);
  digest_ = d.hex();
  // The text names the block's structure; K and M only through the digest (their 10⁵–10⁶ values).
  text_ += "K and M: digest " + digest_ + "\n";
}

// ---- cache ----------------------------------------------------------------------------------------

SuperelementCache::SuperelementCache(std::string path, MPI_Comm comm) : path_(std::move(path)), comm_(comm) {
  if (enabled()) MPI_Comm_rank(comm_, &rank_);
}

ReducedBlock SuperelementCache::find_or_reduce(const std::string& name, const SuperelementKey& key,
                                               const std::function<ReducedBlock()>& reduce) {
  // The block's group: its name as an HDF5 link name ('/' separates groups; "." is the file's
  // root). Names that map to one group differ in the key's text, so they never share an entry.
  std::string block = name;
  std::replace(block.begin(), block.end(), '/', '_');
  if (block == ".") block = "_";
  std::string packed, warning;
  if (enabled() && rank_ == 0) {
    std::error_code ec;
    if (fs::exists(path_, ec)) {
      H5Calls silence(path_);  // HDF5's own error stack is not printed (our warning says it)
      const unsigned long long bytes = fs::file_size(path_, ec);
      const hid_t f = H5Fopen(path_.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
      std::string error;
      if (f < 0) {
        error = "cannot be read as an HDF5 file (cut off or not a superelement cache)";
      } else {
        // Rank 0 alone is here, the others wait in the broadcast below: nothing may escape (a size
        // read from a corrupt header could still make an allocation throw).
        try {
          std::string format;
          long long version = 0;
          if (!io_detail::read_attribute(f, "format", format) || format != kCacheFormat)
            error = "is not a superelement cache (its attribute 'format' is not '" + std::string(kCacheFormat) + "')";
          else if (io_detail::read_attribute(f, "version", version) && version == kCacheVersion)
            packed = read_entry(f, ec ? 0 : bytes, block, key.digest(), key.text(), error);
          // (another version: its entries are not read, and the file is rewritten)
        } catch (const std::exception& e) {
          packed.clear();
          error = std::string("cannot be read (") + e.what() + ")";
        }
        if (H5Fclose(f) < 0 && error.empty()) error = "cannot be closed after reading (cut off?)";
      }
      if (!error.empty()) {
        packed.clear();
        warning = path_ + ": " + error + "; the superelement of block '" + name + "' is computed again and the file rewritten";
      }
    }
  }
  if (enabled()) {
    packed = broadcast_text(packed, comm_);
    warning = broadcast_text(warning, comm_);
  }
  if (!packed.empty()) {
    ReducedBlock rb = unpack_reduced_block(packed);  // rank 0's own bytes: it cannot fail here
    bool fits = rb.positions.size() == key.nodes() && rb.rotations.size() == key.nodes() && rb.shapes.size() == key.nodes();
    try {
      rb.matrices.check();
    } catch (const std::invalid_argument&) {
      fits = false;
    }
    for (const auto& s : rb.shapes) fits = fits && s.rows() == 6 && s.cols() == rb.matrices.elastic();
    if (fits) {
      notes_.push_back(name + ": read from " + path_);
      read_.emplace_back(block, key.digest());
      return rb;
    }
    warning = path_ + ": the entry of block '" + name + "' is not a consistent reduced block (corrupted); it is computed again and the file rewritten";
  }
  if (!warning.empty()) warnings_.push_back(warning);
  const double c0 = cpu_seconds();
  ReducedBlock rb = reduce();
  const std::string cost = "computed in " + seconds(cpu_seconds() - c0) + " s CPU";
  if (enabled()) {
    computed_.push_back({block, key.digest(), key.text(), rb});
    notes_.push_back(name + ": " + cost + ", written to " + path_);
  } else {
    notes_.push_back(name + ": " + cost + " (no superelement cache)");
  }
  return rb;
}

void SuperelementCache::finish() {
  if (!enabled() || computed_.empty() || rank_ != 0) return;
  const fs::path final_path(path_);
  std::error_code ec;
  if (final_path.has_parent_path()) fs::create_directories(final_path.parent_path(), ec);
  const std::string tmp = path_ + ".tmp" + std::to_string(::getpid());
  H5Calls h5(tmp);
  const hid_t fapl = h5(H5Pcreate(H5P_FILE_ACCESS), "create a file access list");
  hid_t f = -1;
  if (fapl >= 0) {
    // The 1.10 file format: its object headers carry checksums (as the checkpoints).
    h5(H5Pset_libver_bounds(fapl, H5F_LIBVER_V110, H5F_LIBVER_LATEST), "choose the checksummed file format");
    f = h5(H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl), "create the superelement cache");
    h5(H5Pclose(fapl), "close the file access list");
  }
  std::map<std::string, int> kept;  // entries per block
  std::map<std::string, std::vector<std::string>> digests;
  if (f >= 0) {
    io_detail::write_attribute(h5, f, "format", std::string(kCacheFormat));
    io_detail::write_attribute(h5, f, "version", kCacheVersion);
    const double now = static_cast<double>(std::time(nullptr));
    for (const Entry& e : computed_) {
      if (!h5.error().empty()) break;
      hid_t bg = H5Lexists(f, e.block.c_str(), H5P_DEFAULT) > 0 ? H5Gopen2(f, e.block.c_str(), H5P_DEFAULT)
                                                                 : H5Gcreate2(f, e.block.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
      h5(bg, "create the group /" + e.block);
      if (bg < 0) break;
      const hid_t g = h5(H5Gcreate2(bg, e.digest.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), "create the group /" + e.block + "/" + e.digest);
      if (g >= 0) {
        h5.group = "/" + e.block + "/" + e.digest;
        write_entry(h5, g, e.digest, e.text, now, e.rb);
        h5(H5Gclose(g), "close the group " + h5.group);
        h5.group.clear();
      }
      h5(H5Gclose(bg), "close the group /" + e.block);
      ++kept[e.block];
      digests[e.block].push_back(e.digest);
    }
    // The older entries of the file: those read in this run first, then the newest, up to
    // kEntriesPerBlock per block (a study's rungs keep theirs). An unreadable file keeps none.
    const hid_t old = fs::exists(path_, ec) ? H5Fopen(path_.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT) : -1;
    if (old >= 0 && h5.error().empty()) {
      struct Old {
        std::string block, digest;
        bool read = false;
        double written = 0.0;
      };
      std::vector<Old> entries;
      std::string format;
      long long version = 0;
      if (io_detail::read_attribute(old, "format", format) && format == kCacheFormat && io_detail::read_attribute(old, "version", version) &&
          version == kCacheVersion)
        for (const std::string& b : links(old)) {
          const hid_t bg = H5Gopen2(old, b.c_str(), H5P_DEFAULT);
          if (bg < 0) continue;
          for (const std::string& dg : links(bg)) {
            Old o{b, dg};
            o.read = std::find(read_.begin(), read_.end(), std::make_pair(b, dg)) != read_.end();
            const hid_t g = H5Gopen2(bg, dg.c_str(), H5P_DEFAULT);
            if (g < 0 || !io_detail::read_attribute(g, "written", o.written)) o.written = -1.0;
            if (g >= 0) H5Gclose(g);
            entries.push_back(o);
          }
          H5Gclose(bg);
        }
      std::stable_sort(entries.begin(), entries.end(), [](const Old& x, const Old& y) {
        return x.read != y.read ? x.read : x.written > y.written;
      });
      const hid_t lcpl = H5Pcreate(H5P_LINK_CREATE);
      if (lcpl >= 0) H5Pset_create_intermediate_group(lcpl, 1);
      for (const Old& o : entries) {
        auto& mine = digests[o.block];
        if (o.written < 0.0 || kept[o.block] >= kEntriesPerBlock || std::find(mine.begin(), mine.end(), o.digest) != mine.end()) continue;
        const std::string link = o.block + "/" + o.digest;
        // A copy that fails (a corrupt entry) is left out: the next run that needs it reduces again.
        if (H5Ocopy(old, link.c_str(), f, link.c_str(), H5P_DEFAULT, lcpl) >= 0) {
          ++kept[o.block];
          mine.push_back(o.digest);
        } else if (H5Lexists(f, o.block.c_str(), H5P_DEFAULT) > 0) {
          const hid_t bg = H5Gopen2(f, o.block.c_str(), H5P_DEFAULT);
          if (bg >= 0) {
            if (H5Lexists(bg, o.digest.c_str(), H5P_DEFAULT) > 0) H5Ldelete(bg, o.digest.c_str(), H5P_DEFAULT);
            H5Gclose(bg);
          }
        }
      }
      if (lcpl >= 0) H5Pclose(lcpl);
    }
    if (old >= 0) H5Fclose(old);
    // After a failed write the file goes without a second failure in HDF5 (hdf5_rows.hpp, discard_file).
    if (h5.error().empty()) h5(H5Fclose(f), "close the superelement cache");
    else io_detail::discard_file(f, tmp);
  }
  if (h5.error().empty()) {
    fs::rename(tmp, final_path, ec);
    if (ec) h5.fail("rename the superelement cache to " + path_);
  }
  if (!h5.error().empty()) {
    fs::remove(tmp, ec);
    warnings_.push_back(h5.error() + "; the superelements are not kept (the next run reduces its blocks again)");
    // The summary's notes said "written to": they were not.
    const std::string written = ", written to " + path_;
    for (std::string& note : notes_) {
      const size_t at = note.rfind(written);
      if (at != std::string::npos && at + written.size() == note.size()) note.replace(at, written.size(), " (not kept: see the warning)");
    }
  }
}

}  // namespace alphaflex
