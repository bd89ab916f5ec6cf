#include "alphaflex/io/checkpoint.hpp"

#include <hdf5.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <sstream>

#include "alphaflex/core/error.hpp"
#include "hdf5_rows.hpp"

namespace alphaflex {

using io_detail::agree;
using io_detail::Rows;

namespace {

const char* kFormat = "alphaflex checkpoint";
constexpr long long kVersion = 1;

/// FNV-1a: a stable 64-bit fingerprint of a name (stored as a signed integer).
long long fingerprint(const std::string& s) {
  std::uint64_t h = 1469598103934665603ull;
  for (unsigned char c : s) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return static_cast<long long>(h);
}

/// What identifies the model: per node its kind and name, per joint its size, type and name, per
/// element its type and name.
struct Fingerprint {
  std::vector<long long> node_kind, node_name, joint_size, joint_id, element_id;
  explicit Fingerprint(const Model& m) {
    for (const Node& n : m.nodes()) {
      node_kind.push_back(static_cast<long long>(n.kind));
      node_name.push_back(fingerprint(n.name));
    }
    for (const auto& c : m.constraints()) {
      joint_size.push_back(c->size());
      joint_id.push_back(fingerprint(std::string(c->type()) + ":" + c->name()));
    }
    for (const auto& e : m.elements()) element_id.push_back(fingerprint(std::string(e->type()) + ":" + e->name()));
  }
};


std::string numbered(const std::string& path, int k) {
  // NAME.checkpoint.h5 → NAME.checkpoint.K.h5
  const std::string stem = path.size() > 3 && path.compare(path.size() - 3, 3, ".h5") == 0 ? path.substr(0, path.size() - 3) : path;
  return stem + "." + std::to_string(k) + ".h5";
}

/// Everything of a checkpoint in the open file f; flushed, so that a full disk fails here (on
/// every rank alike: OutputError) and not in H5Fclose.
void write_checkpoint_data(io_detail::H5Calls& h5, const Subdomain& sub, hid_t f, const MechanicalState& local,
                           const Eigen::VectorXd& auxiliary, const RunPosition& p, const AlphaParameters& parameters,
                           double h) {
  const hid_t xfer = io_detail::transfer_list(h5, sub.comm());
  agree<OutputError>(sub, h5.error());
  using io_detail::write_attribute;
  const Model& g = sub.global_model();
  write_attribute(h5, f, "format", std::string(kFormat));
  write_attribute(h5, f, "version", kVersion);
  write_attribute(h5, f, "time", local.t);
  write_attribute(h5, f, "step", p.step);
  write_attribute(h5, f, "h_in_use", p.h);
  write_attribute(h5, f, "cuts_in_row", p.cuts_in_row);
  write_attribute(h5, f, "good_steps", p.good_steps);
  write_attribute(h5, f, "newton_total", p.newton_total);
  write_attribute(h5, f, "newton_max", p.newton_max);
  write_attribute(h5, f, "step_cuts", p.step_cuts);
  write_attribute(h5, f, "h_min", p.h_min);
  write_attribute(h5, f, "last_written", p.last_written);
  write_attribute(h5, f, "csv_rows", p.results.csv_rows);
  write_attribute(h5, f, "output_steps", p.results.steps);
  write_attribute(h5, f, "output_parts", p.results.parts);
  write_attribute(h5, f, "alpha_m", parameters.alpha_m);
  write_attribute(h5, f, "alpha_f", parameters.alpha_f);
  write_attribute(h5, f, "beta", parameters.beta);
  write_attribute(h5, f, "gamma", parameters.gamma);
  write_attribute(h5, f, "h", h);
  write_attribute(h5, f, "model", g.name);
  write_attribute(h5, f, "ranks", static_cast<long long>(sub.size()));
  // Group and dataset creation are collective: the ranks agree on each group before its datasets.
  agree<OutputError>(sub, h5.error());
  // The state in model order: each rank its owned rows (owned nodes come first in local vectors).
  const io_detail::StateRows rows(sub);
  const hid_t st = h5(H5Gcreate2(f, "state", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), "create the group state");
  agree<OutputError>(sub, h5.error());
  h5.group = "/state";
  io_detail::write_rows(h5, st, "q", rows.conf, 1, local.q.data(), xfer);
  io_detail::write_rows(h5, st, "v", rows.dof, 1, local.v.data(), xfer);
  io_detail::write_rows(h5, st, "qdd", rows.dof, 1, local.qdd.data(), xfer);
  io_detail::write_rows(h5, st, "a", rows.dof, 1, auxiliary.data(), xfer);
  io_detail::write_rows(h5, st, "lambda", rows.mult, 1, local.lambda.data(), xfer);
  h5(H5Gclose(st), "close the group state");
  agree<OutputError>(sub, h5.error());
  // The model's fingerprint, from the whole model (rank 0 writes it).
  const Fingerprint fp(g);
  const hid_t mg = h5(H5Gcreate2(f, "model", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), "create the group model");
  agree<OutputError>(sub, h5.error());
  h5.group = "/model";
  const bool root = sub.rank() == 0;
  auto put = [&](const char* name, const std::vector<long long>& v) {
    io_detail::write_long_rows(h5, mg, name, Rows::all_on_root(v.size(), root), v.data(), xfer);
  };
  put("node_kind", fp.node_kind);
  put("node_name", fp.node_name);
  put("joint_size", fp.joint_size);
  put("joint_id", fp.joint_id);
  put("element_id", fp.element_id);
  h5.group.clear();
  h5(H5Gclose(mg), "close the group model");
  h5(H5Pclose(xfer), "close the transfer list");
  h5(H5Fflush(f, H5F_SCOPE_LOCAL), "write the checkpoint");
  agree<OutputError>(sub, h5.error());
}

}  // namespace

long long write_checkpoint(const Subdomain& sub, const std::string& path, const MechanicalState& local,
                           const Eigen::VectorXd& auxiliary, const RunPosition& p, const AlphaParameters& parameters,
                           double h, int keep) {
  const std::string tmp = path + ".tmp";
  io_detail::H5Calls h5(tmp);
  // Room for the state and the fingerprint (8 bytes a value) and HDF5's metadata, asked before the
  // collective writes (hdf5_rows.hpp, room_for); the last checkpoint stays if there is none.
  const Model& model = sub.global_model();
  const auto values = static_cast<unsigned long long>(model.num_conf() + 3 * model.num_dofs() + model.num_multipliers() +
                                                      2 * model.nodes().size() + 2 * model.constraints().size() +
                                                      model.elements().size());
  agree<OutputError>(sub, io_detail::room_for(tmp, -1, 8 * values + 65536, "create the checkpoint"));
  const hid_t fapl = io_detail::file_access(h5, sub.comm());
  hid_t f = -1;
  if (fapl >= 0) {
    f = h5(H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl), "create the checkpoint");
    h5(H5Pclose(fapl), "close the file access list");
  }
  agree<OutputError>(sub, h5.error());
  try {
    write_checkpoint_data(h5, sub, f, local, auxiliary, p, parameters, h);
  } catch (const OutputError&) {
    // A full disk: the file goes without a second failure in HDF5 (hdf5_rows.hpp, discard_file),
    // and its space with it; the previous checkpoint stays.
    io_detail::discard_file(f, tmp);
    std::error_code ec;
    if (sub.rank() == 0) std::filesystem::remove(tmp, ec);
    throw;
  }
  h5(H5Fclose(f), "close the checkpoint");
  agree<OutputError>(sub, h5.error());
  // Rotate (rank 0): .K-1 goes, .k → .k+1, the last → .1, the new one → the name.
  const bool root = sub.rank() == 0;
  long long bytes = 0;
  if (root) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (keep > 1) {
      fs::remove(numbered(path, keep - 1), ec);
      for (int k = keep - 2; k >= 1; --k)
        if (fs::exists(numbered(path, k))) fs::rename(numbered(path, k), numbered(path, k + 1), ec);
      if (fs::exists(path)) fs::rename(path, numbered(path, 1), ec);
    }
    fs::rename(tmp, path, ec);
    if (ec) h5.fail("rename the checkpoint to " + path);  // errno says why
    else bytes = static_cast<long long>(fs::file_size(path, ec));
  }
  agree<OutputError>(sub, h5.error());
  if (sub.size() > 1) MPI_Bcast(&bytes, 1, MPI_LONG_LONG, 0, sub.comm());
  return bytes;
}

