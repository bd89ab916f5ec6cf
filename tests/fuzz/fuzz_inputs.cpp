// Fuzz test of the input path: thousands of mutated scenes and meshes through read_scene_text and
// the model builder, up to the point where the run would take its first step (run_simulation with
// RunOptions::stop_after_start: partition, DOF map, assembly structure, solver, consistent start),
// and mutated study files through the study-spec parser (study::read_study).
//
//   fuzz_inputs [--source DIR] [--work DIR] [--scene-cases N] [--msh-cases N] [--study-cases N]
//               [--seed N] [--time-limit S] [--case ID] [--verbose]
//
// Seeds: every *.yaml under inputs/ and tests/, and meshes: meshes/*.msh and a .msh written here
// by gmsh from every meshes/*.geo that a seed scene uses (MSH 4.1, and 2.2 for the small ones),
// each read through the scene that uses its .geo, with `mesh:` pointing at the mutated file.
// Study seeds: inputs/studies/*.yaml and tests/study/**/*.yaml (IDs "study:PATH#K"), each mutated
// like a scene and read by read_study with the scene of inputs/ whose name starts its own (else
// the slider-crank), or as the scene itself when the file is a scene with a study: block. The
// mutated file is written at the seed's own relative place in a copy of the source tree's
// directories (WORK/study_tree, the rest of the tree linked), so that its relative paths (the
// reference CSV, the variants' scenes) resolve as they do for the seed.
// Case ID "inputs/andrews.yaml#17" is mutation 17 of that seed; its random choices come from
// (--seed, ID) only, so `--case ID` reruns one case exactly (the failure report prints the
// command, and writes the mutated files under WORK/failures).
//
// A case passes if the scene (study) is accepted, or rejected with an InputError whose message
// starts with the scene's (study file's) name, then ":LINE" optionally, then ": KEY: what" (a key, a mesh entity, a
// joint, ...: the part before the next ": "). It fails on any other exception type (SolverError,
// std::out_of_range, YAML::Exception, ...), on a message that does not start with the file name
// or names nothing, on a crash (signal or sanitizer report: the case is printed before the process
// dies) and on a hang (a case longer than --time-limit: reported by a watchdog thread, exit 4).
#include <cxxabi.h>
#include <gmsh.h>
#include <petscsys.h>
#include <signal.h>
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <mutex>
#include <sstream>
#include <string>
#include <thread>
#include <typeinfo>
#include <vector>

#include "alphaflex/app/simulation.hpp"
#include "alphaflex/core/error.hpp"
#include "alphaflex/core/mpi_singleton.hpp"
#include "alphaflex/io/scene.hpp"
#include "alphaflex/study/study_spec.hpp"
#include "mutator.hpp"

#if defined(__SANITIZE_ADDRESS__)
#define ALPHAFLEX_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define ALPHAFLEX_ASAN 1
#endif
#endif
#if defined(ALPHAFLEX_ASAN) || defined(ALPHAFLEX_SANITIZE)
#include <sanitizer/common_interface_defs.h>
#endif

namespace fs = std::filesystem;
using namespace alphaflex;

