// Signals a user declares: an input MuJoCo cannot carry is warned at the user's line (the bundles' own
// inputs, declared on every body, stay quiet), and a signal is bound by its type, whatever its attribute is
// named.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "contract/signal_binding.h"
#include "tests/support/front_axle.h"
#include "tests/support/mjcf_fixture.h"
#include "tests/support/scratch_dir.h"
#include "tools/cli/cli.h"

namespace {

namespace fe = openplx::frontend;
namespace mj = openplx::mjcf;
using Q = mj::Quantity;

// A 1 kg rod on a hinge at the world connector `pivot`; `lines` go into the scene.
std::string rod_scene(const std::string& lines) {
  return "Rod is Physics3D.Bodies.RigidBody:\n"                  // 1
         "    inertia.mass: 1\n"                                 // 2
         "    geometry is Physics3D.Geometries.Box:\n"           // 3
         "        size: {1, 0.1, 0.1}\n"                         // 4
         "    end is Physics3D.Interactions.MateConnector:\n"    // 5
         "        position.x: -0.5\n"                            // 6
         "        main_axis: Math.Vec3.Y_AXIS()\n"               // 7
         "        normal: Math.Vec3.X_AXIS()\n"                  // 8
         "Scene is Physics3D.System:\n"                          // 9
         "    pivot is Physics3D.Interactions.MateConnector:\n"  // 10
         "        main_axis: Math.Vec3.Y_AXIS()\n"               // 11
         "        normal: Math.Vec3.X_AXIS()\n"                  // 12
         "    rod is Rod\n" +                                    // 13
         lines;
}

struct Converted {
  int status;
  std::string file, errors;
};

Converted convert(const openplx::testing::ScratchDir& dir, const std::string& text) {
  Converted c;
  c.file = (dir / "scene.openplx").string();
  std::ofstream(c.file) << text;
  std::ostringstream out, errors;
  c.status = openplx::cli::run({c.file, "-o", (dir / "scene.xml").string()}, out, errors);
  c.errors = errors.str();
  return c;
}

TEST(UserSignalWarnings, AnUnmappedInputTheUserDeclaredIsWarnedAtItsLine) {
  const openplx::testing::ScratchDir dir;
  const Converted c = convert(dir, rod_scene("    hinge is Physics3D.Interactions.Hinge:\n"  // 14
                                             "        connectors: [pivot, rod.end]\n"        // 15
                                             "    push is Physics.Signals.BoolInput:\n"      // 16
                                             "        source: hinge\n"));                    // 17
  ASSERT_EQ(c.status, 0) << c.errors;
  EXPECT_NE(c.errors.find(c.file + ":16:5: warning: input `push` (Physics.Signals.BoolInput) has no MuJoCo "
                                   "counterpart: "),
            std::string::npos)
      << c.errors;
}

TEST(UserSignalWarnings, APlainBodyWithItsBundleDeclaredInputsIsQuiet) {
  const openplx::testing::ScratchDir dir;
  // A hinged rod: its velocity inputs (declared by RigidBody on every body) cannot be set in MuJoCo.
  const Converted c = convert(dir, rod_scene("    hinge is Physics3D.Interactions.Hinge:\n"
                                             "        connectors: [pivot, rod.end]\n"));
  ASSERT_EQ(c.status, 0) << c.errors;
  EXPECT_EQ(c.errors.find("input `"), std::string::npos) << c.errors;
}

using UserSignalBindings = openplx::testing::MjcfTest;

// The durations of an automatic clutch: the signal's type says which, not its attribute's name.
TEST_F(UserSignalBindings, ClutchDurationsAreChosenByTheSignalsType) {
  ASSERT_TRUE(
      load("Scene is Physics3D.System:\n"
           "    in is DriveTrain.Shaft:\n        inertia.inertia: 1\n"
           "    out is DriveTrain.Shaft:\n        inertia.inertia: 1\n"
           "    part is DriveTrain.AutomaticClutch:\n"
           "        connectors: [in.output, out.input]\n"
           "        torque_capacity: 100\n"
           "        initial_engagement_fraction: 1\n"
           "        min_relative_slip_ratio: 0.01\n"
           "        engagement_duration: 0.25\n"
           "        disengagement_duration: 0.75\n"
           "    release_time is DriveTrain.Signals.AutomaticClutchDisengagementDurationInput:\n"
           "        source: part\n"
           "    release_time_out is DriveTrain.Signals.AutomaticClutchDisengagementDurationOutput:\n"
           "        source: part\n"
           "    grip_time is DriveTrain.Signals.AutomaticClutchEngagementDurationInput:\n"
           "        source: part\n"));
  ASSERT_FALSE(emit("scene").empty());
  EXPECT_EQ(binding("release_time").quantity, Q::DisengageDuration);
  EXPECT_DOUBLE_EQ(binding("release_time").initial, 0.75);
  EXPECT_EQ(binding("release_time_out").quantity, Q::DisengageDuration);
  EXPECT_EQ(binding("grip_time").quantity, Q::EngageDuration);
  EXPECT_DOUBLE_EQ(binding("grip_time").initial, 0.25);
  // The clutch's own, named by the bundle.
  EXPECT_EQ(binding("part.disengagement_duration_input").quantity, Q::DisengageDuration);
  EXPECT_EQ(binding("part.engagement_duration_input").quantity, Q::EngageDuration);
}

// Any position input on a distance mate sets its target distance, which MuJoCo's tendon equality holds.
TEST_F(UserSignalBindings, APositionInputOnADistanceMateSetsItsTarget) {
  ASSERT_TRUE(
      load(rod_scene("    mate is Physics3D.Interactions.Distance:\n"
                     "        connectors: [pivot, rod.end]\n"
                     "        initial_distance: 0.5\n"
                     "    reach is Physics.Signals.Position1DInput:\n"
                     "        source: mate\n")));
  ASSERT_FALSE(emit("scene").empty());
  const mj::SignalBinding& reach = binding("reach");
  EXPECT_EQ(reach.quantity, Q::DistanceTarget);
  EXPECT_DOUBLE_EQ(reach.initial, 0.5);
  EXPECT_EQ(binding("mate.target_distance_input").quantity, Q::DistanceTarget);
  EXPECT_EQ(binding("mate.target_distance_output").quantity, Q::DistanceTarget);
  mjModel* m = load_mujoco(dir() + "/scene.xml");
  ASSERT_NE(m, nullptr);
  ASSERT_EQ(reach.names.size(), 1u);
  EXPECT_GE(mj_name2id(m, mjOBJ_EQUALITY, reach.names[0].c_str()), 0);
  mj_deleteModel(m);
}

// A RackAndPinion steering system as an angle signal's source: bound as its interaction's own angle
// signals are (the steering-wheel angle through the linkage's polynomial).
TEST_F(UserSignalBindings, ASteeringSystemsAngleIsItsInteractions) {
  ASSERT_TRUE(load(openplx::testing::front_axle("        mate.spring_constant.stiffness: 40000\n", true) +
                   "    steering is Vehicles.Steering.Kinematic.RackAndPinion:\n"
                   "        left_suspension: left_suspension\n        right_suspension: right_suspension\n"
                   "    wheel_in is Physics.Signals.AngleInput:\n        source: steering\n"
                   "    wheel_out is Physics.Signals.AngleOutput:\n        source: steering\n"));
  ASSERT_FALSE(emit("scene").empty());
  expect_diag_containing(fe::DiagCode::MjcfUnmapped, "RackAndPinion linkage");  // its fit, steering_test's
  const mj::SignalBinding& in = binding("wheel_in");
  const mj::SignalBinding& own_in = binding("steering.interaction.steering_angle_input");
  EXPECT_EQ(in.quantity, Q::EqualityTarget);
  EXPECT_EQ(in.names, own_in.names);
  EXPECT_EQ(in.initial_vector, own_in.initial_vector);
  const mj::SignalBinding& out = binding("wheel_out");
  EXPECT_EQ(out.quantity, Q::JointPosition);
  EXPECT_EQ(out.names, binding("steering.interaction.steering_angle_output").names);
}

// Switch-like signals MuJoCo cannot carry say why: the source's meaning, not a missing element.
TEST_F(UserSignalBindings, UnmappedSwitchesAndFractionsGiveTheRealReason) {
  ASSERT_TRUE(
      load("Scene is Physics3D.System:\n"
           "    in is DriveTrain.Shaft:\n        inertia.inertia: 1\n"
           "    out is DriveTrain.Shaft:\n        inertia.inertia: 1\n"
           "    hand is DriveTrain.ManualClutch:\n"
           "        connectors: [in.output, out.input]\n"
           "        torque_capacity: 100\n        initial_engagement_fraction: 1\n"
           "        min_relative_slip_ratio: 0.01\n"
           "    auto is DriveTrain.AutomaticClutch:\n"
           "        connectors: [in.output, out.input]\n"
           "        torque_capacity: 100\n        initial_engagement_fraction: 1\n"
           "        min_relative_slip_ratio: 0.01\n"
           "    hand_engaged is Physics.Signals.EngagedOutput:\n        source: hand\n"
           "    auto_fraction is Physics.Signals.FractionInput:\n        source: auto\n"
           "    hand_flag is Physics.Signals.BoolInput:\n        source: hand\n"
           "    hand_on is Physics.Signals.ActivateInput:\n        source: hand\n"));
  ASSERT_FALSE(emit("scene").empty());
  for (const char* path : {"hand_engaged", "auto_fraction", "hand_flag", "hand_on"}) {
    SCOPED_TRACE(path);
    EXPECT_EQ(binding(path).quantity, Q::None);
    EXPECT_EQ(binding(path).reason.find("not mapped yet"), std::string::npos) << binding(path).reason;
    EXPECT_EQ(binding(path).reason.find("no MuJoCo element"), std::string::npos) << binding(path).reason;
  }
  EXPECT_NE(binding("hand_engaged").reason.find("engagement fraction"), std::string::npos);
  EXPECT_NE(binding("auto_fraction").reason.find("ramps its own engagement fraction"), std::string::npos);
  EXPECT_NE(binding("hand_flag").reason.find("plain Bool"), std::string::npos);
  EXPECT_NE(binding("hand_on").reason.find("activation"), std::string::npos);
  // Each warned at the user's declaration.
  for (const char* name :
       {"output `hand_engaged`", "input `auto_fraction`", "input `hand_flag`", "input `hand_on`"})
    expect_diag_containing(fe::DiagCode::MjcfUnmapped, name);
}

}  // namespace
