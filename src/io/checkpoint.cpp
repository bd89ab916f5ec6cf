#include "alphaflex/io/checkpoint.hpp"

#include <hdf5.h>

#include <algorithm>
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
// Version 2: every dataset with a Fletcher32 checksum and the metadata in HDF5's checksummed
// format (object headers v2), plus the elements' physics; version 1 files are still read.
constexpr long long kVersion = 2;

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

/// What each element does at the model's initial state (t = 0): the sums of |r|, |K|, |C| and |M|,
/// four numbers per element. A changed parameter (a beam's EA through --set, a mass, a spring's
/// stiffness, a load) changes one of them; names and types (Fingerprint) do not see it.
std::vector<double> element_physics(const Model& m) {
  std::vector<double> out;
  out.reserve(4 * m.elements().size());
  const MechanicalState s0 = m.initial_state();
  LocalResidual res;
  for (const auto& e : m.elements()) {
    const LocalState ls = m.local_state(*e, s0);
    res.reset(static_cast<int>(ls.v.size()), true);
    e->evaluate(ls, res, true);
    out.insert(out.end(), {res.r.cwiseAbs().sum(), res.K.cwiseAbs().sum(), res.C.cwiseAbs().sum(), res.M.cwiseAbs().sum()});
  }
  return out;
}

