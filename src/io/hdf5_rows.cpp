#include "hdf5_rows.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <sys/mman.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include "alphaflex/core/fault_injection.hpp"

namespace alphaflex::io_detail {

H5Calls::H5Calls(std::string file) : file_(std::move(file)) {
  // Our message names the file, the operation and errno; HDF5's stack of a hundred lines would
  // bury it (a full disk printed it once per failed call).
  static const bool silenced = H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr) >= 0;
  (void)silenced;
  clear_errno();
}

bool H5Calls::injected_disk_full() {
  // Tests (core/fault_injection.hpp): the COUNT-th checked HDF5 call of a rank fails as on a full disk.
  if (!fault_injected("disk_full")) return false;
  errno = ENOSPC;
  return true;
}

void H5Calls::clear_errno() { errno = 0; }

void H5Calls::fail(const std::string& operation) {
  if (!error_.empty()) return;
  error_ = "cannot " + operation + ": " + file_;
  if (errno != 0) {
    error_ += std::string(" (") + std::strerror(errno) + ")";
    return;
  }
  // MPI-IO reports a failed write without errno: say when the file system is full.
  struct statvfs fs {};
  const std::string dir = std::filesystem::path(file_).parent_path().string();
  if (statvfs(dir.empty() ? "." : dir.c_str(), &fs) == 0 && fs.f_bavail * fs.f_frsize < (1u << 20))
    error_ += " (" + std::string(std::strerror(ENOSPC)) + ": " + std::to_string(fs.f_bavail * fs.f_frsize) + " bytes free)";
}

void Rows::add(unsigned long long first, unsigned long long n) {
  if (n == 0) return;
  if (!start.empty() && start.back() + count.back() == first) count.back() += n;
  else {
    start.push_back(first);
    count.push_back(n);
  }
  mine += n;
}

Rows Rows::all_on_root(unsigned long long total, bool root) {
  Rows r;
  r.total = total;
  if (root) r.add(0, total);
  return r;
}

StateRows::StateRows(const Subdomain& sub) {
  const Model& g = sub.global_model();
  conf.total = static_cast<unsigned long long>(g.num_conf());
  dof.total = static_cast<unsigned long long>(g.num_dofs());
  mult.total = static_cast<unsigned long long>(g.num_multipliers());
  for (int i = 0; i < sub.num_owned_nodes(); ++i) {
    const Node& n = g.node(sub.global_node(i));
    conf.add(static_cast<unsigned long long>(n.first_conf), static_cast<unsigned long long>(n.nconf));
    dof.add(static_cast<unsigned long long>(n.first_dof), static_cast<unsigned long long>(n.ndof));
  }
  for (size_t c = 0; c < sub.model().constraints().size(); ++c) {
    const int gc = sub.global_constraint(static_cast<int>(c));
    mult.add(static_cast<unsigned long long>(g.first_multiplier(gc)),
             static_cast<unsigned long long>(sub.model().constraints()[c]->size()));
  }
}

