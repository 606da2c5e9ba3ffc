// Kinematic steering (Vehicles.Steering.Kinematic.Ackermann, BellCrank, RackAndPinion) with AGX's geometry:
// every length a fraction of the track. Built as a user writes them (a static chassis, two steered wheels
// on spring suspensions) on tracks from 0.1 m to 2 m at dt 0.002 and 0.02: AGX's steering test (input 0.5
// gives the steering angle output 0.5 within 1e-6 after 1 s) on each, and on a small car standing on its
// four wheels (the tyres loading the steering); the wheels against the linkage
// recomputed here in closed form from AGXUnity's drawing (independently of the emitter: circle
// intersections followed step by step from straight ahead) over the whole input range, within the fit
// errors the emitter reports; inputs past the linkage's reach clamped to it; an impossible geometry warned
// at the user's line, naming its attributes, with the wheels held straight.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "contract/steering_linkage.h"
#include "openplx/runtime/simulation.h"
#include "tests/support/scratch_dir.h"

namespace {

namespace rt = openplx::runtime;
namespace mj = openplx::mjcf;
using Eigen::Vector2d;

const char* kNames[3] = {"Ackermann", "BellCrank", "RackAndPinion"};

// A steering's parameters (AGX's defaults unless set) and the lines a user writes for those set.
struct Params {
  mj::SteeringMechanism mechanism = mj::SteeringMechanism::Ackermann;
  std::vector<std::pair<std::string, double>> set;  // attribute, value

  double get(const std::string& name) const {
    for (const auto& [n, v] : set)
      if (n == name) return v;
    const bool ackermann = mechanism == mj::SteeringMechanism::Ackermann;
    if (name == "knuckle_angle") return ackermann ? -2.007 : -1.885;
    if (name == "knuckle_length") return ackermann ? 0.16 : 0.14;
    if (name == "steering_column_distance" || name == "gear") return 1.0;
    if (name == "rack_length") return mechanism == mj::SteeringMechanism::RackAndPinion ? 0.25 : 0.0;
    return 0.0;  // initial_angle_right_tie_rod
  }
  mj::SteeringGeometry geometry(double track) const {
    mj::SteeringGeometry g;
    g.mechanism = mechanism;
    g.track = track;
    g.knuckle_angle = get("knuckle_angle");
    g.knuckle_length = get("knuckle_length");
    g.tie_rod_angle = get("initial_angle_right_tie_rod");
    g.column_distance = get("steering_column_distance");
    g.rack_length = get("rack_length");
    g.gear = get("gear");
    return g;
  }
};

std::string num(double v) {
  std::ostringstream s;
  s << std::setprecision(17) << v;
  return s.str();
}

// A static chassis with two steered front wheels `track` apart (every size in proportion) on 1 kN/m
// critically damped suspensions (1 kg wheels: a 0.2 s period, over ten steps at dt 0.02).
std::string car(double track, const Params& p) {
  const double w = track;
  auto vec = [](double x, double y, double z) { return "{" + num(x) + ", " + num(y) + ", " + num(z) + "}"; };
  std::string text =
      "Chassis is Physics3D.Bodies.RigidBody:\n"
      "    is_dynamic: false\n"
      "    box is Physics3D.Geometries.Box:\n"
      "        size: " +
      vec(2 * w, 0.4 * w, 0.2 * w) +
      "\n"
      "    fl is Physics3D.Interactions.MateConnector:\n"
      "        position: " +
      vec(0.75 * w, w / 2, -0.1 * w) +
      "\n"
      "        main_axis: {0, 1, 0}\n"
      "        normal: {0, 0, 1}\n"
      "    fr is Physics3D.Interactions.MateConnector:\n"
      "        position: " +
      vec(0.75 * w, -w / 2, -0.1 * w) +
      "\n"
      "        main_axis: {0, 1, 0}\n"
      "        normal: {0, 0, 1}\n"
      "Wheel is Vehicles.Wheels.Base:\n"
      "    rim becomes Vehicles.Wheels.Rim:\n"
      "        radius: " +
      num(0.2 * w) +
      "\n"
      "        width: " +
      num(0.15 * w) +
      "\n"
      "        rotational_axis: {0, 1, 0}\n"
      "        inertia.mass: 1\n"
      "Scene is Physics3D.System:\n"
      "    chassis is Chassis\n"
      "    front_left is Wheel\n"
      "    front_right is Wheel\n";
  for (const char* side : {"left", "right"}) {
    text += std::string("    ") + side +
            "_suspension is Vehicles.Suspensions.SingleMate.LinearSpringDamper:\n"
            "        with Vehicles.Suspensions.Properties.Steering\n"
            "        chassis_connector: chassis." +
            (side[0] == 'l' ? "fl" : "fr") + "\n        attachment_connector: front_" + side +
            ".connector\n"
            "        mate.spring_constant.stiffness: 1000\n"
            "        mate.spring_damping.damping_constant: 63.2\n";
  }
  text += "    steering is Vehicles.Steering.Kinematic." + std::string(kNames[int(p.mechanism)]) +
          ":\n"
          "        left_suspension: left_suspension\n"
          "        right_suspension: right_suspension\n";
  for (const auto& [name, value] : p.set) text += "        " + name + ": " + num(value) + "\n";
  return text;
}

// AGXUnity's steering drawing, in the plane across the steering axis (x forward, y left): kingpins at
// (0, ±w/2), knuckle arms b = l w along the axle line turned by π - φ0 (left) and φ0 (right); Ackermann's
// tie rod joins the arm ends; the columns' tie rods, R = (1 + 2 l cos φ0 - lr) w / (2 cos α0) long, leave the
// arm ends at α0 to the axle line towards a rack of lr w (0 for BellCrank), whose column stands lc l w
// ahead: BellCrank's lever end at column + R(θ) (-lc l w, 0), the rack moved by -lc l w tan θ across.
struct Drawing {
  Params p;
  double w = 1;
  Vector2d king[2], arm[2];
  double tie = 0;

