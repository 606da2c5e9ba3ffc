// One small scene per kind of thing a signal can be attached to: a body, a connector, each interaction the
// bundles have, drivetrain parts, vehicle parts, sensors, and other signals (what Control and Robotics
// signals take). Each converts on its own; the catalogue adds one signal at `source` to it.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "tests/support/front_axle.h"

namespace openplx::catalogue {

struct SourceFixture {
  std::string kind;         // the row label: what the source is
  std::string text;         // a complete file whose last model is the scene (a Physics3D.System)
  std::string source;       // path of the source inside the scene
  std::string probe_lines;  // more lines of the probe (indented by 8), e.g. its `relative_to`
  // A constructor (not an aggregate), so that fixtures without probe lines leave them out without a warning.
  SourceFixture(std::string kind_, std::string text_, std::string source_, std::string probe_lines_ = "")
      : kind(std::move(kind_)),
        text(std::move(text_)),
        source(std::move(source_)),
        probe_lines(std::move(probe_lines_)) {}
};

namespace detail {

// A 1 kg rod whose `end` connector sits at the world connector `pivot`; `lines` go into the scene,
// `rod_lines` into the rod's model.
inline std::string rod_scene(const std::string& lines, const std::string& rod_lines = "") {
  return "Rod is Physics3D.Bodies.RigidBody:\n" + rod_lines +
         "    inertia.mass: 1\n"
         "    geometry is Physics3D.Geometries.Box:\n"
         "        size: {1, 0.1, 0.1}\n"
         "    end is Physics3D.Interactions.MateConnector:\n"
         "        position.x: -0.5\n"
         "        main_axis: Math.Vec3.Y_AXIS()\n"
         "        normal: Math.Vec3.X_AXIS()\n"
         "Scene is Physics3D.System:\n"
         "    pivot is Physics3D.Interactions.MateConnector:\n"
         "        main_axis: Math.Vec3.Y_AXIS()\n"
         "        normal: Math.Vec3.X_AXIS()\n"
         "    rod is Rod\n" +
         lines;
}

// `name is Type` joining pivot and the rod's end, with `lines` (indented by 8) below it.
inline std::string joining(const std::string& name, const std::string& type, const std::string& lines = "") {
  return "    " + name + " is " + type + ":\n        connectors: [pivot, rod.end]\n" + lines;
}

inline std::string hinge() {
  return joining("hinge", "Physics3D.Interactions.Hinge");
}
inline std::string prismatic() {
  return joining("slide", "Physics3D.Interactions.Prismatic");
}

// Two shafts, `in` driven at 1 rad/s by the velocity motor `drive`, and `lines`.
inline std::string shaft_scene(const std::string& lines) {
  return "Scene is Physics3D.System:\n"
         "    in is DriveTrain.Shaft:\n        inertia.inertia: 1\n"
         "    out is DriveTrain.Shaft:\n        inertia.inertia: 1\n"
         "    drive is Physics1D.Interactions.RotationalVelocityMotor:\n"
         "        connectors: [in.input]\n        target_speed: 1\n" +
         lines;
}
// `name is Type` between the two shafts.
inline std::string coupling(const std::string& name, const std::string& type, const std::string& lines = "") {
  return shaft_scene("    " + name + " is " + type + ":\n        connectors: [in.output, out.input]\n" +
                     lines);
}

inline std::string vehicle_front() {
  return openplx::testing::front_axle("        mate.spring_constant.stiffness: 40000\n", true);
}

}  // namespace detail

inline std::vector<SourceFixture> source_fixtures() {
  using namespace detail;
  const std::string clutch_lines =
      "        torque_capacity: 100\n        initial_engagement_fraction: 1\n"
      "        min_relative_slip_ratio: 0.01\n";
  return {
      // Bodies and connectors.
      {"RigidBody (free)", rod_scene(""), "rod"},
      {"RigidBody (on a hinge)", rod_scene(hinge()), "rod"},
      {"RigidBody (kinematic)", rod_scene("", "    is_dynamic: false\n"), "rod"},
      // The bundles give no body Torque3DInputTrait: a user's model adds it.
      {"RigidBody (free) with Torque3DInputTrait",
       rod_scene("", "    with Physics3D.Signals.Torque3DInputTrait\n"), "rod"},
      {"MateConnector (on a hinged body)", rod_scene(hinge()), "rod.end"},
      {"MateConnector (world)", rod_scene(hinge()), "pivot"},
      // The same outputs seen from another connector: the hinged rod's end from the world's pivot, and the
      // world's pivot from the moving rod's end.
      {"MateConnector (on a hinged body), relative_to a world connector", rod_scene(hinge()), "rod.end",
       "        relative_to: pivot\n"},
      {"MateConnector (world), relative_to a moving connector", rod_scene(hinge()), "pivot",
       "        relative_to: rod.end\n"},
      // Mates.
      {"Hinge", rod_scene(hinge()), "hinge"},
      // Force and torque outputs expressed in a turned frame (other signals have no `relative_to`).
      {"Hinge, relative_to a transform", rod_scene(hinge()), "hinge",
       "        relative_to: Math.AffineTransform.from({0, 0, 0}, Math.Quat.angle_axis(0.5, {0, 0, 1}))\n"},
      {"Prismatic", rod_scene(prismatic()), "slide"},
      {"Cylindrical", rod_scene(joining("mate", "Physics3D.Interactions.Cylindrical")), "mate"},
      {"Ball", rod_scene(joining("mate", "Physics3D.Interactions.Ball")), "mate"},
      {"Lock", rod_scene(joining("mate", "Physics3D.Interactions.Lock")), "mate"},
      {"Distance",
       rod_scene(joining("mate", "Physics3D.Interactions.Distance", "        initial_distance: 0.5\n")),
       "mate"},
      {"ConstantVelocity", rod_scene(joining("mate", "Physics3D.Interactions.ConstantVelocity")), "mate"},
      // Motors, ranges and springs beside the mate they act along.
      {"RotationalVelocityMotor (3D)",
       rod_scene(hinge() + joining("motor", "Physics3D.Interactions.RotationalVelocityMotor")), "motor"},
      {"LinearVelocityMotor (3D)",
       rod_scene(prismatic() + joining("motor", "Physics3D.Interactions.LinearVelocityMotor")), "motor"},
      {"TorqueMotor (3D)", rod_scene(hinge() + joining("motor", "Physics3D.Interactions.TorqueMotor")),
       "motor"},
      {"ForceMotor (3D)", rod_scene(prismatic() + joining("motor", "Physics3D.Interactions.ForceMotor")),
       "motor"},
      {"DistanceMotor", rod_scene(prismatic() + joining("motor", "Physics3D.Interactions.DistanceMotor")),
       "motor"},
      {"RotationalRange",
       rod_scene(hinge() + joining("range", "Physics3D.Interactions.RotationalRange",
                                   "        start: -0.5\n        end: 0.5\n")),
       "range"},
      {"LinearRange",
       rod_scene(prismatic() + joining("range", "Physics3D.Interactions.LinearRange",
                                       "        start: -0.5\n        end: 0.5\n")),
       "range"},
      {"DistanceRange",
       rod_scene(prismatic() + joining("range", "Physics3D.Interactions.DistanceRange",
                                       "        start: 0.1\n        end: 1\n")),
       "range"},
      {"TorsionSpring",
       rod_scene(hinge() + joining("spring", "Physics3D.Interactions.TorsionSpring",
                                   "        flexibility.stiffness: 100\n")),
       "spring"},
      {"LinearSpring",
       rod_scene(prismatic() + joining("spring", "Physics3D.Interactions.LinearSpring",
                                       "        flexibility.stiffness: 100\n")),
       "spring"},
      // Drivetrain.
      {"Shaft", shaft_scene(""), "in"},
      {"RotationalVelocityMotor (1D)", shaft_scene(""), "drive"},
      {"TorqueMotor (drivetrain)",
       shaft_scene("    load is DriveTrain.TorqueMotor:\n        connectors: [out.input]\n"), "load"},
      {"Gear", coupling("part", "DriveTrain.Gear", "        ratio: 2\n"), "part"},
      {"FlexibleGear", coupling("part", "DriveTrain.FlexibleGear", "        ratio: 2\n"), "part"},
      {"ViscousGear", coupling("part", "DriveTrain.ViscousGear", "        ratio: 2\n"), "part"},
      {"ManualClutch", coupling("part", "DriveTrain.ManualClutch", clutch_lines), "part"},
      {"AutomaticClutch", coupling("part", "DriveTrain.AutomaticClutch", clutch_lines), "part"},
      {"ManualBrake", coupling("part", "DriveTrain.ManualBrake", clutch_lines), "part"},
      {"AutomaticBrake", coupling("part", "DriveTrain.AutomaticBrake", clutch_lines), "part"},
      {"GearBox",
       coupling(
           "part", "DriveTrain.GearBox",
           "        forward_gears: [4.0, 2.0]\n        reverse_gears: [-5.0]\n        initial_gear: 1\n"),
       "part"},
      {"EmpiricalTorqueConverter", coupling("part", "DriveTrain.EmpiricalTorqueConverter"), "part"},
      {"Differential",
       shaft_scene("    left is DriveTrain.Shaft:\n        inertia.inertia: 1\n"
                   "    part is DriveTrain.Differential:\n"
                   "        drive_shaft: in\n        left_axle_shaft: left\n        right_axle_shaft: out\n"),
       "part"},
      {"TorqueLimitedSlipDifferential",
       shaft_scene("    left is DriveTrain.Shaft:\n        inertia.inertia: 1\n"
                   "    part is DriveTrain.TorqueLimitedSlipDifferential:\n"
                   "        drive_shaft: in\n        left_axle_shaft: left\n        right_axle_shaft: out\n"
                   "        breakaway_torque: 50\n"),
       "part"},
      {"MeanValueEngine",
       shaft_scene("    engine is DriveTrain.MeanValueEngine:\n        connectors: [out.input]\n"), "engine"},
      {"EmpiricalEngine",
       shaft_scene("    engine is DriveTrain.EmpiricalEngine:\n        connectors: [out.input]\n"), "engine"},
      {"HingeActuator",
       rod_scene(hinge() + "    shaft is DriveTrain.Shaft:\n        inertia.inertia: 1\n"
                           "    part is DriveTrain.HingeActuator:\n        connector_1d: shaft.output\n"
                           "        mate_3d: hinge\n"),
       "part"},
      // Vehicles: a static chassis with two steered front wheels on spring suspensions.
      {"Wheel rim", vehicle_front(), "front_left.rim"},
      {"SingleMate suspension mate", vehicle_front(), "left_suspension.mate"},
      {"Ackermann steering",
       vehicle_front() +
           "    steering is Vehicles.Steering.Kinematic.Ackermann:\n"
           "        left_suspension: left_suspension\n        right_suspension: right_suspension\n",
       "steering"},
      {"Ackermann steering interaction",
       vehicle_front() +
           "    steering is Vehicles.Steering.Kinematic.Ackermann:\n"
           "        left_suspension: left_suspension\n        right_suspension: right_suspension\n",
       "steering.interaction"},
      {"RackAndPinion steering",
       vehicle_front() +
           "    steering is Vehicles.Steering.Kinematic.RackAndPinion:\n"
           "        left_suspension: left_suspension\n        right_suspension: right_suspension\n",
       "steering"},
      // Sensors.
      {"IMU",
       rod_scene(hinge() + "    imu is Sensors.IMULogic:\n        mate_connector_attachment: rod.end\n"
                           "        accelerometer is Sensors.AccelerometerLogic:\n"
                           "            mate_connector_attachment: rod.end\n"),
       "imu"},
      {"Lidar",
       rod_scene("    lidar is Sensors.PulsedLidarLogic:\n        mate_connector_attachment: pivot\n"
                 "        wavelength: 865\n"
                 "        ray_source becomes Sensors.Optics.HorizontalSweepRaySource:\n"
                 "            frequency: 10\n            horizontal_resolution: 3\n"
                 "            vertical_resolution: 1\n            horizontal_fov: {-0.4, 0.4}\n"
                 "            vertical_fov: {0, 0}\n"),
       "lidar"},
      // Terrain: a shovel on the rod (MuJoCo has no soil).
      {"Terrain Shovel",
       rod_scene(
           "    shovel is Terrain.Shovel:\n        body: rod\n"
           "        top_edge:\n            start: {0.5, 0, 0.05}\n            end: {-0.5, 0, 0.05}\n"
           "        cutting_edge:\n            start: {0.5, 0, -0.05}\n            end: {-0.5, 0, -0.05}\n"),
       "shovel"},
      // Signals themselves (Control and Robotics signals route to or from them).
      {"Input (a torque motor's torque_input)",
       rod_scene(hinge() + joining("motor", "Physics3D.Interactions.TorqueMotor")), "motor.torque_input"},
      {"Output (a hinge's angle_output)", rod_scene(hinge()), "hinge.angle_output"},
  };
}

// Lines a signal type needs besides its source to be meaningful; `{source}` stands for the source's path.
inline std::string extra_lines(const std::string& type) {
  if (type == "Sensors.Signals.IMUOutput")
    return "        fields: [{Sensors.Signals.TriaxialOutputField.Z_F64, {source}.accelerometer}]\n";
  if (type == "Sensors.Signals.LidarOutput")
    return "        fields: [Sensors.Signals.LidarOutputField.Distance_F32]\n";
  return "";
}

}  // namespace openplx::catalogue
