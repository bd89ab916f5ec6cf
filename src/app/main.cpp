// alphaflex — flexible multibody dynamics with the generalized-α scheme of Arnold & Brüls (2007).
//
//   alphaflex run SCENE.yaml [-o OUTDIR] [--set key=value ...] [--restart CHECKPOINT.h5] [PETSc options]
//   alphaflex study SCENE.yaml [--study STUDY.yaml] [-o OUTDIR] [--set key=value ...]
//                   [--study-set key=value ...] [--no-plots] [--ranks-per-run K] [PETSc options]
//   alphaflex keys [--check FILE | --update FILE]
//   alphaflex modes SCENE.yaml [-o OUTDIR] [--set key=value ...] [--restart CHECKPOINT.h5]
//                   [PETSc/SLEPc options]
//
// Exit codes: 0 success, 1 bad input, 2 bad command line, 3 solver failure, 4 internal error,
// 5 stopped by a signal after writing a checkpoint, 6 results or checkpoint not written.
#include <slepcsys.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <unistd.h>
#include <iostream>
#include <string>
#include <vector>

#include "alphaflex/app/exit_agreement.hpp"
#include "alphaflex/app/modal_run.hpp"
#include "alphaflex/app/simulation.hpp"
#include "alphaflex/app/summary_json.hpp"
#include "alphaflex/app/stop_signals.hpp"
#include "alphaflex/core/error.hpp"
#include "alphaflex/core/memory.hpp"
#include "alphaflex/core/mpi_singleton.hpp"
#include "alphaflex/io/schema.hpp"
#include "alphaflex/io/scene_modes.hpp"
#include "alphaflex/study/run_groups.hpp"
#include "alphaflex/study/study.hpp"