  Drawing(const Params& params, double track) : p(params), w(track) {
    const double l = p.get("knuckle_length"), phi = p.get("knuckle_angle"), b = l * w;
    const Vector2d axle(0, -1);  // left to right
    king[0] = Vector2d(0, w / 2);
    king[1] = Vector2d(0, -w / 2);
    arm[0] = Eigen::Rotation2Dd(M_PI - phi) * axle * b;
    arm[1] = Eigen::Rotation2Dd(phi) * axle * b;
    const double lr = p.mechanism == mj::SteeringMechanism::RackAndPinion ? p.get("rack_length") : 0.0;
    tie = p.mechanism == mj::SteeringMechanism::Ackermann
              ? ((king[0] + arm[0]) - (king[1] + arm[1])).norm()
              : (1 + 2 * l * std::cos(phi) - lr) * w / 2 / std::cos(p.get("initial_angle_right_tie_rod"));
  }
  // The inner ends of the tie rods for column angle θ.
  std::pair<Vector2d, Vector2d> inner(double theta) const {
    const double l = p.get("knuckle_length"), alpha = p.get("initial_angle_right_tie_rod");
    const double lr = p.mechanism == mj::SteeringMechanism::RackAndPinion ? p.get("rack_length") : 0.0;
    const double s = p.get("steering_column_distance") * l * w, psi = p.get("gear") * theta;
    const Vector2d rest = king[0] + arm[0] + Eigen::Rotation2Dd(alpha) * Vector2d(0, -1) * tie;
    const Vector2d column = rest + Vector2d(s, 0) + Vector2d(0, -lr * w / 2);
    if (p.mechanism == mj::SteeringMechanism::BellCrank) {
      const Vector2d end = column + Eigen::Rotation2Dd(psi) * Vector2d(-s, 0);
      return {end, end};
    }
    const double shift = s * std::tan(psi);
    return {column + Vector2d(-s, lr * w / 2 - shift), column + Vector2d(-s, -lr * w / 2 - shift)};
  }
  // The arm end of kingpin `k` (arm length |a|) lying `t` from `anchor` nearest `previous`.
  static Vector2d meet(const Vector2d& k, double b, const Vector2d& anchor, double t,
                       const Vector2d& previous) {
    const Vector2d d = anchor - k;
    const double dist = d.norm(), a = (b * b - t * t + dist * dist) / (2 * dist);
    const double h = std::sqrt(std::max(0.0, b * b - a * a));
    const Vector2d mid = k + a * d / dist, across(-d.y() / dist, d.x() / dist);
    const Vector2d p1 = mid + h * across, p2 = mid - h * across;
    return (p1 - previous).norm() < (p2 - previous).norm() ? p1 : p2;
  }
  static double turned(const Vector2d& from, const Vector2d& to) {
    return std::atan2(from.x() * to.y() - from.y() * to.x(), from.dot(to));
  }
  // (left, right) for the input, followed from straight ahead in small steps.
  std::pair<double, double> angles(double input) const {
    const double b = arm[0].norm();
    Vector2d end[2] = {king[0] + arm[0], king[1] + arm[1]};
    constexpr int kSteps = 200;  // enough to keep to the branch; each step solves exactly
    for (int k = 1; k <= kSteps; ++k) {
      const double x = input * k / kSteps;
      if (p.mechanism == mj::SteeringMechanism::Ackermann) {
        end[0] = king[0] + Eigen::Rotation2Dd(x) * arm[0];
        end[1] = meet(king[1], b, end[0], tie, end[1]);
      } else {
        const auto [il, ir] = inner(x);
        end[0] = meet(king[0], b, il, tie, end[0]);
        end[1] = meet(king[1], b, ir, tie, end[1]);
      }
    }
    return {turned(arm[0], end[0] - king[0]), turned(arm[1], end[1] - king[1])};
  }
  // The input whose left wheel angle is `left` (bisection within [low, high], left rising or falling).
  double input_for(double left, double low, double high) const {
    const bool rising = angles(high).first > angles(low).first;
    for (int k = 0; k < 60; ++k) {
      const double mid = (low + high) / 2;
      ((angles(mid).first < left) == rising ? low : high) = mid;
    }
    return (low + high) / 2;
  }
};

double joint(rt::Simulation& sim, const char* name) {
  const mjModel* m = sim.model();
  const int j = mj_name2id(m, mjOBJ_JOINT, name);
  EXPECT_GE(j, 0) << name;
  return j < 0 ? 0.0 : sim.data()->qpos[m->jnt_qposadr[j]];
}

rt::Simulation load(const openplx::testing::ScratchDir& dir, double track, const Params& p, double dt) {
  std::ofstream(dir / "car.openplx") << car(track, p);
  rt::LoadOptions options;
  options.timestep = dt;
  return rt::Simulation::load((dir / "car.openplx").string(), options);
}

const double kTracks[] = {0.1, 0.12, 0.5, 1.6, 2.0};
const double kSteps[] = {0.002, 0.02};

// AGX's steering test at AGX's defaults, on every mechanism, track and step: 0 before, 0.5 after 1 s.
TEST(KinematicSteering, EveryMechanismReachesHalfARadianOnEveryTrack) {
  for (int mechanism = 0; mechanism < 3; ++mechanism) {
    for (const double track : kTracks) {
      for (const double dt : kSteps) {
        SCOPED_TRACE(std::string(kNames[mechanism]) + " track " + num(track) + " dt " + num(dt));
        Params p;
        p.mechanism = mj::SteeringMechanism(mechanism);
        const openplx::testing::ScratchDir dir;
        rt::Simulation sim = load(dir, track, p, dt);
        for (const std::string& w : sim.warnings()) EXPECT_EQ(w.find("left out"), std::string::npos) << w;
        rt::Output out = sim.output("steering.interaction.steering_angle_output");
        EXPECT_EQ(out.real(), 0.0);
        sim.input("steering.interaction.steering_angle_input").set(0.5);
        sim.advance(1.0);  // throws on any MuJoCo instability
        EXPECT_NEAR(out.real(), 0.5, 1e-6);
        EXPECT_GT(joint(sim, "left_suspension.mate.steering"), 0.3);  // a left turn
      }
    }
  }
}

// AGX's steering test on a small car standing on its four wheels (0.12 m track, a 2 kg chassis on
// redirected connectors, 0.1 kg wheels on the ground): under the tyres' loads the output still reads 0.5
// within 1e-6 after 1 s, at dt 0.002 and 0.02, and the car stays on its wheels.
TEST(KinematicSteering, ACarOnItsWheelsReachesHalfARadian) {
  for (int mechanism = 0; mechanism < 3; ++mechanism) {
    for (const double dt : kSteps) {
      SCOPED_TRACE(std::string(kNames[mechanism]) + " dt " + num(dt));
      const openplx::testing::ScratchDir dir;
      std::ofstream(dir / "car.openplx") << "Chassis is Physics3D.Bodies.RigidBody:\n"
                                            "    inertia.mass: 2\n"
                                            "    box is Physics3D.Geometries.Box:\n"
                                            "        size: {0.3, 0.06, 0.03}\n"
                                            "Wheel is Vehicles.Wheels.Base:\n"
                                            "    rim becomes Vehicles.Wheels.Rim:\n"
                                            "        radius: 0.03\n"
                                            "        width: 0.02\n"
                                            "        rotational_axis: Math.Vec3.Y_AXIS()\n"
                                            "        inertia.mass: 0.1\n"
                                            "Attachment is Physics3D.Interactions.RedirectedMateConnector:\n"
                                            "    main_axis: Math.Vec3.Y_AXIS()\n"
                                            "    normal: Math.Vec3.Z_AXIS()\n"
                                            "Corner is Vehicles.Suspensions.SingleMate.LinearSpringDamper:\n"
                                            "    mate.spring_constant.stiffness: 400\n"
                                            "    mate.spring_damping.damping_constant: 15\n"
                                            "Car is Physics3D.System:\n"
                                            "    ground is Physics3D.Bodies.RigidBody:\n"
                                            "        is_dynamic: false\n"
                                            "        kinematics.local_transform.position: {0, 0, -0.06}\n"
                                            "        floor is Physics3D.Geometries.Box:\n"
                                            "            size: {10, 10, 0.02}\n"
                                            "    chassis is Chassis\n"
                                            "    fl is Attachment:\n"
                                            "        redirected_parent: chassis\n"
                                            "        position: {0.1, 0.06, -0.015}\n"
                                            "    fr is Attachment:\n"
                                            "        redirected_parent: chassis\n"
                                            "        position: {0.1, -0.06, -0.015}\n"
                                            "    rl is Attachment:\n"
                                            "        redirected_parent: chassis\n"
                                            "        position: {-0.1, 0.06, -0.015}\n"
                                            "    rr is Attachment:\n"
                                            "        redirected_parent: chassis\n"
                                            "        position: {-0.1, -0.06, -0.015}\n"
                                            "    front_left is Wheel\n"
                                            "    front_right is Wheel\n"
                                            "    rear_left is Wheel\n"
                                            "    rear_right is Wheel\n"
                                            "    left_suspension is Corner:\n"
                                            "        with Vehicles.Suspensions.Properties.Steering\n"
                                            "        chassis_connector: fl\n"
                                            "        attachment_connector: front_left.connector\n"
                                            "    right_suspension is Corner:\n"
                                            "        with Vehicles.Suspensions.Properties.Steering\n"
                                            "        chassis_connector: fr\n"
                                            "        attachment_connector: front_right.connector\n"
                                            "    rear_left_suspension is Corner:\n"
                                            "        chassis_connector: rl\n"
                                            "        attachment_connector: rear_left.connector\n"
                                            "    rear_right_suspension is Corner:\n"
                                            "        chassis_connector: rr\n"
                                            "        attachment_connector: rear_right.connector\n"
                                            "    steering is Vehicles.Steering.Kinematic."
                                         << kNames[mechanism]
                                         << ":\n"
                                            "        left_suspension: left_suspension\n"
                                            "        right_suspension: right_suspension\n"
                                            "    chassis_position is Physics3D.Signals.Position3DOutput:\n"
                                            "        source: chassis\n";
      rt::LoadOptions options;
      options.timestep = dt;
      rt::Simulation sim = rt::Simulation::load((dir / "car.openplx").string(), options);
      sim.advance(0.5);  // settles on its wheels
      const double standing = sim.output("chassis_position").vec3().z();
      // On its wheels (0.03 m, on the floor's top at -0.05, 0.015 m below the chassis' centre): -0.005, less
      // the springs' sag (held rigid at dt 0.02, warned).
      EXPECT_LT(standing, -0.004);
      EXPECT_GT(standing, -0.03);
      sim.input("steering.interaction.steering_angle_input").set(0.5);
      sim.advance(1.0);
      EXPECT_NEAR(sim.output("steering.interaction.steering_angle_output").real(), 0.5, 1e-6);
      EXPECT_NEAR(sim.output("chassis_position").vec3().z(), standing, 2e-3);
    }
  }
}

// Over the whole input range (its ends are the linkage's dead points), each wheel sits where the drawing's
// linkage puts it within the emitter's fit errors (plus MuJoCo's equality residual); the output reads the
// input back; an input beyond the reach is clamped to it. The linkage is the same on every track: its
// lengths scale with the track.
TEST(KinematicSteering, WheelsFollowTheLinkageOverItsWholeRange) {
  constexpr double kSolver = 1e-5;  // rad: the equalities' residual after 1 s
  for (int mechanism = 0; mechanism < 3; ++mechanism) {
    for (const double track : {0.12, 1.6}) {
      for (const double dt : kSteps) {
        SCOPED_TRACE(std::string(kNames[mechanism]) + " track " + num(track) + " dt " + num(dt));
        Params p;
        p.mechanism = mj::SteeringMechanism(mechanism);
        const mj::SteeringLinkage fit = mj::steering_linkage(p.geometry(track));
        ASSERT_TRUE(fit.problem.empty()) << fit.problem;
        const mj::SteeringLinkage unit = mj::steering_linkage(p.geometry(1.0));
        EXPECT_NEAR(fit.low, unit.low, 1e-6);  // bisected at a dead point: sqrt-sensitive
        EXPECT_NEAR(fit.high, unit.high, 1e-6);
        const Drawing drawing(p, track);
        const openplx::testing::ScratchDir dir;
        rt::Simulation sim = load(dir, track, p, dt);
        rt::Output out = sim.output("steering.interaction.steering_angle_output");
        rt::Input in = sim.input("steering.interaction.steering_angle_input");
        for (const double f : {-1.0, -0.7, -0.3, 0.2, 0.6, 0.9, 1.0}) {
          const double input = f < 0 ? -f * fit.low : f * fit.high;
          in.set(input);
          sim.advance(1.0);
          SCOPED_TRACE("input " + num(input));
          EXPECT_NEAR(out.real(), input, 1e-6);
          const double left = joint(sim, "left_suspension.mate.steering");
          const double right = joint(sim, "right_suspension.mate.steering");
          EXPECT_NEAR(left, drawing.angles(input).first, fit.input_to_left.max_error + kSolver);
          const double at = mechanism == 0 ? left : drawing.input_for(left, fit.low, fit.high);
          EXPECT_NEAR(right, drawing.angles(at).second, fit.linkage.max_error + kSolver);
        }
        in.set(3 * fit.high);  // beyond the reach: clamped to it
        sim.advance(1.0);
        EXPECT_NEAR(out.real(), fit.high, 1e-6);
        in.set(3 * fit.low);
        sim.advance(1.0);
        EXPECT_NEAR(out.real(), fit.low, 1e-6);
        int said = 0;
        for (const std::string& w : sim.warnings()) said += w.find("clamped to") != std::string::npos;
        EXPECT_EQ(said, 1);  // once per input
      }
    }
  }
}

// Every parameter as the drawing has it: the tie rods sloping, a shorter steering arm, a longer rack, other
// knuckles, a reversed gear; the wheels against the drawing's linkage at both ends of the reach and between.
TEST(KinematicSteering, EveryParameterActsAsTheDrawingSays) {
  struct Case {
    int mechanism;
    std::vector<std::pair<std::string, double>> set;
  };
  const std::vector<Case> cases = {
      {0, {{"knuckle_length", 0.2}, {"knuckle_angle", -1.9}}},
      {1, {{"initial_angle_right_tie_rod", 0.2}}},
      {1, {{"steering_column_distance", 0.5}, {"gear", -1.5}}},
      {2, {{"initial_angle_right_tie_rod", -0.15}, {"rack_length", 0.4}}},
      {2, {{"steering_column_distance", 0.6}, {"knuckle_length", 0.18}, {"knuckle_angle", -2.0}}},
  };
  for (const Case& c : cases) {
    Params p;
    p.mechanism = mj::SteeringMechanism(c.mechanism);
    p.set = c.set;
    std::string trace = kNames[c.mechanism];
    for (const auto& [name, value] : c.set) trace += " " + name + " " + num(value);
    SCOPED_TRACE(trace);
    const mj::SteeringLinkage fit = mj::steering_linkage(p.geometry(1.6));
    ASSERT_TRUE(fit.problem.empty()) << fit.problem;
    const Drawing drawing(p, 1.6);
    const openplx::testing::ScratchDir dir;
    rt::Simulation sim = load(dir, 1.6, p, 0.002);
    rt::Input in = sim.input("steering.interaction.steering_angle_input");
    for (const double f : {-1.0, -0.5, 0.5, 1.0}) {
      const double input = f < 0 ? -f * fit.low : f * fit.high;
      in.set(input);
      sim.advance(1.0);
      SCOPED_TRACE("input " + num(input));
      EXPECT_NEAR(sim.output("steering.interaction.steering_angle_output").real(), input, 1e-6);
      const double left = joint(sim, "left_suspension.mate.steering");
      const double right = joint(sim, "right_suspension.mate.steering");
      EXPECT_NEAR(left, drawing.angles(input).first, fit.input_to_left.max_error + 1e-5);
      const double at = c.mechanism == 0 ? left : drawing.input_for(left, fit.low, fit.high);
      EXPECT_NEAR(right, drawing.angles(at).second, fit.linkage.max_error + 1e-5);
      if (std::abs(f) == 0.5) {  // within p's and q's fitted parts: their own errors
        EXPECT_LE(fit.fitted_low, input);
        EXPECT_GE(fit.fitted_high, input);
        EXPECT_NEAR(right, drawing.angles(at).second, fit.linkage_fitted + 1e-5);
        EXPECT_LE(fit.input_fitted_low, input);
        EXPECT_GE(fit.input_fitted_high, input);
        EXPECT_NEAR(left, drawing.angles(input).first, fit.input_to_left_fitted + 1e-5);
      }
    }
  }
}

// The output inverts p within the reach: every input across it comes back from its p (to 1e-12 rad), even
// where p, extrapolated past its fitted part, bends hardest; a left angle a little past p's value at an end
// (the equality's residual) gives an input a little past that end.
TEST(KinematicSteering, TheOutputInvertsTheInputPolynomialOverTheReach) {
  for (const int mechanism : {1, 2}) {
    for (const auto& set : std::vector<std::vector<std::pair<std::string, double>>>{
             {},
             {{"initial_angle_right_tie_rod", 0.2}},
             {{"steering_column_distance", 0.6}, {"gear", -1.5}}}) {
      Params p;
      p.mechanism = mj::SteeringMechanism(mechanism);
      p.set = set;
      const mj::SteeringLinkage fit = mj::steering_linkage(p.geometry(1.0));
      ASSERT_TRUE(fit.problem.empty());
      const std::vector<double>& c = fit.input_to_left.c;
      for (int k = 0; k <= 400; ++k) {
        const double input = fit.low + (fit.high - fit.low) * k / 400;
        EXPECT_NEAR(mj::steering_input_for(c, mj::evaluate_polynomial(c, input), fit.low, fit.high), input,
                    1e-12)
            << kNames[mechanism] << " " << input;
      }
      for (const double end : {fit.low, fit.high}) {
        const double past =
            mj::evaluate_polynomial(c, end) + 1e-7 * (mj::evaluate_polynomial(c, end) > 0 ? 1 : -1);
        const double back = mj::steering_input_for(c, past, fit.low, fit.high);
        EXPECT_NEAR(mj::evaluate_polynomial(c, back), past, 1e-12);
        EXPECT_GT(std::abs(back), std::abs(end));
        EXPECT_LT(std::abs(back - end), 1e-4);
      }
    }
  }
}

// gear turns the column: gear 2 at θ puts the wheels where gear 1 does at 2θ; the output still reads θ.
TEST(KinematicSteering, GearTurnsTheColumn) {
  for (const int mechanism : {1, 2}) {
    Params one, two;
    one.mechanism = two.mechanism = mj::SteeringMechanism(mechanism);
    two.set = {{"gear", 2.0}};
    const openplx::testing::ScratchDir dir;
    rt::Simulation a = load(dir, 1.6, one, 0.002);
    a.input("steering.interaction.steering_angle_input").set(0.4);
    a.advance(1.0);
    const openplx::testing::ScratchDir dir2;
    rt::Simulation b = load(dir2, 1.6, two, 0.002);
    b.input("steering.interaction.steering_angle_input").set(0.2);
    b.advance(1.0);
    EXPECT_NEAR(b.output("steering.interaction.steering_angle_output").real(), 0.2, 1e-6);
    const double tolerance = mj::steering_linkage(one.geometry(1.6)).input_to_left.max_error +
                             mj::steering_linkage(two.geometry(1.6)).input_to_left.max_error + 2e-5;
    EXPECT_NEAR(joint(a, "left_suspension.mate.steering"), joint(b, "left_suspension.mate.steering"),
                tolerance);
  }
}

// Geometries that cannot close: knuckle arms reaching across each other, a rack longer than the arm ends are
// apart, tie rods along the vehicle. Each is warned once at the user's line of the attribute, naming it;
// the wheels are held straight ahead and the input is clamped to 0.
TEST(KinematicSteering, AnImpossibleGeometryIsWarnedAtTheUsersLineAndHeldStraight) {
  struct Case {
    int mechanism;
    std::string attribute;
    double value;
  };
  for (const Case& c : {Case{0, "knuckle_length", 2.0}, Case{2, "rack_length", 0.95},
                        Case{1, "initial_angle_right_tie_rod", 1.6}}) {
    SCOPED_TRACE(c.attribute);
    Params p;
    p.mechanism = mj::SteeringMechanism(c.mechanism);
    p.set = {{c.attribute, c.value}};
    const openplx::testing::ScratchDir dir;
    rt::Simulation sim = load(dir, 0.12, p, 0.002);
    int said = 0;
    const std::string text = car(0.12, p);
    const auto last_line = std::count(text.begin(), text.end(), '\n');  // where the attribute is written
    const std::string line = (dir / "car.openplx").string() + ":" + std::to_string(last_line) + ":";
    for (const std::string& w : sim.warnings()) {
      if (w.find("linkage") == std::string::npos) continue;
      ++said;
      EXPECT_NE(w.find(line), std::string::npos) << w;  // the attribute's line, the file's last
      EXPECT_NE(w.find(c.attribute), std::string::npos) << w;
      EXPECT_NE(w.find("straight"), std::string::npos) << w;
    }
    EXPECT_EQ(said, 1);
    rt::Output out = sim.output("steering.interaction.steering_angle_output");
    sim.input("steering.interaction.steering_angle_input").set(0.5);
    sim.advance(1.0);
    EXPECT_EQ(out.real(), 0.0);
    EXPECT_NEAR(joint(sim, "left_suspension.mate.steering"), 0.0, 1e-6);
    EXPECT_NEAR(joint(sim, "right_suspension.mate.steering"), 0.0, 1e-6);
  }
}

}  // namespace
