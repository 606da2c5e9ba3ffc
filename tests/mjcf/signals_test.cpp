// Signal bindings: every OpenPLX input and output gets one binding; what a binding names exists in the
// MuJoCo model that loads the emitted MJCF, and reading or writing it there does what the signal means.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <list>
#include <map>
#include <regex>
#include <set>

#include "contract/signal_binding.h"
#include "frontend/syntax/quoted.h"
#include "runtime/signal_conversions.h"
#include "tests/support/mjcf_fixture.h"

namespace {

namespace fe = openplx::frontend;
namespace mj = openplx::mjcf;
namespace fs = std::filesystem;
using Q = mj::Quantity;

class Signals : public openplx::testing::MjcfTest {
 protected:
  static int id(const mjModel* m, mj::MjObject object, const std::string& name) {
    return mj_name2id(m, openplx::runtime::object_type(object), name.c_str());
  }
};

TEST_F(Signals, EveryCorpusSignalHasOneBindingWhoseElementsExistInMuJoCo) {
  const fs::path agx = fs::path(OPENPLX_CORPUS_DIR) / "agxunity";
  size_t mapped = 0;
  for (const auto& entry : fs::directory_iterator(agx)) {
    const std::string name = entry.path().stem().string();
    if (entry.path().extension() != ".openplx" || name == "extended_pendulum_from_agx") continue;
    SCOPED_TRACE(name);
    std::vector<std::string> bundles;
    if (name == "use_test_bundle") bundles.push_back((agx / "TestBundle").string());
    sink_.clear();
    ASSERT_TRUE(load_file(entry.path().string(), name == "simple_lidar" ? "ValidLidar" : nullptr, bundles));
    const std::string path = emit(name);
    ASSERT_EQ(emitted_.signals.size(), system_.signals.size());
    mjModel* m = load_mujoco(path);
    ASSERT_NE(m, nullptr);
    for (const mj::SignalBinding& b : emitted_.signals) {
      SCOPED_TRACE(b.path);
      if (b.quantity == Q::None) {
        EXPECT_FALSE(b.reason.empty());
        continue;
      }
      ++mapped;
      for (const std::string& element : b.names) EXPECT_GE(id(m, b.object, element), 0) << element;
      if (!b.sensor.empty()) {
        EXPECT_GE(mj_name2id(m, mjOBJ_SENSOR, b.sensor.c_str()), 0);
      }
      if (!b.input && b.enabled && b.quantity != Q::Ctrl && b.quantity != Q::ForceRange &&
          b.quantity != Q::Constant && b.quantity != Q::EqualityActive && b.quantity != Q::MotorForceRange &&
          b.quantity != Q::MotorForce && b.quantity != Q::InteractionEnabled) {
        EXPECT_FALSE(b.sensor.empty()) << "an enabled output with a MuJoCo sensor kind has no sensor";
      }
    }
    mj_deleteModel(m);
  }
  EXPECT_GT(mapped, 100u);
  accept_all_diags();
}

// torque_range: a velocity motor's inputs are its control and its effort band. In the MJCF alone the motor is
// its stand-in: b * target pushed by the actuator and the damper b on the joint (b = I / h), with the effort
// band kept in the actuator's force range, not limited (it would clamp b * target); the runtime's row is what
// the band bounds (owned_rows_test, hard_rows_test).
TEST_F(Signals, TorqueRangeInputBoundsTheMotorTorque) {
  ASSERT_TRUE(load_corpus("torque_range.openplx")) << all_diags();
  const std::string path = emit("torque_range");
  accept_all_diags();
  const mj::SignalBinding& speed = binding("pendulum.motor.target_angular_velocity_input");
  EXPECT_EQ(speed.quantity, Q::Ctrl);
  EXPECT_EQ(speed.object, mj::MjObject::Actuator);
  EXPECT_EQ(speed.initial, 1.0);  // target_speed: 1
  EXPECT_EQ(speed.unit, "rad/s");
  EXPECT_TRUE(speed.runtime);  // exact only with the runtime's row
  const mj::SignalBinding& range = binding("pendulum.motor.torque_range_input");
  EXPECT_EQ(range.quantity, Q::ForceRange);
  EXPECT_EQ(range.object, mj::MjObject::Actuator);
  EXPECT_EQ(range.value, mj::SignalValue::Vec2);
  EXPECT_TRUE(range.runtime);
  const mj::SignalBinding& torque = binding("pendulum.motor.torque_output");
  EXPECT_EQ(torque.quantity, Q::MotorForce);
  EXPECT_EQ(torque.object, mj::MjObject::Tendon);
  EXPECT_EQ(torque.names, range.names);  // the tendon and its stand-in share the motor's name

  mjModel* m = load_mujoco(path);
  ASSERT_NE(m, nullptr);
  mjData* d = mj_makeData(m);
  const int a = id(m, mj::MjObject::Actuator, speed.names[0]);
  const int tendon = id(m, mj::MjObject::Tendon, torque.names[0]);
  const int dof = m->jnt_dofadr[m->actuator_trnid[2 * a]];
  EXPECT_EQ(m->tendon_frictionloss[tendon], 0);  // no row in the MJCF alone
  EXPECT_FALSE(m->actuator_forcelimited[a]);
  EXPECT_GT(m->actuator_forcerange[2 * a + 1], m->actuator_forcerange[2 * a]);  // the band, for the runtime
  const double b = m->actuator_gainprm[a * mjNGAIN];
  EXPECT_GT(b, 0);
  EXPECT_EQ(m->dof_damping[dof], b);
  d->ctrl[a] = speed.initial;
  mj_step(m, d);
  // The stand-in's force on the joint is b (target - v): the actuator's b * target and the damper's -b v.
  EXPECT_NEAR(d->actuator_force[a], b * speed.initial, 1e-9 * b);
  for (int k = 0; k < 500; ++k) mj_step(m, d);
  // The 10 kg rod hangs 0.3 pi off vertical: holding it takes m g (L/2) sin(0.3 pi) = 39.7 N m, which the
  // damper carries at a speed 39.7 / b short of the target.
  EXPECT_NEAR(d->qvel[dof], 1.0, 2 * 39.7 / b);
  mj_deleteData(d);
  mj_deleteModel(m);
}

// A mate's force output reads the force connectors[0]'s side exerts on connectors[1]'s: a 2 kg body hanging
// at rest from a world connector (connectors[0] = the world) is held up by m g = 19.62 N.
TEST_F(Signals, MateForceOutputHoldsAHangingBodyUp) {
  for (const bool body_first : {false, true}) {
    SCOPED_TRACE(body_first ? "body holds connectors[0]" : "body holds connectors[1]");
    const std::string connectors = body_first ? "[ball.top, base]" : "[base, ball.top]";
    ASSERT_TRUE(
        load("Ball is Physics3D.Bodies.RigidBody:\n"
             "    inertia.mass: 2\n"
             "    geometry is Physics3D.Geometries.Sphere:\n"
             "        radius: 0.1\n"
             "    top is Physics3D.Interactions.MateConnector:\n"
             "        position.z: 0.5\n"
             "        main_axis: Math.Vec3.Y_AXIS()\n"
             "        normal: Math.Vec3.Z_AXIS()\n"
             "Scene is Physics3D.System:\n"
             "    base is Physics3D.Interactions.MateConnector:\n"
             "        main_axis: Math.Vec3.Y_AXIS()\n"
             "        normal: Math.Vec3.Z_AXIS()\n"
             "    ball is Ball\n"
             "    hinge is Physics3D.Interactions.Hinge:\n"
             "        connectors: " +
             connectors + "\n        force_output.enabled: true\n"))
        << all_diags();
    const std::string path = emit(body_first ? "force0" : "force1");
    accept_all_diags();
    const mj::SignalBinding& force = binding("hinge.force_output");
    ASSERT_EQ(force.quantity, Q::MateForce);
    EXPECT_EQ(force.sign, body_first ? -1.0 : 1.0);
    mjModel* m = load_mujoco(path);
    ASSERT_NE(m, nullptr);
    mjData* d = mj_makeData(m);
    mj_forward(m, d);
    const int site = id(m, force.object, force.names[0]);
    const int sensor = mj_name2id(m, mjOBJ_SENSOR, force.sensor.c_str());
    // The sensor is in site axes; turn it into world axes and apply the binding's sign.
    const mjtNum* local = d->sensordata + m->sensor_adr[sensor];
    mjtNum world[3];
    mju_mulMatVec(world, d->site_xmat + 9 * site, local, 3, 3);
    const double g = 9.81;
    // Connectors[0]'s side holds connectors[1]'s: up when the world is connectors[0], down on the world
    // otherwise.
    EXPECT_NEAR(force.sign * world[2], body_first ? -2 * g : 2 * g, 1e-9);
    EXPECT_NEAR(world[0], 0, 1e-9);
    mj_deleteData(d);
    mj_deleteModel(m);
  }
}

// is_dynamic: false bodies are mocap bodies: their velocity inputs are kinematic, and what hangs from them
// follows when the runtime moves them.
TEST_F(Signals, KinematicBodyIsMocapAndCarriesItsChildren) {
  ASSERT_TRUE(
      load("Cart is Physics3D.Bodies.RigidBody:\n"
           "    is_dynamic: false\n"
           "    geometry is Physics3D.Geometries.Box:\n"
           "        size: {0.4, 0.2, 0.1}\n"
           "    pivot is Physics3D.Interactions.MateConnector:\n"
           "        main_axis: Math.Vec3.Y_AXIS()\n"
           "        normal: Math.Vec3.Z_AXIS()\n"
           "Rod is Physics3D.Bodies.RigidBody:\n"
           "    inertia.mass: 1\n"
           "    geometry is Physics3D.Geometries.Box:\n"
           "        size: {0.05, 0.05, 1}\n"
           "    top is Physics3D.Interactions.MateConnector:\n"
           "        position.z: 0.5\n"
           "        main_axis: Math.Vec3.Y_AXIS()\n"
           "        normal: Math.Vec3.Z_AXIS()\n"
           "Scene is Physics3D.System:\n"
           "    cart is Cart\n"
           "    rod is Rod\n"
           "    hinge is Physics3D.Interactions.Hinge:\n"
           "        connectors: [cart.pivot, rod.top]\n"))
      << all_diags();
  const std::string path = emit("cart");
  accept_all_diags();
  EXPECT_NE(xml_.find("<body name=\"cart\" pos=\"0 0 0\" quat=\"1 0 0 0\" mocap=\"true\">"),
            std::string::npos)
      << xml_;
  const mj::SignalBinding& v = binding("cart.linear_velocity_world_input");
  EXPECT_EQ(v.quantity, Q::KinematicLinearVelocity);
  EXPECT_EQ(v.names, std::vector<std::string>{"cart"});
  EXPECT_EQ(binding("rod.linear_velocity_world_input").quantity, Q::None);  // it moves through its hinge
  mjModel* m = load_mujoco(path);
  ASSERT_NE(m, nullptr);
  mjData* d = mj_makeData(m);
  const int cart = id(m, v.object, "cart");
  const int rod = mj_name2id(m, mjOBJ_BODY, "rod");
  ASSERT_GE(m->body_mocapid[cart], 0);
  d->mocap_pos[3 * m->body_mocapid[cart]] = 0.3;
  mj_forward(m, d);
  EXPECT_NEAR(d->xpos[3 * rod], 0.3, 1e-12);
  EXPECT_NEAR(d->xpos[3 * rod + 2], -0.5, 1e-12);
  mj_deleteData(d);
  mj_deleteModel(m);
}

// LinearSpringTest: the spring is its own actuator: its target input is the control (starting at its rest,
// in the initial keyframe too), its force output the actuator's force, clamped to its effort limits.
TEST_F(Signals, SpringBindingsCarryRestAndStiffness) {
  ASSERT_TRUE(load_corpus("LinearSpringTest.openplx")) << all_diags();
  const std::string path = emit("spring");
  accept_all_diags();
  const mj::SignalBinding* rest = nullptr;
  const mj::SignalBinding* force = nullptr;
  for (const mj::SignalBinding& b : emitted_.signals) {
    if (b.path.ends_with("target_position_input")) rest = &b;
    if (b.path.ends_with("external_spring.force_output")) force = &b;
  }
  ASSERT_TRUE(rest && force);
  EXPECT_EQ(rest->quantity, Q::Ctrl);
  EXPECT_EQ(force->quantity, Q::ActuatorForce);
  EXPECT_EQ(rest->names, force->names);
  mjModel* m = load_mujoco(path);
  ASSERT_NE(m, nullptr);
  const int actuator = id(m, rest->object, rest->names[0]);
  ASSERT_GE(actuator, 0);
  const int key = mj_name2id(m, mjOBJ_KEY, "initial");
  ASSERT_GE(key, 0);
  EXPECT_DOUBLE_EQ(m->key_ctrl[key * m->nu + actuator], rest->initial);
  EXPECT_DOUBLE_EQ(m->actuator_gainprm[actuator * mjNGAIN], -m->actuator_biasprm[actuator * mjNBIAS + 1]);
  EXPECT_EQ(m->actuator_forcerange[2 * actuator], -200);
  EXPECT_EQ(m->actuator_forcerange[2 * actuator + 1], 200);
  mj_deleteModel(m);
}

TEST_F(Signals, ManifestIsDeterministicAndListsEveryBinding) {
  ASSERT_TRUE(load_corpus("signal_test.openplx")) << all_diags();
  emit("a");
  const std::string first = emitted_.manifest_json;
  emit("b");
  accept_all_diags();
  EXPECT_EQ(first, emitted_.manifest_json);
  size_t entries = 0;
  for (size_t at = first.find("{\"path\": "); at != std::string::npos; at = first.find("{\"path\": ", at + 1))
    ++entries;
  EXPECT_EQ(entries, emitted_.signals.size());
  EXPECT_NE(
      first.find("{\"path\": \"motorSpeedInput\", \"direction\": \"input\", \"type\": "
                 "\"Physics.Signals.AngularVelocity1DInput\", \"value\": \"real\", \"unit\": \"rad/s\", "
                 "\"enabled\": true, \"quantity\": \"ctrl\", \"object\": \"actuator\", \"names\": "
                 "[\"motor\"], \"sensor\": \"\", \"sign\": 1, \"initial\": 0, \"initial_vector\": [], "
                 "\"low\": 0, \"high\": 0, "
                 "\"reason\": \"\", \"runtime\": true}"),
      std::string::npos)
      << first;
}

TEST(SignalKind, UnitsAndValueKindsFollowTheModelName) {
  EXPECT_EQ(mj::signal_kind("Physics.Signals.AngleOutput").unit, "rad");
  EXPECT_EQ(mj::signal_kind("Physics.Signals.TorqueRangeInput").value, mj::SignalValue::Vec2);
  EXPECT_EQ(mj::signal_kind("Physics3D.Signals.LinearVelocity3DOutput").unit, "m/s");
  EXPECT_EQ(mj::signal_kind("Physics.Signals.EnableInteractionInput").value, mj::SignalValue::Bool);
  EXPECT_EQ(mj::signal_stem("Physics3D.Signals.MateConnector.AngularVelocity3DOutput"), "AngularVelocity3D");
}

// The emitter classifies a signal's model once per model name held: for every Input and Output model the
// bundles declare, the class is signal_kind's and signal_stem's, found again for the same name held, and
// alike for an equal name held elsewhere.
TEST(SignalKind, ClassesAreTheKindAndStemOfEveryBundleSignalModel) {
  const fs::path bundles = fs::path(OPENPLX_SAMPLES_DIR).parent_path() / "bundles";
  const std::regex declaration(R"(^([A-Za-z0-9]+(Input|Output)) is )");
  std::set<std::string> types;
  for (const fs::directory_entry& file : fs::recursive_directory_iterator(bundles)) {
    if (file.path().extension() != ".openplx") continue;
    std::string space;  // a model's namespace is its folder below bundles/
    for (const fs::path& part : fs::relative(file.path().parent_path(), bundles))
      space += part.string() + ".";
    std::ifstream in(file.path());
    std::smatch match;
    for (std::string line; std::getline(in, line);) {
      if (std::regex_search(line, match, declaration)) types.insert(space + match[1].str());
    }
  }
  ASSERT_GE(types.size(), 60u);  // Physics, Physics3D, DriveTrain, Robotics, Control, Sensors signals
  EXPECT_TRUE(types.count("Physics3D.Signals.MateConnector.AngularVelocity3DOutput"));
  mj::SignalClasses classes;
  std::list<std::string> elsewhere;  // names held apart from `types`, for as long as `classes` is used
  for (const std::string& type : types) {
    const mj::SignalClasses::Class& c = classes.of(type);
    EXPECT_EQ(c.kind.value, mj::signal_kind(type).value) << type;
    EXPECT_EQ(c.kind.unit, mj::signal_kind(type).unit) << type;
    EXPECT_EQ(c.stem, mj::signal_stem(type)) << type;
    EXPECT_FALSE(c.stem.ends_with("Input") || c.stem.ends_with("Output") || c.stem.empty()) << type;
    EXPECT_EQ(&classes.of(type), &c) << type;
    const mj::SignalClasses::Class& alike = classes.of(elsewhere.emplace_back(type));
    EXPECT_EQ(alike.kind.value, c.kind.value) << type;
    EXPECT_EQ(alike.kind.unit, c.kind.unit) << type;
    EXPECT_EQ(alike.stem, c.stem) << type;
    EXPECT_GE(alike.stem.data(), elsewhere.back().data()) << type;  // in the name it was asked for
  }
  EXPECT_EQ(classes.size(), 2 * types.size());
}

// The manifest's strings are quoted as frontend::quoted writes them (escapes included), its numbers are the
// shortest round trip, and numbers JSON cannot hold are strings.
TEST(Manifest, StringsAreEscapedAndNumbersShortest) {
  mj::SignalBinding b;
  b.path = "odd\"name\\with\nbreaks\tand\rreturns";
  b.type = "Physics.Signals.AngleOutput";
  b.reason = "plain";
  b.sign = -1;
  b.initial = 0.1;
  b.initial_vector = {100000, -0.0, 1.5};
  b.low = -INFINITY;
  b.high = NAN;
  const std::string json = mj::manifest_json("model", "p/", {b}, {});
  EXPECT_NE(json.find("{\"path\": " + fe::quoted(b.path) + ", \"direction\": \"output\""), std::string::npos)
      << json;
  EXPECT_NE(json.find("\"sign\": -1, \"initial\": 0.1, \"initial_vector\": [1e+05, 0, 1.5], \"low\": "
                      "\"-inf\", \"high\": \"nan\", \"reason\": \"plain\""),
            std::string::npos)
      << json;
}

// The manifest scans strings eight bytes at a time for what to escape: each escaped character, and other
// control characters and UTF-8, at every position of a word and of the tail, is written as fe::quoted writes
// it.
TEST(Manifest, EscapesAtEveryPositionAsQuotedDoes) {
  for (const char special : {'"', '\\', '\n', '\t', '\r', '\x01', '\x1f', ' ', '\x7f', '\xc3'}) {
    for (size_t size = 1; size <= 25; ++size) {
      for (size_t at = 0; at < size; ++at) {
        mj::SignalBinding b;
        b.path = std::string(size, 'a');
        b.path[at] = special;
        b.reason = b.path.substr(at);
        const std::string json = mj::manifest_json("model", "p/", {b}, {});
        EXPECT_NE(json.find("{\"path\": " + fe::quoted(b.path) + ", "), std::string::npos) << json;
        EXPECT_NE(json.find("\"reason\": " + fe::quoted(b.reason) + ", "), std::string::npos) << json;
      }
    }
  }
}

// The converter writes the manifest in pieces: they join into exactly the text manifest_json gives, and a
// large manifest (here about 2 MB) comes in many pieces, none much over 64 KiB.
TEST(Manifest, PiecesJoinIntoTheWholeText) {
  std::vector<mj::SignalBinding> bindings(8000);
  for (size_t i = 0; i < bindings.size(); ++i) {
    bindings[i].path = "body" + std::to_string(i) + ".position_output";
    bindings[i].type = "Physics3D.Signals.Position3DOutput";
    bindings[i].names = {"body" + std::to_string(i)};
  }
  mj::RuntimeLaw law;
  law.path = "engine";
  law.curve_x = {0, 1};
  std::string joined;
  size_t pieces = 0;
  size_t largest = 0;
  mj::write_manifest_json("model", "p/", bindings, {law}, [&](std::string_view piece) {
    joined += piece;
    ++pieces;
    largest = std::max(largest, piece.size());
  });
  EXPECT_EQ(joined, mj::manifest_json("model", "p/", bindings, {law}));
  EXPECT_GT(pieces, joined.size() / (128u << 10));
  EXPECT_LT(largest, (64u << 10) + 4096);
}

}  // namespace
