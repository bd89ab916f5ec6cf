// Singular iteration matrices are explained by name (design §5): redundant constraints (dependent
// rows of Φ_q) and massless coordinates on which nothing acts (null space of [M; Φ_q]).
#include <gtest/gtest.h>
#include <petscsys.h>

#include "alphaflex/assembly/diagnostics.hpp"
#include "alphaflex/core/error.hpp"
#include "alphaflex/io/scene.hpp"
#include "alphaflex/app/simulation.hpp"

namespace alphaflex {
namespace {

const char* kPendulumScene = R"(
bodies:
  - {name: bar, type: rigid_body, mass: 1, inertia: 0.1, position: [0.5, 0], angle: 0}
joints:
  - {name: pin, type: revolute, body1: bar, point1: [-0.5, 0], body2: ground, point2: [0, 0]}
)";

TEST(Diagnostics, WellPosedPendulumHasNoFinding) {
  Scene sc = read_scene_text(kPendulumScene, "pendulum.yaml");
  EXPECT_TRUE(find_redundant_constraints(*sc.model, sc.model->initial_state()).empty());
  EXPECT_EQ(diagnose_singular_system(*sc.model, sc.model->initial_state()), "");
}

// A second pin at the same point repeats both equations of the first.
TEST(Diagnostics, DuplicatePinIsNamedAsRedundant) {
  Scene sc = read_scene_text(std::string(kPendulumScene) + "  - {name: pin2, type: fixed_point, body: bar, point: [-0.5, 0]}\n",
                             "pendulum.yaml");
  const auto red = find_redundant_constraints(*sc.model, sc.model->initial_state());
  ASSERT_EQ(red.size(), 2u);
  for (const auto& e : red) {
    EXPECT_EQ(sc.model->constraints()[static_cast<size_t>(e.constraint)]->name(), "pin2");
    ASSERT_EQ(e.depends_on.size(), 1u);
    EXPECT_EQ(sc.model->constraints()[static_cast<size_t>(e.depends_on[0])]->name(), "pin");
  }
  const std::string why = diagnose_singular_system(*sc.model, sc.model->initial_state());
  EXPECT_NE(why.find("joint 'pin2'"), std::string::npos) << why;
}

// A rigid bar pinned to the ground at both ends is over-constrained by one equation: the
// x-equation of the second pin repeats what the first pin and the rigidity impose.
TEST(Diagnostics, BarPinnedAtBothEndsHasOneRedundantEquation) {
  Scene sc = read_scene_text(std::string(kPendulumScene) +
                                 "  - {name: tip, type: revolute, body1: bar, point1: [0.5, 0], body2: ground, point2: [1, 0]}\n",
                             "bar.yaml");
  const auto red = find_redundant_constraints(*sc.model, sc.model->initial_state());
  ASSERT_EQ(red.size(), 1u);
  EXPECT_EQ(sc.model->constraints()[static_cast<size_t>(red[0].constraint)]->name(), "tip");
  EXPECT_EQ(red[0].equation, 0);  // x
  EXPECT_EQ(red[0].depends_on.size(), 1u);
}

// A spherical joint where a revolute one already holds the body repeats its three point equations;
// they are named by the joint table's equation names (joints/spatial_joints.cpp).
TEST(Diagnostics, RedundantSpatialJointEquationsAreNamed) {
  const char* yaml = R"(
dimension: 3
bodies:
  - {name: crank, type: rigid_body, mass: 1, inertia: [1e-3, 1e-2, 1e-2], position: [0.5, 0, 0]}
joints:
  - {name: hinge, type: revolute, body1: crank, body2: ground, location: [0, 0, 0], axis: [0, 0, 1]}
  - {name: ball, type: spherical, body1: crank, body2: ground, location: [0, 0, 0]}
)";
  Scene sc = read_scene_text(yaml, "crank.yaml");
  const auto red = find_redundant_constraints(*sc.model, sc.model->initial_state());
  ASSERT_EQ(red.size(), 3u);
  const std::string why = diagnose_singular_system(*sc.model, sc.model->initial_state());
  for (const char* e : {"equation 1 (x)", "equation 2 (y)", "equation 3 (z)"})
    EXPECT_NE(why.find(std::string("joint 'ball' (spherical) ") + e + " is a combination of equations of 'hinge'"),
              std::string::npos)
        << why;
}