namespace {

/// The file dataspace of a `total` × `cols` dataset with this rank's rows selected, and the
/// matching memory dataspace (−1 where a call failed: recorded in h5).
std::pair<hid_t, hid_t> selections(H5Calls& h5, const Rows& rows, int cols, const std::string& set) {
  const hsize_t dims[2] = {rows.total, static_cast<hsize_t>(cols)};
  const int rank = cols > 1 ? 2 : 1;
  const hid_t file = h5(H5Screate_simple(rank, dims, nullptr), "create the dataspace of " + set);
  const hsize_t mdims[2] = {std::max<hsize_t>(rows.mine, 1), static_cast<hsize_t>(cols)};
  const hid_t mem = h5(H5Screate_simple(rank, mdims, nullptr), "create the memory dataspace of " + set);
  if (file < 0 || mem < 0) return {file, mem};
  h5(H5Sselect_none(file), "select the rows of " + set);
  if (rows.mine == 0) {
    h5(H5Sselect_none(mem), "select the rows of " + set);
    return {file, mem};
  }
  for (size_t k = 0; k < rows.start.size(); ++k) {
    const hsize_t off[2] = {rows.start[k], 0}, cnt[2] = {rows.count[k], static_cast<hsize_t>(cols)};
    h5(H5Sselect_hyperslab(file, H5S_SELECT_OR, off, nullptr, cnt, nullptr), "select the rows of " + set);
  }
  return {file, mem};
}

void write_typed(H5Calls& h5, hid_t loc, const char* name, const Rows& rows, int cols, hid_t file_type, hid_t mem_type,
                 const void* data, hid_t xfer, bool checksum = false) {
  const std::string set = "the dataset " + (h5.group.empty() ? std::string() : h5.group + "/") + name;
  const auto [file_space, mem_space] = selections(h5, rows, cols, set);
  hid_t dcpl = H5P_DEFAULT;
  if (checksum && rows.total > 0) {
    // One chunk up to 2^20 rows (a filter works on chunks); Fletcher32 over each.
    const hsize_t chunk[2] = {std::min<hsize_t>(rows.total, hsize_t{1} << 20), static_cast<hsize_t>(cols)};
    dcpl = h5(H5Pcreate(H5P_DATASET_CREATE), "create the creation list of " + set);
    if (dcpl >= 0) {
      h5(H5Pset_chunk(dcpl, cols > 1 ? 2 : 1, chunk), "chunk " + set);
      h5(H5Pset_fletcher32(dcpl), "add a checksum to " + set);
    }
  }
  if (file_space >= 0 && mem_space >= 0 && dcpl >= 0) {
    const hid_t d = h5(H5Dcreate2(loc, name, file_type, file_space, H5P_DEFAULT, dcpl, H5P_DEFAULT), "create " + set);
    if (d >= 0 && rows.total > 0) h5(H5Dwrite(d, mem_type, mem_space, file_space, xfer, data), "write " + set);
    if (d >= 0) h5(H5Dclose(d), "close " + set);
  }
  if (dcpl >= 0 && dcpl != H5P_DEFAULT) h5(H5Pclose(dcpl), "close the creation list of " + set);
  if (mem_space >= 0) h5(H5Sclose(mem_space), "close the memory dataspace of " + set);
  if (file_space >= 0) h5(H5Sclose(file_space), "close the dataspace of " + set);
}

}  // namespace

template <class T>
bool read_typed(hid_t loc, const char* name, hid_t mem_type, std::vector<T>& out) {
  if (H5Lexists(loc, name, H5P_DEFAULT) <= 0) return false;
  const hid_t set = H5Dopen2(loc, name, H5P_DEFAULT);
  if (set < 0) return false;
  const hid_t space = H5Dget_space(set);
  const hssize_t n = space < 0 ? -1 : H5Sget_simple_extent_npoints(space);
  bool ok = n >= 0;
  if (ok) {
    out.resize(static_cast<size_t>(n));
    ok = out.empty() || H5Dread(set, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) >= 0;
  }
  if (space >= 0) ok = H5Sclose(space) >= 0 && ok;
  return H5Dclose(set) >= 0 && ok;
}

void write_rows(H5Calls& h5, hid_t loc, const char* name, const Rows& rows, int cols, const double* data, hid_t xfer,
                bool checksum) {
  write_typed(h5, loc, name, rows, cols, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, data, xfer, checksum);
}

void write_int_rows(H5Calls& h5, hid_t loc, const char* name, const Rows& rows, const int* data, hid_t xfer) {
  write_typed(h5, loc, name, rows, 1, H5T_STD_I32LE, H5T_NATIVE_INT, data, xfer);
}

void write_long_rows(H5Calls& h5, hid_t loc, const char* name, const Rows& rows, const long long* data, hid_t xfer,
                     bool checksum) {
  write_typed(h5, loc, name, rows, 1, H5T_STD_I64LE, H5T_NATIVE_LLONG, data, xfer, checksum);
}

template <class T>
std::string read_expected_typed(hid_t loc, const std::string& where, const char* name, size_t expected, hid_t mem_type,
                                std::vector<T>& out) {
  const std::string set = "the dataset " + where + "/" + name;
  if (H5Lexists(loc, name, H5P_DEFAULT) <= 0) return set + " is missing";
  const hid_t d = H5Dopen2(loc, name, H5P_DEFAULT);
  if (d < 0) return set + " cannot be opened (corrupted)";
  const hid_t space = H5Dget_space(d);
  const hssize_t n = space < 0 ? -1 : H5Sget_simple_extent_npoints(space);
  std::string err;
  if (n < 0) err = set + " has no readable size (corrupted)";
  else if (static_cast<size_t>(n) != expected)
    err = set + " holds " + std::to_string(n) + " values where this model has " + std::to_string(expected);
  if (err.empty()) {
    out.resize(expected);
    if (expected > 0 && H5Dread(d, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) < 0)
      err = set + " cannot be read: its checksum does not match (the file changed after it was written)";
  }
  if (space >= 0) H5Sclose(space);
  H5Dclose(d);
  return err;
}

std::string read_expected(hid_t loc, const std::string& where, const char* name, size_t expected, std::vector<double>& out) {
  return read_expected_typed(loc, where, name, expected, H5T_NATIVE_DOUBLE, out);
}