namespace {

const char* kUsage =
    "usage: alphaflex run SCENE.yaml [-o OUTDIR] [--set key=value ...] [--restart CHECKPOINT.h5] [PETSc options]\n"
    "       alphaflex study SCENE.yaml [--study STUDY.yaml] [-o OUTDIR] [--set key=value ...]\n"
    "                       [--study-set key=value ...] [--no-plots] [--ranks-per-run K] [PETSc options]\n"
    "       alphaflex keys [--check FILE | --update FILE]\n"
    "       alphaflex modes SCENE.yaml [-o OUTDIR] [--set key=value ...] [--restart CHECKPOINT.h5]\n"
    "                       [PETSc/SLEPc options]\n"
    "\n"
    "  -o OUTDIR          where NAME.h5, NAME.xdmf (ParaView) and NAME.csv (sensors) go (default: .)\n"
    "  --set key=value    override a scene key, e.g. --set solver.h=1e-3 --set solver.rho_inf=0.9\n"
    "                     --set solver.scheme=hht --set solver.scaling=off --set solver.t_end=0.5;\n"
    "                     key=~ removes the key (--set beams.0.reduction=~: a reduced block's full mesh)\n"
    "  --restart FILE     go on from a checkpoint (OUTDIR/NAME.checkpoint.h5) as if the run had not stopped;\n"
    "                     with the same -o, the results continue where the checkpoint left them\n"
    "  PETSc options      passed through, e.g. -log_view, -mat_mumps_icntl_4 2, -ksp_view\n"
    "  study: runs the scene over step sizes and scheme settings (its study: block, or --study FILE),\n"
    "  writes OUTDIR/NAME_study.csv and charts (scripts/study_plots.py); docs/study.md\n"
    "  --study FILE       the study map (a file with one top-level study: key)\n"
    "  --study-set k=v    override a study key, e.g. --study-set h=[1e-3,5e-4]\n"
    "  --ranks-per-run K  under mpirun -np N, a study runs N/K simulations at a time, each\n"
    "                     on K ranks (K divides N; default 1 for scenes up to 20000 unknowns, else N)\n"
    "  --no-plots         write the CSV only\n"
    "  keys: the key tables of every scene and study section, from the reader's schemas (markdown);\n"
    "  --update FILE rewrites the tables between <!-- keys:NAME --> and <!-- /keys --> in FILE,\n"
    "  --check FILE exits 1 if FILE's tables differ from the schemas (docs/input.md)\n"
    "  modes: eigenfrequencies and mode shapes of the scene linearized about its initial state, its\n"
    "  static equilibrium (solver.analysis: static, solver.initial_static) or --restart's checkpoint;\n"
    "  writes OUTDIR/NAME_modes.csv and NAME_modeshapes.xdmf; keys modes.count/below/shift, options\n"
    "  -eps_*, -pep_*, -st_* (SLEPc); docs/modes.md\n"
    "\n"
    "Scene keys: docs/input.md; running long jobs: docs/running.md. Exit codes: 0 ok, 1 bad input,\n"
    "2 bad command line, 3 solver failure, 4 a bug of alphaflex, 5 stopped by a signal (checkpoint written),\n"
    "6 results or checkpoint not written (disk full, no permission).\n";

/// Resident memory of this process now (MB), from /proc/self/statm; 0 where it cannot be read.
double resident_mb() {
  std::FILE* f = std::fopen("/proc/self/statm", "r");
  if (!f) return 0.0;
  long pages = 0, resident = 0;
  const int n = std::fscanf(f, "%ld %ld", &pages, &resident);
  std::fclose(f);
  return n == 2 ? static_cast<double>(resident) * static_cast<double>(sysconf(_SC_PAGESIZE)) / 1048576.0 : 0.0;
}

struct CommandLine {
  std::string command, scene, outdir = ".", study_file, restart;
  std::vector<std::string> overrides, study_overrides;
  bool plots = true, study_options = false;
  int ranks_per_run = 0;  ///< --ranks-per-run (0: the study's default)
  std::vector<char*> petsc_argv;
  std::string error;
};

CommandLine parse(int argc, char** argv) {
  CommandLine cl;
  cl.petsc_argv.push_back(argv[0]);
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "-h" || a == "--help") {
      cl.command = "help";
    } else if (a == "-o" || a == "--output") {
      if (i + 1 >= argc || argv[i + 1][0] == '\0') cl.error = a + " needs a directory";
      else cl.outdir = argv[++i];
    } else if (a == "--set") {
      if (i + 1 >= argc) cl.error = "--set needs key=value";
      else cl.overrides.push_back(argv[++i]);
    } else if (a.rfind("--set=", 0) == 0) {
      cl.overrides.push_back(a.substr(6));
    } else if (a == "--restart") {
      if (i + 1 >= argc || argv[i + 1][0] == '\0') cl.error = "--restart needs a checkpoint file";
      else cl.restart = argv[++i];
    } else if (a == "--study") {
      cl.study_options = true;
      if (i + 1 >= argc || argv[i + 1][0] == '\0') cl.error = "--study needs a study file";
      else cl.study_file = argv[++i];
    } else if (a == "--study-set") {
      cl.study_options = true;
      if (i + 1 >= argc) cl.error = "--study-set needs key=value";
      else cl.study_overrides.push_back(argv[++i]);
    } else if (a == "--ranks-per-run") {
      cl.study_options = true;
      std::size_t used = 0;
      int k = 0;
      try {
        k = i + 1 < argc ? std::stoi(argv[i + 1], &used) : 0;
      } catch (const std::exception&) {
        used = 0;
      }
      if (i + 1 >= argc || used == 0 || argv[i + 1][used] != '\0' || k < 1)
        cl.error = "--ranks-per-run needs a whole number of ranks >= 1" +
                   (i + 1 < argc ? std::string(", got '") + argv[i + 1] + "'" : std::string());
      else
        cl.ranks_per_run = k;
      ++i;
    } else if (a == "--no-plots") {
      cl.study_options = true;
      cl.plots = false;
    } else if (a.rfind("--", 0) == 0) {
      // Every long option is one of ours (PETSc's take one dash): a misspelt one (--ouptut) would
      // otherwise be passed to PETSc and ignored, and the results written elsewhere.
      if (cl.error.empty()) cl.error = "unknown option '" + a + "'";
    } else if (!a.empty() && a[0] == '-') {
      // A PETSc option, with its value if the next word is not an option itself (nor a scene).
      cl.petsc_argv.push_back(argv[i]);
      const auto is_scene = [](const std::string& w) {
        return w.size() > 5 && (w.compare(w.size() - 5, 5, ".yaml") == 0 || w.compare(w.size() - 4, 4, ".yml") == 0);
      };
      if (i + 1 < argc && argv[i + 1][0] != '-' && !is_scene(argv[i + 1])) cl.petsc_argv.push_back(argv[++i]);
    } else if (cl.command.empty()) {
      cl.command = a;
    } else if (cl.scene.empty()) {
      cl.scene = a;
    } else if (cl.error.empty()) {
      cl.error = "unexpected argument '" + a + "'";
    }
  }
  cl.petsc_argv.push_back(nullptr);
  return cl;
}