/// The number of values of dataset `name` in `loc` (−1 if missing or unreadable), without reading it.
long long extent(hid_t loc, const char* name) {
  if (H5Lexists(loc, name, H5P_DEFAULT) <= 0) return -1;
  const hid_t d = H5Dopen2(loc, name, H5P_DEFAULT);
  if (d < 0) return -1;
  const hid_t space = H5Dget_space(d);
  const hssize_t n = space < 0 ? -1 : H5Sget_simple_extent_npoints(space);
  if (space >= 0) H5Sclose(space);
  H5Dclose(d);
  return n;
}


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
  write_attribute(h5, f, "t_anchor", p.t_anchor);
  write_attribute(h5, f, "h_anchor", p.h_anchor);
  write_attribute(h5, f, "steps_from_anchor", p.k);
  write_attribute(h5, f, "error_prev", p.error_prev);
  write_attribute(h5, f, "h_max", p.h_max);
  write_attribute(h5, f, "h_auxiliary", p.h_auxiliary);
  write_attribute(h5, f, "accepted_steps", p.accepted);
  write_attribute(h5, f, "rejected_steps", p.rejected);
  write_attribute(h5, f, "history_count", p.history_count);
  write_attribute(h5, f, "history_h1", p.history_h1);
  write_attribute(h5, f, "history_h2", p.history_h2);
  // The accumulated sensors' running sums (app/sensor_integrals.hpp): a few scalars, the same on
  // every rank, so attributes (checksummed with the metadata).
  write_attribute(h5, f, "accumulated_count", static_cast<long long>(p.accumulated.size()));
  for (size_t i = 0; i < p.accumulated.size(); ++i)
    write_attribute(h5, f, ("accumulated_" + std::to_string(i)).c_str(), p.accumulated[i]);
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
  io_detail::write_rows(h5, st, "q", rows.conf, 1, local.q.data(), xfer, true);
  io_detail::write_rows(h5, st, "v", rows.dof, 1, local.v.data(), xfer, true);
  io_detail::write_rows(h5, st, "qdd", rows.dof, 1, local.qdd.data(), xfer, true);
  io_detail::write_rows(h5, st, "a", rows.dof, 1, auxiliary.data(), xfer, true);
  io_detail::write_rows(h5, st, "lambda", rows.mult, 1, local.lambda.data(), xfer, true);
  if (p.history_count >= 1) io_detail::write_rows(h5, st, "history_m1", rows.dof, 1, p.history_m1.data(), xfer, true);
  if (p.history_count >= 2) io_detail::write_rows(h5, st, "history_m2", rows.dof, 1, p.history_m2.data(), xfer, true);
  h5(H5Gclose(st), "close the group state");
  agree<OutputError>(sub, h5.error());
  // The model's fingerprint, from the whole model (rank 0 writes it).
  const Fingerprint fp(g);
  const hid_t mg = h5(H5Gcreate2(f, "model", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), "create the group model");
  agree<OutputError>(sub, h5.error());
  h5.group = "/model";
  const bool root = sub.rank() == 0;
  auto put = [&](const char* name, const std::vector<long long>& v) {
    io_detail::write_long_rows(h5, mg, name, Rows::all_on_root(v.size(), root), v.data(), xfer, true);
  };
  put("node_kind", fp.node_kind);
  put("node_name", fp.node_name);
  put("joint_size", fp.joint_size);
  put("joint_id", fp.joint_id);
  put("element_id", fp.element_id);
  // The elements' physics (rank 0 evaluates them: the rows are its own).
  const std::vector<double> physics = root ? element_physics(g) : std::vector<double>();
  io_detail::write_rows(h5, mg, "element_physics", Rows::all_on_root(g.elements().size(), root), 4, physics.data(), xfer, true);
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
    // The 1.10 file format: its object headers (attributes, dataspaces) carry checksums.
    h5(H5Pset_libver_bounds(fapl, H5F_LIBVER_V110, H5F_LIBVER_LATEST), "choose the checksummed file format");
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
  if (!read_attribute(f, "format", format) || format != kFormat || !read_attribute(f, "version", version) || version < 1 ||
      version > kVersion)
    err = path + ": not an alphaflex checkpoint (of version 1 to " + std::to_string(kVersion) + ")";
  Checkpoint c;
  RunPosition& p = c.position;
  double t = 0.0, am = 0, af = 0, beta = 0, gamma = 0, h_saved = 0;
  std::string model_name;
  bool ok = err.empty();
  // Each attribute by name: a missing or unreadable one (version 2: a changed byte fails the object
  // header's checksum) is named.
  const std::pair<const char*, double*> reals[] = {{"time", &t}, {"h_in_use", &p.h}, {"h_min", &p.h_min}, {"alpha_m", &am},
                                                   {"alpha_f", &af}, {"beta", &beta}, {"gamma", &gamma}, {"h", &h_saved}};
  const std::pair<const char*, long long*> counts[] = {
      {"step", &p.step}, {"cuts_in_row", &p.cuts_in_row}, {"good_steps", &p.good_steps}, {"newton_total", &p.newton_total},
      {"newton_max", &p.newton_max}, {"step_cuts", &p.step_cuts}, {"last_written", &p.last_written},
      {"csv_rows", &p.results.csv_rows}, {"output_steps", &p.results.steps}, {"output_parts", &p.results.parts}};
  std::string bad;
  for (const auto& [key, value] : reals)
    if (bad.empty() && ok && !(read_attribute(f, key, *value) && std::isfinite(*value))) bad = key;
  for (const auto& [key, value] : counts)
    if (bad.empty() && ok && !(read_attribute(f, key, *value) && *value >= 0)) bad = key;
  if (bad.empty() && ok && !read_attribute(f, "model", model_name)) bad = "model";
  if (!bad.empty())
    err = path + ": the checkpoint's attribute '" + bad + "' is missing, unreadable or out of range (the file is incomplete or corrupted)";
  // The step controller's state (absent from checkpoints written before it was kept).
  p.controller = err.empty() && read_attribute(f, "t_anchor", p.t_anchor) && read_attribute(f, "h_anchor", p.h_anchor) &&
                 read_attribute(f, "steps_from_anchor", p.k) && read_attribute(f, "error_prev", p.error_prev) &&
                 read_attribute(f, "h_max", p.h_max) && read_attribute(f, "h_auxiliary", p.h_auxiliary) &&
                 read_attribute(f, "accepted_steps", p.accepted) && read_attribute(f, "rejected_steps", p.rejected) &&
                 read_attribute(f, "history_count", p.history_count) && read_attribute(f, "history_h1", p.history_h1) &&
                 read_attribute(f, "history_h2", p.history_h2);
  if (p.controller && err.empty() &&
      (p.history_count < 0 || p.history_count > 2 || !std::isfinite(p.t_anchor) || !std::isfinite(p.h_anchor) ||
       !std::isfinite(p.h_auxiliary) || !std::isfinite(p.history_h1) || !std::isfinite(p.history_h2)))
    err = path + ": the checkpoint's step-controller attributes are out of range (the file is corrupted)";
  if (!p.controller) p.history_count = 0;
  // The accumulated sensors (absent from checkpoints written before they were kept: none). The
  // count is bounded before anything is allocated (a flipped byte must not ask for 10^12 values).
  if (long long count = 0; err.empty() && read_attribute(f, "accumulated_count", count)) {
    if (count < 0 || count > 1000000)
      err = path + ": the checkpoint's attribute 'accumulated_count' is out of range (the file is corrupted)";
    for (long long i = 0; err.empty() && i < count; ++i) {
      double value = 0.0;
      const std::string key = "accumulated_" + std::to_string(i);
      if (!(read_attribute(f, key.c_str(), value) && std::isfinite(value)))
        err = path + ": the checkpoint's attribute '" + key + "' is missing, unreadable or out of range (the file is incomplete or corrupted)";
      else
        p.accumulated.push_back(value);
    }
  }

  // The model must be this scene's: counts first, then the first node, joint or element that differs.
  const Model& g = sub.global_model();
  const Fingerprint here(g);
  std::vector<long long> kind, name, jsize, jid, eid;
  std::vector<double> physics;
  if (err.empty()) {
    const hid_t mg = H5Gopen2(f, "model", H5P_DEFAULT);
    if (mg < 0) err = path + ": the checkpoint's group /model is missing or corrupted";
    // Sizes first, read without allocating: another model is told as such (its counts).
    const long long nn = mg < 0 ? -1 : extent(mg, "node_kind"), nj = mg < 0 ? -1 : extent(mg, "joint_size"),
                    ne = mg < 0 ? -1 : extent(mg, "element_id");
    if (err.empty() && nn >= 0 && nj >= 0 && ne >= 0 &&
        (static_cast<size_t>(nn) != here.node_kind.size() || static_cast<size_t>(nj) != here.joint_size.size() ||
         static_cast<size_t>(ne) != here.element_id.size())) {
      std::ostringstream os;
      os << path << ": the checkpoint is of another model ('" << model_name << "': " << nn << " nodes, " << nj
         << " joints, " << ne << " elements); this scene ('" << g.name << "') has " << here.node_kind.size() << " nodes, "
         << here.joint_size.size() << " joints, " << here.element_id.size()
         << " elements. Restart with the scene the checkpoint was written by.";
      err = os.str();
    }
    const std::pair<const char*, std::pair<std::vector<long long>*, size_t>> sets[] = {
        {"node_kind", {&kind, here.node_kind.size()}},   {"node_name", {&name, here.node_name.size()}},
        {"joint_size", {&jsize, here.joint_size.size()}}, {"joint_id", {&jid, here.joint_id.size()}},
        {"element_id", {&eid, here.element_id.size()}}};
    for (const auto& [set, to] : sets)
      if (err.empty()) {
        err = io_detail::read_expected(mg, "/model", set, to.second, *to.first);
        if (!err.empty()) err = path + ": " + err;
      }
    if (err.empty() && version >= 2) {
      err = io_detail::read_expected(mg, "/model", "element_physics", 4 * here.element_id.size(), physics);
      if (!err.empty()) err = path + ": " + err;
    }
    if (mg >= 0) H5Gclose(mg);
  }
  if (err.empty()) {
    std::ostringstream os;
    {
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
  std::vector<double> q, v, qdd, a, lambda, m1, m2;
  if (err.empty()) {
    const hid_t st = H5Gopen2(f, "state", H5P_DEFAULT);
    if (st < 0) err = path + ": the checkpoint's group /state is missing or corrupted";
    const auto nc = static_cast<size_t>(g.num_conf()), nd = static_cast<size_t>(g.num_dofs()),
               nm = static_cast<size_t>(g.num_multipliers());
    const std::pair<const char*, std::pair<std::vector<double>*, size_t>> sets[] = {
        {"q", {&q, nc}}, {"v", {&v, nd}}, {"qdd", {&qdd, nd}}, {"a", {&a, nd}}, {"lambda", {&lambda, nm}}};
    for (const auto& [set, to] : sets)
      if (err.empty()) {
        err = io_detail::read_expected(st, "/state", set, to.second, *to.first);
        if (!err.empty()) err = path + ": " + err;
      }
    // The adaptive steps' error-estimator history (checkpoints of adaptive runs).
    if (err.empty() && p.history_count >= 1) err = io_detail::read_expected(st, "/state", "history_m1", nd, m1);
    if (err.empty() && p.history_count >= 2) err = io_detail::read_expected(st, "/state", "history_m2", nd, m2);
    if (!err.empty() && err.rfind(path, 0) != 0) err = path + ": " + err;
    for (const auto& [set, to] : sets)
      if (err.empty() && !std::all_of(to.first->begin(), to.first->end(), [](double x) { return std::isfinite(x); }))
        err = path + ": the dataset /state/" + set + " holds a value that is not finite (the file is corrupted)";
    if (st >= 0) H5Gclose(st);
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
  for (auto [from, to] : {std::pair{&m1, &p.history_m1}, std::pair{&m2, &p.history_m2}})
    if (!from->empty()) {
      aux.v = Eigen::Map<const Eigen::VectorXd>(from->data(), static_cast<Eigen::Index>(from->size()));
      *to = sub.restrict(aux).v;
    }
  // Settings the uninterrupted run had: a restart may change them, but then it is another run.
  auto differs = [](double x, double y) { return std::fabs(x - y) > 1e-14 * std::max(1.0, std::fabs(y)); };
  if (differs(am, parameters.alpha_m) || differs(af, parameters.alpha_f) || differs(beta, parameters.beta) ||
      differs(gamma, parameters.gamma)) {
    std::ostringstream os;
    os << "the scheme differs from the checkpoint's (alpha_m, alpha_f, beta, gamma = " << am << ", " << af << ", " << beta
       << ", " << gamma << "): the run goes on with the scene's, and its results are not those of the uninterrupted run";
    c.warnings.push_back(os.str());
  }
  c.scene_h = h_saved;
  // The physics: a parameter changed since the checkpoint (e.g. a beam's EA through --set) makes
  // another run from there on; said with the first element whose response at t = 0 differs.
  if (!physics.empty()) {
    const std::vector<double> now = element_physics(g);
    const char* what[] = {"load and internal force", "stiffness", "damping", "mass"};
    for (size_t i = 0; i < now.size(); ++i)
      if (differs(now[i], physics[i])) {
        const Element& e = *g.elements()[i / 4];
        std::ostringstream os;
        os << "element '" << e.name() << "' (" << e.type() << ") differs from the checkpoint's: its " << what[i % 4]
           << " at the initial state sums to " << now[i] << " here, " << physics[i]
           << " in the checkpoint (a changed parameter): the run goes on with the scene's, and its results are not those of the uninterrupted run";
        c.warnings.push_back(os.str());
        break;
      }
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