std::string read_expected(hid_t loc, const std::string& where, const char* name, size_t expected, std::vector<long long>& out) {
  return read_expected_typed(loc, where, name, expected, H5T_NATIVE_LLONG, out);
}

bool read_all(hid_t loc, const char* name, std::vector<double>& out) { return read_typed(loc, name, H5T_NATIVE_DOUBLE, out); }
bool read_all(hid_t loc, const char* name, std::vector<long long>& out) { return read_typed(loc, name, H5T_NATIVE_LLONG, out); }

namespace {

/// Attribute `name` of type `file_type` on `space` (closed here), written from `value`.
void write_attribute_of(H5Calls& h5, hid_t loc, const char* name, hid_t file_type, hid_t mem_type, hid_t space,
                        const void* value) {
  const std::string what = std::string("the attribute ") + name;
  if (space < 0) return;
  const hid_t attr = h5(H5Acreate2(loc, name, file_type, space, H5P_DEFAULT, H5P_DEFAULT), "create " + what);
  if (attr >= 0) {
    h5(H5Awrite(attr, mem_type, value), "write " + what);
    h5(H5Aclose(attr), "close " + what);
  }
  h5(H5Sclose(space), "close the dataspace of " + what);
}

}  // namespace

void write_attribute(H5Calls& h5, hid_t loc, const char* name, double value) {
  const hid_t space = h5(H5Screate(H5S_SCALAR), std::string("create the dataspace of the attribute ") + name);
  write_attribute_of(h5, loc, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, space, &value);
}

void write_attribute(H5Calls& h5, hid_t loc, const char* name, long long value) {
  const hid_t space = h5(H5Screate(H5S_SCALAR), std::string("create the dataspace of the attribute ") + name);
  write_attribute_of(h5, loc, name, H5T_STD_I64LE, H5T_NATIVE_LLONG, space, &value);
}

void write_attribute_array(H5Calls& h5, hid_t loc, const char* name, double value) {
  const hsize_t one = 1;
  const hid_t space = h5(H5Screate_simple(1, &one, nullptr), std::string("create the dataspace of the attribute ") + name);
  write_attribute_of(h5, loc, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, space, &value);
}

void write_attribute(H5Calls& h5, hid_t loc, const char* name, const std::string& value) {
  const std::string what = std::string("the string type of the attribute ") + name;
  const hid_t type = h5(H5Tcopy(H5T_C_S1), "create " + what);
  if (type < 0) return;
  h5(H5Tset_size(type, std::max<size_t>(value.size(), 1)), "size " + what);
  const hid_t space = h5(H5Screate(H5S_SCALAR), std::string("create the dataspace of the attribute ") + name);
  std::string padded = value;
  padded.resize(std::max<size_t>(value.size(), 1), '\0');
  write_attribute_of(h5, loc, name, type, type, space, padded.data());
  h5(H5Tclose(type), "close " + what);
}

namespace {

bool read_attribute_as(hid_t loc, const char* name, hid_t mem_type, void* value) {
  if (H5Aexists(loc, name) <= 0) return false;
  const hid_t attr = H5Aopen(loc, name, H5P_DEFAULT);
  if (attr < 0) return false;
  const bool ok = H5Aread(attr, mem_type, value) >= 0;
  return H5Aclose(attr) >= 0 && ok;
}

}  // namespace

bool read_attribute(hid_t loc, const char* name, double& value) {
  return read_attribute_as(loc, name, H5T_NATIVE_DOUBLE, &value);
}

bool read_attribute(hid_t loc, const char* name, long long& value) {
  return read_attribute_as(loc, name, H5T_NATIVE_LLONG, &value);
}

bool read_attribute(hid_t loc, const char* name, std::string& value) {
  if (H5Aexists(loc, name) <= 0) return false;
  const hid_t attr = H5Aopen(loc, name, H5P_DEFAULT);
  if (attr < 0) return false;
  const hid_t type = H5Aget_type(attr);
  const size_t n = type < 0 ? 0 : H5Tget_size(type);
  std::string buf(n, '\0');
  const hid_t mem = n == 0 ? -1 : H5Tcopy(H5T_C_S1);
  bool ok = mem >= 0 && H5Tset_size(mem, n) >= 0 && H5Aread(attr, mem, buf.data()) >= 0;
  if (mem >= 0) ok = H5Tclose(mem) >= 0 && ok;
  if (type >= 0) ok = H5Tclose(type) >= 0 && ok;
  ok = H5Aclose(attr) >= 0 && ok;
  buf.erase(std::find(buf.begin(), buf.end(), '\0'), buf.end());
  value = buf;
  return ok;
}

