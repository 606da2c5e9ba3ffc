// Springs behave as AGX's spring constraint (docs/mapping.md "Springs"): one row with compliance 1/k, SPOOK
// damping and its force bounded by the effort range, solved with the rest of the system. Swept over what a
// user may set (effort limits 150, 200, 1000 N and none; stiffness 1e3..1e6; time steps 0.002 and 0.02): the
// rod comes to rest where its springs balance its weight, a spring never pushes beyond its limits, parallel
// springs keep their own rests, and the motion is AGX's row step for step.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "openplx/runtime/simulation.h"
#include "tests/support/scratch_dir.h"

namespace {

namespace rt = openplx::runtime;

constexpr double kMass = 10, kGravity = 9.81, kDefaultRelaxationTime = 2.0 / 60.0;
constexpr double kNoLimit = std::numeric_limits<double>::infinity();

std::string number(double x) {
  std::ostringstream out;
  out.precision(17);
  out << x;
  return out.str();
}

struct SpringSpec {
  double stiffness = 1e6;
  double limit = 200;                     // symmetric effort range; kNoLimit: none
  std::optional<double> min_effort;       // overrides -limit
  std::optional<double> relaxation_time;  // none: the model's default dissipation
  double rest = 0;
};

// LinearSpringTest's scene (tests/corpus README): a 10 kg rod on a vertical prismatic whose position q is
// up (0 at the springs' reference, z = -0.5 + q), released at rest from q = `start`, with springs on it.
std::string falling_rod(const std::vector<SpringSpec>& springs, double start = -0.25) {
  std::string text =
      "Rod is Physics3D.Bodies.RigidBody:\n"
      "    inertia.mass: 10\n"
      "    geometry is Physics3D.Geometries.Box:\n"
      "        size: Math.Vec3.from_xyz(0.1, 0.1, 1)\n"
      "    input_connector is Physics3D.Interactions.MateConnector:\n"
      "        position.z: -geometry.size.z * 0.5\n"
      "        main_axis: -Math.Vec3.Z_AXIS()\n"
      "        normal: -Math.Vec3.Y_AXIS()\n"
      "Scene is Physics3D.System:\n"
      "    world_connector is Physics3D.Interactions.MateConnector:\n"
      "        main_axis: Math.Vec3.Z_AXIS()\n"
      "        normal: Math.Vec3.Y_AXIS()\n"
      "    rod is Rod\n"
      "    prismatic is Physics3D.Interactions.Prismatic:\n"
      "        connectors: [world_connector, rod.input_connector]\n"
      "        initial_position: " +
      number(start) + "\n";
  for (size_t i = 0; i < springs.size(); ++i) {
    const SpringSpec& s = springs[i];
    text += "    spring" + std::to_string(i) +
            " is Physics3D.Interactions.LinearSpring:\n"
            "        connectors: [world_connector, rod.input_connector]\n"
            "        force_output.enabled: true\n"
            "        flexibility.stiffness: " +
            number(s.stiffness) + "\n        position: " + number(s.rest) + "\n";
    if (s.limit != kNoLimit) {
      text += "        min_effort: " + number(s.min_effort.value_or(-s.limit)) + "\n";
      text += "        max_effort: " + number(s.limit) + "\n";
    }
    if (s.relaxation_time) {
      text +=
          "        dissipation becomes Physics.Interactions.Dissipation.ConstraintRelaxationTimeDamping:\n"
          "            relaxation_time: " +
          number(*s.relaxation_time) + "\n";
    }
  }
  return text;
}

rt::Simulation load(const openplx::testing::ScratchDir& dir, const std::string& text, double timestep) {
  const auto file = dir / "model.openplx";
  std::ofstream(file) << text;
  rt::LoadOptions options;
  options.timestep = timestep;
  return rt::Simulation::load(file.string(), options);
}

// What the rod does over `seconds`: where it ends, how fast, and each spring's force extremes.
struct RodRun {
  double q = 0, v = 0;
  std::vector<double> largest, smallest, final_force;
  std::vector<double> trajectory;  // q after every step
};

RodRun run(rt::Simulation& sim, size_t springs, double seconds) {
  const mjModel* m = sim.model();
  const int joint = mj_name2id(m, mjOBJ_JOINT, "prismatic");
  EXPECT_GE(joint, 0);
  std::vector<rt::Output> forces;
  for (size_t i = 0; i < springs; ++i)
    forces.push_back(sim.output("spring" + std::to_string(i) + ".force_output"));
  RodRun r;
  r.largest.assign(springs, -kNoLimit);
  r.smallest.assign(springs, kNoLimit);
  const long steps = std::lround(seconds / sim.timestep());
  for (long k = 0; k < steps; ++k) {
    sim.step();
    for (size_t i = 0; i < springs; ++i) {
      r.largest[i] = std::max(r.largest[i], forces[i].real());
      r.smallest[i] = std::min(r.smallest[i], forces[i].real());
    }
    r.trajectory.push_back(sim.data()->qpos[m->jnt_qposadr[joint]]);
  }
  r.q = sim.data()->qpos[m->jnt_qposadr[joint]];
  r.v = sim.data()->qvel[m->jnt_dofadr[joint]];
  for (auto& f : forces) r.final_force.push_back(f.real());
  return r;
}

// AGX's spring row for one body on one axis, in SPOOK's form (Lacoursiere): per step, with Y = 1 / (1 + 4
// tau / h) and softness S = 4 Y / (h^2 k), the row's impulse solves v+ + S h f = -(4 Y / h) x + Y v, clamped
// to [min, max]; then v+ = v + h (f - m g) / m, q+ = q + h v+.
std::vector<double> agx_row(const SpringSpec& s, double h, double start, double seconds) {
  const double upsilon = 1 / (1 + 4 * s.relaxation_time.value_or(kDefaultRelaxationTime) / h);
  const double softness = 4 * upsilon / (h * h * s.stiffness);
  const double low = s.limit == kNoLimit ? -kNoLimit : s.min_effort.value_or(-s.limit), high = s.limit;
  double q = start, v = 0;
  std::vector<double> out;
  for (long k = 0; k < std::lround(seconds / h); ++k) {
    const double free_v = v - h * kGravity;  // the velocity the row's force adds to
    const double f = (-4 * upsilon / h * (q - s.rest) + upsilon * v - free_v) / (h / kMass + softness * h);
    v = free_v + h * std::clamp(f, low, high) / kMass;
    q += h * v;
    out.push_back(q);
  }
  return out;
}

// A relaxation time that damps the rod at least critically whatever k: 2 sqrt(m / k), not below AGX's.
double well_damped(double k) {
  return std::max(kDefaultRelaxationTime, 2 * std::sqrt(kMass / k));
}

// LinearSpringTest itself (1e6 N/m, +-200 N, AGX's default damping), AGXUnity's expectation: at rest within
// 1 mm and 1 mm/s after 2 s at z = -0.5 (the spring's stretch m g / k = 0.1 mm), and never above 200 N.
TEST(SpringRow, LinearSpringTestComesToRestWithinItsLimit) {
  for (const double h : {0.002, 0.02}) {
    SCOPED_TRACE("h = " + number(h));
    const openplx::testing::ScratchDir dir;
    std::ifstream in(std::filesystem::path(OPENPLX_CORPUS_DIR) / "agxunity" / "LinearSpringTest.openplx");
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const auto file = dir / "LinearSpringTest.openplx";
    std::ofstream(file) << text;
    rt::LoadOptions options;
    options.timestep = h;
    options.model = "FallingRodScene";
    rt::Simulation sim = rt::Simulation::load(file.string(), options);
    rt::Output force = sim.output("falling_rod.external_spring.force_output");
    const int body = mj_name2id(sim.model(), mjOBJ_BODY, "falling_rod.rod1");
    ASSERT_GE(body, 0);
    double largest = 0;
    for (long k = 0; k < std::lround(2.0 / h); ++k) {
      sim.step();
      largest = std::max(largest, std::abs(force.real()));
    }
    EXPECT_NEAR(sim.data()->xpos[3 * body + 2], -0.5, 1e-3);
    EXPECT_NEAR(sim.data()->qvel[0], 0.0, 1e-3);
    EXPECT_LE(largest, 200 * (1 + 1e-12));
    EXPECT_GT(largest, 199);                            // it did brake at its limit
    EXPECT_NEAR(force.real(), kMass * kGravity, 1e-6);  // at rest it carries the rod
  }
}

// The sweep: every limit, stiffness and step comes to rest at q = rest - m g / k within 1 mm and 1 mm/s
// after 2 s, pushing no more than its limit on any step.
TEST(SpringRow, SweepComesToRestWithinItsLimit) {
  for (const double h : {0.002, 0.02}) {
    for (const double limit : {150.0, 200.0, 1000.0, kNoLimit}) {
      for (const double k : {1e3, 1e4, 1e5, 1e6}) {
        SCOPED_TRACE("h = " + number(h) + ", limit = " + number(limit) + ", k = " + number(k));
        SpringSpec s;
        s.stiffness = k;
        s.limit = limit;
        s.relaxation_time = well_damped(k);
        const openplx::testing::ScratchDir dir;
        rt::Simulation sim = load(dir, falling_rod({s}), h);
        const RodRun r = run(sim, 1, 2.0);
        EXPECT_NEAR(r.q, -kMass * kGravity / k, 1e-3);
        EXPECT_NEAR(r.v, 0.0, 1e-3);
        if (limit != kNoLimit) {
          EXPECT_LE(r.largest[0], limit * (1 + 1e-12));
          EXPECT_GE(r.smallest[0], -limit * (1 + 1e-12));
        }
      }
    }
  }
}

// Step for step the rod moves as AGX's row moves it (the scalar SPOOK row above), limited or not, at AGX's
// default damping and others.
TEST(SpringRow, MovesAsAgxsRowStepForStep) {
  for (const double h : {0.002, 0.02}) {
    for (const double limit : {200.0, kNoLimit}) {
      for (const double k : {1e3, 1e6}) {
        for (const std::optional<double> tau : {std::optional<double>(), std::optional<double>(0.1)}) {
          SCOPED_TRACE("h = " + number(h) + ", limit = " + number(limit) + ", k = " + number(k) +
                       ", tau = " + (tau ? number(*tau) : "default"));
          SpringSpec s;
          s.stiffness = k;
          s.limit = limit;
          s.relaxation_time = tau;
          const openplx::testing::ScratchDir dir;
          rt::Simulation sim = load(dir, falling_rod({s}), h);
          const RodRun r = run(sim, 1, 1.0);
          const std::vector<double> agx = agx_row(s, h, -0.25, 1.0);
          ASSERT_EQ(r.trajectory.size(), agx.size());
          double worst = 0;
          for (size_t i = 0; i < agx.size(); ++i) worst = std::max(worst, std::abs(r.trajectory[i] - agx[i]));
          EXPECT_LT(worst, 1e-9);
        }
      }
    }
  }
}

// Two springs on one prismatic with their own rests, stiffnesses and limits: the rod rests where their
// forces balance its weight, k1 (r1 - q) + k2 (r2 - q) = m g, and each carries its own share. With limits
// of 1000 N both shares (774.5 and -676.4 N) are inside them.
TEST(SpringRow, ParallelSpringsKeepTheirOwnRests) {
  for (const double h : {0.002, 0.02}) {
    for (const double limit : {1000.0, kNoLimit}) {
      SCOPED_TRACE("h = " + number(h) + ", limit = " + number(limit));
      SpringSpec a, b;
      a.stiffness = 1e4;
      a.rest = 0.1;
      a.limit = limit;
      b.stiffness = 3e4;
      b.rest = 0;
      b.limit = limit;
      a.relaxation_time = b.relaxation_time = well_damped(a.stiffness + b.stiffness);
      const openplx::testing::ScratchDir dir;
      rt::Simulation sim = load(dir, falling_rod({a, b}), h);
      const RodRun r = run(sim, 2, 2.0);
      const double q =
          (a.stiffness * a.rest + b.stiffness * b.rest - kMass * kGravity) / (a.stiffness + b.stiffness);
      EXPECT_NEAR(r.q, q, 1e-6);
      EXPECT_NEAR(r.v, 0.0, 1e-6);
      EXPECT_NEAR(r.final_force[0], a.stiffness * (a.rest - q), 1e-3);
      EXPECT_NEAR(r.final_force[1], b.stiffness * (b.rest - q), 1e-3);
      if (limit != kNoLimit) {
        for (size_t i = 0; i < 2; ++i) {
          EXPECT_LE(r.largest[i], limit * (1 + 1e-12));
          EXPECT_GE(r.smallest[i], -limit * (1 + 1e-12));
        }
      }
    }
  }
}

// When one of two parallel springs would pass its limit at the balance, it pushes its limit and the other
// carries the rest: rests 0.1 and -0.3 m, 1e4 and 3e4 N/m, both +-1000 N: the first pushes 1000 N up, the
// second the remaining m g - 1000 N, so the rod rests at q = -0.3 - (m g - 1000) / 3e4.
TEST(SpringRow, ParallelSpringAtItsLimitLeavesTheRestToTheOther) {
  for (const double h : {0.002, 0.02}) {
    SCOPED_TRACE("h = " + number(h));
    SpringSpec a, b;
    a.stiffness = 1e4;
    a.rest = 0.1;
    a.limit = 1000;
    b.stiffness = 3e4;
    b.rest = -0.3;
    b.limit = 1000;
    a.relaxation_time = b.relaxation_time = well_damped(a.stiffness + b.stiffness);
    const openplx::testing::ScratchDir dir;
    rt::Simulation sim = load(dir, falling_rod({a, b}), h);
    const RodRun r = run(sim, 2, 2.0);
    const double second = kMass * kGravity - 1000;
    EXPECT_NEAR(r.final_force[0], 1000, 1e-6);
    EXPECT_NEAR(r.final_force[1], second, 1e-6);
    EXPECT_NEAR(r.q, b.rest - second / b.stiffness, 1e-6);
    EXPECT_NEAR(r.v, 0.0, 1e-6);
  }
}

// The enable input switches the row: off, the rod falls freely and the spring reads 0; on, the row catches
// it within its limit and it rests at -m g / k.
TEST(SpringRow, EnableInputSwitchesTheRow) {
  for (const double h : {0.002, 0.02}) {
    SCOPED_TRACE("h = " + number(h));
    std::string text = falling_rod({SpringSpec{}}, 0.0);
    text += "        enabled: false\n";
    const openplx::testing::ScratchDir dir;
    rt::Simulation sim = load(dir, text, h);
    rt::Output force = sim.output("spring0.force_output");
    sim.advance(0.1);
    EXPECT_EQ(force.real(), 0.0);
    EXPECT_NEAR(sim.data()->qvel[0], -kGravity * 0.1, 1e-9);  // free fall
    sim.input("spring0.enable_interaction_input").set(true);
    const RodRun r = run(sim, 1, 2.0);
    EXPECT_LE(r.largest[0], 200 * (1 + 1e-12));
    EXPECT_NEAR(r.q, -kMass * kGravity / 1e6, 1e-3);
    EXPECT_NEAR(r.v, 0.0, 1e-3);
  }
}

// An effort range not centred on zero ([-50, 300] N): the spring lifts the rod with at most 300 N, brakes
// its overshoot with at most 50 N, and still rests at the rest less m g / k.
TEST(SpringRow, AsymmetricEffortRangeBoundsEachSide) {
  for (const double h : {0.002, 0.02}) {
    SCOPED_TRACE("h = " + number(h));
    SpringSpec s;
    s.limit = 300;
    s.min_effort = -50;
    const openplx::testing::ScratchDir dir;
    rt::Simulation sim = load(dir, falling_rod({s}), h);
    const RodRun r = run(sim, 1, 2.0);
    EXPECT_LE(r.largest[0], 300 * (1 + 1e-12));
    EXPECT_GT(r.largest[0], 299);
    EXPECT_GE(r.smallest[0], -50 * (1 + 1e-12));
    EXPECT_NEAR(r.q, -kMass * kGravity / s.stiffness, 1e-3);
    EXPECT_NEAR(r.v, 0.0, 1e-3);
    const std::vector<double> agx = agx_row(s, h, -0.25, 2.0);
    double worst = 0;
    for (size_t i = 0; i < agx.size(); ++i) worst = std::max(worst, std::abs(r.trajectory[i] - agx[i]));
    EXPECT_LT(worst, 1e-9);
  }
}

// A torsion spring is the same row about a hinge: a 1 kg, 1 m rod released 0.5 rad from the rest of a
// 1000 N m/rad spring limited to +-10 N m comes to rest where the spring carries gravity's 4.905 N m.
TEST(SpringRow, TorsionSpringComesToRestWithinItsLimit) {
  for (const double h : {0.002, 0.02}) {
    SCOPED_TRACE("h = " + number(h));
    const std::string text =
        "Rod is Physics3D.Bodies.RigidBody:\n"
        "    inertia.mass: 1\n"
        "    geometry is Physics3D.Geometries.Box:\n"
        "        size: {1, 0.02, 0.02}\n"
        "    end is Physics3D.Interactions.MateConnector:\n"
        "        position.x: -0.5\n"
        "        main_axis: Math.Vec3.Y_AXIS()\n"
        "        normal: Math.Vec3.X_AXIS()\n"
        "Scene is Physics3D.System:\n"
        "    pivot is Physics3D.Interactions.MateConnector:\n"
        "        main_axis: Math.Vec3.Y_AXIS()\n"
        "        normal: Math.Vec3.X_AXIS()\n"
        "    rod is Rod\n"
        "    hinge is Physics3D.Interactions.Hinge:\n"
        "        connectors: [pivot, rod.end]\n"
        "        initial_angle: 0.5\n"
        "    spring is Physics3D.Interactions.TorsionSpring:\n"
        "        connectors: [pivot, rod.end]\n"
        "        torque_output.enabled: true\n"
        "        flexibility.stiffness: 1000\n"
        "        min_effort: -10\n"
        "        max_effort: 10\n";
    const openplx::testing::ScratchDir dir;
    rt::Simulation sim = load(dir, text, h);
    rt::Output torque = sim.output("spring.torque_output");
    rt::Output angle = sim.output("hinge.angle_output");
    rt::Output speed = sim.output("hinge.angular_velocity_output");
    double largest = 0;
    for (long k = 0; k < std::lround(2.0 / h); ++k) {
      sim.step();
      largest = std::max(largest, std::abs(torque.real()));
    }
    EXPECT_LE(largest, 10 * (1 + 1e-12));
    EXPECT_GT(largest, 9.9);
    const double gravity = 1.0 * kGravity * 0.5;  // m g L / 2 about the hinge, at an angle near 0
    EXPECT_NEAR(std::abs(angle.real()), gravity / 1000, 1e-3);
    EXPECT_NEAR(speed.real(), 0.0, 1e-3);
    EXPECT_NEAR(std::abs(torque.real()), gravity, 1e-2);
  }
}

// A model with friction-row drives asks MuJoCo for noslip, which would make spring rows rigid servos: the
// runtime turns noslip off and hardens the drives' rows itself, so in one model the limited spring rests as
// AGX's does and a velocity motor under a gravity load holds its target, at both steps.
TEST(SpringRow, SpringAndVelocityMotorInOneModelAreBothExact) {
  for (const double h : {0.002, 0.02}) {
    SCOPED_TRACE("h = " + number(h));
    SpringSpec s;  // LinearSpringTest's spring: 1e6 N/m, +-200 N, AGX's default damping
    const std::string text =
        "Arm is Physics3D.Bodies.RigidBody:\n"
        "    inertia.mass: 1\n"
        "    geometry is Physics3D.Geometries.Box:\n"
        "        size: {1, 0.02, 0.02}\n"
        "    end is Physics3D.Interactions.MateConnector:\n"
        "        position.x: -0.5\n"
        "        main_axis: Math.Vec3.Y_AXIS()\n"
        "        normal: Math.Vec3.X_AXIS()\n" +
        falling_rod({s}) +
        "    pivot is Physics3D.Interactions.MateConnector:\n"
        "        position.x: 5\n"
        "        main_axis: Math.Vec3.Y_AXIS()\n"
        "        normal: Math.Vec3.X_AXIS()\n"
        "    arm is Arm\n"
        "    hinge is Physics3D.Interactions.Hinge:\n"
        "        connectors: [pivot, arm.end]\n"
        "    motor is Physics3D.Interactions.RotationalVelocityMotor:\n"
        "        connectors: [pivot, arm.end]\n"
        "        target_speed: 1\n"
        "        min_effort: -10\n"
        "        max_effort: 10\n";
    const openplx::testing::ScratchDir dir;
    rt::Simulation sim = load(dir, text, h);
    // The motor's friction row is what makes the emitted model ask for noslip.
    EXPECT_GE(mj_name2id(sim.model(), mjOBJ_TENDON, "motor"), 0);
    rt::Output speed = sim.output("hinge.angular_velocity_output");
    const RodRun r = run(sim, 1, 2.0);
    EXPECT_NEAR(r.q, -kMass * kGravity / s.stiffness, 1e-3);
    EXPECT_NEAR(r.v, 0.0, 1e-3);
    EXPECT_LE(r.largest[0], 200 * (1 + 1e-12));
    // The arm's weight (up to m g L / 2 = 4.9 N m, within the motor's 10, on I = m L^2 / 3) leaks h (1 - d)
    // a0 per step through the hardened row, 1 - d = 1e-8 (spring_rows.cpp): the motor holds within it.
    const double a0 = 1.0 * kGravity * 0.5 / (1.0 / 3);
    EXPECT_NEAR(speed.real(), 1.0, 2 * h * 1e-8 * a0);
  }
}

}  // namespace
