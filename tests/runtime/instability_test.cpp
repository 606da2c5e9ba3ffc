// Never silently wrong, the runtime's side: a step MuJoCo had to reset is a SimulationError that
// names the joint and body, the values and a hint (or a warning under OnInstability::Continue); MuJoCo's
// messages never become MUJOCO_LOG.TXT; inputs beyond the model's range are clamped and said once; hostile
// spans, gears, paths and time steps are errors with a message.
#include <gtest/gtest.h>
#include <unistd.h>

#include <climits>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>

#include "contract/signal_binding.h"
#include "openplx/runtime/simulation.h"
#include "tests/support/light_rod.h"
#include "tests/support/scratch_dir.h"

namespace {

namespace rt = openplx::runtime;
namespace fs = std::filesystem;

using openplx::testing::ScratchDir;

// A very light rod on a hinge, driven by a torque motor: a torque of 1e8 N m gives it an angular
// acceleration near 3e11 rad/s^2, beyond what MuJoCo 2.2.2 accepts (1e10): bad QACC on the first step.
const std::string kLightRod =
    std::string(openplx::testing::kLightRodPendulum) + openplx::testing::kLightRodMotor;

std::string write(const ScratchDir& dir, const std::string& name, const std::string& text) {
  const fs::path path = dir / name;
  std::ofstream(path) << text;
  return path.string();
}

const std::string kDrivetrain = std::string(OPENPLX_SAMPLES_DIR) + "/drivetrain_machine.openplx";

TEST(Instability, StepThrowsNamingTheJointBodyValuesAndAHint) {
  const ScratchDir dir;
  rt::Simulation sim = rt::Simulation::load(write(dir, "rod.openplx", kLightRod));
  sim.advance(0.01);
  sim.input("motor.torque_input").set(1e8);
  try {
    sim.step();
    FAIL() << "the step blew up without a word";
  } catch (const rt::SimulationError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("rod.openplx: error: at t = 0.01 s"), std::string::npos) << what;
    EXPECT_NE(what.find("acceleration (qacc)"), std::string::npos) << what;
    EXPECT_NE(what.find("hinge joint `hinge` in body `rod`"), std::string::npos) << what;
    EXPECT_NE(what.find("qacc "), std::string::npos) << what;  // the value that blew up
    EXPECT_NE(what.find("actuator `motor` (control 1e+08)"), std::string::npos) << what;
    EXPECT_NE(what.find("hint:"), std::string::npos) << what;
    EXPECT_NEAR(e.time(), 0.01, 1e-12);
    EXPECT_EQ(e.warning(), mjWARN_BADQACC);
  }
}

// The hung client: "step until t = 1" while MuJoCo keeps resetting time to 0. Now it ends.
TEST(Instability, StepUntilOneSecondEnds) {
  const ScratchDir dir;
  rt::Simulation sim = rt::Simulation::load(write(dir, "rod.openplx", kLightRod));
  rt::Input torque = sim.input("motor.torque_input");
  long steps = 0;
  bool stopped = false;
  while (sim.time() < 1 && steps < 10'000) {
    torque.set(sim.time() > 0.2 ? 1e8 : 0.0);
    try {
      sim.step();
    } catch (const rt::SimulationError&) {
      stopped = true;
      break;
    }
    ++steps;
  }
  EXPECT_TRUE(stopped);
  EXPECT_LT(steps, 200);
}

TEST(Instability, ContinueKeepsMuJoCosResetAndSaysSo) {
  const ScratchDir dir;
  rt::LoadOptions options;
  options.on_instability = rt::OnInstability::Continue;
  rt::Simulation sim = rt::Simulation::load(write(dir, "rod.openplx", kLightRod), options);
  sim.advance(0.1);
  const size_t before = sim.warnings().size();
  sim.input("motor.torque_input").set(1e8);
  EXPECT_NO_THROW(sim.step());
  EXPECT_LT(sim.time(), 0.05);  // MuJoCo's reset stood
  ASSERT_GT(sim.warnings().size(), before);
  EXPECT_NE(sim.warnings().back().find("rod.openplx: warning: at t = 0.1 s"), std::string::npos)
      << sim.warnings().back();
  // The opt-out can be switched back. (MuJoCo's reset zeroed the controls too.)
  EXPECT_EQ(sim.data()->ctrl[0], 0.0);
  sim.set_on_instability(rt::OnInstability::Throw);
  sim.input("motor.torque_input").set(1e8);
  EXPECT_THROW(sim.step(), rt::SimulationError);
}

// MuJoCo 2.2.2 writes MUJOCO_LOG.TXT into the working folder for every warning unless a handler is set.
TEST(Instability, NoMujocoLogInTheWorkingFolder) {
  const ScratchDir dir;
  const std::string model = write(dir, "rod.openplx", kLightRod);
  const fs::path work = dir / "work";
  fs::create_directory(work);
  const fs::path was = fs::current_path();
  fs::current_path(work);
  {
    rt::LoadOptions options;
    options.on_instability = rt::OnInstability::Continue;
    rt::Simulation sim = rt::Simulation::load(model, options);
    sim.input("motor.torque_input").set(1e8);
    for (int k = 0; k < 5; ++k) sim.step();
    // A MuJoCo model stepped outside the runtime, in the same process: MuJoCo's warning goes to the
    // runtime's handler too (stderr), not to a log file.
    mjModel* m = mj_copyModel(nullptr, sim.model());
    mjData* d = mj_makeData(m);
    d->ctrl[0] = 1e8;
    mj_step(m, d);
    EXPECT_GT(d->warning[mjWARN_BADQACC].number, 0);
    mj_deleteData(d);
    mj_deleteModel(m);
    EXPECT_THROW(rt::Simulation::load(model).advance(std::nan("")), std::invalid_argument);
  }
  fs::current_path(was);
  EXPECT_FALSE(fs::exists(work / "MUJOCO_LOG.TXT"));
  EXPECT_TRUE(fs::is_empty(work));
}