Checkpoint read_checkpoint(const Subdomain& sub, const std::string& path, const AlphaParameters& parameters, double h) {
  std::string err;
  if (sub.rank() == 0 && !std::filesystem::exists(path)) err = path + ": no such checkpoint file";
  agree<InputError>(sub, err);
  // Every rank reads the whole file (a restart happens once; the state is O(model) like the model).
  io_detail::H5Calls h5(path);
  const hid_t fapl = io_detail::file_access(h5, sub.comm());
  agree<InputError>(sub, h5.error());
  H5E_auto2_t func = nullptr;
  void* data = nullptr;
  h5(H5Eget_auto2(H5E_DEFAULT, &func, &data), "get HDF5's error printing");
  h5(H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr), "silence HDF5's error printing");  // our message, not HDF5's stack
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl);
  h5(H5Eset_auto2(H5E_DEFAULT, func, data), "restore HDF5's error printing");
  h5(H5Pclose(fapl), "close the file access list");
  agree<InputError>(sub, f < 0 ? path + ": cannot be read as an HDF5 file (not a checkpoint, or cut off)" : h5.error());
  using io_detail::read_attribute;
  std::string format;
  long long version = 0;
  if (!read_attribute(f, "format", format) || format != kFormat || !read_attribute(f, "version", version) || version != kVersion)
    err = path + ": not an alphaflex checkpoint (of version " + std::to_string(kVersion) + ")";
  Checkpoint c;
  RunPosition& p = c.position;
  double t = 0.0, am = 0, af = 0, beta = 0, gamma = 0, h_saved = 0;
  std::string model_name;
  bool ok = err.empty();
  ok = ok && read_attribute(f, "time", t) && read_attribute(f, "step", p.step) && read_attribute(f, "h_in_use", p.h) &&
       read_attribute(f, "cuts_in_row", p.cuts_in_row) && read_attribute(f, "good_steps", p.good_steps) &&
       read_attribute(f, "newton_total", p.newton_total) && read_attribute(f, "newton_max", p.newton_max) &&
       read_attribute(f, "step_cuts", p.step_cuts) && read_attribute(f, "h_min", p.h_min) &&
       read_attribute(f, "last_written", p.last_written) && read_attribute(f, "csv_rows", p.results.csv_rows) &&
       read_attribute(f, "output_steps", p.results.steps) && read_attribute(f, "output_parts", p.results.parts) &&
       read_attribute(f, "alpha_m", am) && read_attribute(f, "alpha_f", af) && read_attribute(f, "beta", beta) &&
       read_attribute(f, "gamma", gamma) && read_attribute(f, "h", h_saved) && read_attribute(f, "model", model_name);
  if (err.empty() && !ok) err = path + ": the checkpoint is incomplete (attributes missing)";

  // The model must be this scene's: counts first, then the first node, joint or element that differs.
  const Model& g = sub.global_model();
  const Fingerprint here(g);
  std::vector<long long> kind, name, jsize, jid, eid;
  if (err.empty()) {
    const hid_t mg = H5Gopen2(f, "model", H5P_DEFAULT);
    ok = mg >= 0 && io_detail::read_all(mg, "node_kind", kind) && io_detail::read_all(mg, "node_name", name) &&
         io_detail::read_all(mg, "joint_size", jsize) && io_detail::read_all(mg, "joint_id", jid) &&
         io_detail::read_all(mg, "element_id", eid);
    if (mg >= 0) ok = H5Gclose(mg) >= 0 && ok;
    if (!ok) err = path + ": the checkpoint is incomplete (its model fingerprint is missing)";
  }
  if (err.empty()) {
    std::ostringstream os;
    if (kind.size() != here.node_kind.size() || jsize.size() != here.joint_size.size() || eid.size() != here.element_id.size()) {
      os << "the checkpoint is of another model ('" << model_name << "': " << kind.size() << " nodes, " << jsize.size()
         << " joints, " << eid.size() << " elements); this scene ('" << g.name << "') has " << here.node_kind.size()
         << " nodes, " << here.joint_size.size() << " joints, " << here.element_id.size() << " elements";
    } else {
      for (size_t i = 0; i < kind.size() && os.str().empty(); ++i)
        if (kind[i] != here.node_kind[i] || name[i] != here.node_name[i])
          os << "the checkpoint is of another model: node " << i << " is '" << g.node(static_cast<int>(i)).name << "' ("
             << to_string(g.node(static_cast<int>(i)).kind) << ") here, another node in the checkpoint (its name or kind differ)";
      for (size_t i = 0; i < jsize.size() && os.str().empty(); ++i)
        if (jsize[i] != here.joint_size[i] || jid[i] != here.joint_id[i]) {
          const Constraint& cc = *g.constraints()[i];
          os << "the checkpoint is of another model: joint " << i << " is '" << cc.name() << "' (" << cc.type() << ", "
             << cc.size() << " equations) here, another joint in the checkpoint";
        }
      for (size_t i = 0; i < eid.size() && os.str().empty(); ++i)
        if (eid[i] != here.element_id[i]) {
          const Element& e = *g.elements()[i];
          os << "the checkpoint is of another model: element " << i << " is '" << e.name() << "' (" << e.type()
             << ") here, another element in the checkpoint";
        }
    }
    if (!os.str().empty()) err = path + ": " + os.str() + ". Restart with the scene the checkpoint was written by.";
  }
  MechanicalState global;
  std::vector<double> q, v, qdd, a, lambda;
  if (err.empty()) {
    const hid_t st = H5Gopen2(f, "state", H5P_DEFAULT);
    ok = st >= 0 && io_detail::read_all(st, "q", q) && io_detail::read_all(st, "v", v) &&
         io_detail::read_all(st, "qdd", qdd) && io_detail::read_all(st, "a", a) && io_detail::read_all(st, "lambda", lambda);
    if (st >= 0) ok = H5Gclose(st) >= 0 && ok;
    if (!ok || q.size() != static_cast<size_t>(g.num_conf()) || v.size() != static_cast<size_t>(g.num_dofs()) ||
        lambda.size() != static_cast<size_t>(g.num_multipliers()))
      err = path + ": the checkpoint's state is incomplete or of other sizes";
  }
  if (H5Fclose(f) < 0 && err.empty()) err = path + ": cannot be closed after reading (cut off?)";
  agree<InputError>(sub, err);
  global.t = t;
  global.q = Eigen::Map<const Eigen::VectorXd>(q.data(), static_cast<Eigen::Index>(q.size()));
  global.v = Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
  global.qdd = Eigen::Map<const Eigen::VectorXd>(qdd.data(), static_cast<Eigen::Index>(qdd.size()));
  global.lambda = Eigen::Map<const Eigen::VectorXd>(lambda.data(), static_cast<Eigen::Index>(lambda.size()));
  c.state = sub.restrict(global);
  MechanicalState aux = global;
  aux.v = Eigen::Map<const Eigen::VectorXd>(a.data(), static_cast<Eigen::Index>(a.size()));
  c.auxiliary = sub.restrict(aux).v;
  // Settings the uninterrupted run had: a restart may change them, but then it is another run.
  auto differs = [](double x, double y) { return std::fabs(x - y) > 1e-14 * std::max(1.0, std::fabs(y)); };
  if (differs(am, parameters.alpha_m) || differs(af, parameters.alpha_f) || differs(beta, parameters.beta) ||
      differs(gamma, parameters.gamma)) {
    std::ostringstream os;
    os << "the scheme differs from the checkpoint's (alpha_m, alpha_f, beta, gamma = " << am << ", " << af << ", " << beta
       << ", " << gamma << "): the run goes on with the scene's, and its results are not those of the uninterrupted run";
    c.warnings.push_back(os.str());
  }
  if (differs(h_saved, h)) {
    std::ostringstream os;
    os << "solver.h differs from the checkpoint's (" << h_saved << " s): the run goes on with h = " << h
       << " s from t = " << t << " s";
    c.warnings.push_back(os.str());
  }
  return c;
}

}  // namespace alphaflex
