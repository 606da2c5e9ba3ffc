// Vehicles: SingleMate suspensions (travel with spring and damper, steering, spin) and kinematic steering,
// measured against the physics: a suspension settles at its static deflection m g / k, the steering input
// holds the left wheel's angle, and the right wheel follows the Ackermann trapezoid (its tie rod keeps its
// length). Warnings about bundle parts point at the user's lines.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <Eigen/Geometry>
#include <cmath>
#include <fstream>

#include "openplx/runtime/simulation.h"
#include "tests/support/front_axle.h"
#include "tests/support/scratch_dir.h"

namespace {

namespace rt = openplx::runtime;

// A chassis held by the world (static) with two front wheels on suspensions, clear of its box (MuJoCo lets
// a child touch a parent welded to the world); `spring` is the suspensions' spring block, `steered` adds the
// steering trait and an Ackermann steering.
std::string car(const std::string& spring, bool steered) {
  std::string text = openplx::testing::front_axle(spring, steered);
  if (steered) {
    text +=
        "    steering is Vehicles.Steering.Kinematic.Ackermann:\n"
        "        left_suspension: left_suspension\n"
        "        right_suspension: right_suspension\n";
  }
  return text;
}

double qpos(rt::Simulation& sim, const char* joint) {
  const mjModel* m = sim.model();
  const int j = mj_name2id(m, mjOBJ_JOINT, joint);
  EXPECT_GE(j, 0) << joint;
  return j < 0 ? 0.0 : sim.data()->qpos[m->jnt_qposadr[j]];
}

// A 20 kg wheel hanging on a 20 kN/m spring sags m g / k = 9.81 mm. The damper is critical (2 sqrt(k m)),
// so after 2 s (over 30 time constants) the travel rests there; MuJoCo's joint stiffness is the spring
// itself, so only Euler's O(h) error remains: 0.5 %.
TEST(VehicleSuspension, SettlesAtItsStaticDeflection) {
  const openplx::testing::ScratchDir dir;
  const double k = 2e4, m = 20, b = 2 * std::sqrt(k * m);
  std::ofstream(dir / "car.openplx") << car(
      "        mate.spring_constant.stiffness: " + std::to_string(k) +
          "\n        mate.spring_damping.damping_constant: " + std::to_string(b) + "\n",
      false);
  rt::Simulation sim = rt::Simulation::load((dir / "car.openplx").string());
  sim.advance(2.0);
  const double sag = -m * 9.81 / k;
  EXPECT_NEAR(qpos(sim, "left_suspension.mate.travel"), sag, 5e-3 * std::abs(sag));
  EXPECT_NEAR(qpos(sim, "right_suspension.mate.travel"), sag, 5e-3 * std::abs(sag));
  EXPECT_LT(std::abs(sim.data()->qvel[sim.model()->jnt_dofadr[mj_name2id(sim.model(), mjOBJ_JOINT,
                                                                         "left_suspension.mate.travel")]]),
            1e-6);
  // Without Properties.Steering the steering rotation is locked: no such joint.
  EXPECT_LT(mj_name2id(sim.model(), mjOBJ_JOINT, "left_suspension.mate.steering"), 0);
  EXPECT_GE(mj_name2id(sim.model(), mjOBJ_JOINT, "left_suspension.mate.spin"), 0);
}

// AGX's default suspension spring (1e8 N/m) on a 20 kg wheel has a period of 2.8 ms, under two steps: it is
// held rigid, with a warning at the user's suspension line (not in the bundle).
TEST(VehicleSuspension, TooStiffASpringIsHeldRigidAndSaidAtTheUsersLine) {
  const openplx::testing::ScratchDir dir;
  std::ofstream(dir / "car.openplx") << car("", false);
  rt::Simulation sim = rt::Simulation::load((dir / "car.openplx").string());
  EXPECT_LT(mj_name2id(sim.model(), mjOBJ_JOINT, "left_suspension.mate.travel"), 0);
  int stiff = 0;
  for (const std::string& w : sim.warnings()) {
    EXPECT_EQ(w.find("bundles/"), std::string::npos) << w;  // every warning at the user's file
    if (w.find("is stiffer than MuJoCo integrates") == std::string::npos) continue;
    ++stiff;
    EXPECT_NE(w.find((dir / "car.openplx").string() + ":2"), std::string::npos) << w;  // lines 22, 26
  }
  EXPECT_EQ(stiff, 2);
}

// AGX's steering test: 0.5 on the steering input gives 0.5 on its output within 1e-6 after 1 s (0 before).
// The right wheel follows the trapezoid: kingpins 1.6 m apart, knuckle arms of 0.16 of that (0.256 m)
// pointing rearward and 25° inward (knuckle_angle -2.007 rad), a tie rod between their ends whose length the
// steering must keep; MuJoCo's quartic fit to that linkage is within 2e-3 rad for left angles -0.38 to 0.72,
// so the tie rod keeps its length to l · 2e-3 = 0.5 mm.
TEST(VehicleSteering, AckermannFollowsItsInputAndKeepsTheTieRod) {
  const openplx::testing::ScratchDir dir;
  std::ofstream(dir / "car.openplx") << car(
      "        mate.spring_constant.stiffness: 20000\n        mate.spring_damping.damping_constant: 1265\n",
      true);
  rt::Simulation sim = rt::Simulation::load((dir / "car.openplx").string());
  rt::Output out = sim.output("steering.interaction.steering_angle_output");
  EXPECT_EQ(out.real(), 0.0);
  sim.input("steering.interaction.steering_angle_input").set(0.5);
  sim.advance(1.0);
  EXPECT_NEAR(out.real(), 0.5, 1e-6);
  const double left = qpos(sim, "left_suspension.mate.steering");
  const double right = qpos(sim, "right_suspension.mate.steering");
  EXPECT_NEAR(left, 0.5, 1e-6);
  EXPECT_GT(right, 0.2);   // both turn left ...
  EXPECT_LT(right, left);  // ... the inner (left) wheel more: Ackermann
  // The tie rod: arm ends at straight ahead and now, in the plane (x forward, y left).
  const double w = 1.6, l = 0.16 * w, beta = 2.007 - M_PI / 2;
  const Eigen::Vector2d kl(0, w / 2), kr(0, -w / 2);
  const Eigen::Vector2d arm_l(-l * std::cos(beta), -l * std::sin(beta)),
      arm_r(-l * std::cos(beta), l * std::sin(beta));
  const double tie = ((kl + arm_l) - (kr + arm_r)).norm();
  const Eigen::Vector2d pl = kl + Eigen::Rotation2Dd(left) * arm_l,
                        pr = kr + Eigen::Rotation2Dd(right) * arm_r;
  EXPECT_NEAR((pl - pr).norm(), tie, 1e-3);
  sim.input("steering.interaction.steering_angle_input").set(-0.3);
  sim.advance(1.0);
  EXPECT_NEAR(out.real(), -0.3, 1e-6);
  EXPECT_LT(qpos(sim, "right_suspension.mate.steering"), -0.3);  // turning right, the right wheel is inner
}

// An elastic wheel's tire is its own body on six compliant joints to the rim (a slide along and a hinge about
// the axle and two radii, each with the wheel's stiffness, default 300 kN/m and 300 kN m/rad, and damping):
// hanging on a static hub it sags m g / k = 30 x 9.81 / 3e5 = 0.981 mm (1 %: Euler's O(h) on a spring of
// period 63 ms), and it turns with the rim when a motor spins the axle (its torsional spring carries it:
// 5 rad/s to 1e-3 after 1 s).
TEST(VehicleWheel, ElasticTireHangsAtItsStiffnessAndTurnsWithTheRim) {
  const openplx::testing::ScratchDir dir;
  std::ofstream(dir / "wheel.openplx") << "Hub is Physics3D.Bodies.RigidBody:\n"
                                          "    is_dynamic: false\n"
                                          "    axle is Physics3D.Interactions.MateConnector:\n"
                                          "        main_axis: {0, 1, 0}\n"
                                          "        normal: {0, 0, 1}\n"
                                          "Tyre is Vehicles.Wheels.ElasticWheel:\n"
                                          "    rim becomes Vehicles.Wheels.Rim:\n"
                                          "        radius: 0.3\n"
                                          "        width: 0.2\n"
                                          "        rotational_axis: {0, 1, 0}\n"
                                          "        inertia.mass: 10\n"
                                          "    tire becomes Vehicles.Wheels.Tire:\n"
                                          "        outer_radius: 0.4\n"
                                          "        inner_radius: 0.3\n"
                                          "        width: 0.25\n"
                                          "        rotational_axis: {0, 1, 0}\n"
                                          "        inertia.mass: 30\n"
                                          "Scene is Physics3D.System:\n"
                                          "    hub is Hub\n"
                                          "    wheel is Tyre\n"
                                          "    axle is Physics3D.Interactions.Hinge:\n"
                                          "        connectors: [hub.axle, wheel.connector]\n"
                                          "    spin is Physics3D.Interactions.RotationalVelocityMotor:\n"
                                          "        connectors: axle.connectors\n"
                                          "        target_speed: 0\n"
                                          "    tire_position is Physics3D.Signals.Position3DOutput:\n"
                                          "        source: wheel.tire\n"
                                          "    tire_spin is Physics3D.Signals.AngularVelocity3DOutput:\n"
                                          "        source: wheel.tire\n";
  rt::Simulation sim = rt::Simulation::load((dir / "wheel.openplx").string());
  sim.advance(2.0);
  EXPECT_NEAR(sim.output("tire_position").vec3().z(), -30 * 9.81 / 3e5, 0.01 * 30 * 9.81 / 3e5);
  sim.input("spin.target_angular_velocity_input").set(5.0);
  sim.advance(1.0);
  EXPECT_NEAR(sim.output("tire_spin").vec3().y(), 5.0, 1e-3);
}

// A tracked vehicle: a 100 kg chassis on a sprocket and an idler (0.2 m) 2 m apart, 60 box links (5 cm
// thick) around them, on the ground. Its sprocket driven at 2 rad/s moves the track at ω (r + h / 2) =
// 0.45 m/s past the wheels; the ground holds the lower run, so the vehicle rolls forward at that speed, less
// the slip of the links' friction contacts on the sprocket (10 %), and straight ahead.
TEST(VehicleTracks, MovesWhenItsSprocketTurns) {
  const openplx::testing::ScratchDir dir;
  std::ofstream(dir / "tank.openplx")
      << "Sprocket is Vehicles.TrackSystem.Components.TrackWheels.Sprocket:\n"
         "    with Vehicles.TrackSystem.Components.TrackWheels.Traits.CylindricalShape\n"
         "    radius: 0.2\n"
         "    width: 0.3\n"
         "    body.inertia.mass: 10\n"
         "\n"
         "Idler is Vehicles.TrackSystem.Components.TrackWheels.Idler:\n"
         "    with Vehicles.TrackSystem.Components.TrackWheels.Traits.CylindricalShape\n"
         "    radius: 0.2\n"
         "    width: 0.3\n"
         "    body.inertia.mass: 10\n"
         "\n"
         "const LinkMaterial is Physics.Geometries.Material:\n"
         "    density: 2000\n"
         "\n"
         "Tank is Physics3D.System:\n"
         "    ground is Physics3D.Bodies.RigidBody:\n"
         "        is_dynamic: false\n"
         "        kinematics.local_transform.position: {0, 0, -0.55}\n"
         "        floor is Physics3D.Geometries.Box:\n"
         "            size: {40, 10, 0.2}\n"
         "    chassis is Physics3D.Bodies.RigidBody:\n"
         "        inertia.mass: 100\n"
         "        geometry is Physics3D.Geometries.Box:\n"
         "            size: {2, 0.2, 0.2}\n"
         "        sprocket_connector is Physics3D.Interactions.MateConnector:\n"
         "            main_axis: Math.Vec3.Y_AXIS()\n"
         "            normal: Math.Vec3.Z_AXIS()\n"
         "            position: {-1, 0.3, -0.2}\n"
         "        idler_connector is Physics3D.Interactions.MateConnector:\n"
         "            main_axis: Math.Vec3.Y_AXIS()\n"
         "            normal: Math.Vec3.Z_AXIS()\n"
         "            position: {1, 0.3, -0.2}\n"
         "    track_system is Vehicles.TrackSystem.Base:\n"
         "        tracks.link_count: 60\n"
         "        tracks.link_description becomes "
         "Vehicles.TrackSystem.Components.Tracks.LinkDescription.Box:\n"
         "            width: 0.3\n"
         "            height: 0.05\n"
         "            contact_geometry.material: LinkMaterial\n"
         "        track_wheels: [track_system.sprocket, track_system.idler]\n"
         "        sprocket is Sprocket\n"
         "        idler is Idler\n"
         "        chassis_body: chassis\n"
         "    tracks_connection is Vehicles.TrackSystem.Connections.Base with "
         "Vehicles.TrackSystem.Connections.Traits.TwoWheels:\n"
         "        track_system: track_system\n"
         "        connectors: [chassis.sprocket_connector, chassis.idler_connector]\n"
         "    drive is Physics3D.Interactions.RotationalVelocityMotor:\n"
         "        connectors: tracks_connection.hinge_1.hinge.connectors\n"
         "        min_effort: -500\n"
         "        max_effort: 500\n"
         "    speed is Physics.Signals.AngularVelocity1DInput:\n"
         "        source: drive\n"
         "    position is Physics3D.Signals.Position3DOutput:\n"
         "        source: chassis\n";
  rt::Simulation sim = rt::Simulation::load((dir / "tank.openplx").string());
  EXPECT_GE(mj_name2id(sim.model(), mjOBJ_BODY, "track_system.link59"), 0);
  sim.input("speed").set(2.0);
  sim.advance(1.0);  // up to speed
  const Eigen::Vector3d from = sim.output("position").vec3();
  sim.advance(2.0);
  const Eigen::Vector3d moved = sim.output("position").vec3() - from;
  EXPECT_NEAR(moved.x() / 2.0, 2.0 * (0.2 + 0.025), 0.1 * 0.45);
  EXPECT_LT(std::abs(moved.y()), 0.02);
  EXPECT_LT(std::abs(moved.z()), 0.02);
}

// samples/vehicle_circle: held at a steering angle of 0.3 rad with its rear wheels spun at 8 rad/s, the car
// drives a circle. Its centre of turning lies on the rear axle's line at L / tan(left angle) + w / 2 from the
// rear axle's middle (Ackermann: the inner, left, wheel sets it), so the chassis centre, L / 2 ahead of the
// axle, circles at sqrt((L / tan 0.3 + w / 2)² + (L / 2)²) = 8.95 m (L = 2.5 m, w = 1.6 m). Tyres slip a
// little sideways at 0.9 m/s² of lateral acceleration: 5 %. The fitted circle must also be a circle (every
// point within 2 % of its radius) and the car must come round (more than one lap in 25 s of fitting).
TEST(VehicleSample, DrivesACircleAtItsSteeringRadius) {
  rt::Simulation sim = rt::Simulation::load(std::string(OPENPLX_SAMPLES_DIR) + "/vehicle_circle.openplx");
  sim.input("steering").set(0.3);
  sim.input("speed").set(8.0);
  sim.advance(3.0);  // sags onto its springs and gets up to speed
  std::vector<Eigen::Vector2d> points;
  for (int k = 0; k < 250; ++k) {
    sim.advance(0.1);
    const Eigen::Vector3d p = sim.output("position").vec3();
    points.emplace_back(p.x(), p.y());
  }
  // Kasa's algebraic circle fit: x² + y² + D x + E y + F = 0 in the least-squares sense.
  Eigen::MatrixXd a(points.size(), 3);
  Eigen::VectorXd b(points.size());
  for (size_t k = 0; k < points.size(); ++k) {
    a.row(static_cast<int>(k)) << points[k].x(), points[k].y(), 1.0;
    b(static_cast<int>(k)) = -points[k].squaredNorm();
  }
  const Eigen::Vector3d def = a.colPivHouseholderQr().solve(b);
  const Eigen::Vector2d centre = -def.head<2>() / 2;
  const double radius = std::sqrt(centre.squaredNorm() - def(2));
  const double expected = std::hypot(2.5 / std::tan(0.3) + 0.8, 1.25);
  EXPECT_NEAR(radius, expected, 0.05 * expected);
  double swept = 0;
  for (size_t k = 0; k < points.size(); ++k) {
    EXPECT_NEAR((points[k] - centre).norm(), radius, 0.02 * radius);
    if (k == 0) continue;
    const Eigen::Vector2d u = points[k - 1] - centre, v = points[k] - centre;
    swept += std::atan2(u.x() * v.y() - u.y() * v.x(), u.dot(v));
  }
  EXPECT_GT(swept, 2 * M_PI);  // counter-clockwise: a left turn
}

}  // namespace
