#include "alphaflex/study/run_groups.hpp"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <numeric>
#include <stdexcept>
#include <thread>

#include "alphaflex/core/error.hpp"

namespace alphaflex::study {

int default_ranks_per_run(int unknowns, int ranks) { return unknowns <= kSmallSceneUnknowns ? 1 : ranks; }

std::string ranks_per_run_problem(int k, int ranks) {
  const std::string n = std::to_string(ranks);
  if (k < 1) return "--ranks-per-run: expected a whole number of ranks >= 1, got " + std::to_string(k);
  if (k > ranks)
    return "--ranks-per-run " + std::to_string(k) + ": more ranks per run than the job has (" + n + ")";
  if (ranks % k != 0)
    return "--ranks-per-run " + std::to_string(k) + ": does not divide the job's " + n +
           " ranks into groups of equal size (give a divisor of " + n + ")";
  return "";
}

RunGroups::RunGroups(MPI_Comm comm, int ranks_per_run) : comm_(comm) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  groups_ = size / ranks_per_run;
  group_index_ = rank / ranks_per_run;  // consecutive ranks together: they share a node first
  MPI_Comm_split(comm, group_index_, rank, &group_);
  MPI_Comm_rank(group_, &group_rank_);
  // One node: a counter in memory every rank maps (MPI-3 shared windows), read and advanced with
  // the processor's atomic fetch-and-add: no rank needs to be in an MPI call for another to take
  // its next run. Across nodes the counter would need MPI's one-sided progress: static shares.
  MPI_Comm node;
  MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, rank, MPI_INFO_NULL, &node);
  int node_size = 0, one_node = 0;
  MPI_Comm_size(node, &node_size);
  one_node = node_size == size ? 1 : 0;
  MPI_Allreduce(MPI_IN_PLACE, &one_node, 1, MPI_INT, MPI_MIN, comm);
  if (one_node && groups_ > 1) {
    void* base = nullptr;
    MPI_Win_allocate_shared(rank == 0 ? static_cast<MPI_Aint>(sizeof(long)) : 0, sizeof(long), MPI_INFO_NULL, node, &base,
                            &window_);
    MPI_Aint bytes = 0;
    int unit = 0;
    void* first = nullptr;
    MPI_Win_shared_query(window_, 0, &bytes, &unit, &first);
    counter_ = static_cast<long*>(first);
    if (rank == 0) __atomic_store_n(counter_, 0L, __ATOMIC_SEQ_CST);
    MPI_Barrier(comm);
  }
  MPI_Comm_free(&node);
}

RunGroups::~RunGroups() {
  if (window_ != MPI_WIN_NULL) MPI_Win_free(&window_);
  if (group_ != MPI_COMM_NULL) MPI_Comm_free(&group_);
}

long RunGroups::next_task() const { return __atomic_fetch_add(counter_, 1L, __ATOMIC_SEQ_CST); }