namespace {

struct Options {
  std::string source = ALPHAFLEX_SOURCE_DIR;
  /// Scratch files and failures; by default under the system's temporary directory, not in the
  /// working directory (which may be the source tree).
  std::string work = (fs::temp_directory_path() / "alphaflex_fuzz_work").string();
  int scene_cases = 40;  ///< mutated cases per scene seed
  int msh_cases = 40;    ///< mutated cases per mesh seed
  int study_cases = 40;  ///< mutated cases per study seed
  std::uint64_t seed = 20240601;
  double time_limit = 10.0;  ///< s per case
  std::string only;          ///< run this case only
  bool verbose = false;
};

/// What is being fuzzed: a scene file, a mesh read through a scene that uses it, or a study file.
struct Seed {
  std::string id;     ///< path relative to the source tree (case IDs, messages)
  std::string label;  ///< the scene's (study's) file name as the reader sees it (absolute path)
  std::string text;   ///< the scene, the .msh, or the study
  bool msh = false;
  YAML::Node scene;   ///< msh seeds: the scene whose mesh.file is replaced by the mutated .msh
  bool study = false;       ///< a study file: the mutated text is written to `label`, read by read_study
  std::string study_scene;  ///< study seeds: the scene it studies (empty: the file is that scene)
};

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

void write_file(const fs::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  out << text;
  if (!out) throw std::runtime_error("cannot write " + p.string());
}

std::string demangle(const char* name) {
  int status = 0;
  char* d = abi::__cxa_demangle(name, nullptr, nullptr, &status);
  std::string out = status == 0 && d ? d : name;
  std::free(d);
  return out;
}

// ---- The current case, for the crash handlers and the watchdog ------------------------------------
// Handlers must not allocate: the banner is formatted into a fixed buffer before each case.
char g_banner[16384];
std::atomic<long long> g_case_start_ns{0};  // 0: no case running

void set_banner(const std::string& text) {
  const size_t n = std::min(text.size(), sizeof g_banner - 1);
  std::memcpy(g_banner, text.data(), n);
  g_banner[n] = '\0';
}

void write_banner(const char* why) {
  const ssize_t a = write(2, why, std::strlen(why));
  const ssize_t b = write(2, g_banner, std::strlen(g_banner));
  (void)a;
  (void)b;
}

extern "C" void on_fatal_signal(int sig) {
  write_banner("\nFUZZ FAILURE: fatal signal in case:\n");
  signal(sig, SIG_DFL);
  raise(sig);
}

#if defined(ALPHAFLEX_ASAN) || defined(ALPHAFLEX_SANITIZE)
extern "C" void on_sanitizer_death() { write_banner("\nFUZZ FAILURE: sanitizer report in case:\n"); }
#endif

void install_crash_handlers() {
#if defined(ALPHAFLEX_ASAN) || defined(ALPHAFLEX_SANITIZE)
  __sanitizer_set_death_callback(on_sanitizer_death);
#endif
  // Under AddressSanitizer SIGSEGV/SIGBUS/SIGFPE are its own (it reports them, then the callback).
#if !defined(ALPHAFLEX_ASAN)
  for (int sig : {SIGSEGV, SIGBUS, SIGFPE, SIGILL}) signal(sig, on_fatal_signal);
#endif
  signal(SIGABRT, on_fatal_signal);
}

long long now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// Ends the process when a case runs longer than the limit: an in-process case cannot be
/// interrupted, and a hang must be a failure, not a test that never ends.
class Watchdog {
 public:
  explicit Watchdog(double limit_s) : limit_ns_(static_cast<long long>(limit_s * 1e9)), thread_([this] { loop(); }) {}
  ~Watchdog() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    cv_.notify_all();
    thread_.join();
  }

 private:
  void loop() {
    std::unique_lock<std::mutex> lock(mutex_);
    while (!cv_.wait_for(lock, std::chrono::milliseconds(50), [this] { return stop_; })) {
      const long long start = g_case_start_ns.load();
      if (start != 0 && now_ns() - start > limit_ns_) {
        char head[128];
        std::snprintf(head, sizeof head, "\nFUZZ FAILURE: hang: the case ran longer than %.1f s:\n", limit_ns_ * 1e-9);
        write_banner(head);
        std::_Exit(4);
      }
    }
  }
  long long limit_ns_;
  std::mutex mutex_;
  std::condition_variable cv_;
  bool stop_ = false;
  std::thread thread_;
};

// ---- Seeds ----------------------------------------------------------------------------------------

std::vector<fs::path> yaml_files(const fs::path& dir) {
  std::vector<fs::path> out;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file() && e.path().extension() == ".yaml") out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

/// The .geo a scene's mesh.file names (resolved against the scene's directory), or empty.
fs::path scene_geo(const fs::path& scene) {
  try {
    const YAML::Node root = YAML::LoadFile(scene.string());
    if (!root.IsMap() || !root["mesh"] || !root["mesh"].IsMap() || !root["mesh"]["file"]) return {};
    fs::path p = root["mesh"]["file"].as<std::string>();
    if (p.is_relative()) p = scene.parent_path() / p;
    return p.extension() == ".geo" && fs::exists(p) ? fs::canonical(p) : fs::path();
  } catch (const std::exception&) {
    return {};
  }
}

