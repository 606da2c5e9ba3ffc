#include "tests/support/car_model.h"

namespace openplx::testing {

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

Car elastic_steered_car() {
  Car c;
  c.elastic_wheels = true;
  c.steered = true;
  return c;
}

}  // namespace openplx::testing
