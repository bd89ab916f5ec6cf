// Input errors found by the fuzz test (tests/fuzz, docs/testing.md), one test each: the input that
// went wrong, and the message it gets now (file, line, key, what was expected).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "alphaflex/app/simulation.hpp"
#include "alphaflex/core/error.hpp"
#include "alphaflex/io/scene.hpp"
#include "alphaflex/io/schema.hpp"
#include "alphaflex/study/study_spec.hpp"
#include "test_support.hpp"

namespace alphaflex {
namespace {

const std::string kPendulum = R"(solver: {h: 1.0e-3, t_end: 0.01}
bodies:
  - {name: bar, type: rigid_body, mass: 1, inertia: 0.1, position: [0.5, 0]}
joints:
  - {name: pin, type: revolute, body1: bar, point1: [-0.5, 0], body2: ground, point2: [0, 0]}
)";

using testing::input_error_of;

/// The InputError message of reading (and starting, with stop_after_start) `yaml`.
std::string error_of(const std::string& yaml) {
  return input_error_of([&] {
    Scene sc = read_scene_text(yaml, "scene.yaml");
    RunOptions o;
    o.write_results = false;
    o.verbose = false;
    o.stop_after_start = true;
    run_simulation(sc, o, MPI_COMM_SELF);
  });
}

// YAML allows a map as a key (`? {a: b}`); yaml-cpp's conversion to a string then threw a
// YAML::BadConversion, reported as "scene.yaml:2: bad conversion" (no key, no expectation).
TEST(SceneErrors, MapAsKeyIsNamed) {
  EXPECT_EQ(error_of("? {a: b}\n" + kPendulum),
            "scene.yaml:1: (top level): expected key names, found a list or a map used as a key");
  EXPECT_EQ(error_of("parameters:\n  ? [x]\n  : 1\n" + kPendulum),
            "scene.yaml:2: parameters: expected key names, found a list or a map used as a key");
}

// A name is quoted in every later message about its item: a 5000-character one is refused first.
// A name given twice in `parameters` or `mesh.parameters` (issue 24, defect 5): yaml-cpp keeps both
// entries and the last one won silently, while every other map refuses a repeated key.
TEST(SceneErrors, RepeatedParameterNamesAreRefused) {
  EXPECT_EQ(error_of("parameters: {L: 1, L: 2}\n" + kPendulum), "scene.yaml:1: parameters.L: given twice");
  const std::string meshed = "dimension: 3\nmesh: {file: " + testing::source_path("meshes/cantilever.geo") +
                             ", parameters: {L: 1, L: 2}}\n"
                             "beams: [{name: b, group: beam, orientation: [0, 1, 0], section: {EA: 1, GA2: 1, GA3: 1,"
                             " GJ: 1, EI2: 1, EI3: 1, rhoA: 1, rhoI2: 1, rhoI3: 1}}]\n";
  EXPECT_EQ(error_of(meshed), "scene.yaml:2: mesh.parameters.L: given twice");
}

TEST(SceneErrors, OverlongStringIsRefusedNotQuoted) {
  const std::string long_name(5000, 'x');
  std::string yaml = kPendulum;
  yaml.replace(yaml.find("name: bar"), 9, "name: " + long_name);
  EXPECT_EQ(error_of(yaml), "scene.yaml:3: bodies[0].name: expected a string of at most 4096 characters, got 5000");
}

// A mass of 1e308 (finite) made the first iteration matrix singular: a SolverError without the
// file. Values whose square is not a normal double are refused where they are read.
TEST(SceneErrors, ValuesBeyondTheSquarableRangeAreRefused) {
  for (const char* v : {"1e308", "-1e151", "1e-308"}) {
    std::string yaml = kPendulum;
    yaml.replace(yaml.find("inertia: 0.1"), 12, std::string("inertia: ") + v);
    EXPECT_EQ(error_of(yaml), "scene.yaml:3: bodies[bar].inertia: '" + std::string(v) +
                                  "' is out of range: expected 0 or a magnitude from 1e-150 to 1e150");
  }
  std::string yaml = kPendulum;
  yaml.replace(yaml.find("position: [0.5, 0]"), 18, "position: [0.5, 1e-150]");  // the bounds are inside
  Scene sc = read_scene_text(yaml, "scene.yaml");
  EXPECT_EQ(sc.model->node(0).q0[1], 1e-150);
}

// A reference to a body that does not exist lists the known ones: the first 20, not every node.
TEST(SceneErrors, UnknownBodyListsAtMostTwentyNames) {
  std::string yaml = "bodies:\n";
  for (int i = 0; i < 30; ++i)
    yaml += "  - {name: b" + std::to_string(i) + ", type: particle, mass: 1, position: [" + std::to_string(i) + ", 0]}\n";
  yaml += "joints:\n  - {name: pin, type: revolute, body1: nobody, body2: ground}\n";
  EXPECT_EQ(error_of(yaml), "scene.yaml:33: joints[pin].body1: no body named 'nobody' (bodies: b0 b1 b2 b3 b4 b5 b6 b7 b8 b9 "
                            "b10 b11 b12 b13 b14 b15 b16 b17 b18 b19 ... (10 more) ground)");
}

// The consistent start moves p onto the spring's ground point: a SolverError of the spring came
// out of the start without the scene's name; it is the scene's fault, so an InputError naming it.
TEST(SceneErrors, SpringCollapsingAtTheStartIsAnInputError) {
  const std::string e = error_of(R"(solver: {h: 1.0e-3, t_end: 0.01}
bodies:
  - {name: p, type: particle, mass: 1, position: [3, 0]}
joints:
  - {name: F, type: fixed_point, body: p, location: [2, 2]}
forces:
  - {name: s, type: spring_damper, body1: p, body2: ground, point2: [2, 2], stiffness: 10}
)");
  EXPECT_EQ(e.rfind("scene.yaml: the scene cannot start (consistent start at t = 0): spring_damper 's': its two points coincide", 0), 0u)
      << e;
}

// stop_after_start sets the run up and stops before the first step, writing nothing.
TEST(SceneErrors, StopAfterStartTakesNoStepAndWritesNothing) {
  namespace fs = std::filesystem;
  const testing::TestOutputDir dir("stop_after_start");
  const fs::path out = fs::path(dir.path()) / "out";  // must not come into existence
  Scene sc = read_scene_text(kPendulum, "pendulum.yaml");
  RunOptions o;
  o.outdir = out.string();
  o.verbose = false;
  o.stop_after_start = true;
  int observed = 0;
  o.on_step = [&](const MechanicalState&) { ++observed; };
  const RunSummary s = run_simulation(sc, o, MPI_COMM_SELF);
  EXPECT_EQ(s.steps, 0);
  EXPECT_EQ(observed, 0);
  EXPECT_EQ(s.unknowns, 5);  // x, y, θ and the pin's two multipliers
  EXPECT_FALSE(fs::exists(out));
}


// The study reader is the scene's reader (io/schema.hpp). Its former copy converted keys with
// kv.first.as<std::string>(): a map used as a key threw YAML::BadConversion, an internal error
// (exit 4) instead of a message naming the file and the key (exit 1).
TEST(StudyErrors, MapAsKeyIsNamed) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / "alphaflex_study_map_key";
  fs::create_directories(dir);
  const fs::path scene = dir / "pendulum.yaml", study = dir / "study.yaml";
  std::ofstream(scene) << kPendulum;
  auto error = [&](const std::string& text, const std::vector<std::string>& set = {}) {
    std::ofstream(study) << text;
    return input_error_of([&] { study::read_study(scene.string(), study.string(), set); });
  };
  const std::string f = study.string();
  EXPECT_EQ(error("study:\n  ? {a: b}\n  : 1\n  h: [1e-3]\n"),
            f + ":2: study: expected key names, found a list or a map used as a key");
  EXPECT_EQ(error("study:\n  h: [1e-3]\n  mode: oscillation\n  settings:\n    - label: a\n      newton:\n        ? [x]\n        : 1\n"),
            f + ":7: study.settings[a].newton: expected key names, found a list or a map used as a key");
  // A 5000-character value is refused with its length, not quoted (the fuzz test's second study finding).
  EXPECT_EQ(error("study:\n  h: [1e-3]\n  mode: " + std::string(5000, 'x') + "\n"),
            f + ":3: study.mode: expected a string of at most 4096 characters, got 5000");
  // --study-set goes through the scene's override function: errors name the option.
  EXPECT_EQ(error("study:\n  h: [1e-3]\n  mode: oscillation\n", {"t_end=-1"}),
            f + ": --study-set t_end=-1: study.t_end: expected a positive final time (s), got -1");
  EXPECT_EQ(error("study:\n  h: [1e-3]\n  t_end: 1\n", {"t_end.x=1"}),
            f + ": --study-set t_end.x=1: 't_end' is a value, not a map: it has no key 'x'");
  fs::remove_all(dir);
}