// A massless point hanging on one revolute joint is fixed; a second massless point attached to
// nothing has two free coordinates on which neither mass nor joint acts.
TEST(Diagnostics, MasslessPointWithoutJointIsNamed) {
  const char* yaml = R"(
bodies:
  - {name: bar, type: rigid_body, mass: 1, inertia: 0.1, position: [0.5, 0], angle: 0}
  - {name: tipnode, type: particle, position: [1, 0]}
  - {name: loose, type: particle, position: [2, 0]}
joints:
  - {name: pin, type: revolute, body1: bar, point1: [-0.5, 0], body2: ground, point2: [0, 0]}
  - {name: tip, type: revolute, body1: bar, point1: [0.5, 0], body2: tipnode}
)";
  Scene sc = read_scene_text(yaml, "loose.yaml");
  const std::string why = diagnose_singular_system(*sc.model, sc.model->initial_state());
  EXPECT_NE(why.find("body 'loose' (x)"), std::string::npos) << why;
  EXPECT_NE(why.find("body 'loose' (y)"), std::string::npos) << why;
  EXPECT_EQ(why.find("tipnode"), std::string::npos) << why;
  EXPECT_EQ(why.find("redundant"), std::string::npos) << why;
}

// A massless point held by two springs but by no joint has no defined acceleration: the
// consistent start's [[M, Φ_qᵀ],[Φ_q, 0]] is singular although the springs act on it. The run
// stops as bad input naming the point and saying that springs are not enough.
TEST(Diagnostics, MasslessPointOnSpringsAloneIsNamed) {
  const char* yaml = R"(
solver: {h: 1e-3, t_end: 0.01}
bodies:
  - {name: p, type: particle, position: [0.5, 0.1]}
forces:
  - {name: s1, type: spring_damper, body1: p, body2: ground, point2: [0, 0], stiffness: 100, rest_length: 0.4}
  - {name: s2, type: spring_damper, body1: p, body2: ground, point2: [1, 0], stiffness: 100, rest_length: 0.4}
)";
  Scene sc = read_scene_text(yaml, "springs.yaml");
  RunOptions opt;
  opt.write_results = false;
  try {
    run_simulation(sc, opt, PETSC_COMM_WORLD);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("body 'p' (x)"), std::string::npos) << m;
    EXPECT_NE(m.find("springs alone"), std::string::npos) << m;
  }
}

// Through the run driver: redundant joints stop the run before any step, as bad input naming
// the joint; so does a free massless point, naming the body.
TEST(Diagnostics, RunReportsRedundantJointsAndFreeMasslessPointsByName) {
  RunOptions opt;
  opt.write_results = false;
  Scene red = read_scene_text(std::string(kPendulumScene) + "  - {name: pin2, type: fixed_point, body: bar, point: [-0.5, 0]}\n",
                              "red.yaml");
  try {
    run_simulation(red, opt, PETSC_COMM_WORLD);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("'pin2'"), std::string::npos) << e.what();
  }
  const char* yaml = R"(
bodies:
  - {name: bar, type: rigid_body, mass: 1, inertia: 0.1, position: [0.5, 0], angle: 0}
  - {name: loose, type: particle, position: [2, 0]}
joints:
  - {name: pin, type: revolute, body1: bar, point1: [-0.5, 0], body2: ground, point2: [0, 0]}
)";
  Scene free = read_scene_text(yaml, "free.yaml");
  try {
    run_simulation(free, opt, PETSC_COMM_WORLD);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("free.yaml"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("body 'loose'"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace alphaflex
