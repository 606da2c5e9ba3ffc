// A Distance mate is a spatial tendon held at its target length by a tendon equality: a 1 kg bob on a free
// joint, 1 m from a pivot along x, swings down on an invisible rod and stays 1 m away; the target input
// shortens it; the distance and force outputs read the tendon and the constraint.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "openplx/runtime/simulation.h"
#include "tests/support/scratch_dir.h"

namespace {

namespace rt = openplx::runtime;
namespace fs = std::filesystem;

const char kModel[] =
    "Bob is Physics3D.Bodies.RigidBody:\n"
    "    inertia.mass: 1\n"
    "    ball is Physics3D.Geometries.Sphere:\n"
    "        radius: 0.05\n"
    "    c is Physics3D.Interactions.MateConnector:\n"
    "        main_axis: Math.Vec3.X_AXIS()\n"
    "Scene is Physics3D.System:\n"
    "    pivot is Physics3D.Interactions.MateConnector:\n"
    "        main_axis: Math.Vec3.X_AXIS()\n"
    "    bob is Bob\n"
    "    rod is Physics3D.Interactions.Distance:\n"
    "        connectors: [pivot, bob.c]\n"
    "        initial_distance: 1.0\n"
    "        distance_output.enabled: true\n"
    "        force_output.enabled: true\n";

TEST(DistanceMate, HoldsItsLengthWhileSwingingAndFollowsItsTarget) {
  const openplx::testing::ScratchDir dir;
  std::ofstream(dir / "rod.openplx") << kModel;
  rt::Simulation sim = rt::Simulation::load((dir / "rod.openplx").string());
  EXPECT_TRUE(sim.warnings().empty()) << sim.warnings().front();
  rt::Output distance = sim.output("rod.distance_output");
  rt::Output position = sim.output("bob.position_output");
  EXPECT_NEAR(position.vec3().x(), 1.0, 1e-12);  // SNAP put it at its initial distance along main_axis
  double worst = 0;
  double lowest = 0;
  for (int k = 0; k < 500; ++k) {  // from horizontal, through the bottom (near 0.59 s) and up the other side
    sim.step();
    worst = std::max(worst, std::abs(position.vec3().norm() - 1.0));
    lowest = std::min(lowest, position.vec3().z());
  }
  EXPECT_LT(lowest, -0.99);  // it swung through the bottom
  EXPECT_LT(worst, 2e-3);    // and stayed on its 1 m radius
  EXPECT_NEAR(distance.real(), position.vec3().norm(), 1e-9);
  EXPECT_GT(std::abs(sim.output("rod.force_output").real()), 9.81 * 0.5);  // it carries the bob
  sim.input("rod.target_distance_input").set(0.5);
  EXPECT_EQ(sim.output("rod.target_distance_output").real(), 0.5);
  sim.advance(0.5);
  EXPECT_NEAR(distance.real(), 0.5, 2e-3);
}

}  // namespace

namespace {

// A DistanceRange [0, 1 m] is a rope: a 1 kg bob released 0.5 m below its anchor falls freely until the rope
// is taut, then hangs 1 m below, the limit carrying its weight (MuJoCo's limit is soft: a few mm of stretch).
TEST(DistanceRange, IsARope) {
  const openplx::testing::ScratchDir dir;
  std::ofstream(dir / "rope.openplx") << "Bob is Physics3D.Bodies.RigidBody:\n"
                                         "    inertia.mass: 1\n"
                                         "    ball is Physics3D.Geometries.Sphere:\n"
                                         "        radius: 0.05\n"
                                         "    c is Physics3D.Interactions.MateConnector\n"
                                         "Scene is Physics3D.System:\n"
                                         "    anchor is Physics3D.Interactions.MateConnector\n"
                                         "    bob is Bob:\n"
                                         "        kinematics.local_transform.position: {0, 0, -0.5}\n"
                                         "    rope is Physics3D.Interactions.DistanceRange:\n"
                                         "        connectors: [anchor, bob.c]\n"
                                         "        start: 0\n"
                                         "        end: 1\n";
  rt::Simulation sim = rt::Simulation::load((dir / "rope.openplx").string());
  EXPECT_TRUE(sim.warnings().empty()) << sim.warnings().front();
  rt::Output length = sim.output("rope.distance_output");
  rt::Output force = sim.output("rope.force_output");
  sim.advance(0.25);  // free fall: 0.5 + g t^2 / 2 = 0.8066 m
  EXPECT_NEAR(length.real(), 0.5 + 9.81 * 0.25 * 0.25 / 2, 0.01);
  EXPECT_EQ(force.real(), 0.0);
  sim.advance(1.75);
  EXPECT_NEAR(length.real(), 1.0, 0.01);
  EXPECT_NEAR(std::abs(force.real()), 9.81, 0.05 * 9.81);
}

}  // namespace

