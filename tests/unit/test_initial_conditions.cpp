// Initial conditions of mesh groups (`initial_conditions`, src/io/scene_initial.cpp): a rigid
// velocity field v(x) = v0 + ω0 × (x − x_ref), Ω = Rᵀω0 on beam and shell nodes, and a rigid
// placement x ↦ R x + t of a group applied before its nodes' frames are built.
#include <Eigen/Geometry>

#include "test_scene_runs.hpp"

namespace alphaflex::testing {
namespace {

std::string yaml_list(const Eigen::Vector3d& v) {
  std::ostringstream os;
  os.precision(17);
  os << "[" << v.x() << ", " << v.y() << ", " << v.z() << "]";
  return os.str();
}

// A free beam of length 1 m along x from the origin (meshes/cantilever.geo, 4 elements), section
// axis 2 along y: m = rhoA L = 1.2 kg; rotary inertia per length rhoI2 (about y), rhoI3 (about z),
// rhoI_polar (about x).
const char* kFreeBeam =
    "dimension: 3\nmesh: {file: meshes/cantilever.geo, elements: 4}\n"
    "beams:\n  - {name: beam, group: beam, orientation: [0, 1, 0], section: {EA: 2.8e7, GA2: 1.0e7, GA3: 1.0e7, GJ: 1.4e4, "
    "EI2: 1.4e4, EI3: 1.4e4, rhoA: 1.2, rhoI2: 6.0e-4, rhoI3: 8.0e-4, rhoI_polar: 1.4e-3}}\n";

/// The beam's kinetic and strain energies, summed over its elements (sensor `energy` of: beam).
std::string beam_energy_sensors() {
  return "sensors:\n  - {name: T, type: energy, of: beam, kind: kinetic}\n  - {name: V, type: energy, of: beam, kind: strain}\n";
}

double sum_of(const RunSummary& r, size_t row, char kind) { return r.sensor_history[row][column(r, std::string(1, kind))]; }

}  // namespace

TEST(InitialConditions, ARigidVelocityFieldGivesTheClosedFormKineticEnergyOfTheBeam) {
  // v(x) = v0 + ω0 × (x − x_ref) over the beam, Ω = Rᵀω0 at its nodes: the kinetic energy is that of
  // a rigid body, T = ½ m |v_c|² + ½ ω0ᵀ I_c ω0 with v_c = v0 + ω0 × (c − x_ref), c = (½, 0, 0), and
  // I_c = diag(rhoI_polar L, rhoA L³/12 + rhoI2 L, rhoA L³/12 + rhoI3 L). The beam's consistent mass
  // integrates ρA |v|² exactly (v is linear along a straight element) and its rotary inertia sums
  // to ρI L (the shape functions sum to 1), so T is exact to round-off. Strain energy at t = 0: 0.
  const Eigen::Vector3d v0(0.3, -0.2, 0.1), w0(1.5, -2.0, 3.0), xref(0.2, 0.4, -0.1), c(0.5, 0, 0);
  const std::string yaml = std::string("name: spin_energy\n") + kFreeBeam + "solver: {rho_inf: 1.0, h: 1e-4, t_end: 1e-4}\n" +
                           "initial_conditions:\n  - {group: beam, velocity: " + yaml_list(v0) + ", angular_velocity: " + yaml_list(w0) +
                           ", about: " + yaml_list(xref) + "}\n" + beam_energy_sensors();
  const RunSummary r = run_text(yaml, source_path("spin_energy.yaml"));
  const double m = 1.2, L = 1.0;
  const Eigen::Vector3d vc = v0 + w0.cross(c - xref);
  const Eigen::Matrix3d Ic = Eigen::Vector3d(1.4e-3 * L, m * L * L / 12 + 6e-4 * L, m * L * L / 12 + 8e-4 * L).asDiagonal();
  const double T = 0.5 * m * vc.squaredNorm() + 0.5 * w0.dot(Ic * w0);
  std::printf("[ closed   ] rigid velocity field on a beam: T(0) = %.15f J, closed form %.15f J\n", sum_of(r, 0, 'T'), T);
  EXPECT_NEAR(sum_of(r, 0, 'T'), T, 1e-13 * T);
  EXPECT_NEAR(sum_of(r, 0, 'V'), 0.0, 1e-20);
}

TEST(InitialConditions, AFreeBeamSpinningAboutItsAxisMovesRigidlyWithoutStrainAtConstantMomentum) {
  // Spin ω about the beam's own axis (a principal axis of inertia through the section centres) plus
  // a translation v0: the exact motion is rigid, x(t) = x0 + v0 t, R(t) = exp(ω t e_x) R0, with zero
  // strain energy and constant linear and angular momentum (m v0 and rhoI_polar L ω), so kinetic
  // energy ½ m |v0|² + ½ rhoI_polar L ω² at every step.
  const double w = 6.0;
  const Eigen::Vector3d v0(0.3, -0.2, 0.1);
  const std::string yaml = std::string("name: axial_spin\n") + kFreeBeam + "solver: {rho_inf: 0.8, h: 0.01, t_end: 0.4}\n" +
                           "initial_conditions:\n  - {group: beam, velocity: " + yaml_list(v0) + ", angular_velocity: [" +
                           std::to_string(w) + ", 0, 0]}\n" + beam_energy_sensors() +
                           "  - {name: tip_x, type: point_position, body: tip, component: x}\n"
                           "  - {name: tip_y, type: point_position, body: tip, component: y}\n"
                           "  - {name: tip_turn, type: body_rotation, body: tip, component: x}\n";
  const RunSummary r = run_text(yaml, source_path("axial_spin.yaml"));
  const double T = 0.5 * 1.2 * v0.squaredNorm() + 0.5 * 1.4e-3 * w * w;
  double worst_T = 0.0, worst_V = 0.0, worst_x = 0.0, worst_turn = 0.0;
  for (size_t i = 0; i < r.times_out.size(); ++i) {
    const double t = r.times_out[i];
    worst_T = std::max(worst_T, std::fabs(sum_of(r, i, 'T') - T) / T);
    worst_V = std::max(worst_V, sum_of(r, i, 'V'));
    worst_x = std::max({worst_x, std::fabs(r.sensor_history[i][column(r, "tip_x")] - (1.0 + v0.x() * t)),
                        std::fabs(r.sensor_history[i][column(r, "tip_y")] - v0.y() * t)});
    worst_turn = std::max(worst_turn, std::fabs(r.sensor_history[i][column(r, "tip_turn")] - w * t));
  }
  std::printf("[ closed   ] free beam spinning about its axis: max |T − T0|/T0 = %.1e, max strain energy %.1e J, "
              "max tip position error %.1e m, max turn error %.1e rad\n", worst_T, worst_V, worst_x, worst_turn);
  // Round-off: the motion is exactly rigid, which the scheme reproduces up to Newton's tolerance
  // (rtol 1e-9 on ‖q‖ ~ 1) for positions and turns.
  EXPECT_LE(worst_T, 1e-9);
  EXPECT_LE(worst_V, 1e-12);
  EXPECT_LE(worst_x, 1e-9);
  EXPECT_LE(worst_turn, 1e-8);
}

namespace {

// A beam (curve "beam" from `a` to `b`, 4 elements, points "root", "tip") and a plate (surface
// "plate": corners p0..p3, 3×2 quadrilaterals, edge "clamped" p3–p0, point "corner" p2), apart.
std::string geo(const std::vector<Eigen::Vector3d>& beam, const std::vector<Eigen::Vector3d>& plate) {
  std::ostringstream os;
  os.precision(17);
  int k = 1;
  for (const auto* pts : {&beam, &plate})
    for (const Eigen::Vector3d& p : *pts) os << "Point(" << k++ << ") = {" << p.x() << ", " << p.y() << ", " << p.z() << "};\n";
  os << "Line(1) = {1, 2};\nTransfinite Curve{1} = 5;\n"
        "Line(2) = {3, 4}; Line(3) = {4, 5}; Line(4) = {5, 6}; Line(5) = {6, 3};\n"
        "Transfinite Curve{2, 4} = 4; Transfinite Curve{3, 5} = 3;\n"
        "Curve Loop(1) = {2, 3, 4, 5};\nPlane Surface(1) = {1};\nTransfinite Surface{1};\nRecombine Surface{1};\n"
        "Physical Curve(\"beam\") = {1};\nPhysical Point(\"root\") = {1};\nPhysical Point(\"tip\") = {2};\n"
        "Physical Surface(\"plate\") = {1};\nPhysical Curve(\"clamped\") = {5};\nPhysical Point(\"corner\") = {5};\n";
  return os.str();
}

std::string placed_scene(const std::string& name, const std::string& geo_file, const std::string& beam_orientation,
                         const std::string& placements) {
  return "name: " + name + "\ndimension: 3\ngravity: [0, 0, -9.81]\n"
         "solver: {rho_inf: 0.8, h: 0.002, t_end: 0.04, newton: {rtol: 1e-12, modified: off}}\n"
         "mesh: {file: " + geo_file + "}\n"
         "beams:\n  - {name: beam, group: beam, orientation: " + beam_orientation +
         ", section: {EA: 2.8e7, GA2: 1.0e7, GA3: 1.0e7, GJ: 1.4e3, EI2: 1.4e3, EI3: 2.0e3, rhoA: 1.2, rhoI2: 6.0e-4, rhoI3: 8.0e-4}}\n"
         "shells:\n  - {name: plate, group: plate, thickness: 0.01, material: {E: 2.0e9, nu: 0.3, rho: 1000}}\n"
         "joints:\n  - {name: root, type: fixed, body1: root}\n  - {name: edge, type: fixed, group: clamped}\n"
         "forces:\n  - {name: push, type: force, body: tip, value: [0, 3, {type: ramp, t0: 0, t1: 0.02, to: 5}]}\n" +
         placements +
         "sensors:\n"
         "  - {name: tip_x, type: point_position, body: tip, component: x}\n"
         "  - {name: tip_y, type: point_position, body: tip, component: y}\n"
         "  - {name: tip_z, type: point_position, body: tip, component: z}\n"
         "  - {name: corner_x, type: point_position, body: corner, component: x}\n"
         "  - {name: corner_y, type: point_position, body: corner, component: y}\n"
         "  - {name: corner_z, type: point_position, body: corner, component: z}\n"
         "  - {name: root_fz, type: joint_reaction, joint: root, component: fz}\n"
         "  - {name: root_mx, type: joint_reaction, joint: root, component: mx}\n";
}

}  // namespace

TEST(InitialConditions, APlacedBeamAndPlateMoveAsTheSameBlocksMeshedInThePlacedPosition) {
  // The same beam and plate, (a) meshed in their own position and placed by `initial_conditions`
  // (R = exp(axis-angle), translation), (b) meshed where (a) places them, the beam's orientation
  // vector turned by hand. Under gravity and a tip force they must move alike. The two models differ
  // by the round-off of R x in the node coordinates (~1e-16 m) and of the frames built from them;
  // Newton stops at rtol 1e-12 (quadratic convergence leaves far less), so the sensors agree to
  // ~1e-12 of their size: the test allows 1e-10 m and 1e-8 N (reactions of ~10 N). Full Newton by
  // name: modified Newton (the default from 30 unknowns; modified_newton tests) converges linearly and leaves ~4e-6 N.
  const std::vector<Eigen::Vector3d> beam{{0, 0, 0}, {1, 0, 0}};
  const std::vector<Eigen::Vector3d> plate{{0, 1, 0}, {0.3, 1, 0}, {0.3, 1.2, 0}, {0, 1.2, 0}};
  const Eigen::Vector3d axis1 = Eigen::Vector3d(1, 2, 3).normalized(), axis2 = Eigen::Vector3d(-1, 0.5, 2).normalized();
  const double angle1 = 0.7, angle2 = -1.1;
  const Eigen::Vector3d t1(0.5, -0.2, 1.0), t2(-0.3, 0.4, 0.2);
  const Eigen::Matrix3d R1 = Eigen::AngleAxisd(angle1, axis1).toRotationMatrix(), R2 = Eigen::AngleAxisd(angle2, axis2).toRotationMatrix();
  std::vector<Eigen::Vector3d> beam_p, plate_p;
  for (const auto& p : beam) beam_p.push_back(R1 * p + t1);
  for (const auto& p : plate) plate_p.push_back(R2 * p + t2);
  const TestOutputDir dir("placement");
  const std::string here = dir.write("here.geo", geo(beam, plate)), there = dir.write("there.geo", geo(beam_p, plate_p));
  std::ostringstream rot2;  // the plate's rotation as a matrix (rows), the beam's as {axis, angle}
  rot2.precision(17);
  rot2 << "[[" << R2(0, 0) << ", " << R2(0, 1) << ", " << R2(0, 2) << "], [" << R2(1, 0) << ", " << R2(1, 1) << ", " << R2(1, 2)
       << "], [" << R2(2, 0) << ", " << R2(2, 1) << ", " << R2(2, 2) << "]]";
  std::ostringstream a1;
  a1.precision(17);
  a1 << angle1;
  const RunSummary placed = run_text(
      placed_scene("placed", here, "[0, 1, 0]",
                   "initial_conditions:\n  - {group: beam, rotation: {axis: " + yaml_list(axis1) + ", angle: " + a1.str() + "}, translation: " + yaml_list(t1) +
                       "}\n  - {group: plate, rotation: " + rot2.str() + ", translation: " + yaml_list(t2) + "}\n"),
      dir.file("placed.yaml"));
  const RunSummary meshed = run_text(placed_scene("meshed", there, yaml_list(R1 * Eigen::Vector3d::UnitY()), ""), dir.file("meshed.yaml"));
  ASSERT_EQ(placed.times_out.size(), meshed.times_out.size());
  double worst_x = 0.0, worst_f = 0.0, moved = 0.0;
  for (size_t i = 0; i < placed.times_out.size(); ++i)
    for (size_t c = 0; c < placed.sensor_names.size(); ++c) {
      const double d = std::fabs(placed.sensor_history[i][c] - meshed.sensor_history[i][c]);
      if (placed.sensor_names[c].rfind("root_", 0) == 0) worst_f = std::max(worst_f, d);
      else worst_x = std::max(worst_x, d);
    }
  for (size_t c = 0; c < 6; ++c) moved = std::max(moved, std::fabs(placed.final_sensors[c] - placed.sensor_history[0][c]));
  std::printf("[ compare  ] placed vs meshed in place: max position difference %.1e m (motion %.1e m), reaction %.1e N\n", worst_x, moved, worst_f);
  EXPECT_GT(moved, 1e-4);  // the blocks do move (0.9 mm)
  EXPECT_NEAR(placed.sensor_history[0][0], beam_p[1].x(), 1e-14);
  EXPECT_NEAR(placed.sensor_history[0][5], plate_p[2].z(), 1e-14);
  EXPECT_LE(worst_x, 1e-10);
  EXPECT_LE(worst_f, 1e-8);
}

TEST(InitialConditions, AVelocityThatViolatesAJointIsProjectedByTheConsistentStart) {
  // A clamped beam given a uniform velocity (0, 0, 1) m/s: the clamp allows none at the root. The
  // consistent start (on by default) projects the velocities onto Φ_q v = 0 with the least change
  // of kinetic energy, so the root's velocity is 0 at t = 0 and the tip keeps a part of its own.
  const std::string yaml = std::string("name: clamped_spin\n") + kFreeBeam + "solver: {rho_inf: 0.8, h: 1e-3, t_end: 2e-3}\n" +
                           "joints:\n  - {name: clamp, type: fixed, body1: root}\n"
                           "initial_conditions:\n  - {group: beam, velocity: [0, 0, 1]}\n"
                           "sensors:\n  - {name: root_vz, type: point_velocity, body: root, component: z}\n"
                           "  - {name: tip_vz, type: point_velocity, body: tip, component: z}\n";
  const RunSummary r = run_text(yaml, source_path("clamped_spin.yaml"));
  std::printf("[ start    ] clamped beam given v = 1 m/s: root %.1e m/s, tip %.3f m/s at t = 0\n", r.sensor_history[0][0], r.sensor_history[0][1]);
  EXPECT_NEAR(r.sensor_history[0][0], 0.0, 1e-12);
  EXPECT_GT(r.sensor_history[0][1], 0.1);
  EXPECT_LT(r.sensor_history[0][1], 1.0);
}

TEST(InitialConditions, BadInputIsRefusedNamingTheKey) {
  const std::string head = std::string("name: bad\n") + kFreeBeam + "solver: {h: 0.01, t_end: 0.01}\n";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"initial_conditions:\n  - {group: nope, translation: [1, 0, 0]}\n", "initial_conditions[0].group: mesh '"},
      {"initial_conditions:\n  - {group: tip, rotation: [0, 0, 1]}\n", "(a placement moves a curve or surface group)"},
      {"initial_conditions:\n  - {group: beam, rotation: [[1, 0, 0], [0, 1, 0], [0, 0, -1]]}\n",
       "initial_conditions[0].rotation: expected a rotation matrix (RᵀR = I to 1e-9, det R = +1)"},
      {"initial_conditions:\n  - {group: beam, translation: [1, 0, 0]}\n  - {group: beam, translation: [0, 1, 0]}\n",
       "initial_conditions[1].group: group 'beam' is placed twice"},
      {"initial_conditions:\n  - {group: beam, spin: [1, 0, 0]}\n", "initial_conditions[0].spin: unknown key"},
      {"initial_conditions:\n  - {group: beam, velocity: [1, 0]}\n", "initial_conditions[0].velocity: expected a list of 3 numbers"},
  };
  for (const auto& [tail, expected] : cases) {
    const std::string msg = input_error_of([&] { read_scene_text(head + tail, source_path("bad.yaml")); });
    EXPECT_NE(msg.find(expected), std::string::npos) << "got: " << msg << "\nexpected: " << expected;
  }
  const std::string no_mesh = input_error_of([&] {
    read_scene_text("name: bad\ndimension: 3\nsolver: {h: 0.01, t_end: 0.01}\nbodies:\n  - {name: b, type: rigid_body, mass: 1, inertia: [1, 1, 1], position: [0, 0, 0]}\n"
                    "initial_conditions:\n  - {group: beam, velocity: [1, 0, 0]}\n", "bad.yaml");
  });
  EXPECT_NE(no_mesh.find("initial_conditions: the scene has no `mesh`"), std::string::npos) << no_mesh;
}

}  // namespace alphaflex::testing
