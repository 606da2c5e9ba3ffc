// What a URDF says beyond links and joints reaches MuJoCo: <dynamics> damping and friction, effort and
// velocity limits on the motors a user adds, material colours, package:// meshes through Urdf.PackagePath,
// floating joints; non-physical inertias are repaired with a warning (planar joints: urdf_real_robots_test).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "openplx/runtime/simulation.h"
#include "tests/support/scratch_dir.h"
#include "tests/support/tetrahedron_stl.h"
#include "tools/cli/cli.h"

namespace {

namespace fs = std::filesystem;
namespace rt = openplx::runtime;

// A base and an arm on a vertical hinge (gravity exerts no torque about it). The arm's 1 kg sits 0.25 m out
// with its own 0.01 kg m² about z, so I about the hinge is 0.01 + 1 * 0.25² = 0.0725 kg m². Its inertial
// tensor at `arm_inertia` is deliberately non-physical in the non-physical test only.
std::string arm_urdf(const std::string& arm_inertia = "ixx=\"0.01\" iyy=\"0.01\" izz=\"0.01\"") {
  return R"(<?xml version="1.0"?>
<robot name="dyn_arm">
  <material name="red"><color rgba="1 0 0 1"/></material>
  <link name="base">
    <inertial><mass value="2"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
    <visual name="shell"><geometry><box size="0.1 0.1 0.1"/></geometry><material name="red"/></visual>
  </link>
  <link name="arm">
    <inertial><origin xyz="0.25 0 0"/><mass value="1"/><inertia )" +
         arm_inertia + R"( ixy="0" ixz="0" iyz="0"/></inertial>
    <visual><geometry><mesh filename="package://my_pkg/meshes/tetra.stl"/></geometry>
      <material name="blue"><color rgba="0 0 1 0.5"/></material></visual>
  </link>
  <joint name="shoulder" type="continuous">
    <parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>
    <limit effort="3" velocity="2"/>
    <dynamics damping="0.5" friction="0.2"/>
  </joint>
</robot>
)";
}

using openplx::testing::write_tetrahedron;

class UrdfRobotProperties : public ::testing::Test {
 protected:
  void SetUp() override { write_tetrahedron(dir_ / "packages" / "my_pkg" / "meshes" / "tetra.stl"); }
  fs::path write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
    return dir_ / name;
  }
  // An .openplx extending the arm; `body` is indented under the extending model.
  fs::path robot(const std::string& body, const std::string& urdf = arm_urdf()) {
    write("arm.urdf", urdf);
    return write("robot.openplx",
                 "import @\"arm.urdf\"\nRobot is arm:\n    pkg is Urdf.PackagePath:\n"
                 "        name: \"my_pkg\"\n        path: @\"packages/my_pkg\"\n" +
                     body);
  }
  int cli(const std::vector<std::string>& args, std::string* err) {
    std::ostringstream out, errors;
    const int status = openplx::cli::run(args, out, errors);
    *err = errors.str();
    return status;
  }
  openplx::testing::ScratchDir scratch_;
  fs::path dir_ = scratch_.path();
};

const std::string kTorqueMotor =
    "    motor is Physics3D.Interactions.TorqueMotor:\n        connectors: shoulder.connectors\n"
    "    torque is Physics.Signals.Torque1DInput:\n        source: motor\n"
    "    speed is Physics.Signals.AngularVelocity1DOutput:\n        source: shoulder\n";

TEST_F(UrdfRobotProperties, DynamicsBecomeJointDampingAndFriction) {
  rt::Simulation sim = rt::Simulation::load(robot(kTorqueMotor).string());
  const mjModel* m = sim.model();
  const int dof = m->jnt_dofadr[mj_name2id(m, mjOBJ_JOINT, "shoulder")];
  EXPECT_EQ(m->dof_damping[dof], 0.5);
  EXPECT_EQ(m->dof_frictionloss[dof], 0.2);
}

// The effort limit bounds the motor the user added: asked for 10 N m it gives 3. Spinning up against the
// 0.2 N m friction and 0.5 N m s damping, ω(t) = (3 - 0.2) / 0.5 · (1 - exp(-0.5 t / I)) with I = 0.0725.
// MuJoCo's friction is a soft constraint and Euler integrates in 2 ms steps: 1 % covers both.
TEST_F(UrdfRobotProperties, EffortLimitBoundsAnAddedMotor) {
  rt::Simulation sim = rt::Simulation::load(robot(kTorqueMotor).string());
  const mjModel* m = sim.model();
  const int motor = mj_name2id(m, mjOBJ_ACTUATOR, "motor");
  EXPECT_EQ(m->actuator_forcerange[2 * motor], -3.0);
  EXPECT_EQ(m->actuator_forcerange[2 * motor + 1], 3.0);
  sim.input("torque").set(10.0);
  sim.advance(0.5);
  const double t = sim.data()->time, inertia = 0.0725;
  const double expected = (3 - 0.2) / 0.5 * (1 - std::exp(-0.5 * t / inertia));
  EXPECT_NEAR(sim.output("speed").real(), expected, 0.01 * expected);
}