/// meshes `geo` with gmsh as alphaflex would (2D with physical surfaces, else 1D) and writes it.
void write_msh(const fs::path& geo, const fs::path& out, double version) {
  gmsh::initialize(0, nullptr, false);
  gmsh::option::setNumber("General.Terminal", 0);
  gmsh::open(geo.string());
  gmsh::vectorpair surfaces;
  gmsh::model::getPhysicalGroups(surfaces, 2);
  gmsh::model::mesh::generate(surfaces.empty() ? 1 : 2);
  gmsh::option::setNumber("Mesh.MshFileVersion", version);
  gmsh::write(out.string());
  gmsh::finalize();
}

/// Study seeds (see the head of this file), their mutated files to be written under `tree`: a copy
/// of the directories that hold a seed, every other entry of those directories linked to the
/// source tree's.
std::vector<Seed> study_seeds(const fs::path& src, const fs::path& tree) {
  std::vector<fs::path> files;
  for (const auto& p : yaml_files(src / "inputs" / "studies")) files.push_back(p);
  for (const auto& p : yaml_files(src / "tests" / "study")) files.push_back(p);
  std::vector<fs::path> scenes;  // inputs/*.yaml, longest name first
  for (const auto& e : fs::directory_iterator(src / "inputs"))
    if (e.is_regular_file() && e.path().extension() == ".yaml") scenes.push_back(e.path());
  std::sort(scenes.begin(), scenes.end(), [](const fs::path& a, const fs::path& b) {
    return a.stem().string().size() != b.stem().string().size() ? a.stem().string().size() > b.stem().string().size() : a < b;
  });
  fs::remove_all(tree);
  std::vector<fs::path> real;  // directories of the tree that are copies (relative), parents first
  for (const auto& f : files)
    for (fs::path d = fs::relative(f.parent_path(), src); !d.empty() && d != "."; d = d.parent_path())
      if (std::find(real.begin(), real.end(), d) == real.end()) real.push_back(d);
  real.push_back("");
  for (const auto& d : real) fs::create_directories(tree / d);
  for (const auto& d : real)
    for (const auto& e : fs::directory_iterator(src / d)) {
      const fs::path rel = fs::relative(e.path(), src);
      const bool is_real = std::find(real.begin(), real.end(), rel) != real.end();
      const bool is_seed = std::find(files.begin(), files.end(), e.path()) != files.end();
      if (!is_real && !is_seed && !fs::exists(fs::symlink_status(tree / rel))) fs::create_symlink(e.path(), tree / rel);
    }
  std::vector<Seed> out;
  for (const auto& f : files) {
    Seed s;
    s.study = true;
    s.id = "study:" + fs::relative(f, src).string();
    s.label = (tree / fs::relative(f, src)).string();
    s.text = read_file(f);
    YAML::Node root;
    try {
      root = YAML::Load(s.text);
    } catch (const YAML::Exception&) {
    }
    const bool scene_with_study = root.IsMap() && root["study"] && root.size() > 1;
    if (!scene_with_study) {
      s.study_scene = (src / "inputs" / "slider_crank.yaml").string();
      for (const auto& sc : scenes)
        if (f.stem().string().rfind(sc.stem().string(), 0) == 0) {
          s.study_scene = sc.string();
          break;
        }
    }
    out.push_back(s);
  }
  return out;
}