TEST(InputRange, FractionsAndControlsAreClampedAndSaidOnce) {
  rt::Simulation sim = rt::Simulation::load(kDrivetrain);
  const size_t before = sim.warnings().size();
  rt::Input throttle = sim.input("throttle");
  throttle.set(5.0);  // an engine's throttle is a fraction: [0, 1]
  EXPECT_EQ(sim.data()->ctrl[mj_name2id(sim.model(), mjOBJ_ACTUATOR, "power.engine")], 1.0);
  ASSERT_EQ(sim.warnings().size(), before + 1);
  EXPECT_NE(sim.warnings().back().find("input `throttle` got 5, outside its range [0, 1]: clamped to 1"),
            std::string::npos)
      << sim.warnings().back();
  throttle.set(-3.0);  // said once
  EXPECT_EQ(sim.warnings().size(), before + 1);
  throttle.set(0.5);
  EXPECT_EQ(sim.data()->ctrl[mj_name2id(sim.model(), mjOBJ_ACTUATOR, "power.engine")], 0.5);
  sim.input("brake_left").set(5.0);  // a brake's engagement fraction
  EXPECT_EQ(sim.warnings().size(), before + 2);
  EXPECT_NE(sim.warnings().back().find("clamped to 1"), std::string::npos);
  // NaN and Inf stay errors.
  EXPECT_THROW(throttle.set(std::nan("")), rt::SignalError);
  EXPECT_THROW(throttle.set(std::numeric_limits<double>::infinity()), rt::SignalError);
  EXPECT_THROW(sim.input("brake_left").set(-std::numeric_limits<double>::infinity()), rt::SignalError);
  sim.advance(0.1);
}

TEST(HostileInputs, HugeGearsAreSignalErrors) {
  rt::Simulation sim = rt::Simulation::load(kDrivetrain);
  rt::Input gear = sim.input("gear");
  for (double g :
       {2147483648.0, -2147483648.0, 4294967296.0, 1e300, -1e300, double(INT_MIN), double(INT_MAX)})
    EXPECT_THROW(gear.set(g), rt::SignalError) << g;
  gear.set(1.0);
  sim.advance(0.05);
  EXPECT_EQ(sim.output("power.gear_box.gear_output").real(), 1.0);
}

// -INT_MIN does not fit an int: the gear was negated before it was compared (a crash in the emitter for
// `initial_gear: -2147483648`).
TEST(HostileInputs, GearboxRatioTakesEveryInt) {
  const std::vector<double> forward = {3.5, 2.0}, reverse = {4.0};
  for (int gear : {INT_MIN, INT_MIN + 1, INT_MAX, 3, -2})
    EXPECT_FALSE(openplx::mjcf::gearbox_ratio(forward, reverse, true, gear).valid) << gear;
  EXPECT_EQ(openplx::mjcf::gearbox_ratio(forward, reverse, true, -1).ratio, -4.0);
  EXPECT_EQ(openplx::mjcf::gearbox_ratio(forward, reverse, true, 2).ratio, 2.0);
  EXPECT_EQ(openplx::mjcf::gearbox_ratio(forward, reverse, true, 0).ratio, 0.0);
}

TEST(HostileInputs, AdvanceTakesOnlySaneSpans) {
  rt::Simulation sim = rt::Simulation::load(std::string(OPENPLX_SAMPLES_DIR) + "/pendulum.openplx");
  for (double span : {std::nan(""), std::numeric_limits<double>::infinity(), -1.0, 1e300, 1e7}) {
    try {
      sim.advance(span);
      ADD_FAILURE() << span << " was taken";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("advance"), std::string::npos);
    }
  }
  EXPECT_EQ(sim.time(), 0.0);
  sim.advance(0.01);
  EXPECT_NEAR(sim.time(), 0.01, 1e-12);
}

TEST(HostileInputs, LoadRefusesEmptyPathsMissingBundlesAndWildTimeSteps) {
  EXPECT_THROW(rt::Simulation::load(""), rt::LoadError);
  const std::string pendulum = std::string(OPENPLX_SAMPLES_DIR) + "/pendulum.openplx";
  rt::LoadOptions options;
  options.bundle_paths = {"/no/such/bundle/folder"};
  try {
    rt::Simulation::load(pendulum, options);
    ADD_FAILURE() << "a missing bundle folder was accepted";
  } catch (const rt::LoadError& e) {
    EXPECT_NE(std::string(e.what()).find("/no/such/bundle/folder: error: bundle folder not found"),
              std::string::npos)
        << e.what();
  }
  for (double h : {1e308, 2.0, 1e-7, 1e-320, 0.0, -0.002, std::nan("")}) {
    rt::LoadOptions step;
    step.timestep = h;
    EXPECT_THROW(rt::Simulation::load(pendulum, step), rt::LoadError) << h;
  }
}

}  // namespace
