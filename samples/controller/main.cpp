// A PD controller for samples/two_joint_arm.openplx, written against OpenPLX signal names only.
//   arm_controller path/to/two_joint_arm.openplx
#include <cmath>
#include <cstdio>
#include <exception>

#include "openplx/runtime/simulation.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: arm_controller MODEL.openplx\n");
    return 2;
  }
  try {
    auto sim = openplx::runtime::Simulation::load(argv[1]);
    auto shoulder_torque = sim.input("shoulder_torque");
    auto elbow_torque = sim.input("elbow_torque");
    auto shoulder = sim.output("shoulder_angle");
    auto elbow = sim.output("elbow_angle");
    auto shoulder_speed = sim.output("shoulder_speed");
    auto elbow_speed = sim.output("elbow_speed");
    const double shoulder_target = 0.5, elbow_target = -0.4;
    while (sim.time() < 3.0) {
      shoulder_torque.set(60 * (shoulder_target - shoulder.real()) - 6 * shoulder_speed.real());
      elbow_torque.set(30 * (elbow_target - elbow.real()) - 3 * elbow_speed.real());
      sim.step();
    }
    const auto tip = sim.output("tip_position").vec3();
    std::printf("shoulder %.4f rad, elbow %.4f rad, tip {%.4f, %.4f, %.4f}\n", shoulder.real(), elbow.real(),
                tip.x(), tip.y(), tip.z());
    const bool held =
        std::abs(shoulder.real() - shoulder_target) < 0.2 && std::abs(elbow.real() - elbow_target) < 0.2;
    return held ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
}