std::vector<Seed> collect_seeds(const Options& o) {
  const fs::path src = fs::canonical(o.source);
  std::vector<Seed> seeds;
  std::map<fs::path, fs::path> scene_of_geo;  // .geo → the first scene that uses it
  std::vector<fs::path> scenes = yaml_files(src / "inputs");
  for (const auto& p : yaml_files(src / "tests")) scenes.push_back(p);
  for (const auto& p : scenes) {
    Seed s;
    s.id = fs::relative(p, src).string();
    s.label = p.string();
    s.text = read_file(p);
    seeds.push_back(s);
    const fs::path geo = scene_geo(p);
    if (!geo.empty() && !scene_of_geo.count(geo)) scene_of_geo[geo] = p;
  }
  // Meshes: every .geo a scene uses, written as .msh here, and the checked-in .msh files (whose
  // .geo is the file name without its last _suffix: cantilever_n4.msh → cantilever.geo).
  const fs::path msh_dir = fs::absolute(o.work) / "seed_meshes";
  fs::create_directories(msh_dir);
  std::vector<std::pair<fs::path, fs::path>> meshes;  // (.msh, its .geo)
  for (const auto& [geo, scene] : scene_of_geo) {
    for (double version : {4.1, 2.2}) {
      const fs::path out = msh_dir / (geo.stem().string() + (version > 3 ? "" : "_msh22") + ".msh");
      write_msh(geo, out, version);
      // MSH 2.2 only for small meshes: the format's own paths, not the same large mesh twice.
      if (version < 3 && fs::file_size(out) > 20000) continue;
      meshes.emplace_back(out, geo);
    }
  }
  for (const auto& e : fs::directory_iterator(src / "meshes")) {
    if (e.path().extension() != ".msh") continue;
    std::string stem = e.path().stem().string();
    while (!fs::exists(src / "meshes" / (stem + ".geo")) && stem.find('_') != std::string::npos) stem = stem.substr(0, stem.rfind('_'));
    const fs::path geo = fs::canonical(src / "meshes").string() + "/" + stem + ".geo";
    if (fs::exists(geo)) meshes.emplace_back(e.path(), fs::canonical(geo));
  }
  std::sort(meshes.begin(), meshes.end());
  for (const auto& [msh, geo] : meshes) {
    const auto it = scene_of_geo.find(geo);
    if (it == scene_of_geo.end()) continue;
    Seed s;
    s.msh = true;
    const bool ours = msh.parent_path() == msh_dir;
    s.id = "msh:" + (ours ? "gmsh(" + fs::relative(geo, src).string() + ")" + (msh.stem().string().find("_msh22") != std::string::npos ? "@2.2" : "@4.1")
                          : fs::relative(msh, src).string()) +
           " via " + fs::relative(it->second, src).string();
    s.label = it->second.string();
    s.text = read_file(msh);
    s.scene = YAML::LoadFile(it->second.string());
    seeds.push_back(s);
  }
  for (Seed& s : study_seeds(src, fs::absolute(o.work) / "study_tree")) seeds.push_back(std::move(s));
  return seeds;
}

// ---- One case -------------------------------------------------------------------------------------

enum class Outcome { Accepted, Rejected, Failed };

/// Why an InputError's message is not acceptable, or empty: it must start with the file name, an
/// optional ":LINE", then ": " and what it names (a key, an entity), then ": " and what is wrong.
std::string bad_message(const std::string& msg, const std::string& label) {
  if (msg.compare(0, label.size(), label) != 0) return "does not start with the file name";
  size_t i = label.size();
  if (i < msg.size() && msg[i] == ':' && i + 1 < msg.size() && std::isdigit(static_cast<unsigned char>(msg[i + 1]))) {
    ++i;
    while (i < msg.size() && std::isdigit(static_cast<unsigned char>(msg[i]))) ++i;
  }
  if (msg.compare(i, 2, ": ") != 0) return "has no ': ' after the file name and line";
  const size_t key_end = msg.find(": ", i + 2);
  if (key_end == std::string::npos || key_end == i + 2 || key_end + 2 >= msg.size())
    return "names no key or entity ('FILE[:LINE]: KEY: what')";
  // A message quotes what it refuses, not pages of it: the reader takes strings of up to 4096
  // characters (scene_reader.hpp) and shortens expressions, so a longer line repeats a value the
  // reader should have refused or shortened.
  size_t line = 0;
  for (char c : msg) {
    line = c == '\n' ? 0 : line + 1;
    if (line > 2 * 4096) return "has a line of more than " + std::to_string(2 * 4096) + " bytes";
  }
  return {};
}

/// The outcome of reading a case (`read` throws what the reader throws): accepted, rejected with
/// a good InputError message (starting with `label`), or failed (`detail` says why).
Outcome verdict(const std::function<void()>& read, const std::string& label, std::string& detail) {
  try {
    read();
    return Outcome::Accepted;
  } catch (const InputError& e) {
    detail = e.what();
    const std::string why = bad_message(detail, label);
    if (why.empty()) return Outcome::Rejected;
    detail = "InputError whose message " + why + ":\n    " + detail.substr(0, 3000);
    return Outcome::Failed;
  } catch (const std::exception& e) {
    detail = "unexpected exception " + demangle(typeid(e).name()) + " (expected alphaflex::InputError): " + e.what();
    return Outcome::Failed;
  } catch (...) {
    detail = "unexpected exception of a type that is not std::exception";
    return Outcome::Failed;
  }
}

