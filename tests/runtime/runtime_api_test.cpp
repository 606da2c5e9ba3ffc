// The runtime's public contract: name lookup and its errors, value checks that leave the state untouched,
// load errors with locations, and the signal kinds beyond motors (kinematic bodies, free bodies, springs).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "openplx/runtime/simulation.h"
#include "tests/support/scratch_dir.h"

namespace {

namespace rt = openplx::runtime;
namespace fs = std::filesystem;

using openplx::testing::ScratchDir;

// Writes `text` to `name` in the test's scratch folder; returns the path.
std::string write(const ScratchDir& dir, const std::string& name, const std::string& text) {
  const fs::path path = dir / name;
  std::ofstream(path) << text;
  return path.string();
}

std::string corpus(const std::string& file) {
  return (fs::path(OPENPLX_CORPUS_DIR) / "agxunity" / file).string();
}

const char* kCart =
    "Cart is Physics3D.Bodies.RigidBody:\n"
    "    is_dynamic: false\n"
    "    geometry is Physics3D.Geometries.Box:\n"
    "        size: {0.4, 0.2, 0.1}\n"
    "    pivot is Physics3D.Interactions.MateConnector:\n"
    "        main_axis: Math.Vec3.Y_AXIS()\n"
    "        normal: Math.Vec3.Z_AXIS()\n"
    "Ball is Physics3D.Bodies.RigidBody:\n"
    "    inertia.mass: 1\n"
    "    geometry is Physics3D.Geometries.Sphere:\n"
    "        radius: 0.1\n"
    "    top is Physics3D.Interactions.MateConnector:\n"
    "        position.z: 0.5\n"
    "        main_axis: Math.Vec3.Y_AXIS()\n"
    "        normal: Math.Vec3.Z_AXIS()\n"
    "Stone is Physics3D.Bodies.RigidBody:\n"
    "    inertia.mass: 2\n"
    "    geometry is Physics3D.Geometries.Sphere:\n"
    "        radius: 0.05\n"
    "Scene is Physics3D.System:\n"
    "    cart is Cart\n"
    "    ball is Ball\n"
    "    stone is Stone:\n"
    "        kinematics.local_transform.position: {5, 0, 0}\n"
    "    hinge is Physics3D.Interactions.Hinge:\n"
    "        connectors: [cart.pivot, ball.top]\n"
    "        angle_output.enabled: true\n";

TEST(RuntimeApi, UnknownNamesListCloseOnes) {
  rt::Simulation sim = rt::Simulation::load(corpus("signal_test.openplx"));
  try {
    sim.input("motorSpeedInptu");
    FAIL() << "no exception";
  } catch (const rt::SignalError& e) {
    EXPECT_EQ(std::string(e.what()), "no input named `motorSpeedInptu`; did you mean `motorSpeedInput`?");
  }
  EXPECT_THROW(sim.output("motorSpeedInput"), rt::SignalError);  // an input is not an output
  EXPECT_NO_THROW(sim.output("SignalScene.angularVelocity"));
  EXPECT_EQ(sim.root_model(), "SignalScene");
}

TEST(RuntimeApi, BadValuesAreRejectedAndLeaveTheStateAlone) {
  rt::Simulation sim = rt::Simulation::load(corpus("torque_range.openplx"));
  rt::Input speed = sim.input("pendulum.motor.target_angular_velocity_input");
  rt::Input range = sim.input("pendulum.motor.torque_range_input");
  const int motor = mj_name2id(sim.model(), mjOBJ_ACTUATOR, "pendulum.motor");
  EXPECT_EQ(sim.data()->ctrl[motor], 1.0);  // target_speed: 1, set before the first step
  EXPECT_THROW(speed.set(std::nan("")), rt::SignalError);
  EXPECT_THROW(speed.set(INFINITY), rt::SignalError);
  EXPECT_THROW(speed.set(true), rt::SignalError);
  EXPECT_THROW(speed.set(Eigen::Vector3d(1, 2, 3)), rt::SignalError);
  EXPECT_THROW(range.set(2.0), rt::SignalError);
  EXPECT_THROW(range.set(Eigen::Vector2d(1, -1)), rt::SignalError);  // min above max
  try {
    speed.set(true);
  } catch (const rt::SignalError& e) {
    EXPECT_EQ(std::string(e.what()),
              "input `pendulum.motor.target_angular_velocity_input` takes a Real, not a Bool");
  }
  EXPECT_EQ(sim.data()->ctrl[motor], 1.0);
  EXPECT_EQ(sim.model()->actuator_forcerange[2 * motor + 1], 1e10);  // the range is untouched
  EXPECT_THROW(sim.output("pendulum.hinge.angle_output").vec3(), rt::SignalError);
  EXPECT_THROW(sim.input("pendulum.hinge.enable_interaction_input").set(false), rt::SignalError);
}

TEST(RuntimeApi, LoadErrorsCarryTheirLocation) {
  const ScratchDir scratch;
  const std::string path =
      write(scratch, "broken.openplx", "Scene is Physics3D.System:\n    x is Real: 1 +\n");
  try {
    rt::Simulation::load(path);
    FAIL() << "no exception";
  } catch (const rt::LoadError& e) {
    EXPECT_NE(std::string(e.what()).find(path + ":2:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(": error: "), std::string::npos) << e.what();
  }
  EXPECT_THROW(
      rt::Simulation::load(write(scratch, "missing_model.openplx", "A is Physics3D.System\n"), {"Nope", {}}),
      rt::LoadError);
}

// LoadOptions::timestep is MuJoCo's step (OpenPLX has none); a step that is not a positive number is refused.
TEST(RuntimeApi, TimestepComesFromTheLoadOptions) {
  const std::string path = std::string(OPENPLX_SAMPLES_DIR) + "/pendulum.openplx";
  rt::LoadOptions options;
  options.timestep = 0.001;
  rt::Simulation sim = rt::Simulation::load(path, options);
  EXPECT_EQ(sim.model()->opt.timestep, 0.001);
  sim.step();
  EXPECT_DOUBLE_EQ(sim.time(), 0.001);
  EXPECT_EQ(rt::Simulation::load(path).model()->opt.timestep, 0.002);
  options.timestep = 0;
  EXPECT_THROW(rt::Simulation::load(path, options), rt::LoadError);
}

// A kinematic cart (is_dynamic: false) follows its velocity input exactly, and what hangs from it comes
// along; a free body takes its velocity input as its initial velocity and then falls under gravity.
TEST(RuntimeApi, KinematicAndFreeBodiesTakeVelocityInputs) {
  const ScratchDir scratch;
  rt::Simulation sim = rt::Simulation::load(write(scratch, "cart.openplx", kCart));
  sim.input("cart.linear_velocity_world_input").set(Eigen::Vector3d(0.5, 0, 0));
  sim.input("cart.angular_velocity_world_input").set(Eigen::Vector3d(0, 0, 0.25));
  sim.input("stone.linear_velocity_world_input").set(Eigen::Vector3d(0, 0, 3));
  rt::Output cart = sim.output("cart.position_output");
  rt::Output stone = sim.output("stone.linear_velocity_world_output");
  sim.advance(1.0);
  EXPECT_NEAR(cart.vec3().x(), 0.5, 1e-12);
  const int cart_body = mj_name2id(sim.model(), mjOBJ_BODY, "cart");
  const mjtNum* q = sim.data()->xquat + 4 * cart_body;  // a turn about z by 0.25 rad
  EXPECT_NEAR(2 * std::atan2(q[3], q[0]), 0.25, 1e-9);
  const int ball = mj_name2id(sim.model(), mjOBJ_BODY, "ball");
  EXPECT_GT(sim.data()->xpos[3 * ball], 0.3);  // carried along (it swings behind the cart)
  // v = 3 - g t with explicit Euler's velocity update: exact for constant gravity.
  EXPECT_NEAR(stone.vec3().z(), 3 - 9.81 * 1.0, 1e-9);
}

TEST(RuntimeApi, ListsSignalsWithTypesAndMuJoCoElements) {
  rt::Simulation sim = rt::Simulation::load(corpus("signal_test.openplx"));
  bool found = false;
  for (const rt::SignalInfo& s : sim.inputs()) {
    if (s.name != "motorSpeedInput") continue;
    found = true;
    EXPECT_EQ(s.value, rt::ValueType::Real);
    EXPECT_EQ(s.unit, "rad/s");
    EXPECT_TRUE(s.mapped);
    EXPECT_EQ(s.mujoco, "actuator motor: ctrl");
  }
  EXPECT_TRUE(found);
  EXPECT_EQ(sim.outputs().size() + sim.inputs().size(), 21u);  // every signal of the model, mapped or not
}

// Body and connector velocities agree with MuJoCo's own mj_objectVelocity on a moving linkage.
TEST(RuntimeApi, VelocityOutputsMatchMuJoCo) {
  rt::Simulation sim = rt::Simulation::load(std::string(OPENPLX_SAMPLES_DIR) + "/four_bar.openplx");
  rt::Output v = sim.output("crank.linear_velocity_world_output");
  rt::Output w = sim.output("crank.angular_velocity_world_output");
  sim.advance(0.3);
  const int crank = mj_name2id(sim.model(), mjOBJ_BODY, "crank");
  mjtNum expected[6];
  mj_objectVelocity(sim.model(), sim.data(), mjOBJ_XBODY, crank, expected, 0);
  EXPECT_GT(w.vec3().norm(), 0.1);  // it turns, so the lever term counts
  EXPECT_LT((v.vec3() - Eigen::Vector3d(expected[3], expected[4], expected[5])).norm(), 1e-12);
  EXPECT_LT((w.vec3() - Eigen::Vector3d(expected[0], expected[1], expected[2])).norm(), 1e-12);
}

// Mate force and torque outputs, enabled or not: a 2 kg, 1 m rod held level by a hinge about z at its end
// takes m g = 19.62 N up and, about the hinge, the torque m g L / 2 = 9.81 N m about -y (connectors[0] is the
// world, so the values are what the world exerts on the rod).
TEST(RuntimeApi, MateForceAndTorqueOutputs) {
  const ScratchDir scratch;
  const std::string path = write(scratch, "level_rod.openplx",
                                 "Rod is Physics3D.Bodies.RigidBody:\n"
                                 "    inertia.mass: 2\n"
                                 "    geometry is Physics3D.Geometries.Box:\n"
                                 "        size: {1, 0.05, 0.05}\n"
                                 "    end is Physics3D.Interactions.MateConnector:\n"
                                 "        position.x: -0.5\n"
                                 "        main_axis: Math.Vec3.Z_AXIS()\n"
                                 "        normal: Math.Vec3.X_AXIS()\n"
                                 "Scene is Physics3D.System:\n"
                                 "    pivot is Physics3D.Interactions.MateConnector:\n"
                                 "        main_axis: Math.Vec3.Z_AXIS()\n"
                                 "        normal: Math.Vec3.X_AXIS()\n"
                                 "    rod is Rod\n"
                                 "    hinge is Physics3D.Interactions.Hinge:\n"
                                 "        connectors: [pivot, rod.end]\n"
                                 "        force_output.enabled: true\n");
  rt::Simulation sim = rt::Simulation::load(path);
  rt::Output force = sim.output("hinge.force_output");    // enabled: also a MuJoCo sensor
  rt::Output torque = sim.output("hinge.torque_output");  // not enabled: computed all the same
  sim.advance(0.5);
  const double g = 9.81;
  EXPECT_LT((force.vec3() - Eigen::Vector3d(0, 0, 2 * g)).norm(), 1e-4) << force.vec3().transpose();
  EXPECT_LT((torque.vec3() - Eigen::Vector3d(0, -g, 0)).norm(), 1e-4) << torque.vec3().transpose();
}

}  // namespace