/// The values of options the run reads as numbers: alphaflex's own and MUMPS' integer (ICNTL) and
/// real (CNTL) controls. PETSc would stop on a bad one with its error trace deep in the solver's
/// set-up (exit 63 or 3); here it is a bad command line (exit 2) naming the option. Empty if all
/// are numbers.
std::string check_number_options(const std::vector<char*>& argv) {
  auto number = [](const std::string& v, bool integer) {
    if (v.empty()) return false;
    char* end = nullptr;
    errno = 0;
    if (integer) (void)std::strtol(v.c_str(), &end, 10);
    else {
      const double x = std::strtod(v.c_str(), &end);
      if (!std::isfinite(x)) return false;
    }
    return errno == 0 && end && *end == '\0';
  };
  for (size_t i = 1; i + 1 < argv.size(); ++i) {
    if (!argv[i]) break;
    const std::string o = argv[i];
    const bool integer = o == "-af_dense_lu" || o.rfind("-mat_mumps_icntl_", 0) == 0;
    const bool real = o == "-af_exit_timeout" || o.rfind("-mat_mumps_cntl_", 0) == 0;
    if (!integer && !real) continue;
    const char* value = argv[i + 1];
    if (!value || value[0] == '-' && !number(value, integer))
      return o + " needs " + (integer ? "an integer" : "a number");
    if (!number(value, integer))
      return o + ": expected " + (integer ? "an integer" : "a number") + ", got '" + value + "'";
  }
  return {};
}

/// What `read` returns (a scene, a study), read on every rank; the ranks agree that it is valid
/// before anything collective (an InputError on one rank is thrown on all, with its message).
template <class Read>
auto read_on_every_rank(const std::string& file, Read read, std::string& message) -> decltype(read()) {
  decltype(read()) out;
  int ok = 1;
  try {
    out = read();
  } catch (const alphaflex::InputError& e) {
    ok = 0;
    message = e.what();
  }
  int all_ok = 1;
  MPI_Allreduce(&ok, &all_ok, 1, MPI_INT, MPI_MIN, PETSC_COMM_WORLD);
  if (!all_ok) throw alphaflex::InputError(message.empty() ? file + ": unreadable on another rank" : message);
  return out;
}

// `alphaflex run`: read the scene on every rank (agreeing on its validity), run it, print the summary.
void run_command(const CommandLine& cl, int rank, int size, MPI_Comm exit_comm, double exit_timeout, std::string& message) {
  // Every rank reads the scene; they must agree that it is valid before anything collective.
  // The scene's whole model is built on every rank (docs/architecture.md): its memory is the
  // replicated part of a parallel run, reported with the summary.
  const double before_mb = resident_mb();
  alphaflex::Scene scene = read_on_every_rank(
      cl.scene, [&] { return alphaflex::read_scene(cl.scene, cl.overrides, PETSC_COMM_WORLD, cl.outdir); }, message);

  if (rank == 0) {
    const auto& p = scene.settings.parameters;
    std::cout << "alphaflex: " << scene.name << " (" << cl.scene << ") on " << size << " rank(s)\n"
              << "  scheme " << p.scheme << ": alpha_m = " << p.alpha_m << ", alpha_f = " << p.alpha_f
              << ", beta = " << p.beta << ", gamma = " << p.gamma
              << " (rho_inf = " << std::round(p.rho_infinity() * 1e4) / 1e4
              << "), scaling " << (scene.settings.integrator.scaling ? "on" : "off") << "\n";
    for (const auto& w : scene.warnings) std::cout << "  warning: " << w << "\n";
    for (const auto& w : scene.superelement_warnings) std::cout << "  warning: " << w << "\n";
  }
  alphaflex::RunOptions opt;
  opt.outdir = cl.outdir;
  opt.exit_comm = exit_comm;
  opt.exit_timeout = exit_timeout;
  opt.restart = cl.restart;
  double description_mb = resident_mb() - before_mb, largest_mb = 0.0;
  MPI_Allreduce(&description_mb, &largest_mb, 1, MPI_DOUBLE, MPI_MAX, PETSC_COMM_WORLD);
  alphaflex::RunSummary sum = alphaflex::run_simulation(scene, opt, PETSC_COMM_WORLD);
  sum.scene_memory_mb = largest_mb;
  if (rank == 0) {
    if (sum.projection > 1e-12) std::cout << "  consistent start: initial coordinates moved by at most " << sum.projection << "\n";
    std::cout << alphaflex::format_summary(scene, sum);
    // The same figures for scripts (python/alphaflex_results.py); rank 0 writes, end_run makes a
    // failure every rank's exit code.
    std::cout << "  summary  "
              << alphaflex::write_summary_json(cl.outdir, scene.name, alphaflex::summary_json(scene, sum)) << "\n";
  }
}