/// A scene case: read, then started (no step).
Outcome run_case(const std::string& text, const std::string& label, std::string& detail) {
  return verdict(
      [&] {
        Scene scene = read_scene_text(text, label);
        RunOptions ro;
        ro.write_results = false;
        ro.verbose = false;
        ro.stop_after_start = true;
        run_simulation(scene, ro, MPI_COMM_SELF);
      },
      label, detail);
}

/// A study case: the mutated file is at seed.label already; read_study with the seed's scene.
Outcome run_study_case(const Seed& seed, std::string& detail) {
  return verdict(
      [&] {
        if (seed.study_scene.empty()) study::read_study(seed.label, "");
        else study::read_study(seed.study_scene, seed.label);
      },
      seed.label, detail);
}

std::string safe_name(std::string id) {
  for (char& c : id)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '-') c = '_';
  return id;
}

struct Tally {
  int cases = 0, accepted = 0, rejected = 0, failed = 0;
};

class Fuzzer {
 public:
  explicit Fuzzer(const Options& o) : o_(o), work_(fs::absolute(o.work)) {
    fs::create_directories(work_ / "failures");
  }

  /// Case k of a seed (k = 0: the seed itself, unmutated).
  void run(const Seed& seed, int k, Tally& t) {
    const std::string id = seed.id + "#" + std::to_string(k);
    fuzz::Rng rng(fuzz::stable_hash(id, o_.seed * 1099511628211ULL + 1469598103934665603ULL));
    // One mutation in half the cases (most of them still reach the model builder), else 2 or 3.
    const int count = k == 0 ? 0 : rng.percent(50) ? 1 : 2 + static_cast<int>(rng.below(2));
    const fuzz::Mutation m = seed.msh ? fuzz::mutate_msh(seed.text, rng, count) : fuzz::mutate_scene(seed.text, rng, count);
    std::string scene_text = m.text, msh_path;
    if (seed.msh) {
      msh_path = (work_ / "case.msh").string();
      write_file(msh_path, m.text);
      YAML::Node scene = YAML::Clone(seed.scene);
      YAML::Node mesh(YAML::NodeType::Map);
      mesh["file"] = msh_path;
      scene["mesh"] = mesh;
      YAML::Emitter em;
      em << scene;
      scene_text = em.c_str();
    }
    if (seed.study) write_file(seed.label, m.text);
    std::ostringstream banner;
    banner << "  case " << id << " (seed " << o_.seed << ")\n";
    for (const auto& l : m.log) banner << "    " << l << "\n";
    banner << "  rerun: fuzz_inputs --seed " << o_.seed << " --case '" << id << "'\n";
    set_banner(banner.str());

    std::string detail;
    g_case_start_ns = now_ns();
    const auto t0 = std::chrono::steady_clock::now();
    const Outcome out = seed.study ? run_study_case(seed, detail) : run_case(scene_text, seed.label, detail);
    const double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    g_case_start_ns = 0;
    slowest_ = std::max(slowest_, dt);
    if (dt == slowest_) slowest_id_ = id;
    ++t.cases;
    if (out == Outcome::Accepted) ++t.accepted;
    if (out == Outcome::Rejected) ++t.rejected;
    if (out == Outcome::Failed) {
      ++t.failed;
      const fs::path keep = work_ / "failures" / safe_name(id);
      write_file(keep.string() + ".yaml", scene_text);
      if (seed.msh) fs::copy_file(msh_path, keep.string() + ".msh", fs::copy_options::overwrite_existing);
      std::cout << "FUZZ FAILURE: " << detail << "\n" << banner.str() << "  files: " << keep.string()
                << (seed.msh ? ".yaml, .msh" : ".yaml") << " (" << (seed.study ? "study" : "scene")
                << " file name in messages: " << seed.label
                << (seed.study && !seed.study_scene.empty() ? ", its scene " + seed.study_scene : std::string()) << ")\n"
                << std::endl;
    } else if (o_.verbose) {
      std::cout << id << ": " << (out == Outcome::Accepted ? "accepted" : "rejected: " + detail.substr(0, 200)) << " ("
                << dt << " s)" << std::endl;
    }
  }

  double slowest() const { return slowest_; }
  const std::string& slowest_id() const { return slowest_id_; }

 private:
  const Options& o_;
  fs::path work_;
  double slowest_ = 0.0;
  std::string slowest_id_;
};

