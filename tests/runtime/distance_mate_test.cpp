// A Distance mate is a spatial tendon held at its target length by a tendon equality: a 1 kg bob on a free
// joint, 1 m from a pivot along x, swings down on an invisible rod and stays 1 m away; the target input
// shortens it; the distance and force outputs read the tendon and the constraint.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "openplx/runtime/simulation.h"
#include "tests/support/scratch_dir.h"

namespace {

namespace rt = openplx::runtime;

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