void discard_file(hid_t file, const std::string& path) {
  if (file < 0) return;
  // Every descriptor of this process open on the file (the sec2 driver's, or MPI-IO's on this
  // rank) is pointed at an anonymous memory file: HDF5's flush on close then writes there, and
  // succeeds (the file's metadata, at most the size of the file), and the close completes.
  // The memory files get one size on every rank, beyond any address HDF5 can still write to (its
  // end of allocation, the same on every rank, plus 1 GiB: sparse, no memory): with MPI-IO each
  // rank asks its own descriptor for the file's size on close and resizes the file collectively
  // if it is short; ranks that saw different sizes would call that collective apart (a hang).
  haddr_t eoa = 0;
  if (H5Fget_eoa(file, &eoa) < 0) eoa = 0;
  const off_t size = static_cast<off_t>(eoa) + (off_t{1} << 30);
  struct stat target {};
  if (stat(path.c_str(), &target) == 0) {
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator("/proc/self/fd", ec)) {
      const int fd = std::atoi(entry.path().filename().c_str());
      struct stat st {};
      if (fstat(fd, &st) != 0 || st.st_dev != target.st_dev || st.st_ino != target.st_ino) continue;
      const int mem = memfd_create("alphaflex-discarded", MFD_CLOEXEC);
      if (mem < 0) continue;
      if (ftruncate(mem, size) == 0) dup2(mem, fd);
      close(mem);
    }
  }
  const unsigned types = H5F_OBJ_DATASET | H5F_OBJ_GROUP | H5F_OBJ_ATTR | H5F_OBJ_DATATYPE | H5F_OBJ_LOCAL;
  const ssize_t n = H5Fget_obj_count(file, types);
  if (n > 0) {
    std::vector<hid_t> ids(static_cast<size_t>(n));
    const ssize_t got = H5Fget_obj_ids(file, types, static_cast<size_t>(n), ids.data());
    for (ssize_t k = 0; k < got; ++k) {
      const hid_t id = ids[static_cast<size_t>(k)];
      switch (H5Iget_type(id)) {
        case H5I_DATASET: H5Dclose(id); break;
        case H5I_GROUP: H5Gclose(id); break;
        case H5I_ATTR: H5Aclose(id); break;
        case H5I_DATATYPE: H5Tclose(id); break;
        default: break;
      }
    }
  }
  H5Fclose(file);
}

std::string room_for(const std::string& path, hid_t file, unsigned long long more, const std::string& operation) {
  if (fault_injected("no_room_check")) return {};  // tests: a full disk found by HDF5's writes
  struct statvfs fs {};
  const std::string dir = std::filesystem::path(path).parent_path().string();
  if (statvfs(dir.empty() ? "." : dir.c_str(), &fs) != 0) return {};  // cannot tell: let the write say
  const unsigned long long free_bytes = static_cast<unsigned long long>(fs.f_bavail) * fs.f_frsize;
  unsigned long long pending = 0;
  haddr_t eoa = 0;
  struct stat st {};
  if (file >= 0 && H5Fget_eoa(file, &eoa) >= 0 && stat(path.c_str(), &st) == 0) {
    const unsigned long long on_disk = static_cast<unsigned long long>(st.st_blocks) * 512ull;
    if (eoa > on_disk) pending = eoa - on_disk;
  }
  const unsigned long long need = pending + more;
  if (free_bytes >= need) return {};
  return "cannot " + operation + ": " + path + " (" + std::strerror(ENOSPC) + ": " + std::to_string(free_bytes) +
         " bytes free, about " + std::to_string(need) + " needed)";
}

hid_t file_access(H5Calls& h5, MPI_Comm comm) {
  int size = 1;
  MPI_Comm_size(comm, &size);
  const hid_t fapl = h5(H5Pcreate(H5P_FILE_ACCESS), "create a file access list");
  if (fapl >= 0 && size > 1) h5(H5Pset_fapl_mpio(fapl, comm, MPI_INFO_NULL), "set MPI-IO file access");
  return fapl;
}

hid_t transfer_list(H5Calls& h5, MPI_Comm comm) {
  int size = 1;
  MPI_Comm_size(comm, &size);
  const hid_t xfer = h5(H5Pcreate(H5P_DATASET_XFER), "create a transfer list");
  if (xfer >= 0 && size > 1) h5(H5Pset_dxpl_mpio(xfer, H5FD_MPIO_COLLECTIVE), "set collective MPI-IO transfers");
  return xfer;
}

}  // namespace alphaflex::io_detail
