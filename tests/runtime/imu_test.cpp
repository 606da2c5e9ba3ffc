// An IMU (Sensors.IMULogic with an accelerometer and a gyroscope on a body's connector) read through one
// IMUOutput whose fields pick axes: at rest on a hinge the accelerometer reads gravity's reaction along the
// connector's up axis (+9.81, proper acceleration), and while the body spins about that axis at 2 rad/s the
// gyroscope reads 2 on it.
#include <gtest/gtest.h>

#include <fstream>

#include "openplx/runtime/simulation.h"
#include "tests/support/scratch_dir.h"

namespace {

namespace rt = openplx::runtime;

const char kModel[] =
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
    "    ground is Physics3D.Interactions.MateConnector:\n"
    "        main_axis: Math.Vec3.Z_AXIS()\n"
    "        normal: Math.Vec3.X_AXIS()\n"
    "    puck is Puck\n"
    "    hinge is Physics3D.Interactions.Hinge:\n"
    "        connectors: [ground, puck.axle]\n"
    "    spin is Physics3D.Interactions.RotationalVelocityMotor:\n"
    "        connectors: [ground, puck.axle]\n"
    "        target_speed: 2\n"
    "    imu is Sensors.IMULogic:\n"
    "        mate_connector_attachment: puck.mount\n"
    "        accelerometer is Sensors.AccelerometerLogic:\n"
    "            mate_connector_attachment: puck.mount\n"
    "        gyroscope is Sensors.GyroscopeLogic:\n"
    "            mate_connector_attachment: puck.mount\n"
    "    readings is Sensors.Signals.IMUOutput:\n"
    "        source: imu\n"
    "        fields: [{Sensors.Signals.TriaxialOutputField.Z_F64, imu.accelerometer},\n"
    "                 {Sensors.Signals.TriaxialOutputField.X_F64, imu.accelerometer},\n"
    "                 {Sensors.Signals.TriaxialOutputField.Z_F64, imu.gyroscope}]\n";

TEST(Imu, FieldsReadTheAccelerometerAndGyroscopeAxes) {
  const openplx::testing::ScratchDir dir;
  std::ofstream(dir / "imu.openplx") << kModel;
  rt::Simulation sim = rt::Simulation::load((dir / "imu.openplx").string());
  EXPECT_TRUE(sim.warnings().empty()) << sim.warnings().front();
  rt::Output readings = sim.output("readings");
  EXPECT_EQ(readings.info().size, 3u);
  sim.advance(0.5);
  const Eigen::VectorXd v = readings.vector();
  EXPECT_NEAR(v[0], 9.81, 1e-6);  // proper acceleration: the hinge holds it up against gravity
  // Spinning at w about the mount's z, the mount (at the axis) has no centripetal acceleration.
  EXPECT_NEAR(v[1], 0.0, 1e-6);
  EXPECT_NEAR(v[2], 2.0, 1e-3);  // the motor's speed
}

}  // namespace
