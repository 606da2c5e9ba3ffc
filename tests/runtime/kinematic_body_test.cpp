// Kinematic bodies (mocap in MuJoCo) behave like OpenPLX's: their velocity outputs, and those of their
// connectors, report the velocity their inputs command (MuJoCo itself gives mocap bodies none); their initial
// velocities drive them; `Physics3D.System.kinematically_controlled` makes the bodies it lists kinematic.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <fstream>
#include <string>

#include "openplx/runtime/simulation.h"
#include "tests/support/scratch_dir.h"

namespace {

namespace rt = openplx::runtime;

// A kinematic box with a connector 1 m along its x axis and a velocity output on that connector.
std::string kinematic_box(const std::string& extra) {
  return "Scene is Physics3D.System:\n"
         "    box is Physics3D.Bodies.RigidBody:\n"
         "        is_dynamic: false\n"
         "        inertia.mass: 1\n"
         "        geometry is Physics3D.Geometries.Box:\n"
         "            size: {0.2, 0.2, 0.2}\n"
         "        tip is Physics3D.Interactions.MateConnector:\n"
         "            position: {1, 0, 0}\n" +
         extra +
         "    tip_velocity is Physics3D.Signals.MateConnector.LinearVelocity3DOutput:\n"
         "        source: box.tip\n"
         "    tip_spin is Physics3D.Signals.MateConnector.AngularVelocity3DOutput:\n"
         "        source: box.tip\n";
}

rt::Simulation load(const openplx::testing::ScratchDir& dir, const std::string& text) {
  const auto file = dir / "kinematic.openplx";
  std::ofstream(file) << text;
  return rt::Simulation::load(file.string());
}

Eigen::Vector3d position_of(rt::Simulation& sim, const char* body) {
  const int id = mj_name2id(sim.model(), mjOBJ_BODY, body);
  EXPECT_GE(id, 0) << body;
  return Eigen::Map<const Eigen::Vector3d>(sim.data()->xpos + 3 * id);
}

TEST(KinematicBody, VelocityOutputsReportTheCommandedVelocity) {
  const openplx::testing::ScratchDir dir;
  rt::Simulation sim = load(dir, kinematic_box(""));
  const Eigen::Vector3d v(1, 2, 3), w(0, 0, 0.5);
  sim.input("box.linear_velocity_world_input").set(v);
  sim.input("box.angular_velocity_world_input").set(w);
  const Eigen::Vector3d start = position_of(sim, "box");
  const int steps = 100;
  for (int k = 0; k < steps; ++k) sim.step();
  EXPECT_LT((sim.output("box.linear_velocity_world_output").vec3() - v).norm(), 1e-9);
  EXPECT_LT((sim.output("box.angular_velocity_world_output").vec3() - w).norm(), 1e-9);
  const Eigen::Vector3d body = position_of(sim, "box");
  EXPECT_LT((body - start - v * steps * sim.timestep()).norm(), 1e-9);
  // The connector: v + w x r, r the tip's offset turned by the body's rotation so far (w t about z).
  const double angle = w.z() * steps * sim.timestep();
  const Eigen::Vector3d r = Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()) * Eigen::Vector3d(1, 0, 0);
  EXPECT_LT((sim.output("tip_velocity").vec3() - (v + w.cross(r))).norm(), 1e-9);
  EXPECT_LT((sim.output("tip_spin").vec3() - w).norm(), 1e-9);
}

TEST(KinematicBody, InitialVelocitiesDriveIt) {
  const openplx::testing::ScratchDir dir;
  rt::Simulation sim =
      load(dir, kinematic_box("        kinematics.initial_local_linear_velocity: {0.5, 0, 0}\n"
                              "        kinematics.initial_local_angular_velocity: {0, 0, 1}\n"));
  const Eigen::Vector3d start = position_of(sim, "box");
  sim.advance(1.0);
  EXPECT_LT((sim.output("box.linear_velocity_world_output").vec3() - Eigen::Vector3d(0.5, 0, 0)).norm(),
            1e-9);
  EXPECT_LT((sim.output("box.angular_velocity_world_output").vec3() - Eigen::Vector3d(0, 0, 1)).norm(), 1e-9);
  EXPECT_NEAR(position_of(sim, "box").x() - start.x(), 0.5, 1e-9);
}

// The deprecated list on a system: the body it names is kinematic (mocap), so gravity does not move it,
// while its dynamic sibling falls.
TEST(KinematicBody, KinematicallyControlledListMakesBodiesKinematic) {
  const openplx::testing::ScratchDir dir;
  rt::Simulation sim = load(dir,
                            "Block is Physics3D.Bodies.RigidBody:\n"
                            "    inertia.mass: 1\n"
                            "    geometry is Physics3D.Geometries.Box:\n"
                            "        size: {0.2, 0.2, 0.2}\n"
                            "Scene is Physics3D.System:\n"
                            "    held is Block:\n"
                            "        kinematics.local_transform.position.x: 5\n"
                            "    dropped is Block\n"
                            "    kinematically_controlled: [held]\n");
  EXPECT_GE(sim.model()->body_mocapid[mj_name2id(sim.model(), mjOBJ_BODY, "held")], 0);
  sim.advance(0.5);
  EXPECT_EQ(position_of(sim, "held").z(), 0.0);
  EXPECT_LT(position_of(sim, "dropped").z(), -1.0);  // g t^2 / 2 = 1.23 m
}

// A velocity MuJoCo cannot hold (it read 1e308 back as {1e308, nan, nan}) is refused, naming the input, on a
// kinematic body and on a free one alike; the bodies keep moving as before.
TEST(KinematicBody, VelocitiesBeyondWhatMuJoCoTakesAreRefused) {
  const openplx::testing::ScratchDir dir;
  rt::Simulation sim = load(dir,
                            "Block is Physics3D.Bodies.RigidBody:\n"
                            "    inertia.mass: 1\n"
                            "    geometry is Physics3D.Geometries.Box:\n"
                            "        size: {0.2, 0.2, 0.2}\n"
                            "Scene is Physics3D.System:\n"
                            "    held is Block:\n"
                            "        is_dynamic: false\n"
                            "    free is Block\n");
  for (const char* name : {"held.linear_velocity_world_input", "free.linear_velocity_world_input",
                           "free.angular_velocity_world_input"}) {
    rt::Input input = sim.input(name);
    try {
      input.set(Eigen::Vector3d(1e308, 0, 0));
      ADD_FAILURE() << name << " took 1e308";
    } catch (const rt::SignalError& e) {
      EXPECT_NE(std::string(e.what()).find(std::string("`") + name + "` got 1e+308, beyond"),
                std::string::npos)
          << e.what();
    }
    input.set(Eigen::Vector3d(1e10, 0, 0));  // MuJoCo's largest sound value is taken
    input.set(Eigen::Vector3d(0, 0, 0));
  }
  sim.advance(0.1);
  EXPECT_TRUE(sim.output("free.linear_velocity_world_output").vec3().allFinite());
}

}  // namespace