long RunGroups::from_leader(long value) const {
  MPI_Request req;
  MPI_Ibcast(&value, 1, MPI_LONG, 0, group_, &req);
  for (int done = 0;;) {
    MPI_Test(&req, &done, MPI_STATUS_IGNORE);
    if (done) return value;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

std::vector<int> RunGroups::assign(const std::vector<double>& cost) const {
  std::vector<size_t> order(cost.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return cost[a] > cost[b]; });
  std::vector<double> load(static_cast<size_t>(groups_), 0.0);
  std::vector<int> group(cost.size(), 0);
  for (size_t t : order) {
    const auto g = static_cast<size_t>(std::min_element(load.begin(), load.end()) - load.begin());
    group[t] = static_cast<int>(g);
    load[g] += cost[t];
  }
  return group;
}

void RunGroups::wait_for_all() const { wait_asleep(comm_); }

void wait_asleep(MPI_Comm comm) {
  // A non-blocking barrier tested every millisecond: a group that is done sleeps instead of
  // spinning in a blocking collective, which would take a core from the groups still running
  // (Open MPI polls) whenever the job has no more cores than ranks.
  MPI_Request req;
  MPI_Ibarrier(comm, &req);
  for (int done = 0;;) {
    MPI_Test(&req, &done, MPI_STATUS_IGNORE);
    if (done) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

std::vector<std::string> RunGroups::allgather(const std::string& mine) const {
  wait_for_all();
  int size = 1;
  MPI_Comm_size(comm_, &size);
  int len = static_cast<int>(mine.size());
  std::vector<int> lens(static_cast<size_t>(size)), offsets(static_cast<size_t>(size), 0);
  MPI_Allgather(&len, 1, MPI_INT, lens.data(), 1, MPI_INT, comm_);
  for (size_t r = 1; r < lens.size(); ++r) offsets[r] = offsets[r - 1] + lens[r - 1];
  std::string all(static_cast<size_t>(offsets.back() + lens.back()), '\0');
  MPI_Allgatherv(mine.data(), len, MPI_CHAR, all.data(), lens.data(), offsets.data(), MPI_CHAR, comm_);
  std::vector<std::string> out;
  for (size_t r = 0; r < lens.size(); ++r) out.push_back(all.substr(static_cast<size_t>(offsets[r]), static_cast<size_t>(lens[r])));
  return out;
}

namespace {

/// Bytes of plain values, strings and vectors, read back in the order written (same machine and
/// build on every rank, so no byte-order question).
struct Writer {
  std::string b;
  template <class T>
  void put(const T& x) {
    static_assert(std::is_trivially_copyable<T>::value, "plain values only");
    b.append(reinterpret_cast<const char*>(&x), sizeof x);
  }
  void put(const std::string& s) {
    put(static_cast<long>(s.size()));
    b.append(s);
  }
  void put(const std::vector<double>& v) {
    put(static_cast<long>(v.size()));
    b.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(double));
  }
  void put(const Eigen::VectorXd& v) { put(std::vector<double>(v.data(), v.data() + v.size())); }
};

struct Reader {
  const std::string& b;
  size_t at = 0;
  template <class T>
  void get(T& x) {
    static_assert(std::is_trivially_copyable<T>::value, "plain values only");
    std::memcpy(&x, b.data() + at, sizeof x);
    at += sizeof x;
  }
  void get(std::string& s) {
    long n = 0;
    get(n);
    s = b.substr(at, static_cast<size_t>(n));
    at += static_cast<size_t>(n);
  }
  void get(std::vector<double>& v) {
    long n = 0;
    get(n);
    v.resize(static_cast<size_t>(n));
    std::memcpy(v.data(), b.data() + at, static_cast<size_t>(n) * sizeof(double));
    at += static_cast<size_t>(n) * sizeof(double);
  }
  void get(Eigen::VectorXd& v) {
    std::vector<double> x;
    get(x);
    v = Eigen::Map<Eigen::VectorXd>(x.data(), static_cast<Eigen::Index>(x.size()));
  }
};

template <class IO, class Row>
void each_field(IO& io, Row& r) {
  io(r.method), io(r.label), io(r.params.scheme), io(r.params.alpha_m), io(r.params.alpha_f), io(r.params.beta),
      io(r.params.gamma), io(r.scaling), io(r.h), io(r.tol), io(r.t_end), io(r.ok), io(r.failure), io(r.steps),
      io(r.newton_total), io(r.newton_max), io(r.cpu), io(r.wall);
}

}  // namespace

std::string pack(const std::vector<RunOutcome>& outcomes) {
  Writer w;
  auto put = [&](const auto& x) { w.put(x); };
  w.put(static_cast<long>(outcomes.size()));
  for (const auto& o : outcomes) {
    w.put(o.task);
    each_field(put, o.row);
    w.put(static_cast<long>(o.row.errors.size()));
    for (const auto& [k, v] : o.row.errors) w.put(k), w.put(v);
    w.put(static_cast<long>(o.row.extra.size()));
    for (const auto& [k, v] : o.row.extra) w.put(k), w.put(v);
    w.put(static_cast<long>(o.sensor_names.size()));
    for (const auto& s : o.sensor_names) w.put(s);
    w.put(o.final_sensors);
    w.put(o.final_state.t);
    w.put(o.final_state.q), w.put(o.final_state.v), w.put(o.final_state.qdd), w.put(o.final_state.lambda);
    w.put(o.times);
    w.put(static_cast<long>(o.histories.size()));
    for (const auto& h : o.histories) w.put(h);
    w.put(static_cast<long>(o.energy.size()));
    for (const auto& e : o.energy)
      w.put(e.variant), w.put(e.part), w.put(e.kind), w.put(e.elements), w.put(e.mean), w.put(e.peak), w.put(e.share_mean),
          w.put(e.share_peak);
    w.put(o.history_t);
    w.put(static_cast<long>(o.history.size()));
    for (const auto& v : o.history) w.put(v);
    w.put(o.error_code);
    w.put(o.error);
  }
  return w.b;
}

std::vector<RunOutcome> unpack(const std::string& bytes) {
  std::vector<RunOutcome> out;
  if (bytes.empty()) return out;
  Reader r{bytes};
  auto get = [&](auto& x) { r.get(x); };
  long n = 0, m = 0;
  r.get(n);
  for (long i = 0; i < n; ++i) {
    RunOutcome o;
    r.get(o.task);
    each_field(get, o.row);
    r.get(m);
    for (long j = 0; j < m; ++j) {
      std::string k;
      double v = 0.0;
      r.get(k), r.get(v);
      o.row.errors[k] = v;
    }
    r.get(m);
    for (long j = 0; j < m; ++j) {
      std::string k;
      double v = 0.0;
      r.get(k), r.get(v);
      o.row.extra.emplace_back(k, v);
    }
    r.get(m);
    o.sensor_names.resize(static_cast<size_t>(m));
    for (auto& s : o.sensor_names) r.get(s);
    r.get(o.final_sensors);
    r.get(o.final_state.t);
    r.get(o.final_state.q), r.get(o.final_state.v), r.get(o.final_state.qdd), r.get(o.final_state.lambda);
    r.get(o.times);
    r.get(m);
    o.histories.resize(static_cast<size_t>(m));
    for (auto& h : o.histories) r.get(h);
    r.get(m);
    o.energy.resize(static_cast<size_t>(m));
    for (auto& e : o.energy)
      r.get(e.variant), r.get(e.part), r.get(e.kind), r.get(e.elements), r.get(e.mean), r.get(e.peak), r.get(e.share_mean),
          r.get(e.share_peak);
    r.get(o.history_t);
    r.get(m);
    o.history.resize(static_cast<size_t>(m));
    for (auto& v : o.history) r.get(v);
    r.get(o.error_code);
    r.get(o.error);
    out.push_back(std::move(o));
  }
  return out;
}

void rethrow(const RunOutcome& o) {
  switch (o.error_code) {
    case 1: throw InputError(o.error);
    case 3: throw SolverError(o.error);
    case 5: throw Interrupted(o.error);
    case 6: throw OutputError(o.error);
    default: throw std::runtime_error(o.error);
  }
}

}  // namespace alphaflex::study