// Type names come from the registry: the message lists every registered type, in order.
TEST(SceneErrors, UnknownTypeListsTheRegisteredTypes) {
  std::string yaml = kPendulum;
  yaml.replace(yaml.find("type: revolute"), 14, "type: hinge");
  EXPECT_EQ(error_of(yaml), "scene.yaml:5: joints[pin].type: unknown joint type 'hinge' "
                            "(expected revolute, fixed_point, fixed, point_on_line, prismatic)");
  EXPECT_EQ(error_of("dimension: 3\nbodies:\n  - {name: b, type: particle}\n"),
            "scene.yaml:3: bodies[b].type: unknown body type 'particle' for dimension 3 (expected rigid_body; beams come from `beams`)");
}

// A schema's range gives the message; a choice lists the schema's names and quotes the value.
TEST(SceneErrors, RangeAndChoiceMessagesComeFromTheSchema) {
  EXPECT_EQ(error_of("solver: {h: 1.0e-3, t_end: 0.01, newton: {max_contraction: 1}}\n" + kPendulum.substr(kPendulum.find('\n') + 1)),
            "scene.yaml:1: solver.newton.max_contraction: expected contraction rate in (0, 1), got 1");
  EXPECT_EQ(error_of("solver: {h: 1.0e-3, t_end: 0.01, scheme: rk4}\n" + kPendulum.substr(kPendulum.find('\n') + 1)),
            "scene.yaml:1: solver.scheme: unknown scheme 'rk4' (expected one of generalized-alpha, hht, newmark)");
  EXPECT_EQ(error_of("solver: {h: 1.0e-3, t_end: 0.01, newton: {modified: sometimes}}\n" + kPendulum.substr(kPendulum.find('\n') + 1)),
            "scene.yaml:1: solver.newton.modified: unknown modified 'sometimes' (expected one of auto, on, off)");
  EXPECT_EQ(error_of("solver: {h: 1.0e-3, t_end: 0.01, newton: {modified_from: 0}}\n" + kPendulum.substr(kPendulum.find('\n') + 1)),
            "scene.yaml:1: solver.newton.modified_from: expected an integer from 1 to 1000000000");
}