// The velocity limit bounds what a velocity motor may be asked for: 5 rad/s becomes 2.
TEST_F(UrdfRobotProperties, VelocityLimitBoundsAVelocityMotor) {
  rt::Simulation sim = rt::Simulation::load(
      robot("    motor is Physics3D.Interactions.RotationalVelocityMotor:\n        connectors: "
            "shoulder.connectors\n"
            "        target_speed: 5.0\n"
            "    speed is Physics.Signals.AngularVelocity1DOutput:\n        source: shoulder\n")
          .string());
  const mjModel* m = sim.model();
  const int motor = mj_name2id(m, mjOBJ_ACTUATOR, "motor");
  EXPECT_EQ(m->actuator_ctrllimited[motor], 1);
  EXPECT_EQ(m->actuator_ctrlrange[2 * motor], -2.0);
  EXPECT_EQ(m->actuator_ctrlrange[2 * motor + 1], 2.0);
  sim.advance(3.0);
  // The motor's row holds 2 rad/s exactly against friction and damping, 0.2 + 0.5 * 2 N m, within its effort.
  EXPECT_NEAR(sim.output("speed").real(), 2.0, 1e-9);
}

TEST_F(UrdfRobotProperties, MaterialsKeepTheirColours) {
  rt::Simulation sim = rt::Simulation::load(robot("").string());
  const mjModel* m = sim.model();
  auto rgba = [&](const char* geom) {
    const int g = mj_name2id(m, mjOBJ_GEOM, geom);
    EXPECT_GE(g, 0) << geom;
    const float* c = m->mat_rgba + 4 * m->geom_matid[g];
    return std::vector<float>(c, c + 4);
  };
  // The base's visual keeps its URDF name (`shell`); the arm's has none and is numbered.
  EXPECT_EQ(rgba("base.visual_shell"), (std::vector<float>{1, 0, 0, 1}));  // a named robot-level material
  EXPECT_EQ(rgba("arm.visual_0"), (std::vector<float>{0, 0, 1, 0.5f}));    // an inline one
}

// Urdf.PackagePath decides where package://my_pkg/ is; without one the import looks beside and above the URDF
// (here it does not find the package, which lives under packages/).
TEST_F(UrdfRobotProperties, PackagePathResolvesPackageMeshes) {
  rt::Simulation sim = rt::Simulation::load(robot("").string());
  const mjModel* m = sim.model();
  ASSERT_EQ(m->nmesh, 1);
  EXPECT_EQ(m->mesh_vertnum[0], 4);
  // Without it the visual mesh is not found: a warning at its element, and the arm converts without it.
  write("plain.openplx", "import @\"arm.urdf\"\nRobot is arm\n");
  std::string err;
  EXPECT_EQ(cli({(dir_ / "plain.openplx").string(), "-o", (dir_ / "plain.xml").string()}, &err), 0) << err;
  EXPECT_NE(err.find((dir_ / "arm.urdf").string() + ":10:23: warning: mesh file "), std::string::npos) << err;
}

// A tensor that breaks the triangle inequality is repaired (moments set to their mean, MuJoCo's
// balanceinertia rule) with a warning at its <inertia> element.
TEST_F(UrdfRobotProperties, NonPhysicalInertiaIsRepairedWithAWarning) {
  const fs::path path = robot("", arm_urdf("ixx=\"0.1\" iyy=\"0.01\" izz=\"0.01\""));
  std::string err;
  EXPECT_EQ(cli({path.string(), "-o", (dir_ / "robot.xml").string(), "--check"}, &err), 0) << err;
  EXPECT_NE(
      err.find(
          (dir_ / "arm.urdf").string() +
          ":9:56: warning: link `arm` has a non-physical inertia: principal moments 0.1, 0.01, 0.01 (as "
          "MuJoCo computes them) violate the triangle inequality A + B >= C, which MuJoCo checks exactly; "
          "they were set to their mean 0.04 (MuJoCo's balanceinertia) [urdf-warning]"),
      std::string::npos)
      << err;
  rt::Simulation sim = rt::Simulation::load(path.string());
  const int arm = mj_name2id(sim.model(), mjOBJ_BODY, "arm");
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(sim.model()->body_inertia[3 * arm + k], 0.04, 1e-12);
}

// A COLLADA mesh (common in ROS packages) is read (tests/mjcf/mesh_conversion_test.cpp); one that cannot be
// read, on a visual, is a located warning and the visual is left out.
TEST_F(UrdfRobotProperties, UnreadableColladaVisualIsALocatedWarning) {
  std::string urdf = arm_urdf();
  urdf.replace(urdf.find("package://my_pkg/meshes/tetra.stl"), 33, "meshes/part.dae");
  fs::create_directories(dir_ / "meshes");
  std::ofstream(dir_ / "meshes" / "part.dae") << "<COLLADA/>";
  std::string err;
  EXPECT_EQ(cli({robot("", urdf).string()}, &err), 0) << err;
  EXPECT_EQ(
      err.rfind((dir_ / "arm.urdf").string() + ":10:23: warning: mesh file " +
                    (dir_ / "meshes" / "part.dae").string() +
                    " of `arm.visual_0.path` cannot be a MuJoCo mesh: the Open Asset Import Library cannot "
                    "read it",
                0),
      0u)
      << err;
  EXPECT_NE(err.find("; this visual geometry was left out [mjcf-unmapped]"), std::string::npos) << err;
}

