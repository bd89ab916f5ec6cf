#include "hdf5_rows.hpp"

#include <algorithm>

namespace alphaflex::io_detail {

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
/// matching memory dataspace.
std::pair<hid_t, hid_t> selections(const Rows& rows, int cols) {
  const hsize_t dims[2] = {rows.total, static_cast<hsize_t>(cols)};
  const int rank = cols > 1 ? 2 : 1;
  const hid_t file = H5Screate_simple(rank, dims, nullptr);
  const hsize_t mdims[2] = {std::max<hsize_t>(rows.mine, 1), static_cast<hsize_t>(cols)};
  const hid_t mem = H5Screate_simple(rank, mdims, nullptr);
  H5Sselect_none(file);
  if (rows.mine == 0) {
    H5Sselect_none(mem);
    return {file, mem};
  }
  for (size_t k = 0; k < rows.start.size(); ++k) {
    const hsize_t off[2] = {rows.start[k], 0}, cnt[2] = {rows.count[k], static_cast<hsize_t>(cols)};
    H5Sselect_hyperslab(file, H5S_SELECT_OR, off, nullptr, cnt, nullptr);
  }
  return {file, mem};
}

std::string write_typed(hid_t loc, const char* name, const Rows& rows, int cols, hid_t file_type, hid_t mem_type,
                        const void* data, hid_t xfer) {
  const auto [file_space, mem_space] = selections(rows, cols);
  std::string error;
  const hid_t set = H5Dcreate2(loc, name, file_type, file_space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  if (set < 0) error = std::string("cannot create the dataset ") + name;
  else if (rows.total > 0 && H5Dwrite(set, mem_type, mem_space, file_space, xfer, data) < 0)
    error = std::string("cannot write the dataset ") + name + " (file system full or gone?)";
  if (set >= 0) H5Dclose(set);
  H5Sclose(mem_space);
  H5Sclose(file_space);
  return error;
}

template <class T>
bool read_typed(hid_t loc, const char* name, hid_t mem_type, std::vector<T>& out) {
  if (H5Lexists(loc, name, H5P_DEFAULT) <= 0) return false;
  const hid_t set = H5Dopen2(loc, name, H5P_DEFAULT);
  if (set < 0) return false;
  const hid_t space = H5Dget_space(set);
  out.resize(static_cast<size_t>(H5Sget_simple_extent_npoints(space)));
  const bool ok = out.empty() || H5Dread(set, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) >= 0;
  H5Sclose(space);
  H5Dclose(set);
  return ok;
}

}  // namespace

std::string write_rows(hid_t loc, const char* name, const Rows& rows, int cols, const double* data, hid_t xfer) {
  return write_typed(loc, name, rows, cols, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, data, xfer);
}

std::string write_int_rows(hid_t loc, const char* name, const Rows& rows, const int* data, hid_t xfer) {
  return write_typed(loc, name, rows, 1, H5T_STD_I32LE, H5T_NATIVE_INT, data, xfer);
}

std::string write_long_rows(hid_t loc, const char* name, const Rows& rows, const long long* data, hid_t xfer) {
  return write_typed(loc, name, rows, 1, H5T_STD_I64LE, H5T_NATIVE_LLONG, data, xfer);
}

bool read_all(hid_t loc, const char* name, std::vector<double>& out) { return read_typed(loc, name, H5T_NATIVE_DOUBLE, out); }
bool read_all(hid_t loc, const char* name, std::vector<long long>& out) { return read_typed(loc, name, H5T_NATIVE_LLONG, out); }

void write_attribute(hid_t loc, const char* name, double value) {
  const hid_t space = H5Screate(H5S_SCALAR);
  const hid_t attr = H5Acreate2(loc, name, H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(attr, H5T_NATIVE_DOUBLE, &value);
  H5Aclose(attr);
  H5Sclose(space);
}

void write_attribute(hid_t loc, const char* name, long long value) {
  const hid_t space = H5Screate(H5S_SCALAR);
  const hid_t attr = H5Acreate2(loc, name, H5T_STD_I64LE, space, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(attr, H5T_NATIVE_LLONG, &value);
  H5Aclose(attr);
  H5Sclose(space);
}

void write_attribute(hid_t loc, const char* name, const std::string& value) {
  const hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, std::max<size_t>(value.size(), 1));
  const hid_t space = H5Screate(H5S_SCALAR);
  const hid_t attr = H5Acreate2(loc, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
  std::string padded = value;
  padded.resize(std::max<size_t>(value.size(), 1), '\0');
  H5Awrite(attr, type, padded.data());
  H5Aclose(attr);
  H5Sclose(space);
  H5Tclose(type);
}

bool read_attribute(hid_t loc, const char* name, double& value) {
  if (H5Aexists(loc, name) <= 0) return false;
  const hid_t attr = H5Aopen(loc, name, H5P_DEFAULT);
  const bool ok = H5Aread(attr, H5T_NATIVE_DOUBLE, &value) >= 0;
  H5Aclose(attr);
  return ok;
}

bool read_attribute(hid_t loc, const char* name, long long& value) {
  if (H5Aexists(loc, name) <= 0) return false;
  const hid_t attr = H5Aopen(loc, name, H5P_DEFAULT);
  const bool ok = H5Aread(attr, H5T_NATIVE_LLONG, &value) >= 0;
  H5Aclose(attr);
  return ok;
}

bool read_attribute(hid_t loc, const char* name, std::string& value) {
  if (H5Aexists(loc, name) <= 0) return false;
  const hid_t attr = H5Aopen(loc, name, H5P_DEFAULT);
  const hid_t type = H5Aget_type(attr);
  const size_t n = H5Tget_size(type);
  std::string buf(n, '\0');
  const hid_t mem = H5Tcopy(H5T_C_S1);
  H5Tset_size(mem, n);
  const bool ok = H5Aread(attr, mem, buf.data()) >= 0;
  H5Tclose(mem);
  H5Tclose(type);
  H5Aclose(attr);
  buf.erase(std::find(buf.begin(), buf.end(), '\0'), buf.end());
  value = buf;
  return ok;
}

hid_t file_access(MPI_Comm comm) {
  int size = 1;
  MPI_Comm_size(comm, &size);
  const hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  if (size > 1) H5Pset_fapl_mpio(fapl, comm, MPI_INFO_NULL);
  return fapl;
}

hid_t transfer_list(MPI_Comm comm) {
  int size = 1;
  MPI_Comm_size(comm, &size);
  const hid_t xfer = H5Pcreate(H5P_DATASET_XFER);
  if (size > 1) H5Pset_dxpl_mpio(xfer, H5FD_MPIO_COLLECTIVE);
  return xfer;
}

}  // namespace alphaflex::io_detail
