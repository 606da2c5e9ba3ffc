// Loads a scene of two prefixed copies of the cart-pole (two_carts_scene.xml, placed on two rails, or
// samples/merged_scene.xml; see their headers) with MuJoCo's own mj_loadXML and balances both poles upright,
// each through its own SignalBridge, by OpenPLX signal names only. Exits 1 when a pole tilts past 0.2 rad or
// a cart reaches its rail's end stop within 10 s.
//   two_carts SCENE.xml LEFT.signals.json RIGHT.signals.json
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>

#include "openplx/runtime/signal_bridge.h"

namespace {

// State feedback push = kx x + kv v + ka angle + kr rate (angle 0 upright, positive toward +x). Derived by
// pole placement on cart_pole.openplx linearized about upright: cart M = 1 kg, pole m = 0.1 kg with its
// centre l = 0.5 m above the hinge and J = m (1 m)^2 / 12 + m l^2 about it, g = 9.81:
//   (M + m) x'' + m l angle'' = push,   m l x'' + J angle'' = m g l angle.
// The gains put the closed loop's poles at -2, -3, -4 and -5 1/s: settled in about 2 s, and at the model's
// 0.1 rad start the push peaks near 6.5 N, inside the motor's 10 N.
constexpr double kx = 8.36, kv = 10.73, ka = 64.89, kr = 16.72;
constexpr double kFallen = 0.2;   // rad
constexpr double kRailEnd = 2.3;  // m; rail_limits stop the cart at 2.4

// One cart-pole's signals, found by name in the manifest its bridge read.
struct Balancer {
  explicit Balancer(openplx::runtime::SignalBridge& bridge)
      : push(bridge.input("push")),
        x(bridge.output("cart_position")),
        v(bridge.output("cart_speed")),
        angle(bridge.output("pole_angle")),
        rate(bridge.output("pole_rate")) {}
  void control() {
    push.set(std::clamp(kx * x.real() + kv * v.real() + ka * angle.real() + kr * rate.real(), -10.0, 10.0));
  }
  bool upright() const { return std::abs(angle.real()) < kFallen && std::abs(x.real()) < kRailEnd; }
  openplx::runtime::Input push;
  openplx::runtime::Output x, v, angle, rate;
};

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: two_carts SCENE.xml LEFT.signals.json RIGHT.signals.json\n");
    return 2;
  }
  char error[1000] = "";
  mjModel* m = mj_loadXML(argv[1], nullptr, error, sizeof(error));
  if (!m) {
    std::fprintf(stderr, "%s: %s\n", argv[1], error);
    return 1;
  }
  mjData* d = mj_makeData(m);
  // The left pole starts where the model puts it (the hinge's initial_angle, 0.1 rad); the scene's own
  // initial state tilts the right one the other way. MuJoCo names are the prefix + the OpenPLX name.
  if (int hinge = mj_name2id(m, mjOBJ_JOINT, "right/hinge"); hinge >= 0)
    d->qpos[m->jnt_qposadr[hinge]] = -0.05;
  mj_forward(m, d);
  int status = 0;
  try {
    auto left_bridge = openplx::runtime::SignalBridge::attach(argv[2], m, d);
    auto right_bridge = openplx::runtime::SignalBridge::attach(argv[3], m, d);
    Balancer left(left_bridge), right(right_bridge);
    std::printf("start: left pole %.4f rad, right pole %.4f rad\n", left.angle.real(), right.angle.real());
    while (d->time < 10.0 && left.upright() && right.upright()) {
      left.control();
      right.control();
      left_bridge.before_step();
      right_bridge.before_step();
      mj_step(m, d);
      left_bridge.after_step();
      right_bridge.after_step();
    }
    std::printf("after %.2f s: left pole %.2e rad, cart %.2e m; right pole %.2e rad, cart %.2e m\n", d->time,
                left.angle.real(), left.x.real(), right.angle.real(), right.x.real());
    status = left.upright() && right.upright() ? 0 : 1;
    if (status) std::fprintf(stderr, "a pole fell past %.1f rad or a cart ran to its end stop\n", kFallen);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    status = 1;
  }
  mj_deleteData(d);
  mj_deleteModel(m);
  return status;
}