int usage(const char* why) {
  std::cerr << "fuzz_inputs: " << why
            << "\nusage: fuzz_inputs [--source DIR] [--work DIR] [--scene-cases N] [--msh-cases N] [--study-cases N] [--seed N]"
               " [--time-limit S] [--case ID] [--verbose]\n";
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument(a + " needs a value");
      return argv[++i];
    };
    try {
      if (a == "--source") o.source = value();
      else if (a == "--work") o.work = value();
      else if (a == "--scene-cases") o.scene_cases = std::stoi(value());
      else if (a == "--msh-cases") o.msh_cases = std::stoi(value());
      else if (a == "--study-cases") o.study_cases = std::stoi(value());
      else if (a == "--seed") o.seed = std::stoull(value());
      else if (a == "--time-limit") o.time_limit = std::stod(value());
      else if (a == "--case") o.only = value();
      else if (a == "--verbose") o.verbose = true;
      else return usage(("unknown option " + a).c_str());
    } catch (const std::exception& e) {
      return usage(e.what());
    }
  }
  // PETSc's own signal handler would hide a crash's case: ours prints it (install_crash_handlers).
  PetscCall(PetscOptionsSetValue(nullptr, "-no_signal_handler", nullptr));
  int pargc = 1;
  char** pargv = argv;
  alphaflex::prepare_mpi_start();  // before MPI_Init: no orted when run without mpirun, no network layers on one node
  PetscCall(PetscInitialize(&pargc, &pargv, nullptr, nullptr));
  int status = 0;
  {
    const auto t0 = std::chrono::steady_clock::now();
    std::vector<Seed> seeds;
    try {
      seeds = collect_seeds(o);
    } catch (const std::exception& e) {
      std::cerr << "fuzz_inputs: cannot prepare the seeds: " << e.what() << std::endl;
      PetscFinalize();
      return 2;
    }
    install_crash_handlers();
    Fuzzer fuzzer(o);
    Tally scenes, meshes, studies;
    const auto tally = [&](const Seed& s) -> Tally& { return s.msh ? meshes : s.study ? studies : scenes; };
    {
      const Watchdog watchdog(o.time_limit);
      bool found = o.only.empty();
      // --case SEED#K: case K of that seed alone (whatever the number of cases per seed).
      const size_t hash = o.only.rfind('#');
      const std::string only_seed = o.only.substr(0, hash);
      const int only_k = hash == std::string::npos ? -1 : std::atoi(o.only.c_str() + hash + 1);
      for (const Seed& s : seeds) {
        if (!o.only.empty()) {
          if (s.id != only_seed || only_k < 0) continue;
          found = true;
          fuzzer.run(s, only_k, tally(s));
          continue;
        }
        const int n = s.msh ? o.msh_cases : s.study ? o.study_cases : o.scene_cases;
        for (int k = 0; k <= n; ++k) fuzzer.run(s, k, tally(s));
      }
      if (!found) {
        std::cerr << "fuzz_inputs: no case '" << o.only << "' (IDs are SEED#K, e.g. inputs/andrews.yaml#3)" << std::endl;
        status = 2;
      }
    }
    // A report from here on (LeakSanitizer runs at exit) belongs to no case.
    set_banner("  (no case: after the last one, at exit)\n");
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    int nscene = 0, nmsh = 0, nstudy = 0;
    for (const Seed& s : seeds) (s.msh ? nmsh : s.study ? nstudy : nscene)++;
    const auto line = [](const char* what, const Tally& t) {
      return "  " + std::string(what) + ": " + std::to_string(t.cases) + " cases, " + std::to_string(t.accepted) +
             " accepted, " + std::to_string(t.rejected) + " rejected, " + std::to_string(t.failed) + " failed\n";
    };
    std::cout << "fuzz_inputs: seed " << o.seed << ": " << nscene << " scene seeds x " << o.scene_cases << " mutations, "
              << nmsh << " mesh seeds x " << o.msh_cases << " mutations, " << nstudy << " study seeds x "
              << o.study_cases << " mutations (each seed also unmutated)\n"
              << line("scenes", scenes) << line("meshes", meshes) << line("studies", studies) << "  " << wall << " s in all; slowest case " << fuzzer.slowest() << " s (" << fuzzer.slowest_id() << ")"
              << std::endl;
    if (scenes.failed + meshes.failed + studies.failed > 0) status = 1;
  }
  PetscFinalize();
  return status;
}
