// Articulated steering (Vehicles.Steering.Articulated.DualActuator): a front and a rear frame on a vertical
// hinge, two distance actuators across it. Driving them in opposite directions turns the hinge by the angle
// their lengths imply (from the connector positions), and their distance ranges stop it at the stroke's end.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <Eigen/Geometry>
#include <cmath>
#include <fstream>

#include "openplx/runtime/simulation.h"
#include "tests/support/scratch_dir.h"

namespace {

namespace rt = openplx::runtime;
using Eigen::Vector2d;

// The hinge sits 0.6 m behind the front frame's origin; each actuator runs from 0.5 m ahead of the hinge to
// 0.5 m behind it, 0.4 m to the side: 1 m long straight ahead, within [0.8, 1.2] m.
constexpr const char* kLoader =
    "Front is Physics3D.Bodies.RigidBody:\n"
    "    is_dynamic: false\n"
    "    box is Physics3D.Geometries.Box:\n"
    "        size: {0.8, 1.0, 0.3}\n"
    "    joint is Physics3D.Interactions.MateConnector:\n"
    "        position: {-0.6, 0, 0}\n"
    "        main_axis: {0, 0, 1}\n"
    "        normal: {1, 0, 0}\n"
    "    left is Physics3D.Interactions.MateConnector:\n"
    "        position: {-0.1, 0.4, 0}\n"
    "    right is Physics3D.Interactions.MateConnector:\n"
    "        position: {-0.1, -0.4, 0}\n"
    "Rear is Physics3D.Bodies.RigidBody:\n"
    "    inertia.mass: 100\n"
    "    box is Physics3D.Geometries.Box:\n"
    "        size: {0.8, 1.0, 0.3}\n"
    "    joint is Physics3D.Interactions.MateConnector:\n"
    "        position: {0.6, 0, 0}\n"
    "        main_axis: {0, 0, 1}\n"
    "        normal: {1, 0, 0}\n"
    "    left is Physics3D.Interactions.MateConnector:\n"
    "        position: {0.1, 0.4, 0}\n"
    "    right is Physics3D.Interactions.MateConnector:\n"
    "        position: {0.1, -0.4, 0}\n"
    "Loader is Physics3D.System:\n"
    "    front is Front\n"
    "    rear is Rear\n"
    "    articulation is Physics3D.Interactions.Hinge:\n"
    "        connectors: [front.joint, rear.joint]\n"
    "    steering is Vehicles.Steering.Articulated.DualActuator:\n"
    "        left_front_connector: front.left\n"
    "        right_front_connector: front.right\n"
    "        left_rear_connector: rear.left\n"
    "        right_rear_connector: rear.right\n"
    "        min_length: 0.8\n"
    "        stroke_length: 0.4\n";

// Connector positions relative to the hinge, in the plane (x forward, y left), straight ahead.
const Vector2d kFront[2] = {{0.5, 0.4}, {0.5, -0.4}};  // left, right
const Vector2d kRear[2] = {{-0.5, 0.4}, {-0.5, -0.4}};

// An actuator's length with the rear frame turned by phi about the hinge (up).
double length(int side, double phi) {
  return (kFront[side] - Eigen::Rotation2Dd(phi) * kRear[side]).norm();
}

// The angle (within ±1 rad) at which an actuator has `l` (lengths are monotonic there), by bisection.
double angle_for(int side, double l) {
  double lo = -1, hi = 1;
  const bool rising = length(side, 0.1) > length(side, 0);
  for (int k = 0; k < 100; ++k) {
    const double mid = (lo + hi) / 2;
    ((length(side, mid) < l) == rising ? lo : hi) = mid;
  }
  return (lo + hi) / 2;
}

struct State {
  double yaw = 0;              // the rear frame's turn about up (from its orientation)
  double lengths[2] = {0, 0};  // the actuators' tendons (MuJoCo)
  double hinge_velocity = 0;   // rad/s
};

State state(rt::Simulation& sim) {
  const mjModel* m = sim.model();
  const mjData* d = sim.data();
  State s;
  const int rear = mj_name2id(m, mjOBJ_BODY, "rear");
  EXPECT_GE(rear, 0);
  s.yaw = std::atan2(d->xmat[9 * rear + 3], d->xmat[9 * rear]);
  const char* tendons[2] = {"steering.left_steering_actuator.source",
                            "steering.right_steering_actuator.source"};
  for (int side = 0; side < 2; ++side) {
    const int t = mj_name2id(m, mjOBJ_TENDON, tendons[side]);
    EXPECT_GE(t, 0) << tendons[side];
    s.lengths[side] = t < 0 ? 0 : d->ten_length[t];
  }
  const int j = mj_name2id(m, mjOBJ_JOINT, "articulation");
  EXPECT_GE(j, 0);
  s.hinge_velocity = j < 0 ? 0 : d->qvel[m->jnt_dofadr[j]];
  return s;
}

void steer(rt::Simulation& sim, double left_speed, double right_speed) {
  sim.input("steering.left_steering_actuator.source.target_speed_input").set(left_speed);
  sim.input("steering.right_steering_actuator.source.target_speed_input").set(right_speed);
}

TEST(ArticulatedSteering, ActuatorsTurnTheHingeByTheirLengthsAndStopAtTheStroke) {
  const openplx::testing::ScratchDir dir;
  std::ofstream(dir / "loader.openplx") << kLoader;
  rt::Simulation sim = rt::Simulation::load((dir / "loader.openplx").string());
  // Converted without error; what it warns about (the distance motors' velocity servos) is at the user's
  // line.
  for (const std::string& w : sim.warnings()) {
    EXPECT_NE(w.find((dir / "loader.openplx").string() + ":30:"), std::string::npos) << w;
    EXPECT_NE(w.find("velocity servo"), std::string::npos) << w;
  }
  // The strokes' ranges are tendon limits, which the runtime cannot switch: their enable inputs say so.
  int range_switches = 0;
  for (const rt::SignalInfo& in : sim.inputs()) {
    if (in.type != "Physics.Signals.EnableInteractionInput" ||
        in.name.find("connection") == std::string::npos)
      continue;
    ++range_switches;
    EXPECT_FALSE(in.mapped) << in.name;
    EXPECT_NE(in.mujoco.find("length limit of MuJoCo tendon"), std::string::npos)
        << in.name << ": " << in.mujoco;
  }
  EXPECT_EQ(range_switches, 2);
  State s = state(sim);
  EXPECT_NEAR(s.lengths[0], 1.0, 1e-9);
  EXPECT_NEAR(s.yaw, 0.0, 1e-12);

  // Left lengthens, right shortens: the rear frame turns left (positive) by the angle each length implies.
  steer(sim, 0.1, -0.1);
  sim.advance(1.0);
  s = state(sim);
  EXPECT_GT(s.lengths[0], 1.08);
  EXPECT_LT(s.lengths[1], 0.92);
  EXPECT_GT(s.yaw, 0.2);
  EXPECT_NEAR(angle_for(0, s.lengths[0]), s.yaw, 1e-6);
  EXPECT_NEAR(angle_for(1, s.lengths[1]), s.yaw, 1e-6);

  // Driven on, it stops where the first actuator reaches its stroke's end: here the right one at its
  // min_length 0.8 m (0.443 rad), before the left one reaches 1.2 m (0.634 rad).
  const double stop = std::min(angle_for(0, 1.2), angle_for(1, 0.8));
  EXPECT_LT(angle_for(1, 0.8), angle_for(0, 1.2));
  sim.advance(4.0);
  s = state(sim);
  EXPECT_NEAR(s.lengths[1], 0.8, 1e-3);
  EXPECT_NEAR(s.yaw, stop, 2e-3);
  EXPECT_NEAR(s.hinge_velocity, 0.0, 1e-3);

  // Reversed, it turns right and stops symmetrically: the left one at 0.8 m.
  steer(sim, -0.1, 0.1);
  sim.advance(10.0);
  s = state(sim);
  EXPECT_NEAR(s.lengths[0], 0.8, 1e-3);
  EXPECT_NEAR(s.yaw, -stop, 2e-3);
  EXPECT_NEAR(angle_for(1, s.lengths[1]), s.yaw, 1e-6);
}

// A DualActuator connector left unbound belongs to the steering system, not to a frame: said at the user's
// steering line, for the motor and the range that act on it, as is the motor that then drives nothing.
TEST(ArticulatedSteering, AnUnboundConnectorIsWarnedAtTheUsersLine) {
  const openplx::testing::ScratchDir dir;
  std::string text = kLoader;
  const std::string bound = "        right_rear_connector: rear.right\n";
  text.erase(text.find(bound), bound.size());
  std::ofstream(dir / "loader.openplx") << text;
  rt::Simulation sim = rt::Simulation::load((dir / "loader.openplx").string());
  int unbound = 0, idle = 0;
  for (const std::string& w : sim.warnings()) {
    EXPECT_NE(w.find((dir / "loader.openplx").string() + ":30:"), std::string::npos) << w;
    if (w.find("`steering.right_rear_connector`, which belongs to `steering`, not to a body") !=
        std::string::npos)
      ++unbound;
    if (w.find("drives nothing") != std::string::npos) ++idle;
  }
  EXPECT_EQ(unbound, 2);  // the motor and the range
  EXPECT_EQ(idle, 1);
}

}  // namespace
