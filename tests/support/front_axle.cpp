#include "tests/support/front_axle.h"

namespace openplx::testing {

std::string front_axle(const std::string& spring, bool steerable) {
  std::string text =
      "Chassis is Physics3D.Bodies.RigidBody:\n"
      "    is_dynamic: false\n"
      "    box is Physics3D.Geometries.Box:\n"
      "        size: {3, 0.6, 0.4}\n"
      "    fl is Physics3D.Interactions.MateConnector:\n"
      "        position: {1.2, 0.8, -0.2}\n"
      "        main_axis: {0, 1, 0}\n"
      "        normal: {0, 0, 1}\n"
      "    fr is Physics3D.Interactions.MateConnector:\n"
      "        position: {1.2, -0.8, -0.2}\n"
      "        main_axis: {0, 1, 0}\n"
      "        normal: {0, 0, 1}\n"
      "Wheel is Vehicles.Wheels.Base:\n"
      "    rim becomes Vehicles.Wheels.Rim:\n"
      "        radius: 0.35\n"
      "        width: 0.25\n"
      "        rotational_axis: {0, 1, 0}\n"
      "        inertia.mass: 20\n"
      "Scene is Physics3D.System:\n"
      "    chassis is Chassis\n"
      "    front_left is Wheel\n"
      "    front_right is Wheel\n";
  for (const char* side : {"left", "right"}) {
    text +=
        std::string("    ") + side + "_suspension is Vehicles.Suspensions.SingleMate.LinearSpringDamper:\n";
    if (steerable) text += "        with Vehicles.Suspensions.Properties.Steering\n";
    text += std::string("        chassis_connector: chassis.") + (side[0] == 'l' ? "fl" : "fr") + "\n";
    text += std::string("        attachment_connector: front_") + side + ".connector\n";
    text += spring;
  }
  return text;
}

}  // namespace openplx::testing
