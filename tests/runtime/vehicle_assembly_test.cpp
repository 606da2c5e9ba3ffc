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
#include "tests/support/car_model.h"
#include "tests/support/scratch_dir.h"

namespace {

namespace rt = openplx::runtime;

using openplx::testing::Car;
using openplx::testing::car;

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