// `alphaflex study` (docs/study.md): every rank reads the study and agrees it is valid (as for a
// scene), then all run it together; rank 0 writes the files.
void study_command(const CommandLine& cl, int rank, std::string& message) {
  alphaflex::study::StudySpec spec = read_on_every_rank(
      cl.scene, [&] { return alphaflex::study::read_study(cl.scene, cl.study_file, cl.study_overrides); }, message);
  alphaflex::study::StudyOptions sopt;
  sopt.outdir = cl.outdir;
  sopt.scene_overrides = cl.overrides;
  sopt.plots = cl.plots;
  sopt.ranks_per_run = cl.ranks_per_run;
  const auto res = alphaflex::study::run_study(spec, sopt, PETSC_COMM_WORLD);
  if (rank == 0)
    for (const auto& f : res.files) std::cout << "wrote " << f << "\n";
}

// `alphaflex keys`: the key tables generated from the schemas (no PETSc, no MPI). Exit 0, 1 when
// --check finds a difference or a marker names no schema, 2 for a bad command line.
int keys_command(int argc, char** argv) {
  std::vector<const alphaflex::input::Schema*> schemas = alphaflex::input::scene_schemas();
  for (const auto* s : alphaflex::study::schemas()) schemas.push_back(s);
  if (argc == 2) {
    for (const auto* s : schemas) std::cout << "### " << s->name << "\n\n" << s->markdown() << "\n";
    return 0;
  }
  const std::string option = argv[2];
  if (argc != 4 || (option != "--check" && option != "--update")) {
    std::cerr << "alphaflex: keys takes no argument, --check FILE or --update FILE\n\n" << kUsage;
    return 2;
  }
  const std::string file = argv[3];
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    std::cerr << "alphaflex: " << file << ": cannot open the file\n";
    return 1;
  }
  std::ostringstream text;
  text << in.rdbuf();
  try {
    std::vector<std::string> unused;
    const std::string updated = alphaflex::input::update_key_tables(text.str(), schemas, file, &unused);
    if (!unused.empty()) {  // every schema's table is in the document
      std::cerr << "alphaflex: " << file << ": no key-table marker for";
      for (const auto& n : unused) std::cerr << " " << n;
      std::cerr << "\n";
      if (option == "--check") return 1;
    }
    if (option == "--update") {
      if (updated != text.str()) std::ofstream(file, std::ios::binary) << updated;
      return 0;
    }
    if (updated != text.str()) {
      std::cerr << "alphaflex: " << file << ": the key tables differ from the reader's schemas; "
                << "run `alphaflex keys --update " << file << "` and review the difference\n";
      return 1;
    }
    return 0;
  } catch (const alphaflex::InputError& e) {
    std::cerr << "alphaflex: " << e.what() << "\n";
    return 1;
  }
}

