// `enabled: false` on a mate is honoured: the mate never joins MuJoCo's body tree, it becomes an inactive
// equality, its body moves as if it were not there, its enabled output reads false, and its enable input
// switches it on at run time.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <fstream>

#include "openplx/runtime/simulation.h"
#include "tests/support/scratch_dir.h"

namespace {

namespace rt = openplx::runtime;

// Two boxes, each locked to its own world connector 1 m apart (so they never touch); the second Lock is
// disabled.
constexpr const char* kTwoLocks =
    "Box is Physics3D.Bodies.RigidBody:\n"
    "    inertia.mass: 1\n"
    "    geometry is Physics3D.Geometries.Box:\n"
    "        size: {0.1, 0.1, 0.1}\n"
    "    c is Physics3D.Interactions.MateConnector:\n"
    "        main_axis: Math.Vec3.Z_AXIS()\n"
    "        normal: Math.Vec3.X_AXIS()\n"
    "Scene is Physics3D.System:\n"
    "    w1 is Physics3D.Interactions.MateConnector:\n"
    "        main_axis: Math.Vec3.Z_AXIS()\n"
    "        normal: Math.Vec3.X_AXIS()\n"
    "    w2 is Physics3D.Interactions.MateConnector:\n"
    "        position: {1, 0, 0}\n"
    "        main_axis: Math.Vec3.Z_AXIS()\n"
    "        normal: Math.Vec3.X_AXIS()\n"
    "    held is Box\n"
    "    dropped is Box\n"
    "    held_lock is Physics3D.Interactions.Lock:\n"
    "        connectors: [w1, held.c]\n"
    "    dropped_lock is Physics3D.Interactions.Lock:\n"
    "        connectors: [w2, dropped.c]\n"
    "        enabled: false\n";

double height(rt::Simulation& sim, const char* body) {
  const int id = mj_name2id(sim.model(), mjOBJ_BODY, body);
  EXPECT_GE(id, 0) << body;
  return sim.data()->xpos[3 * id + 2];
}

rt::Simulation load(const openplx::testing::ScratchDir& dir) {
  const auto file = dir / "two_locks.openplx";
  std::ofstream(file) << kTwoLocks;
  return rt::Simulation::load(file.string());
}

TEST(DisabledMate, ADisabledLockLetsItsBodyFall) {
  openplx::testing::ScratchDir dir;
  rt::Simulation sim = load(dir);
  EXPECT_FALSE(sim.output("dropped_lock.interaction_enabled_output").boolean());
  EXPECT_TRUE(sim.output("held_lock.interaction_enabled_output").boolean());
  const int steps = 250;
  for (int k = 0; k < steps; ++k) sim.step();
  // MuJoCo's Euler step updates the velocity first: after n steps z = -g h^2 n (n + 1) / 2.
  const double h = sim.timestep();
  const double fallen = -9.81 * h * h * steps * (steps + 1) / 2;
  EXPECT_NEAR(height(sim, "dropped"), fallen, 1e-9);
  EXPECT_NEAR(height(sim, "held"), 0.0, 1e-12);  // an enabled Lock to the world: welded into the world
}

TEST(DisabledMate, ItsEnableInputSwitchesItOn) {
  openplx::testing::ScratchDir dir;
  rt::Simulation sim = load(dir);
  sim.advance(0.1);
  EXPECT_LT(height(sim, "dropped"), -0.04);  // falling freely: g t^2 / 2 = 0.049 m
  sim.input("dropped_lock.enable_interaction_input").set(true);
  sim.step();
  EXPECT_TRUE(sim.output("dropped_lock.interaction_enabled_output").boolean());
  // The weld pulls the body back to where SNAP assembled it and holds it there: a rigid equality relaxes
  // with time constant 2 h, so 1 s is 250 of them, and sags by about m g / k, k ~ 1 / (2 h)^2 per unit
  // mass: 9.81 * 0.004^2 = 0.16 mm.
  sim.advance(1.0);
  EXPECT_NEAR(height(sim, "dropped"), 0.0, 3e-4);
  const int id = mj_name2id(sim.model(), mjOBJ_BODY, "dropped");
  EXPECT_NEAR(sim.data()->xpos[3 * id], 1.0, 3e-4);
}

}  // namespace
