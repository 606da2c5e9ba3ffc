// Loads a scene of two prefixed copies of the cart-pole (two_carts_scene.xml, placed on two rails, or
// samples/merged_scene.xml; see their headers) with MuJoCo's own mj_loadXML and drives each copy by OpenPLX
// signal names through its own SignalBridge: the left cart is pushed forward, the right one back.
//   two_carts SCENE.xml LEFT.signals.json RIGHT.signals.json
#include <mujoco/mujoco.h>

#include <cstdio>
#include <exception>

#include "openplx/runtime/signal_bridge.h"

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
  int status = 0;
  try {
    auto left = openplx::runtime::SignalBridge::attach(argv[2], m, d);
    auto right = openplx::runtime::SignalBridge::attach(argv[3], m, d);
    left.input("push").set(5.0);
    right.input("push").set(-5.0);
    auto left_x = left.output("cart_position");
    auto right_x = right.output("cart_position");
    while (d->time < 1.0) {
      left.before_step();
      right.before_step();
      mj_step(m, d);
      left.after_step();
      right.after_step();
    }
    std::printf("after %.2f s: left cart at %.4f m, right cart at %.4f m\n", d->time, left_x.real(),
                right_x.real());
    status = left_x.real() > 0.1 && right_x.real() < -0.1 ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    status = 1;
  }
  mj_deleteData(d);
  mj_deleteModel(m);
  return status;
}
