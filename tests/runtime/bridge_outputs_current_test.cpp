// A bridge's outputs after the user's own mj_step are the state at the new time. Before, body, connector,
// tendon and sensor outputs read through a bridge were one step old (mj_step computes xpos, cvel and the
// sensors before it integrates), while joint outputs were current.
// - Exactness: after every step of vehicle_circle (contacts, suspensions, steering, drive rows), every
//   output that describes the state equals the same output read from a copy of the data brought current by
//   mj_forward, to 1e-12.
// - Against a Simulation of the same model: every output of the samples, read after every step of a plain
//   mj_step loop, equals the Simulation's to 1e-12 (they are equal bit for bit: reading an output leaves the
//   user's trajectory untouched, see bring_current.cpp). drivetrain_machine is not among them: its two paths
//   part at round-off (2e-15 relative in a hinge force at 0.04 s), from where its engine and clutch laws run.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "openplx/runtime/signal_bridge.h"
#include "openplx/runtime/simulation.h"
#include "tests/support/converted_model.h"
#include "tests/support/scratch_dir.h"

namespace {

namespace rt = openplx::runtime;
namespace fs = std::filesystem;

// The numbers an output carries, by its kind.
std::vector<double> values(const rt::Output& out) {
  switch (out.info().value) {
    case rt::ValueType::Vec2: {
      const std::array<double, 2> v = out.vec2_values();
      return {v[0], v[1]};
    }
    case rt::ValueType::Vec3: {
      const std::array<double, 3> v = out.vec3_values();
      return {v[0], v[1], v[2]};
    }
    case rt::ValueType::Vector:
      return out.vector_values();
    case rt::ValueType::Bool:
      return {out.boolean() ? 1.0 : 0.0};
    default:
      return {out.real()};
  }
}

void set(rt::Input in, double value) {
  if (in.info().value == rt::ValueType::Bool)
    in.set(value != 0);
  else
    in.set(value);
}

// A sample converted to MJCF and loaded as a user would (tests/support/converted_model.h).
struct Loaded {
  openplx::testing::ScratchDir dir;
  std::string model;
  openplx::testing::ConvertedModel converted;
  mjModel* m;
  mjData* d;
  explicit Loaded(const std::string& sample)
      : model(std::string(OPENPLX_SAMPLES_DIR) + "/" + sample + ".openplx"),
        converted(dir.path(), model),
        m(converted.m),
        d(converted.d) {}
  std::string manifest() const { return converted.manifest.string(); }
};

// Outputs whose value is the state at an instant (not a force or an acceleration the step kept, nor an
// input's target the bridge holds).
bool describes_state(const rt::SignalInfo& info) {
  const bool kinematic = info.unit == "m" || info.unit == "rad" || info.unit == "m/s" || info.unit == "rad/s";
  return info.mapped && kinematic && info.name.find("target") == std::string::npos;
}

TEST(BridgeOutputs, AreTheStateAtTheNewTimeAfterEveryStepOfVehicleCircle) {
  Loaded a("vehicle_circle");
  ASSERT_NE(a.m, nullptr);
  mjData* reference = mj_makeData(a.m);
  {
    rt::SignalBridge bridge = rt::SignalBridge::attach(a.manifest(), a.m, a.d);
    bridge.input("steering").set(0.3);
    bridge.input("speed").set(8.0);
    std::vector<std::string> names;
    for (const rt::SignalInfo& info : bridge.outputs())
      if (describes_state(info)) names.push_back(info.name);
    ASSERT_GT(names.size(), 10u);
    double lag = 0;  // how far MuJoCo's own xpos after mj_step is from the state: what was read before
    for (int k = 0; k < 1500; ++k) {
      bridge.before_step();
      mj_step(a.m, a.d);
      bridge.after_step();
      mj_copyData(reference, a.m, a.d);
      mj_forward(a.m, reference);
      for (int i = 0; i < 3 * a.m->nbody; ++i)
        lag = std::max(lag, std::abs(a.d->xpos[i] - reference->xpos[i]));
      // The reference: a second bridge on the data mj_forward brought current (read without a step).
      rt::SignalBridge current = rt::SignalBridge::attach(a.manifest(), a.m, reference);
      for (const std::string& name : names) {
        const std::vector<double> mine = values(bridge.output(name)), want = values(current.output(name));
        for (size_t i = 0; i < mine.size(); ++i)
          ASSERT_NEAR(mine[i], want[i], 1e-12) << "`" << name << "`[" << i << "] at t = " << a.d->time;
      }
    }
    EXPECT_GT(lag, 1e-3) << "the test would not see one-step-old body positions";
  }
  mj_deleteData(reference);
}

TEST(BridgeOutputs, EqualASimulationsAfterEveryStep) {
  const std::vector<std::pair<std::string, std::map<std::string, double>>> cases = {
      {"cart_pole", {{"push", 5.0}}},
      {"two_joint_arm", {{"shoulder_torque", 2.0}, {"elbow_torque", -1.0}}},
      {"four_bar", {}},
      {"vehicle_circle", {{"steering", 0.3}, {"speed", 8.0}}},
  };
  for (const auto& [sample, inputs] : cases) {
    Loaded a(sample);
    ASSERT_NE(a.m, nullptr);
    rt::SignalBridge bridge = rt::SignalBridge::attach(a.manifest(), a.m, a.d);
    rt::Simulation sim = rt::Simulation::load(a.model);
    for (const auto& [name, value] : inputs) {
      set(bridge.input(name), value);
      set(sim.input(name), value);
    }
    std::vector<std::pair<rt::Output, rt::Output>> outputs;
    for (const rt::SignalInfo& info : bridge.outputs())
      if (info.mapped) outputs.emplace_back(bridge.output(info.name), sim.output(info.name));
    for (int k = 0; k < 1500; ++k) {  // 3 s: vehicle_circle drives most of its circle
      bridge.before_step();
      mj_step(a.m, a.d);
      bridge.after_step();
      sim.step();
      for (const auto& [mine, theirs] : outputs) {
        const std::vector<double> x = values(mine), y = values(theirs);
        ASSERT_EQ(x.size(), y.size());
        for (size_t i = 0; i < x.size(); ++i)
          ASSERT_NEAR(x[i], y[i], 1e-12)
              << sample << ": `" << mine.info().name << "`[" << i << "] at t = " << a.d->time;
      }
    }
  }
}

}  // namespace