// Values a URDF can hold but a robot cannot: each is located at its element. A negative mass and a name no
// OpenPLX identifier can hold are errors; a zero axis and an inverted range are warnings with what was done.
TEST_F(UrdfRobotProperties, ImpossibleValuesAreLocated) {
  struct Case {
    std::string from, to, diagnostic;
    int exit;
  };
  const std::vector<Case> cases = {
      {"<mass value=\"1\"/>", "<mass value=\"-1\"/>",
       ":9:39: error: link `arm` has a negative mass [urdf-invalid]", openplx::cli::kExitInputError},
      {"<axis xyz=\"0 0 1\"/>", "<axis xyz=\"0 0 0\"/>",
       ":14:45: warning: joint `shoulder` has a zero axis; the x axis was used [urdf-warning]", 0},
      {"type=\"continuous\"", "type=\"revolute\"", "", 0},  // effort and velocity only: no range, no warning
      {"<link name=\"arm\">", "<link name=\"a`rm\">", "", openplx::cli::kExitInputError},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.to);
    std::string urdf = arm_urdf();
    urdf.replace(urdf.find(c.from), c.from.size(), c.to);
    if (c.to.find("a`rm") != std::string::npos) urdf.replace(urdf.find("link=\"arm\""), 10, "link=\"a`rm\"");
    const fs::path path = robot("", urdf);
    std::string err;
    EXPECT_EQ(cli({path.string(), "-o", (dir_ / "robot.xml").string()}, &err), c.exit) << err;
    if (!c.diagnostic.empty()) {
      EXPECT_NE(err.find((dir_ / "arm.urdf").string() + c.diagnostic), std::string::npos) << err;
    }
    if (c.to.find("a`rm") != std::string::npos) {
      EXPECT_NE(err.find(":8:3: error: link name contains a backtick or a line break"), std::string::npos)
          << err;
    }
    if (c.diagnostic.empty() && c.exit == 0) {
      EXPECT_EQ(err.find("warning"), std::string::npos) << err;
    }
  }
  std::string urdf = arm_urdf();
  urdf.replace(urdf.find("type=\"continuous\""), 17, "type=\"revolute\"");
  urdf.replace(urdf.find("<limit effort"), 13, "<limit lower=\"1\" upper=\"-1\" effort");
  std::string err;
  EXPECT_EQ(cli({robot("", urdf).string(), "-o", (dir_ / "robot.xml").string()}, &err), 0) << err;
  EXPECT_NE(
      err.find(
          ":15:5: warning: joint `shoulder` has lower > upper; it was left without a range [urdf-warning]"),
      std::string::npos)
      << err;
}

// A floating joint leaves its child free, starting where the joint's origin puts it.
TEST_F(UrdfRobotProperties, FloatingChildIsFreeAtItsOrigin) {
  std::string urdf = arm_urdf();
  urdf.replace(urdf.find("type=\"continuous\""), 17, "type=\"floating\"");
  urdf.replace(urdf.find("<axis xyz=\"0 0 1\"/>"), 19, "<origin xyz=\"0.5 0 1\"/>");
  rt::Simulation sim = rt::Simulation::load(robot("", urdf).string());
  const mjModel* m = sim.model();
  const int arm = mj_name2id(m, mjOBJ_BODY, "arm");
  ASSERT_GE(arm, 0);
  ASSERT_EQ(m->body_jntnum[arm], 1);
  EXPECT_EQ(m->jnt_type[m->body_jntadr[arm]], mjJNT_FREE);
  mj_forward(m, sim.data());
  EXPECT_NEAR(sim.data()->xpos[3 * arm], 0.5, 1e-12);
  EXPECT_NEAR(sim.data()->xpos[3 * arm + 2], 1.0, 1e-12);
}

// The import forms OpenPLX documents: the robot's own name, and a dotted alias.
TEST_F(UrdfRobotProperties, RobotNameAndDottedAliasNameTheModel) {
  write("arm.urdf", arm_urdf());
  write_tetrahedron(dir_ / "meshes" / "tetra.stl");  // where the import looks for package my_pkg: none
  fs::create_directories(dir_ / "my_pkg" / "meshes");
  write_tetrahedron(dir_ / "my_pkg" / "meshes" / "tetra.stl");  // a package folder beside the URDF
  for (const std::string& text : {std::string("import @\"arm.urdf\"\nRobot is dyn_arm\n"),
                                  std::string("import $\"arm.urdf\" as robots.arm\nRobot is robots.arm\n")}) {
    SCOPED_TRACE(text);
    rt::Simulation sim = rt::Simulation::load(write("named.openplx", text).string());
    EXPECT_GE(mj_name2id(sim.model(), mjOBJ_JOINT, "shoulder"), 0);
  }
}

}  // namespace