// `alphaflex modes` (docs/modes.md): the scene and its modes: keys read on every rank, the modes
// computed together, the table printed by rank 0.
void modes_command(const CommandLine& cl, int rank, MPI_Comm exit_comm, double exit_timeout, std::string& message) {
  alphaflex::Scene scene = read_on_every_rank(
      cl.scene, [&] { return alphaflex::read_scene(cl.scene, cl.overrides, PETSC_COMM_WORLD, cl.outdir); }, message);
  alphaflex::ModalRunOptions opt;
  opt.modes = read_on_every_rank(
      cl.scene, [&] { return alphaflex::read_modal_options(cl.scene, cl.overrides, PETSC_COMM_WORLD); }, message);
  opt.outdir = cl.outdir;
  opt.restart = cl.restart;
  opt.exit_comm = exit_comm;
  opt.exit_timeout = exit_timeout;
  const alphaflex::ModalRunSummary sum = alphaflex::run_modes(scene, opt, PETSC_COMM_WORLD);
  if (rank == 0) {
    std::cout << alphaflex::format_modes(scene, sum);
    std::cout << "  summary: "
              << alphaflex::write_summary_json(cl.outdir, scene.name + "_modes", alphaflex::modes_json(scene, sum)) << "\n";
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc >= 2 && std::strcmp(argv[1], "keys") == 0) return keys_command(argc, argv);
  // From the start: a stop signal during start-up (MPI and PETSc take ~0.7 s) is kept, and the run
  // stops after its first step with a checkpoint (exit 5) instead of dying with no message. PETSc's
  // initialization installs handlers of its own: ours are installed again after it.
  alphaflex::install_stop_signals();
  CommandLine cl = parse(argc, argv);
  if (cl.command == "help") {
    std::cout << kUsage;
    return 0;
  }
  if (cl.error.empty() && cl.command != "run" && cl.command != "study" && cl.command != "modes")
    cl.error = cl.command.empty() ? "no command given" : "unknown command '" + cl.command + "'";
  if (cl.error.empty() && cl.scene.empty()) cl.error = cl.command + " needs a scene file";
  if (cl.error.empty() && cl.command == "study" && !cl.restart.empty()) cl.error = "--restart is an option of `alphaflex run` and `alphaflex modes`";
  if (cl.error.empty() && cl.command != "study" && cl.study_options)
    cl.error = "--study, --study-set, --no-plots and --ranks-per-run are options of `alphaflex study`";
  if (cl.error.empty()) cl.error = check_number_options(cl.petsc_argv);
  if (!cl.error.empty()) {
    std::cerr << "alphaflex: " << cl.error << "\n\n" << kUsage;
    return 2;
  }

  int pargc = static_cast<int>(cl.petsc_argv.size()) - 1;
  char** pargv = cl.petsc_argv.data();
  alphaflex::prepare_mpi_start();  // before MPI_Init: no orted for a one-rank run, no network layers on one node
  // SLEPc's initialization (it initializes PETSc): EPS and PEP refuse to run without it (modes).
  PetscCall(SlepcInitialize(&pargc, &pargv, nullptr, nullptr));
  int rank = 0, size = 1;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  // The communicator on which the ranks agree how the run ends (app/exit_agreement.hpp), and how
  // long a rank that caught an error waits for the others before it ends the job.
  MPI_Comm exit_comm;
  MPI_Comm_dup(PETSC_COMM_WORLD, &exit_comm);
  PetscReal exit_timeout = 5.0;
  PetscCall(PetscOptionsGetReal(nullptr, nullptr, "-af_exit_timeout", &exit_timeout, nullptr));
  alphaflex::install_stop_signals();

  int code = 0;
  std::string message;
  // --ranks-per-run must split the job's ranks into equal groups: known only now (exit 2, every rank).
  const std::string groups_problem =
      cl.ranks_per_run > 0 ? alphaflex::study::ranks_per_run_problem(cl.ranks_per_run, size) : std::string();
  if (!groups_problem.empty()) {
    code = 2;
    message = groups_problem;
  }
  if (code == 0) try {
    if (cl.command == "study") {
      study_command(cl, rank, message);
    } else if (cl.command == "modes") {
      modes_command(cl, rank, exit_comm, exit_timeout, message);
    } else {
      run_command(cl, rank, size, exit_comm, exit_timeout, message);
    }
  } catch (const std::bad_alloc&) {
    // Memory exhaustion outside a run's body (reading the scene, meshing): exit 3 with what to do.
    code = 3;
    message = alphaflex::out_of_memory_message("running `alphaflex " + cl.command + " " + cl.scene + "`", 0.0, rank);
  } catch (const std::exception& e) {
    // The code of the error's type (exit_agreement.hpp: one table for main and run_simulation).
    code = alphaflex::exit_code_of(e);
    message = code == 4 ? std::string("internal error on rank ") + std::to_string(rank) + ": " + e.what() : e.what();
  }
  // Every rank ends alike: an error the ranks agreed on ends them all cleanly with one message; an
  // error only this rank saw ends the job (the others wait in a collective call it has left).
  code = alphaflex::end_run(exit_comm, code, message, exit_timeout);
  MPI_Comm_free(&exit_comm);
  PetscCall(SlepcFinalize());
  return code;
}
