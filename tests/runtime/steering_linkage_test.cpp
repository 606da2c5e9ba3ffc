// Steering columns (Vehicles.Steering.Kinematic.BellCrank and RackAndPinion): the steering input is the
// steering-wheel angle, read back exactly by the steering output; the wheels take the angles of the linkage
// (steering_linkage.h), recomputed here in closed form from the geometry, within the emitter's reported fit
// errors; gear and steering_column_distance act as the geometry says.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <Eigen/Geometry>
#include <cmath>
#include <fstream>
#include <functional>

#include "mjcf_emitter/steering_linkage.h"
#include "openplx/runtime/simulation.h"
#include "tests/support/front_axle.h"
#include "tests/support/scratch_dir.h"

namespace {

namespace rt = openplx::runtime;
namespace mj = openplx::mjcf;
using Eigen::Vector2d;

// A static chassis with two steered front wheels 1.6 m apart on soft suspensions, and `steering` (its
// parameter lines under the steering's interaction).
std::string car(const std::string& mechanism, const std::string& parameters) {
  std::string text = openplx::testing::front_axle(
      "        mate.spring_constant.stiffness: 20000\n"
      "        mate.spring_damping.damping_constant: 1265\n",
      true);
  text += "    steering is Vehicles.Steering.Kinematic." + mechanism +
          ":\n"
          "        left_suspension: left_suspension\n"
          "        right_suspension: right_suspension\n" +
          parameters;
  return text;
}

// The linkage in closed form, written independently of the emitter's circle intersection: an arm `a` from
// kingpin `k` whose end must lie `t` from `anchor` turns by δ with (R(δ) a)·v = (|a|² + |v|² - t²) / 2,
// v = anchor - k, i.e. δ = angle(v) - angle(a) ± acos(...), the branch nearer straight ahead.
double closed_form_angle(const Vector2d& k, const Vector2d& a, const Vector2d& anchor, double t) {
  const Vector2d v = anchor - k;
  const double c = (a.squaredNorm() + v.squaredNorm() - t * t) / 2;
  const double spread = std::acos(std::clamp(c / (a.norm() * v.norm()), -1.0, 1.0));
  const double base = std::atan2(v.y(), v.x()) - std::atan2(a.y(), a.x());
  double best = 1e9;
  for (const double candidate : {base + spread, base - spread}) {
    const double wrapped = std::remainder(candidate, 2 * M_PI);
    if (std::abs(wrapped) < std::abs(best)) best = wrapped;
  }
  return best;
}

struct Params {
  double knuckle_angle = -1.885, knuckle_length = 0.14, tie_rod_angle = 0, column = 1.0, rack = 0.25,
         gear = 1;
};

// The exact wheel angles (left, right) for steering-wheel angle `theta`.
std::pair<double, double> exact(bool lever, const Params& p, double theta) {
  const double w = 1.6, l = p.knuckle_length, beta = std::abs(p.knuckle_angle) - M_PI / 2;
  const Vector2d kl(0, w / 2), kr(0, -w / 2);
  const Vector2d al(-l * std::cos(beta), -l * std::sin(beta)), ar(-l * std::cos(beta), l * std::sin(beta));
  const Vector2d end_l = kl + al;
  const double half = lever ? 0 : p.rack / 2;
  const Vector2d inner_l(end_l.x() + (end_l.y() - half) * std::tan(p.tie_rod_angle), half);
  const Vector2d inner_r(inner_l.x(), -half);
  const double tie = (end_l - inner_l).norm();
  Vector2d at_l, at_r;
  if (lever) {  // the lever's end, pivoted lc ahead of it, turned gear·θ
    const double psi = p.gear * theta;
    at_l = at_r = inner_l + Vector2d(p.column, 0) - p.column * Vector2d(std::cos(psi), std::sin(psi));
  } else {  // the rack, moved right by lc·gear·θ
    at_l = inner_l - Vector2d(0, p.column * p.gear * theta);
    at_r = inner_r - Vector2d(0, p.column * p.gear * theta);
  }
  return {closed_form_angle(kl, al, at_l, tie), closed_form_angle(kr, ar, at_r, tie)};
}

mj::SteeringLinkage emitter_fit(bool lever, const Params& p) {
  mj::SteeringGeometry g{1.6, p.knuckle_length, p.knuckle_angle, p.tie_rod_angle, p.column, p.rack, p.gear};
  return lever ? mj::bell_crank_linkage(g) : mj::rack_and_pinion_linkage(g);
}

std::string lines(bool lever, const Params& p) {
  auto line = [](const char* name, double v) {
    return "        " + std::string(name) + ": " + std::to_string(v) + "\n";
  };
  std::string text = line("knuckle_angle", p.knuckle_angle) + line("knuckle_length", p.knuckle_length) +
                     line("initial_angle_right_tie_rod", p.tie_rod_angle) +
                     line("steering_column_distance", p.column) + line("gear", p.gear);
  if (!lever) text += line("rack_length", p.rack);
  return text;
}

struct Steered {
  double before = 0, output = 0, left = 0, right = 0;
  std::vector<std::string> warnings;
};

Steered drive(bool lever, const Params& p, double theta) {
  const openplx::testing::ScratchDir dir;
  std::ofstream(dir / "car.openplx") << car(lever ? "BellCrank" : "RackAndPinion", lines(lever, p));
  rt::Simulation sim = rt::Simulation::load((dir / "car.openplx").string());
  Steered run;
  run.warnings = sim.warnings();
  rt::Output out = sim.output("steering.interaction.steering_angle_output");
  run.before = out.real();
  sim.input("steering.interaction.steering_angle_input").set(theta);
  sim.advance(1.0);
  run.output = out.real();
  const mjModel* m = sim.model();
  auto q = [&](const char* joint) {
    const int j = mj_name2id(m, mjOBJ_JOINT, joint);
    EXPECT_GE(j, 0) << joint;
    return j < 0 ? 0.0 : sim.data()->qpos[m->jnt_qposadr[j]];
  };
  run.left = q("left_suspension.mate.steering");
  run.right = q("right_suspension.mate.steering");
  return run;
}

// The wheels against the closed form: the left wheel at the exact left(θ) within the fit of p; the right at
// the exact right for the left wheel's actual angle (found by bisection on θ) within the fit of q.
void expect_linkage(bool lever, const Params& p, double theta, const Steered& run) {
  const mj::SteeringLinkage fit = emitter_fit(lever, p);
  ASSERT_TRUE(fit.problem.empty()) << fit.problem;
  constexpr double kSolver = 1e-6;  // MuJoCo's equality residual after 1 s
  EXPECT_NEAR(run.left, exact(lever, p, theta).first, fit.input_to_left.max_error + kSolver);
  double lo = fit.low, hi = fit.high;
  for (int k = 0; k < 100; ++k) {
    const double mid = (lo + hi) / 2;
    ((exact(lever, p, mid).first < run.left) == (exact(lever, p, 1e-3).first > 0) ? lo : hi) = mid;
  }
  EXPECT_NEAR(run.right, exact(lever, p, (lo + hi) / 2).second, fit.linkage.max_error + kSolver);
}

// AGX's steering test on each column: 0.5 in gives 0.5 out within 1e-6 after 1 s, 0 before. The steering arm
// is 0.1 m so that a 0.5 rad steering-wheel angle stays within the wheels' lock.
TEST(SteeringColumn, BellCrankFollowsItsInputAndItsLinkage) {
  Params p;
  p.column = 0.1;
  const Steered run = drive(true, p, 0.5);
  EXPECT_EQ(run.before, 0.0);
  EXPECT_NEAR(run.output, 0.5, 1e-6);
  EXPECT_GT(run.left, 0.2);        // a left turn ...
  EXPECT_LT(run.right, run.left);  // ... the inner (left) wheel more
  expect_linkage(true, p, 0.5, run);
  for (const std::string& w : run.warnings) {
    EXPECT_EQ(w.find("not honoured"), std::string::npos) << w;
    EXPECT_EQ(w.find("steering"), std::string::npos) << w;  // its fits are within 1e-2 rad
  }
}

TEST(SteeringColumn, RackAndPinionFollowsItsInputAndItsLinkage) {
  Params p;
  p.column = 0.1;
  const Steered run = drive(false, p, 0.5);
  EXPECT_EQ(run.before, 0.0);
  EXPECT_NEAR(run.output, 0.5, 1e-6);
  EXPECT_GT(run.left, 0.2);
  EXPECT_LT(run.right, run.left);
  expect_linkage(false, p, 0.5, run);
  const Steered back = drive(false, p, -0.3);
  EXPECT_NEAR(back.output, -0.3, 1e-6);
  EXPECT_LT(back.right, back.left);  // turning right, the right wheel is inner
  expect_linkage(false, p, -0.3, back);
}

// gear scales the input: gear 2 at θ turns the lever (or pinion) as far as gear 1 at 2θ, so the wheels match;
// the output still reports the steering-wheel angle.
TEST(SteeringColumn, GearScalesTheSteeringArmsTurn) {
  for (const bool lever : {true, false}) {
    Params one, two;
    one.column = two.column = 0.1;
    two.gear = 2;
    const Steered a = drive(lever, one, 0.4), b = drive(lever, two, 0.2);
    EXPECT_NEAR(b.output, 0.2, 1e-6);
    const double tolerance = emitter_fit(lever, one).input_to_left.max_error +
                             emitter_fit(lever, two).input_to_left.max_error + 2e-6;
    EXPECT_NEAR(a.left, b.left, tolerance) << lever;
    expect_linkage(lever, two, 0.2, b);
  }
}

// A longer steering arm turns the wheels further for the same input, as the closed form says; the tie rods'
// initial angle and the knuckle geometry change the angles too (each checked against the closed form).
TEST(SteeringColumn, EveryParameterActsAsTheGeometrySays) {
  for (const bool lever : {true, false}) {
    Params base;
    base.column = 0.1;
    Params longer = base, slanted = base, knuckle = base;
    longer.column = 0.15;
    slanted.tie_rod_angle = 0.2;
    knuckle.knuckle_length = 0.18;
    knuckle.knuckle_angle = -2.0;
    const Steered r0 = drive(lever, base, 0.3);
    for (const Params& p : {longer, slanted, knuckle}) {
      const Steered r = drive(lever, p, 0.3);
      EXPECT_NEAR(r.output, 0.3, 1e-6);
      EXPECT_GT(std::abs(r.left - r0.left), 1e-3) << lever;
      expect_linkage(lever, p, 0.3, r);
    }
    EXPECT_GT(drive(lever, longer, 0.3).left, r0.left);
    if (!lever) {
      Params rack = base;
      rack.rack = 0.5;
      const Steered r = drive(false, rack, 0.3);
      EXPECT_GT(std::abs(r.left - r0.left), 1e-4);
      expect_linkage(false, rack, 0.3, r);
    }
  }
}

// A rack longer than the arm ends are apart cannot be built: a warning at the user's steering line, naming
// the attribute, and the steering is left out.
TEST(SteeringColumn, ARackTooLongIsWarnedAtTheUsersLine) {
  Params p;
  p.rack = 2.0;
  const openplx::testing::ScratchDir dir;
  std::ofstream(dir / "car.openplx") << car("RackAndPinion", lines(false, p));
  rt::Simulation sim = rt::Simulation::load((dir / "car.openplx").string());
  int said = 0;
  for (const std::string& w : sim.warnings()) {
    if (w.find("rack_length") == std::string::npos) continue;
    ++said;
    EXPECT_NE(w.find((dir / "car.openplx").string() + ":"), std::string::npos) << w;
    EXPECT_NE(w.find("left out"), std::string::npos) << w;
  }
  EXPECT_EQ(said, 1);
}

// The default steering arm (1 m) and gear (1) turn the wheels to their lock within a small steering-wheel
// angle; the linkage still closes over the whole lock and its fits are within 1e-2 rad: no warning.
TEST(SteeringColumn, DefaultsCoverTheLockWithoutWarning) {
  for (const bool lever : {true, false}) {
    const Params p;
    const mj::SteeringLinkage fit = emitter_fit(lever, p);
    EXPECT_TRUE(fit.closes) << lever;
    EXPECT_LT(fit.input_to_left.max_error, 1e-2) << lever;
    EXPECT_LT(fit.linkage.max_error, 1e-2) << lever;
    const Steered run = drive(lever, p, 0.05);
    EXPECT_NEAR(run.output, 0.05, 1e-6);
    expect_linkage(lever, p, 0.05, run);
    for (const std::string& w : run.warnings) EXPECT_EQ(w.find("linkage"), std::string::npos) << w;
  }
}

}  // namespace
