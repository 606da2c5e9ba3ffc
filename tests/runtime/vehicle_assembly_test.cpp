// Vehicles assembled as AGX assembles them. A vehicle written the AGX way declares where its wheels attach
// in its own frame, with connectors redirected to the chassis, whose placement it leaves to SNAP: the
// suspensions then join the wheels to the chassis (not to the world), so the wheels go where the chassis
// goes. And a wheel never touches the chassis it hangs on, as AGX's wheel joint excludes that pair: MuJoCo
// filters a child from its parent only when neither is welded to the world, so a static chassis and an
// elastic wheel's tire (two bodies below the chassis) get an <exclude>.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <Eigen/Dense>
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "openplx/runtime/simulation.h"
#include "tests/support/scratch_dir.h"

namespace {

namespace rt = openplx::runtime;

struct Car {
  bool static_chassis = false;
  bool elastic_wheels = false;
  bool steered = false;        // front suspensions with Properties.Steering and an Ackermann steering
  double chassis_width = 0.8;  // m; 1.6 puts the wheels half inside the chassis box (wheel wells)
  bool steel = false;          // chassis and rims of one material, with a SurfaceContact model for it
};

// Four wheels on spring-damper suspensions. The mounts are the vehicle's own connectors, redirected to the
// chassis (the front ones in 0.31's trait spelling, the rear ones as RedirectedMateConnector); the chassis
// has no placement of its own. Rear wheels driven by `speed` (rad/s).
std::string car(const Car& c) {
  std::string text = "Chassis is Physics3D.Bodies.RigidBody:\n" +
                     std::string(c.static_chassis ? "    is_dynamic: false\n" : "    inertia.mass: 800\n") +
                     "    body is Physics3D.Geometries.Box:\n"
                     "        size: {3.0, " +
                     std::to_string(c.chassis_width) + ", 0.4}\n" +
                     (c.steel ? "        material: Steel\n" : "") +
                     "Rim is Vehicles.Wheels.Rim:\n"
                     "    radius: 0.35\n"
                     "    width: 0.25\n"
                     "    rotational_axis: Math.Vec3.Y_AXIS()\n"
                     "    inertia.mass: 20\n" +
                     (c.steel ? "    geometry.material: Steel\n" : "");
  if (c.steel) text = "const Steel is Physics.Geometries.Material\n" + text;
  if (c.elastic_wheels) {
    text +=
        "Wheel is Vehicles.Wheels.ElasticWheel:\n"
        "    rim becomes Rim\n"
        "    tire becomes Vehicles.Wheels.Tire:\n"
        "        outer_radius: 0.4\n"
        "        inner_radius: 0.35\n"
        "        width: 0.25\n"
        "        rotational_axis: Math.Vec3.Y_AXIS()\n"
        "        inertia.mass: 10\n";
  } else {
    text +=
        "Wheel is Vehicles.Wheels.Base:\n"
        "    rim becomes Rim\n";
  }
  text +=
      "Corner is Vehicles.Suspensions.SingleMate.LinearSpringDamper:\n"
      "    mate.spring_constant.stiffness: 40000\n"
      "    mate.spring_damping.damping_constant: 1500\n"
      "Car is Vehicles.Base:\n"
      "    ground is Physics3D.Bodies.RigidBody:\n"
      "        is_dynamic: false\n"
      "        kinematics.local_transform.position: {0, 0, -0.75}\n"
      "        floor is Physics3D.Geometries.Box:\n"
      "            size: {100, 100, 0.2}\n"
      "    chassis is Chassis\n";
  if (c.steel) {
    text +=
        "    grip is Physics.Interactions.SurfaceContact.Model:\n"
        "        material_1: Steel\n"
        "        material_2: Steel\n"
        "        normal_restitution: 0\n"
        "        tangential_restitution: 0\n";
  }
  const char* corners[] = {"front_left", "front_right", "rear_left", "rear_right"};
  for (const char* corner : corners) {
    const std::string name = corner;
    const bool front = name[0] == 'f', left = name.find("left") != std::string::npos;
    text += "    " + name + "_mount is Physics3D.Interactions." +
            (front ? "MateConnector with Physics3D.Interactions.ConnectorProperties.Redirected:\n"
                   : "RedirectedMateConnector:\n") +
            "        redirected_parent: chassis\n"
            "        position: {" +
            (front ? "1.25" : "-1.25") + ", " + (left ? "0.8" : "-0.8") +
            ", -0.2}\n"
            "        main_axis: Math.Vec3.Y_AXIS()\n"
            "        normal: Math.Vec3.Z_AXIS()\n"
            "    " +
            name + " is Wheel\n";
    text += "    " + name + "_suspension is Corner:\n";
    if (front && c.steered) text += "        with Vehicles.Suspensions.Properties.Steering\n";
    text += "        chassis_connector: " + name + "_mount\n" + "        attachment_connector: " + name +
            ".connector\n";
  }
  if (c.steered) {
    text +=
        "    steering_system is Vehicles.Steering.Kinematic.Ackermann:\n"
        "        left_suspension: front_left_suspension\n"
        "        right_suspension: front_right_suspension\n"
        "    steering is Physics.Signals.AngleInput:\n"
        "        source: steering_system.interaction\n";
  }
  for (const char* side : {"left", "right"}) {
    text += std::string("    rear_") + side +
            "_drive is Physics3D.Interactions.RotationalVelocityMotor:\n"
            "        connectors: rear_" +
            side +
            "_suspension.mate.connectors\n"
            "        target_speed: 0\n"
            "        min_effort: -600\n"
            "        max_effort: 600\n";
  }
  text +=
      "    speed is Control.Virtual.BroadcastInput:\n"
      "        targets: [rear_left_drive.target_angular_velocity_input, "
      "rear_right_drive.target_angular_velocity_input]\n";
  return text;
}

rt::Simulation load(const openplx::testing::ScratchDir& dir, const Car& c, double dt) {
  std::ofstream(dir / "car.openplx") << car(c);
  rt::LoadOptions options;
  options.timestep = dt;
  return rt::Simulation::load((dir / "car.openplx").string(), options);
}

int body(const mjModel* m, const std::string& name) {
  const int b = mj_name2id(m, mjOBJ_BODY, name.c_str());
  EXPECT_GE(b, 0) << name;
  return b;
}

// A body's position in the chassis frame.
Eigen::Vector3d in_chassis(const mjData* d, int chassis, int b) {
  const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> r(d->xmat + 9 * chassis);
  const Eigen::Map<const Eigen::Vector3d> origin(d->xpos + 3 * chassis), p(d->xpos + 3 * b);
  return r.transpose() * (p - origin);
}

const char* kWheels[] = {"front_left", "front_right", "rear_left", "rear_right"};

// The mounts are redirected onto the chassis, so the suspensions are the chassis's joints and the wheels go
// where the chassis goes, whatever moves it:
// - driven by its rear wheels (4 rad/s on a 0.35 m radius) the car rolls over 2 m in 2 s;
// - carried (a kinematic chassis moved by its velocity inputs, 1 m/s forward, 0.25 m/s up and 0.3 rad/s
//   about the vertical) it lifts its wheels off the ground and turns them with it.
// Every wheel stays at its mount in the chassis frame: x and y to 1 mm (only the spin and the travel along
// the chassis's vertical are free), z within the travel the springs allow (the car's 800 kg sag 49 mm on
// four 40 kN/m springs). At dt 0.02 the springs are too stiff for the step (held rigid, warned): the wheels
// follow all the same.
TEST(VehicleAssembly, WheelsFollowTheChassisTheyAreRedirectedTo) {
  for (const double dt : {0.002, 0.02}) {
    for (const bool carried : {false, true}) {
      SCOPED_TRACE("dt " + std::to_string(dt) + (carried ? " carried" : " driven"));
      const openplx::testing::ScratchDir dir;
      Car c;
      c.static_chassis = carried;
      rt::Simulation sim = load(dir, c, dt);
      for (const std::string& w : sim.warnings())
        EXPECT_EQ(w.find("redirected_parent"), std::string::npos) << w;  // every mount found its chassis
      const mjModel* m = sim.model();
      const mjData* d = sim.data();
      const int chassis = body(m, "chassis");
      for (const char* wheel : kWheels)  // each suspension is a joint of the chassis, not of the world
        EXPECT_EQ(m->body_parentid[body(m, std::string(wheel) + ".rim")], chassis) << wheel;
      const Eigen::Vector3d start(d->xpos + 3 * chassis);
      if (carried) {
        sim.input("chassis.linear_velocity_world_input").set(Eigen::Vector3d(1, 0, 0.25));
        sim.input("chassis.angular_velocity_world_input").set(Eigen::Vector3d(0, 0, 0.3));
      } else {
        sim.input("speed").set(4.0);
      }
      sim.advance(2.0);
      const Eigen::Vector3d moved = Eigen::Vector3d(d->xpos + 3 * chassis) - start;
      EXPECT_GT(std::abs(moved.x()), carried ? 1.5 : 2.0);
      for (const char* wheel : kWheels) {
        const std::string name = wheel;
        const Eigen::Vector3d at = in_chassis(d, chassis, body(m, name + ".rim"));
        EXPECT_NEAR(std::abs(at.x()), 1.25, 1e-3) << name;
        EXPECT_NEAR(std::abs(at.y()), 0.8, 1e-3) << name;
        EXPECT_NEAR(at.z(), -0.2, 0.1) << name;  // within the suspension's travel
      }
    }
  }
}

// Contacts between a wheel's bodies and its chassis's, at this step.
int wheel_chassis_contacts(const mjModel* m, const mjData* d, int chassis, const std::vector<int>& wheels) {
  int count = 0;
  for (int k = 0; k < d->ncon; ++k) {
    const int b1 = m->geom_bodyid[d->contact[k].geom1], b2 = m->geom_bodyid[d->contact[k].geom2];
    for (int w : wheels) count += (b1 == chassis && b2 == w) || (b2 == chassis && b1 == w);
  }
  return count;
}

// Wheels half inside the chassis box (wheel wells 0.125 m deep) are steered by an Ackermann steering over
// the inputs a user may set (AGX's 0.05 rad and ±0.3 rad): not one contact between a wheel and the chassis
// at any step, for a chassis on the ground (parent of its wheels), a static one (welded to the world, where
// MuJoCo would let its children touch it: 2000 contacts up to 14 cm deep in 1 s without the <exclude>s),
// elastic wheels (the tire two bodies below the chassis: 2000 contacts up to 24 cm deep without) and a
// contact model naming the chassis's and the rims' material (a <pair> would bypass every filter).
TEST(VehicleAssembly, WheelsNeverTouchTheirChassisWhileSteering) {
  struct Case {
    const char* name;
    Car car;
  };
  const Case cases[] = {{"dynamic", {false, false, true, 1.6}},
                        {"static", {true, false, true, 1.6}},
                        {"elastic", {false, true, true, 1.6}},
                        {"pairs", {false, false, true, 1.6, true}}};
  for (const Case& c : cases) {
    for (const double dt : {0.002, 0.02}) {
      for (const double steer : {0.05, 0.3, -0.3}) {
        SCOPED_TRACE(std::string(c.name) + " dt " + std::to_string(dt) + " steer " + std::to_string(steer));
        const openplx::testing::ScratchDir dir;
        rt::Simulation sim = load(dir, c.car, dt);
        const mjModel* m = sim.model();
        const mjData* d = sim.data();
        const int chassis = body(m, "chassis");
        std::vector<int> wheels;
        for (const char* wheel : kWheels) {
          wheels.push_back(body(m, std::string(wheel) + ".rim"));
          if (c.car.elastic_wheels) wheels.push_back(body(m, std::string(wheel) + ".tire"));
        }
        sim.input("steering").set(steer);
        sim.input("speed").set(2.0);
        int touching = 0;
        for (double t = 0; t < 1.0; t += dt) {
          sim.step();
          touching += wheel_chassis_contacts(m, d, chassis, wheels);
        }
        EXPECT_EQ(touching, 0);
        const int left = mj_name2id(m, mjOBJ_JOINT, "front_left_suspension.mate.steering");
        ASSERT_GE(left, 0);
        EXPECT_NEAR(d->qpos[m->jnt_qposadr[left]], steer, 1e-2);  // it did steer
        for (int w : wheels)
          EXPECT_LT((in_chassis(d, chassis, w).head<2>().cwiseAbs() - Eigen::Vector2d(1.25, 0.8)).norm(),
                    0.05);
      }
    }
  }
}

}  // namespace
