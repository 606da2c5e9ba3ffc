// Mate connector outputs (position, RPY, velocities, accelerations), with and without `relative_to` another
// connector, Force3DOutput `relative_to` a transform, and Torque3DInput on a body, against closed forms and
// MuJoCo's own sensors (the MJCF is loaded by MuJoCo's mj_loadXML in Simulation::load).
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include "openplx/runtime/simulation.h"
#include "tests/support/scratch_dir.h"

namespace {

namespace rt = openplx::runtime;
using Eigen::Vector3d;
using RowMatrix = Eigen::Matrix<mjtNum, 3, 3, Eigen::RowMajor>;

// A box falling freely with a connector `tip` off its centre; `anchor`, fixed in the world 1 m away and
// turned (its z along world x, its x along world y); a puck spinning about world z at 2 rad/s on a hinge
// held by a velocity motor, with `mount` on its axis, turned with it.
const char kScene[] =
    "Box is Physics3D.Bodies.RigidBody:\n"
    "    with Physics3D.Signals.Torque3DInputTrait\n"
    "    inertia.mass: 1\n"
    "    shape is Physics3D.Geometries.Box:\n"
    "        size: {0.2, 0.4, 0.6}\n"
    "    tip is Physics3D.Interactions.MateConnector:\n"
    "        position: {0.1, 0.05, 0}\n"
    "        main_axis: Math.Vec3.Z_AXIS()\n"
    "        normal: Math.Vec3.X_AXIS()\n"
    "Puck is Physics3D.Bodies.RigidBody:\n"
    "    inertia.mass: 1\n"
    "    disc is Physics3D.Geometries.Box:\n"
    "        size: {0.2, 0.2, 0.05}\n"
    "    axle is Physics3D.Interactions.MateConnector:\n"
    "        main_axis: Math.Vec3.Z_AXIS()\n"
    "        normal: Math.Vec3.X_AXIS()\n"
    "    mount is Physics3D.Interactions.MateConnector:\n"
    "        main_axis: Math.Vec3.Z_AXIS()\n"
    "        normal: Math.Vec3.X_AXIS()\n"
    "Scene is Physics3D.System:\n"
    "    anchor is Physics3D.Interactions.MateConnector:\n"
    "        position: {1, 0, 0}\n"
    "        main_axis: Math.Vec3.X_AXIS()\n"
    "        normal: Math.Vec3.Y_AXIS()\n"
    "    ground is Physics3D.Interactions.MateConnector:\n"
    "        position: {0, 0, -5}\n"
    "        main_axis: Math.Vec3.Z_AXIS()\n"
    "        normal: Math.Vec3.X_AXIS()\n"
    "    box is Box\n"
    "    puck is Puck:\n"
    "        kinematics.local_transform.position: {0, 0, -5}\n"
    "    hinge is Physics3D.Interactions.Hinge:\n"
    "        connectors: [ground, puck.axle]\n"
    "        force_output.enabled: true\n"
    "    spin is Physics3D.Interactions.RotationalVelocityMotor:\n"
    "        connectors: [ground, puck.axle]\n"
    "        target_speed: 2\n"
    "    turned_force is Physics3D.Signals.Force3DOutput:\n"
    "        source: hinge\n"
    "        relative_to: Math.AffineTransform.from({3, 2, 1}, Math.Quat.angle_axis(0.7, {1, 2, 3}))\n"
    "    turned_torque is Physics3D.Signals.Torque3DOutput:\n"
    "        source: hinge\n"
    "        relative_to: Math.AffineTransform.from({0, 0, 0}, Math.Quat.angle_axis(0.7, {1, 2, 3}))\n"
    "    world_torque is Physics3D.Signals.Torque3DOutput:\n"
    "        source: hinge\n"
    "    torque is Physics3D.Signals.Torque3DInput:\n"
    "        source: box\n"
    "    tip_position is Physics3D.Signals.MateConnector.PositionOutput:\n"
    "        source: box.tip\n"
    "    tip_from_anchor is Physics3D.Signals.MateConnector.PositionOutput:\n"
    "        source: box.tip\n"
    "        relative_to: anchor\n"
    "    tip_velocity_from_anchor is Physics3D.Signals.MateConnector.LinearVelocity3DOutput:\n"
    "        source: box.tip\n"
    "        relative_to: anchor\n"
    "    tip_acceleration is Physics3D.Signals.MateConnector.Acceleration3DOutput:\n"
    "        source: box.tip\n"
    "    tip_angular_acceleration is Physics3D.Signals.MateConnector.AngularAcceleration3DOutput:\n"
    "        source: box.tip\n"
    "    tip_from_mount is Physics3D.Signals.MateConnector.PositionOutput:\n"
    "        source: box.tip\n"
    "        relative_to: puck.mount\n"
    "    tip_acceleration_from_mount is Physics3D.Signals.MateConnector.Acceleration3DOutput:\n"
    "        source: box.tip\n"
    "        relative_to: puck.mount\n"
    "    mount_acceleration is Physics3D.Signals.MateConnector.Acceleration3DOutput:\n"
    "        source: puck.mount\n"
    "    anchor_from_mount is Physics3D.Signals.MateConnector.PositionOutput:\n"
    "        source: anchor\n"
    "        relative_to: puck.mount\n"
    "    anchor_rpy_from_mount is Physics3D.Signals.MateConnector.RPYOutput:\n"
    "        source: anchor\n"
    "        relative_to: puck.mount\n"
    "    anchor_velocity_from_mount is Physics3D.Signals.MateConnector.LinearVelocity3DOutput:\n"
    "        source: anchor\n"
    "        relative_to: puck.mount\n"
    "    anchor_spin_from_mount is Physics3D.Signals.MateConnector.AngularVelocity3DOutput:\n"
    "        source: anchor\n"
    "        relative_to: puck.mount\n"
    "    anchor_acceleration_from_mount is Physics3D.Signals.MateConnector.Acceleration3DOutput:\n"
    "        source: anchor\n"
    "        relative_to: puck.mount\n"
    "    anchor_angular_acceleration_from_mount is "
    "Physics3D.Signals.MateConnector.AngularAcceleration3DOutput:\n"
    "        source: anchor\n"
    "        relative_to: puck.mount\n";

rt::Simulation load_scene(const openplx::testing::ScratchDir& dir, double timestep) {
  std::ofstream(dir / "scene.openplx") << kScene;
  rt::LoadOptions options;
  options.timestep = timestep;
  return rt::Simulation::load((dir / "scene.openplx").string(), options);
}

int site(const rt::Simulation& sim, const char* name) {
  const int id = mj_name2id(sim.model(), mjOBJ_SITE, name);
  EXPECT_GE(id, 0) << name;
  return id;
}

RowMatrix site_rotation(rt::Simulation& sim, int id) {
  return Eigen::Map<const RowMatrix>(sim.data()->site_xmat + 9 * id);
}

Vector3d site_position(rt::Simulation& sim, int id) {
  return Eigen::Map<const Vector3d>(sim.data()->site_xpos + 3 * id);
}

Vector3d sensor(rt::Simulation& sim, const char* name) {
  const int id = mj_name2id(sim.model(), mjOBJ_SENSOR, name);
  EXPECT_GE(id, 0) << name;
  return Eigen::Map<const Vector3d>(sim.data()->sensordata + sim.model()->sensor_adr[id]);
}

class ConnectorSignals : public ::testing::TestWithParam<double> {};

// The falling tip seen from the fixed, turned anchor: R_anchor^T (p - p_anchor), exact geometry (1e-9), each
// step, and MuJoCo's framepos / framelinvel with reftype="site" hold the same values.
TEST_P(ConnectorSignals, PositionRelativeToAFixedConnectorIsTheOffsetInItsAxes) {
  const openplx::testing::ScratchDir dir;
  rt::Simulation sim = load_scene(dir, GetParam());
  const int anchor = site(sim, "anchor");
  rt::Output world = sim.output("tip_position"), relative = sim.output("tip_from_anchor");
  rt::Output velocity = sim.output("tip_velocity_from_anchor");
  const RowMatrix r = site_rotation(sim, anchor);
  EXPECT_NEAR((r.col(2) - Vector3d::UnitX()).norm(), 0, 1e-12);  // main axis along world x
  for (int k = 0; k < static_cast<int>(0.6 / GetParam()); ++k) {
    sim.step();
    const Vector3d expected = r.transpose() * (world.vec3() - Vector3d(1, 0, 0));
    ASSERT_NEAR((relative.vec3() - expected).norm(), 0, 1e-9) << "step " << k;
    ASSERT_NEAR((relative.vec3() - sensor(sim, "tip_from_anchor")).norm(), 0, 1e-9);
    ASSERT_NEAR((velocity.vec3() - sensor(sim, "tip_velocity_from_anchor")).norm(), 0, 1e-9);
  }
  EXPECT_LT(world.vec3().z(), -1.0);  // it fell
}

// Free fall: the coordinate acceleration is gravity, (0, 0, -9.81), and no angular acceleration (MuJoCo's
// framelinacc, the proper acceleration, reads 0 there).
TEST_P(ConnectorSignals, AFreelyFallingConnectorAcceleratesAtGravity) {
  const openplx::testing::ScratchDir dir;
  rt::Simulation sim = load_scene(dir, GetParam());
  rt::Output a = sim.output("tip_acceleration"), alpha = sim.output("tip_angular_acceleration");
  for (int k = 0; k < 20; ++k) {
    sim.step();
    ASSERT_NEAR((a.vec3() - Vector3d(0, 0, -9.81)).norm(), 0, 1e-9);
    ASSERT_NEAR(alpha.vec3().norm(), 0, 1e-9);
  }
}

// Seen from the puck's mount, turning at w about z, the fixed anchor 1 m off the axis turns at -w: with x
// its position in the mount's axes, velocity -w z x x, angular velocity (0, 0, -w), acceleration
// R^T (-alpha z x r) + w z x (w z x x), the centripetal part toward the axis (alpha = the hinge's angular
// acceleration, ~0 under the motor), angular acceleration R^T (-alpha z). Accelerations are of the state the
// last step started from: the x, w and R kept from the step before. All exact up to rounding (1e-9); w is the
// hinge's own speed.
TEST_P(ConnectorSignals, AFixedConnectorSeenFromARotatingOneTurnsTheOtherWay) {
  const openplx::testing::ScratchDir dir;
  rt::Simulation sim = load_scene(dir, GetParam());
  const int mount = site(sim, "puck.mount");
  const mjModel* m = sim.model();
  const int hinge = m->body_dofadr[m->site_bodyid[mount]];
  rt::Output position = sim.output("anchor_from_mount"), rpy = sim.output("anchor_rpy_from_mount");
  rt::Output velocity = sim.output("anchor_velocity_from_mount"), spin = sim.output("anchor_spin_from_mount");
  rt::Output a = sim.output("anchor_acceleration_from_mount");
  rt::Output alpha = sim.output("anchor_angular_acceleration_from_mount");
  Vector3d before_x = Vector3d::Zero();
  RowMatrix before_r = RowMatrix::Identity();
  double before_w = 0;
  for (int k = 0; k < 300; ++k) {
    sim.step();
    const double w = sim.data()->qvel[hinge], angular_acc = sim.data()->qacc[hinge];  // qacc: last step's
    const RowMatrix r = site_rotation(sim, mount);
    const Vector3d x = r.transpose() * (Vector3d(1, 0, 0) - site_position(sim, mount));
    ASSERT_NEAR((position.vec3() - x).norm(), 0, 1e-9);
    ASSERT_NEAR((velocity.vec3() - (-w * Vector3d::UnitZ().cross(x))).norm(), 0, 1e-9);
    ASSERT_NEAR((spin.vec3() - Vector3d(0, 0, -w)).norm(), 0, 1e-9);
    const Eigen::Matrix3d relative = r.transpose();  // the anchor's axes are world's turned: R_r^T R_anchor
    const Eigen::Matrix3d anchor_axes = (Eigen::AngleAxisd(rpy.vec3().z(), Vector3d::UnitZ()) *
                                         Eigen::AngleAxisd(rpy.vec3().y(), Vector3d::UnitY()) *
                                         Eigen::AngleAxisd(rpy.vec3().x(), Vector3d::UnitX()))
                                            .toRotationMatrix();
    const RowMatrix anchor = site_rotation(sim, site(sim, "anchor"));
    ASSERT_NEAR((anchor_axes - relative * anchor).norm(), 0, 1e-9);
    if (k > 0) {
      const Vector3d turn = before_r.transpose() * Vector3d(0, 0, angular_acc);
      const Vector3d spin_axis = before_w * Vector3d::UnitZ();  // the mount's z is world z
      const Vector3d expected = -turn.cross(before_x) + spin_axis.cross(spin_axis.cross(before_x));
      ASSERT_NEAR((a.vec3() - expected).norm(), 0, 1e-9) << "step " << k;
      ASSERT_NEAR((alpha.vec3() + turn).norm(), 0, 1e-9);
    }
    before_x = x;
    before_r = r;
    before_w = w;
  }
  EXPECT_NEAR(before_w, 2.0, 1e-3);                          // the motor's speed
  EXPECT_NEAR(position.vec3().head<2>().norm(), 1.0, 1e-9);  // 1 m from the axis, 5 m above the mount
}

// The falling tip seen from the turning mount: its relative acceleration against the second difference of its
// relative position x_k = R_k^T (p_k - p_r). Semi-implicit Euler makes the world positions' second difference
// exactly h^2 times the acceleration of the state it starts from, and the motor turns R_k at a constant rate
// (exact rotations), so what remains is the centred difference's truncation, (h^2 / 12) |d4x/dt4| with
// |d4x/dt4| <= w^4 |r| + 4 w^3 |v| + 6 w^2 |a| ~ 16 * 6 + 32 * 3 + 24 * 10 ~ 430 (w = 2, |r| <= 6 m,
// |v| <= 3 m/s, |a| ~ g): below 40 h^2, and a quarter of it at half the step. Measured: 6.0e-7 at h = 0.002,
// 1.5e-7 at 0.001.
TEST(ConnectorSignalsFiniteDifference, RelativeAccelerationIsTheSecondDerivativeOfRelativePosition) {
  double worst[2] = {0, 0};
  const double steps[2] = {0.002, 0.001};
  for (int run = 0; run < 2; ++run) {
    const openplx::testing::ScratchDir dir;
    const double h = steps[run];
    rt::Simulation sim = load_scene(dir, h);
    rt::Output x = sim.output("tip_from_mount"), a = sim.output("tip_acceleration_from_mount");
    for (int k = 0; k < static_cast<int>(0.2 / h); ++k) sim.step();  // the motor up to speed
    Vector3d x0 = x.vec3();
    sim.step();
    Vector3d x1 = x.vec3();
    for (int k = 0; k < static_cast<int>(0.3 / h); ++k) {
      sim.step();
      const Vector3d x2 = x.vec3();
      // The acceleration now read is of the state x1 was read from.
      worst[run] = std::max(worst[run], ((x2 - 2 * x1 + x0) / (h * h) - a.vec3()).norm());
      x0 = x1;
      x1 = x2;
    }
    EXPECT_LT(worst[run], 40 * h * h) << "h = " << h;
    std::printf("h = %g: largest |second difference - acceleration| = %g m/s^2\n", h, worst[run]);
  }
  EXPECT_LT(worst[1], 0.35 * worst[0]);  // second order in h
}

// Force3DOutput relative_to a transform: the world force in the transform's axes, R^T f (its position does
// not matter for a force; a torque stays about the connector's origin).
TEST_P(ConnectorSignals, ForceRelativeToATransformIsTheWorldForceInItsAxes) {
  const openplx::testing::ScratchDir dir;
  rt::Simulation sim = load_scene(dir, GetParam());
  const Eigen::Quaterniond q(Eigen::AngleAxisd(0.7, Vector3d(1, 2, 3).normalized()));
  rt::Output world = sim.output("hinge.force_output"), turned = sim.output("turned_force");
  rt::Output world_torque = sim.output("world_torque"), turned_torque = sim.output("turned_torque");
  for (int k = 0; k < 50; ++k) {
    sim.step();
    ASSERT_GT(world.vec3().norm(), 1.0);  // it holds the puck up
    ASSERT_NEAR((turned.vec3() - q.conjugate() * world.vec3()).norm(), 0, 1e-9);
    ASSERT_NEAR((turned_torque.vec3() - q.conjugate() * world_torque.vec3()).norm(), 0, 1e-9);
  }
}

// Torque3DInput on the free box: a pure torque, so from rest its angular acceleration is I^-1 tau (world
// axes; the box starts aligned with the world and its principal axes are its own) and its centre does not
// accelerate beyond gravity.
TEST_P(ConnectorSignals, TorqueInputOnAFreeBodyGivesInverseInertiaTimesTorque) {
  const openplx::testing::ScratchDir dir;
  rt::Simulation sim = load_scene(dir, GetParam());
  const Vector3d tau(0.3, -0.2, 0.1);
  sim.input("torque").set(tau);
  rt::Output alpha = sim.output("tip_angular_acceleration");
  sim.step();  // alpha of the state at rest, with the torque applied
  const mjModel* m = sim.model();
  const int body = m->site_bodyid[site(sim, "box.tip")];
  const Eigen::Quaterniond principal(m->body_iquat[4 * body], m->body_iquat[4 * body + 1],
                                     m->body_iquat[4 * body + 2], m->body_iquat[4 * body + 3]);
  const Eigen::Matrix3d inertia = principal.toRotationMatrix() *
                                  Vector3d(m->body_inertia + 3 * body).asDiagonal() *
                                  principal.toRotationMatrix().transpose();
  EXPECT_NEAR((alpha.vec3() - inertia.inverse() * tau).norm(), 0, 1e-9);
  EXPECT_GT(alpha.vec3().norm(), 1.0);
}

INSTANTIATE_TEST_SUITE_P(Timesteps, ConnectorSignals, ::testing::Values(0.002, 0.02));

// Where nothing can take a torque or a connector output cannot be formed, the warning says why.
TEST(ConnectorSignalsWarnings, ATorqueOnAStaticBodySaysWhy) {
  const openplx::testing::ScratchDir dir;
  std::ofstream(dir / "static.openplx") << "Block is Physics3D.Bodies.RigidBody:\n"
                                           "    with Physics3D.Signals.Torque3DInputTrait\n"
                                           "    is_dynamic: false\n"
                                           "    shape is Physics3D.Geometries.Box:\n"
                                           "        size: {1, 1, 1}\n"
                                           "Scene is Physics3D.System:\n"
                                           "    block is Block\n"
                                           "    torque is Physics3D.Signals.Torque3DInput:\n"
                                           "        source: block\n";
  rt::Simulation sim = rt::Simulation::load((dir / "static.openplx").string());
  std::string all;
  for (const std::string& w : sim.warnings()) all += w;
  EXPECT_NE(all.find("`block` is static"), std::string::npos) << all;
}

}  // namespace