namespace {

// A 2 kg slider on a rail along x, 1 m from an anchor, and a DistanceMotor between them at 0.5 m/s within
// ±`effort` N.
fs::path slider_pushed_within(const openplx::testing::ScratchDir& dir, int effort) {
  const std::string e = std::to_string(effort);
  std::ofstream(dir / "motor.openplx")
      << "Slider is Physics3D.Bodies.RigidBody:\n"
         "    inertia.mass: 2\n"
         "    ball is Physics3D.Geometries.Sphere:\n"
         "        radius: 0.05\n"
         "    c is Physics3D.Interactions.MateConnector:\n"
         "        main_axis: Math.Vec3.X_AXIS()\n"
         "Scene is Physics3D.System:\n"
         "    anchor is Physics3D.Interactions.MateConnector:\n"
         "        main_axis: Math.Vec3.X_AXIS()\n"
         "    rail is Physics3D.Interactions.MateConnector:\n"
         "        position: {1, 0, 0}\n"
         "        main_axis: Math.Vec3.X_AXIS()\n"
         "    slider is Slider\n"
         "    slide is Physics3D.Interactions.Prismatic:\n"
         "        connectors: [rail, slider.c]\n"
         "    push is Physics3D.Interactions.DistanceMotor:\n"
         "        connectors: [anchor, slider.c]\n"
         "        target_speed: 0.5\n"
      << "        min_effort: -" << e << "\n        max_effort: " << e << "\n";
  return dir / "motor.openplx";
}

// A DistanceMotor on a 2 kg slider along x, 1 m from its anchor: the distance grows at the target 0.5 m/s
// (a servo: within a few steps, then exactly); its speed input reverses it; its force output is the push.
TEST(DistanceMotor, DrivesTheDistanceRate) {
  const openplx::testing::ScratchDir dir;
  const fs::path file = slider_pushed_within(dir, 1000);
  rt::Simulation sim = rt::Simulation::load(file.string());
  ASSERT_EQ(sim.warnings().size(), 1u);  // the servo's
  EXPECT_NE(sim.warnings().front().find("is a velocity servo here"), std::string::npos);
  rt::Output speed = sim.output("slide.velocity_output");
  rt::Output force = sim.output("push.force_output");
  sim.step();
  EXPECT_NEAR(speed.real(), 0.25, 1e-9);              // half the way in one step: gain = m / (2 h)
  EXPECT_NEAR(force.real(), 2 * 0.25 / 0.002, 1e-6);  // the push that did it: m dv / h
  sim.advance(0.1);
  EXPECT_NEAR(speed.real(), 0.5, 1e-9);
  sim.input("push.target_speed_input").set(-0.5);
  sim.advance(0.1);
  EXPECT_NEAR(speed.real(), -0.5, 1e-9);
  EXPECT_NEAR(force.real(), 0.0, 1e-6);  // nothing resists: no force at speed
}

// The push stays within the effort range: 100 N on 2 kg gains 0.1 m/s per 2 ms step until the target.
TEST(DistanceMotor, PushesWithinItsEffortRange) {
  const openplx::testing::ScratchDir dir;
  const fs::path file = slider_pushed_within(dir, 100);
  rt::Simulation sim = rt::Simulation::load(file.string());
  rt::Output speed = sim.output("slide.velocity_output");
  rt::Output force = sim.output("push.force_output");
  sim.step();
  EXPECT_NEAR(speed.real(), 0.1, 1e-9);
  EXPECT_NEAR(force.real(), 100.0, 1e-9);
  sim.step();
  EXPECT_NEAR(speed.real(), 0.2, 1e-9);
}

}  // namespace