// output.checkpoint_every is a key of type Interval: a whole number of steps (a name of
// `parameters` too) or a wall time with its unit, read by the Section from the schema.
TEST(SceneSchemas, CheckpointEveryIsStepsOrAWallTime) {
  const auto every = [](const std::string& value) {
    const Scene sc = read_scene_text("parameters: {n: 3}\noutput: {checkpoint_every: " + value + "}\n" + kPendulum, "scene.yaml");
    return std::make_pair(sc.settings.checkpoint_steps, sc.settings.checkpoint_wall);
  };
  EXPECT_EQ(every("5"), std::make_pair(5L, 0.0));
  EXPECT_EQ(every("n"), std::make_pair(3L, 0.0));
  EXPECT_EQ(every("\"10 min\""), std::make_pair(0L, 600.0));
  EXPECT_EQ(every("\"2 h\""), std::make_pair(0L, 7200.0));
  EXPECT_EQ(error_of("output: {checkpoint_every: 0}\n" + kPendulum),
            "scene.yaml:1: output.checkpoint_every: expected an integer from 1 to 1000000000");
  EXPECT_EQ(error_of("output: {checkpoint_every: [1]}\n" + kPendulum),
            "scene.yaml:1: output.checkpoint_every: expected a number of steps (an integer >= 1) or a wall time with its "
            "unit, e.g. \"600 s\", \"10 min\", \"2 h\"");
}

// Beams and shells are registered block types: the scene's schemas hold one per dimension and kind
// of cell, and the lists of blocks are read through them.
TEST(SceneSchemas, BeamAndShellBlocksAreRegisteredTypes) {
  std::set<std::string> names;
  for (const auto* s : input::scene_schemas()) names.insert(s->name);
  for (const char* block : {"beams.2d", "beams.3d", "shells", "beams.section.material", "shells.section"})
    EXPECT_TRUE(names.count(block)) << block;
  const std::string meshed = "dimension: 3\nmesh: {file: " + testing::source_path("meshes/cantilever.geo") + "}\n"
                             "beams: [{name: b, group: beam, orientation: [0, 1, 0], section: {EA: 1, GA2: 1, GA3: 1,"
                             " GJ: 1, EI2: 1, EI3: 1, rhoA: 1, rhoI2: 1, rhoI3: 1}}, {name: b, group: beam}]\n";
  EXPECT_EQ(error_of(meshed), "scene.yaml:3: beams[b].name: a beam named 'b' exists already");
  EXPECT_EQ(error_of("dimension: 3\nmesh: {file: " + testing::source_path("meshes/cantilever.geo") + "}\nbeams: [1]\n"),
            "scene.yaml:3: beams[0]: expected a map with name, group, section, orientation");
}

// Every key a reader reads is in its schema with the type it is read with: the docs tables are
// what the reader does (a key read but not declared is a std::logic_error, not an input error).
TEST(SceneSchemas, EverySchemaHasDocumentedKeysWithUnits) {
  std::vector<const input::Schema*> all = input::scene_schemas();
  for (const auto* s : study::schemas()) all.push_back(s);
  std::set<std::string> names;
  for (const auto* s : all) {
    EXPECT_TRUE(names.insert(s->name).second) << "two schemas are named " << s->name;
    for (const auto& k : s->keys) {
      EXPECT_FALSE(k.doc.empty()) << s->name << "." << k.name;
      EXPECT_FALSE(k.unit.empty()) << s->name << "." << k.name;
      if (k.type == input::KeyType::Choice) EXPECT_FALSE(k.choices.empty()) << s->name << "." << k.name;
    }
  }
  EXPECT_GT(all.size(), 50u);
}

}  // namespace
}  // namespace alphaflex
