// Drives samples/drivetrain_machine.openplx by OpenPLX signal names: throttles up to cruising speed, shifts
// up by engine speed, and brakes to stop at a mark.
//   machine_driver path/to/drivetrain_machine.openplx
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>

#include "openplx/runtime/simulation.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: machine_driver MODEL.openplx\n");
    return 2;
  }
  try {
    auto sim = openplx::runtime::Simulation::load(argv[1]);
    auto throttle = sim.input("throttle");
    auto clutch = sim.input("clutch");
    auto gear = sim.input("gear");
    auto brake_left = sim.input("brake_left");
    auto brake_right = sim.input("brake_right");
    auto position = sim.output("position");
    auto velocity = sim.output("velocity");
    auto rpm = sim.output("engine_rpm");
    const double mark = 30.0, cruise = 7.0, braking = 6.5;  // m, m/s, m/s^2 (under the tyres' grip)
    int selected = 1;
    double top = 0;
    bool stopping = false;
    while (sim.time() < 20.0) {
      const double x = position.vec3().x(), v = velocity.vec3().x();
      top = std::max(top, v);
      if (!stopping && x >= mark - v * v / (2 * braking)) {
        stopping = true;
        throttle.set(0.0);
        clutch.set(false);
        brake_left.set(1.0);
        brake_right.set(1.0);
      }
      if (stopping && std::abs(v) < 1e-3) break;
      if (!stopping) {
        throttle.set(std::clamp(0.1 + 0.5 * (cruise - v), 0.0, 1.0));
        if (rpm.real() > 2800 && selected < 3) gear.set(static_cast<double>(++selected));
      }
      sim.step();
    }
    const double x = position.vec3().x(), v = velocity.vec3().x();
    std::printf("machine stopped at x = %.2f m (mark %.0f) after %.2f s, top speed %.2f m/s in gear %d\n", x,
                mark, sim.time(), top, selected);
    return std::abs(x - mark) < 3 && std::abs(v) < 0.01 ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
}
