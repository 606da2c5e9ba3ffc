// Test support: the models of the owned-rows acceptance tests (tests/runtime/owned_rows_test.cpp) besides the
// N-link arm (tests/support/arm_chain.h) — the gear pair and the car on (elastic) wheels — and converting one
// the way openplx2mjcf does, so the same models can be run with the runtime (owned_rows_test) and as the MJCF
// alone in plain MuJoCo (bare_mjcf_rows_test).
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/arm_chain.h"
#include "tests/support/scratch_dir.h"
#include "tools/cli/cli.h"

namespace openplx::testing {

// ---------------------------------------------------------------------------------------------------------
// Converting

inline std::filesystem::path write_model(const ScratchDir& dir, const std::string& text) {
  const std::filesystem::path file = dir / "model.openplx";
  std::ofstream(file) << text;
  return file;
}

// The converter's MJCF (and the manifest beside it) for `source` at time step h, as openplx2mjcf writes them.
inline std::filesystem::path emit(const ScratchDir& dir, const std::filesystem::path& source, double h,
                                  const std::string& model = "") {
  const std::filesystem::path xml = dir / "model.xml";
  std::vector<std::string> args{source.string(), "-o", xml.string(), "--timestep", arm_number(h)};
  if (!model.empty()) {
    args.push_back("--model");
    args.push_back(model);
  }
  std::ostringstream out, err;
  EXPECT_EQ(openplx::cli::run(args, out, err), openplx::cli::kExitOk) << err.str();
  return xml;
}

inline std::filesystem::path manifest_of(const std::filesystem::path& xml) {
  return openplx::cli::manifest_path(xml.string());
}

// ---------------------------------------------------------------------------------------------------------
// A gear

// A 1-D drivetrain: a velocity motor `drive` (target 0, its AngularVelocity1DInput `speed`) on an input shaft
// `in` (1 kg m^2), a DriveTrain.Gear `gear` of `ratio` to an output shaft `out` (1 kg m^2). The convention
// (tests/runtime/rigid_coupling_test.cpp, drivetrain_parts_test.cpp): the output turns at input / ratio, the
// same way.
inline std::string gear_pair(double ratio) {
  return "Pair is Physics3D.System:\n"
         "    in is DriveTrain.Shaft:\n"
         "        inertia.inertia: 1\n"
         "    out is DriveTrain.Shaft:\n"
         "        inertia.inertia: 1\n"
         "    drive is Physics1D.Interactions.RotationalVelocityMotor:\n"
         "        connectors: [in.input]\n"
         "        target_speed: 0\n"
         "    gear is DriveTrain.Gear:\n"
         "        connectors: [in.output, out.input]\n"
         "        ratio: " +
         arm_number(ratio) +
         "\n"
         "    speed is Physics.Signals.AngularVelocity1DInput:\n"
         "        source: drive\n";
}

// ---------------------------------------------------------------------------------------------------------
// A car

// tests/runtime/vehicle_assembly_test.cpp's car (copied: that file's builder is not shared): an 800 kg
// chassis on the ground, four wheels on SingleMate.LinearSpringDamper suspensions (40 kN/m, 1500 N s/m)
// redirected to the chassis, the front ones with Properties.Steering and an Ackermann steering
// `steering_system` driven by the AngleInput `steering`; the rear wheels driven at `speed` (rad/s) by
// velocity motors of +-600 N m. Elastic wheels: Vehicles.Wheels.ElasticWheel, a 20 kg rim of 0.35 m in a
// 10 kg tire of 0.4 m on six joints of AGX's 300 kN/m (and N m/rad) default stiffness.
struct Car {
  bool elastic_wheels = true;
  bool steered = true;
  double chassis_width = 0.8;  // m; 1.6 puts the wheels half inside the chassis box (wheel wells)
};

inline std::string car(const Car& c) {
  std::string text =
      "Chassis is Physics3D.Bodies.RigidBody:\n"
      "    inertia.mass: 800\n"
      "    body is Physics3D.Geometries.Box:\n"
      "        size: {3.0, " +
      arm_number(c.chassis_width) +
      ", 0.4}\n"
      "Rim is Vehicles.Wheels.Rim:\n"
      "    radius: 0.35\n"
      "    width: 0.25\n"
      "    rotational_axis: Math.Vec3.Y_AXIS()\n"
      "    inertia.mass: 20\n";
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
  for (const std::string corner : {"front_left", "front_right", "rear_left", "rear_right"}) {
    const bool front = corner[0] == 'f', left = corner.find("left") != std::string::npos;
    text += "    " + corner + "_mount is Physics3D.Interactions." +
            (front ? "MateConnector with Physics3D.Interactions.ConnectorProperties.Redirected:\n"
                   : "RedirectedMateConnector:\n") +
            "        redirected_parent: chassis\n"
            "        position: {" +
            (front ? "1.25" : "-1.25") + ", " + (left ? "0.8" : "-0.8") +
            ", -0.2}\n"
            "        main_axis: Math.Vec3.Y_AXIS()\n"
            "        normal: Math.Vec3.Z_AXIS()\n"
            "    " +
            corner + " is Wheel\n";
    text += "    " + corner + "_suspension is Corner:\n";
    if (front && c.steered) text += "        with Vehicles.Suspensions.Properties.Steering\n";
    text += "        chassis_connector: " + corner + "_mount\n" + "        attachment_connector: " + corner +
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
  for (const std::string side : {"left", "right"}) {
    text += "    rear_" + side +
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

}  // namespace openplx::testing
