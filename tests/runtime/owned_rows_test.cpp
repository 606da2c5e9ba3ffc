// Acceptance tests for the runtime's owned constraint rows (/work/shared/design/owned-rows.md): velocity
// motors, springs, elastic tyre DOFs, ranges and gears solved as AGX solves them (SPOOK rows with force
// bounds), the runtime writing MuJoCo's row references and softness from a process-wide mjcb_control, so a
// plain mj_step loop around a SignalBridge gets them as Simulation does. A velocity motor is a row on its
// joint's own DOF, with no reference joint: nv is the number of real joints.
//
// Why: the reference-joint design misses a 7-link arm's one-step target by 23 % and lets it sag 28 mm
// (dt 0.002) to 0.28 m (dt 0.02) in 5 s; the prototype's rows hit it to 5e-9 and hold it to 4e-11 m.
// These are the figures the work must reach (most fail before it is done; a single link's effort limits
// already hold):
//   - the 7-link arm (tests/support/arm_chain.h), dt 0.002 and 0.02, through Simulation and through a
//     SignalBridge in a plain mj_step loop: 0.5 rad/s on every joint after one step and on every step for
//     0.5 s (1e-6), held horizontal for 5 s (1e-6 rad), nv == 7;
//   - chains of 1..10 links at dt 0.0005, 0.002, 0.02: held for 1 s (1e-6 rad), one step to the target;
//     a motor 1 % weaker than the weight it holds pushes exactly its limit, 1 % stronger holds;
//   - 1..4 threads each stepping its own model through its own bridge, and two mjData of one mjModel in two
//     threads, each moving exactly as alone; a control callback the program set is still called once per
//     step;
//   - LinearSpringTest rests (AGXUnity's 1 mm, 1 mm/s) through a bridge as through Simulation;
//   - a range holds a 5e4 N m motor at its end (1e-3 rad); a gear's output turns at input / ratio after one
//     step (1e-6); Ackermann steering of elastic wheels reaches its input (1e-6) at dt 0.0005..0.02 and a car
//     on elastic wheels drives 5 s at dt 0.02, with no SimulationError.
// Each test owns its ScratchDir, so tests run in parallel; the figures measured are printed ("measured:").
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <latch>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "openplx/runtime/signal_bridge.h"
#include "openplx/runtime/simulation.h"
#include "tests/support/arm_chain.h"
#include "tests/support/owned_rows_models.h"
#include "tests/support/scratch_dir.h"
#include "tools/cli/cli.h"

namespace {

namespace rt = openplx::runtime;
namespace fs = std::filesystem;
using openplx::testing::arm_chain;
using openplx::testing::arm_number;
using openplx::testing::ArmChain;
using openplx::testing::Car;
using openplx::testing::car;
using openplx::testing::elastic_steered_car;
using openplx::testing::emit;
using openplx::testing::gear_pair;
using openplx::testing::manifest_of;
using openplx::testing::ScratchDir;
using openplx::testing::write_model;

constexpr double kGravity = 9.81;  // MuJoCo's default, which the converter keeps
// A 1 kg, 0.3 m link about its end: weight m g L / 2, inertia m (L^2 + w^2) / 12 + m (L / 2)^2.
constexpr double kLinkWeightTorque = openplx::testing::kArmLinkMass * kGravity * 0.15;  // 1.4715 N m
constexpr double kLinkInertia = 1.0 * (0.3 * 0.3 + 0.04 * 0.04) / 12 + 1.0 * 0.15 * 0.15;
constexpr double kUnsaturated = 1e6;  // N m: an effort limit no one-step target here comes near

// ---------------------------------------------------------------------------------------------------------
// Converting and loading

// A model loaded by plain MuJoCo from the converter's MJCF, started as a program starts it: from the emitted
// "initial" keyframe when there is one (initial joint positions and velocities, initial controls).
class PlainModel {
 public:
  explicit PlainModel(const fs::path& xml) {
    char error[1000] = "";
    m_ = mj_loadXML(xml.c_str(), nullptr, error, sizeof(error));
    if (!m_) {
      error_ = xml.string() + ": " + error;
      return;
    }
    d_ = new_data();
  }
  ~PlainModel() {
    for (mjData* d : extra_) mj_deleteData(d);
    if (d_) mj_deleteData(d_);
    if (m_) mj_deleteModel(m_);
  }
  PlainModel(const PlainModel&) = delete;
  PlainModel& operator=(const PlainModel&) = delete;

  bool ok() const { return m_ != nullptr; }
  const std::string& error() const { return error_; }
  mjModel* m() const { return m_; }
  mjData* d() const { return d_; }
  // Another mjData of the same mjModel, started the same way; deleted with this object.
  mjData* another_data() { return extra_.emplace_back(new_data()); }

 private:
  mjData* new_data() const {
    mjData* d = mj_makeData(m_);
    const int key = mj_name2id(m_, mjOBJ_KEY, "initial");
    if (key >= 0) mj_resetDataKeyframe(m_, d, key);
    mj_forward(m_, d);
    return d;
  }
  mjModel* m_ = nullptr;
  mjData* d_ = nullptr;
  std::vector<mjData*> extra_;
  std::string error_;
};

int joint_id(const mjModel* m, const std::string& joint) {
  const int id = mj_name2id(m, mjOBJ_JOINT, joint.c_str());
  EXPECT_GE(id, 0) << "no MuJoCo joint named " << joint;
  return id;
}
double joint_qpos(const mjModel* m, const mjData* d, const std::string& joint) {
  const int id = joint_id(m, joint);
  return id < 0 ? NAN : d->qpos[m->jnt_qposadr[id]];
}
double joint_qvel(const mjModel* m, const mjData* d, const std::string& joint) {
  const int id = joint_id(m, joint);
  return id < 0 ? NAN : d->qvel[m->jnt_dofadr[id]];
}

// One model driven by signal names, either way a user drives one: a Simulation, or a SignalBridge attached
// to a model plain MuJoCo loaded, stepped by before_step(); mj_step(m, d); after_step().
class Runner {
 public:
  virtual ~Runner() = default;
  virtual void set(const std::string& input, double value) = 0;
  virtual double output(const std::string& name) = 0;
  virtual void step() = 0;
  virtual const mjModel* model() const = 0;
  virtual const mjData* data() const = 0;

  double qpos(const std::string& joint) const { return joint_qpos(model(), data(), joint); }
  double qvel(const std::string& joint) const { return joint_qvel(model(), data(), joint); }
  double time() const { return data()->time; }
};

class SimulationRunner final : public Runner {
 public:
  explicit SimulationRunner(rt::Simulation sim) : sim_(std::move(sim)) {}
  void set(const std::string& input, double value) override { sim_.input(input).set(value); }
  double output(const std::string& name) override { return sim_.output(name).real(); }
  void step() override { sim_.step(); }
  const mjModel* model() const override { return sim_.model(); }
  const mjData* data() const override { return sim_.data(); }

 private:
  mutable rt::Simulation sim_;  // its data() is not const
};

class BridgeRunner final : public Runner {
 public:
  explicit BridgeRunner(const fs::path& xml) : plain_(xml) {
    if (plain_.ok())
      bridge_.emplace(rt::SignalBridge::attach(manifest_of(xml).string(), plain_.m(), plain_.d()));
  }
  ~BridgeRunner() override { bridge_.reset(); }  // before the model and data it points into
  bool ok() const { return bridge_.has_value(); }
  const std::string& error() const { return plain_.error(); }
  void set(const std::string& input, double value) override { bridge_->input(input).set(value); }
  double output(const std::string& name) override { return bridge_->output(name).real(); }
  void step() override {
    bridge_->before_step();
    mj_step(plain_.m(), plain_.d());
    bridge_->after_step();
  }
  const mjModel* model() const override { return plain_.m(); }
  const mjData* data() const override { return plain_.d(); }

 private:
  PlainModel plain_;
  std::optional<rt::SignalBridge> bridge_;
};

enum class Path { Simulation, Bridge };
const Path kBothPaths[] = {Path::Simulation, Path::Bridge};

std::string name(Path path) {
  return path == Path::Simulation ? "Simulation" : "SignalBridge + mj_step";
}

// `source` (its root `model`, empty: the file's last) at time step h, loaded `path`'s way; null, with the
// failure recorded, when it does not convert, load or attach.
std::unique_ptr<Runner> load(Path path, const ScratchDir& dir, const fs::path& source, double h,
                             const std::string& model = "") {
  try {
    if (path == Path::Simulation) {
      rt::LoadOptions options;
      options.timestep = h;
      if (!model.empty()) options.model = model;
      return std::make_unique<SimulationRunner>(rt::Simulation::load(source.string(), options));
    }
    auto runner = std::make_unique<BridgeRunner>(emit(dir, source, h, model));
    if (!runner->ok()) {
      ADD_FAILURE() << runner->error();
      return nullptr;
    }
    return runner;
  } catch (const std::exception& e) {
    ADD_FAILURE() << "loading " << source << " (" << name(path) << "): " << e.what();
    return nullptr;
  }
}

std::unique_ptr<Runner> load_text(Path path, const ScratchDir& dir, const std::string& text, double h) {
  return load(path, dir, write_model(dir, text), h);
}

// Runs `body`, turning an exception (a SimulationError, a SignalError for a name) into a failure of the case
// at hand, so the other cases still run.
template <typename F>
void guarded(F&& body) {
  try {
    body();
  } catch (const rt::SimulationError& e) {
    ADD_FAILURE() << "SimulationError at t = " << e.time() << " s: " << e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "exception: " << e.what();
  }
}

std::string hinge(int k) {
  return "hinge" + std::to_string(k);
}
std::string speed_input(int k) {
  return "speed" + std::to_string(k);
}

// ---------------------------------------------------------------------------------------------------------
// Arms

// Sets every motor's target to `target`, steps once and returns the largest |joint speed - target|.
double one_step_error(Runner& r, int links, double target) {
  for (int k = 0; k < links; ++k) r.set(speed_input(k), target);
  r.step();
  double worst = 0;
  for (int k = 0; k < links; ++k) worst = std::max(worst, std::abs(r.qvel(hinge(k)) - target));
  return worst;
}

// Holds every motor's target at 0 for `seconds` and returns the largest |angle - its start| over every
// joint and step.
double hold_drift(Runner& r, int links, double seconds, double h) {
  std::vector<double> start(links);
  for (int k = 0; k < links; ++k) {
    r.set(speed_input(k), 0.0);
    start[k] = r.qpos(hinge(k));
    EXPECT_NEAR(start[k], 0.0, 1e-12) << hinge(k) << ": the arm starts straight out, horizontal";
  }
  double worst = 0;
  for (long n = std::lround(seconds / h); n > 0; --n) {
    r.step();
    for (int k = 0; k < links; ++k) worst = std::max(worst, std::abs(r.qpos(hinge(k)) - start[k]));
  }
  return worst;
}

// The prototype's benchmark: 7 links, every motor +-1e6 N m, from rest to 0.5 rad/s on every joint in one
// step. Owned rows: 5.3e-9 (dt 0.002) and 5.0e-9 (dt 0.02); the reference-joint design: 23 % off.
TEST(OwnedRowsArm, SevenLinksReachTheirTargetInOneStep) {
  for (const Path path : kBothPaths) {
    for (const double h : {0.002, 0.02}) {
      SCOPED_TRACE(name(path) + ", dt " + arm_number(h));
      const ScratchDir dir;
      ArmChain arm;
      arm.effort = kUnsaturated;
      auto r = load_text(path, dir, arm_chain(arm), h);
      if (!r) continue;
      guarded([&] {
        const double error = one_step_error(*r, 7, 0.5);
        std::printf("measured: 7 links, %s, dt %g: max |v - 0.5| after one step = %.3g rad/s\n",
                    name(path).c_str(), h, error);
        EXPECT_LT(error, 1e-6);
      });
    }
  }
}

// The same unsaturated arm keeps 0.5 rad/s on every joint on every step after the first too, for 0.5 s (it
// curls 0.25 rad per joint): the row's force changes most from the first step (the whole acceleration) to
// the second (the weight and the coupling only), which a row shifted by the last step's force must still
// meet. The threads' and callback's tests below hold their arms to this too.
TEST(OwnedRowsArm, SevenLinksKeepTheirTargetOnEveryStep) {
  for (const Path path : kBothPaths) {
    for (const double h : {0.002, 0.02}) {
      SCOPED_TRACE(name(path) + ", dt " + arm_number(h));
      const ScratchDir dir;
      ArmChain arm;
      arm.effort = kUnsaturated;
      auto r = load_text(path, dir, arm_chain(arm), h);
      if (!r) continue;
      guarded([&] {
        const double first = one_step_error(*r, 7, 0.5);
        double worst = 0;
        long worst_step = 0;
        for (long n = 1; n < std::lround(0.5 / h); ++n) {
          r->step();
          for (int k = 0; k < 7; ++k) {
            const double error = std::abs(r->qvel(hinge(k)) - 0.5);
            if (error > worst) worst = error, worst_step = n;
          }
        }
        std::printf(
            "measured: 7 links, %s, dt %g: max |v - 0.5| after the first step %.3g, on the steps "
            "after it %.3g (step %ld, counting from 0)\n",
            name(path).c_str(), h, first, worst, worst_step);
        EXPECT_LT(first, 1e-6);
        EXPECT_LT(worst, 1e-6) << "on step " << worst_step << " (counting from 0)";
      });
    }
  }
}

// The same arm with +-200 N m motors (its weight needs 72 N m at the shoulder) holding itself horizontal,
// every target 0, for 5 s. Owned rows: 4e-13 m (dt 0.002), 4e-11 m (dt 0.02) at the tip; the reference-joint
// design: 28 mm and 0.28 m.
TEST(OwnedRowsArm, SevenLinksHoldThemselvesHorizontalForFiveSeconds) {
  for (const Path path : kBothPaths) {
    for (const double h : {0.002, 0.02}) {
      SCOPED_TRACE(name(path) + ", dt " + arm_number(h));
      const ScratchDir dir;
      auto r = load_text(path, dir, arm_chain(ArmChain{}), h);
      if (!r) continue;
      guarded([&] {
        const double drift = hold_drift(*r, 7, 5.0, h);
        std::printf("measured: 7 links, %s, dt %g: max |angle - start| over 5 s = %.3g rad\n",
                    name(path).c_str(), h, drift);
        EXPECT_LT(drift, 1e-6);
      });
    }
  }
}

// No reference joints: one degree of freedom per hinge, whichever way the model is loaded.
TEST(OwnedRowsArm, SevenLinksHaveOneDegreeOfFreedomPerHinge) {
  for (const Path path : kBothPaths) {
    for (const double h : {0.002, 0.02}) {
      SCOPED_TRACE(name(path) + ", dt " + arm_number(h));
      const ScratchDir dir;
      auto r = load_text(path, dir, arm_chain(ArmChain{}), h);
      if (!r) continue;
      std::printf("measured: 7 links, %s, dt %g: nv = %d, njnt = %d\n", name(path).c_str(), h, r->model()->nv,
                  r->model()->njnt);
      EXPECT_EQ(r->model()->nv, 7);
      for (int k = 0; k < 7; ++k) EXPECT_GE(mj_name2id(r->model(), mjOBJ_JOINT, hinge(k).c_str()), 0);
    }
  }
}

// ---------------------------------------------------------------------------------------------------------
// Families: chain length x time step

const int kChainLengths[] = {1, 2, 3, 5, 10};
const double kFamilySteps[] = {0.0005, 0.002, 0.02};

// Every chain, +-200 N m motors (the 10-link one's weight needs 147 N m at the shoulder), held horizontal
// for 1 s within 1e-6 rad.
TEST(OwnedRowsFamily, ChainsHoldThemselvesForOneSecond) {
  for (const int links : kChainLengths) {
    for (const double h : kFamilySteps) {
      SCOPED_TRACE(std::to_string(links) + " links, dt " + arm_number(h));
      const ScratchDir dir;
      ArmChain arm;
      arm.links = links;
      auto r = load_text(Path::Simulation, dir, arm_chain(arm), h);
      if (!r) continue;
      guarded([&] {
        const double drift = hold_drift(*r, links, 1.0, h);
        std::printf("measured: %d links, dt %g: max |angle - start| over 1 s = %.3g rad\n", links, h, drift);
        EXPECT_LT(drift, 1e-6);
      });
    }
  }
}

// Every chain, unsaturated motors: 0.5 rad/s on every joint after one step within 1e-6.
TEST(OwnedRowsFamily, ChainsReachTheirTargetInOneStep) {
  for (const int links : kChainLengths) {
    for (const double h : kFamilySteps) {
      SCOPED_TRACE(std::to_string(links) + " links, dt " + arm_number(h));
      const ScratchDir dir;
      ArmChain arm;
      arm.links = links;
      arm.effort = kUnsaturated;
      auto r = load_text(Path::Simulation, dir, arm_chain(arm), h);
      if (!r) continue;
      guarded([&] {
        const double error = one_step_error(*r, links, 0.5);
        std::printf("measured: %d links, dt %g: max |v - 0.5| after one step = %.3g rad/s\n", links, h,
                    error);
        EXPECT_LT(error, 1e-6);
      });
    }
  }
}

// One link whose motor (target 0) is 1 % weaker than the link's weight about the hinge, m g L / 2 =
// 1.4715 N m: it pushes exactly its limit (the prototype: to 12 digits) and the link falls, on the first step
// at (m g L / 2 - limit) / I (Euler's first step is exact); 0.5 s on it has turned down by about
// a t^2 / 2 = 0.06 rad (less as its weight's arm shortens).
TEST(OwnedRowsFamily, MotorJustBelowTheWeightPushesExactlyItsLimit) {
  const double limit = 0.99 * kLinkWeightTorque;
  for (const double h : kFamilySteps) {
    SCOPED_TRACE("dt " + arm_number(h));
    const ScratchDir dir;
    ArmChain arm;
    arm.links = 1;
    arm.effort = limit;
    auto r = load_text(Path::Simulation, dir, arm_chain(arm), h);
    if (!r) continue;
    guarded([&] {
      r->step();
      const double torque = r->output("motor0.torque_output");
      const double expected_speed = h * (kLinkWeightTorque - limit) / kLinkInertia;
      std::printf(
          "measured: 1 link, limit %.6g N m, dt %g: |motor torque| = %.15g, speed after one step %.6g "
          "(expected %.6g)\n",
          limit, h, std::abs(torque), r->qvel("hinge0"), expected_speed);
      EXPECT_NEAR(std::abs(torque), limit, 1e-9 * limit);
      EXPECT_NEAR(r->qvel("hinge0"), expected_speed, 1e-3 * expected_speed);
      for (long n = std::lround(0.5 / h) - 1; n > 0; --n) r->step();
      EXPECT_NEAR(std::abs(r->output("motor0.torque_output")), limit, 1e-9 * limit);  // still at its limit
      EXPECT_GT(r->qpos("hinge0"), 0.03);                                             // it fell
    });
  }
}

// The same link with a motor 1 % stronger than its weight: held within 1e-6 rad for 1 s, the motor carrying
// exactly the weight (1.4715 N m) at rest.
TEST(OwnedRowsFamily, MotorJustAboveTheWeightHolds) {
  const double limit = 1.01 * kLinkWeightTorque;
  for (const double h : kFamilySteps) {
    SCOPED_TRACE("dt " + arm_number(h));
    const ScratchDir dir;
    ArmChain arm;
    arm.links = 1;
    arm.effort = limit;
    auto r = load_text(Path::Simulation, dir, arm_chain(arm), h);
    if (!r) continue;
    guarded([&] {
      const double drift = hold_drift(*r, 1, 1.0, h);
      const double torque = r->output("motor0.torque_output");
      std::printf("measured: 1 link, limit %.6g N m, dt %g: drift over 1 s %.3g rad, |motor torque| %.12g\n",
                  limit, h, drift, std::abs(torque));
      EXPECT_LT(drift, 1e-6);
      EXPECT_NEAR(std::abs(torque), kLinkWeightTorque, 1e-6);
    });
  }
}

// ---------------------------------------------------------------------------------------------------------
// Threads and the program's own mjcb_control

constexpr double kThreadStep = 0.002;
constexpr int kThreadLinks = 3, kThreadHoldSteps = 250;

// What one thread saw driving a 3-link arm: the largest |speed - target| after the first step and over all.
struct ArmRun {
  std::string error;  // "attach: ..." or "step: ...": the exception that stopped it
  double first = NAN, worst = NAN;
  std::vector<double> qpos, qvel;  // at the end
};

// Joint j's target in run `i`: a different speed per run and alternating signs along the arm.
double thread_target(int i, int j) {
  return (0.2 + 0.1 * i) * (j % 2 ? -1.0 : 1.0);
}

// Attaches a bridge to (m, d), waits for every other thread to have attached too, then sets its targets and
// steps kThreadHoldSteps times in a plain mj_step loop.
ArmRun drive_arm(const fs::path& manifest, mjModel* m, mjData* d, int i, std::latch& attached) {
  ArmRun run;
  std::optional<rt::SignalBridge> bridge;
  try {
    bridge.emplace(rt::SignalBridge::attach(manifest.string(), m, d));
  } catch (const std::exception& e) {
    run.error = std::string("attach: ") + e.what();
  }
  attached.arrive_and_wait();
  if (!bridge) return run;
  try {
    for (int j = 0; j < kThreadLinks; ++j) bridge->input(speed_input(j)).set(thread_target(i, j));
    run.worst = 0;
    for (int n = 0; n < kThreadHoldSteps; ++n) {
      bridge->before_step();
      mj_step(m, d);
      bridge->after_step();
      double error = 0;
      for (int j = 0; j < kThreadLinks; ++j)
        error = std::max(error, std::abs(joint_qvel(m, d, hinge(j)) - thread_target(i, j)));
      if (n == 0) run.first = error;
      run.worst = std::max(run.worst, error);
    }
    run.qpos.assign(d->qpos, d->qpos + m->nq);
    run.qvel.assign(d->qvel, d->qvel + m->nv);
  } catch (const std::exception& e) {
    run.error = std::string("step: ") + e.what();
  }
  return run;
}

// Runs drive_arm on each (model, data) in a thread of its own, all at once.
std::vector<ArmRun> drive_concurrently(const fs::path& manifest,
                                       const std::vector<std::pair<mjModel*, mjData*>>& md) {
  std::vector<ArmRun> runs(md.size());
  std::latch attached(static_cast<std::ptrdiff_t>(md.size()));
  std::vector<std::thread> threads;
  for (size_t i = 0; i < md.size(); ++i) {
    threads.emplace_back(
        [&, i] { runs[i] = drive_arm(manifest, md[i].first, md[i].second, int(i), attached); });
  }
  for (std::thread& t : threads) t.join();
  return runs;
}

// What drive_arm does with targets `i` on a model of its own, alone on this thread: the motion each thread
// must reproduce exactly (MuJoCo is deterministic; nothing a thread shares may change its result).
ArmRun drive_alone(const fs::path& xml, int i) {
  PlainModel model(xml);
  if (!model.ok()) {
    ArmRun failed;
    failed.error = "load: " + model.error();
    return failed;
  }
  std::latch attached(1);
  return drive_arm(manifest_of(xml), model.m(), model.d(), i, attached);
}

// A run in a thread against the same run alone: the same motion to the last bit.
void expect_same_motion(const ArmRun& run, const ArmRun& alone) {
  EXPECT_EQ(alone.error, "");
  EXPECT_EQ(run.qpos, alone.qpos) << "a concurrent run's final positions differ from the same run alone";
  EXPECT_EQ(run.qvel, alone.qvel) << "a concurrent run's final speeds differ from the same run alone";
}

// 1 to 4 threads, each with its own mjModel and mjData of the 3-link arm (unsaturated motors, dt 0.002)
// attached through its own bridge, stepping at the same time with different targets: each reaches its own
// targets within 1e-6 after one step and holds them for 0.5 s, and moves exactly as the same run alone on
// this thread. The models are loaded on this thread (mj_loadXML is not ours to make thread-safe); attaching,
// stepping and detaching happen in the threads.
TEST(OwnedRowsThreads, EachThreadsModelReachesItsOwnTargets) {
  const ScratchDir dir;
  ArmChain arm;
  arm.links = kThreadLinks;
  arm.effort = kUnsaturated;
  const fs::path xml = emit(dir, write_model(dir, arm_chain(arm)), kThreadStep);
  std::vector<ArmRun> alone;
  for (int i = 0; i < 4; ++i) alone.push_back(drive_alone(xml, i));
  for (int count = 1; count <= 4; ++count) {
    SCOPED_TRACE(std::to_string(count) + " threads");
    std::vector<std::unique_ptr<PlainModel>> models;
    std::vector<std::pair<mjModel*, mjData*>> md;
    for (int i = 0; i < count; ++i) {
      models.push_back(std::make_unique<PlainModel>(xml));
      ASSERT_TRUE(models.back()->ok()) << models.back()->error();
      md.emplace_back(models.back()->m(), models.back()->d());
    }
    const std::vector<ArmRun> runs = drive_concurrently(manifest_of(xml), md);
    for (int i = 0; i < count; ++i) {
      SCOPED_TRACE("thread " + std::to_string(i));
      std::printf(
          "measured: %d threads, thread %d: max |v - target| after one step %.3g, over %d steps %.3g\n",
          count, i, runs[i].first, kThreadHoldSteps, runs[i].worst);
      EXPECT_EQ(runs[i].error, "");
      EXPECT_LT(runs[i].first, 1e-6);
      EXPECT_LT(runs[i].worst, 1e-6);
      expect_same_motion(runs[i], alone[i]);
    }
  }
}

// Two mjData of ONE mjModel, each with its own bridge, stepped in two threads with different targets: each
// reaches its own, moving exactly as the same run alone. If attach refuses the second mjData, that is this
// test's failure (the design must allow it: a program may run several instances of one model).
TEST(OwnedRowsThreads, TwoDataOfOneModelReachTheirOwnTargets) {
  const ScratchDir dir;
  ArmChain arm;
  arm.links = kThreadLinks;
  arm.effort = kUnsaturated;
  const fs::path xml = emit(dir, write_model(dir, arm_chain(arm)), kThreadStep);
  PlainModel model(xml);
  ASSERT_TRUE(model.ok()) << model.error();
  mjData* second = model.another_data();
  const std::vector<ArmRun> runs =
      drive_concurrently(manifest_of(xml), {{model.m(), model.d()}, {model.m(), second}});
  for (int i = 0; i < 2; ++i) {
    SCOPED_TRACE("data " + std::to_string(i));
    if (runs[i].error.rfind("attach: ", 0) == 0) {
      ADD_FAILURE() << "SignalBridge::attach refused mjData " << i
                    << " of an mjModel another mjData of which has a bridge: " << runs[i].error;
      continue;
    }
    std::printf("measured: one model, data %d: max |v - target| after one step %.3g, over %d steps %.3g\n", i,
                runs[i].first, kThreadHoldSteps, runs[i].worst);
    EXPECT_EQ(runs[i].error, "");
    EXPECT_LT(runs[i].first, 1e-6);
    EXPECT_LT(runs[i].worst, 1e-6);
    expect_same_motion(runs[i], drive_alone(xml, i));
  }
}

std::atomic<long> g_program_calls{0}, g_program_foreign_calls{0};
std::atomic<const mjModel*> g_program_model{nullptr};
std::atomic<const mjData*> g_program_data{nullptr};

// The program's own control callback: counts its calls, and those for another model or data.
void program_control(const mjModel* m, mjData* d) {
  ++g_program_calls;
  if (m != g_program_model.load() || d != g_program_data.load()) ++g_program_foreign_calls;
}

// Puts back the control callback a test found.
struct ControlCallbackGuard {
  mjfGeneric saved = mjcb_control;
  ~ControlCallbackGuard() { mjcb_control = saved; }
};

// A program sets mjcb_control before attaching a bridge: the runtime, which needs mjcb_control for its rows,
// chains it. Over N steps through the bridge the program's callback runs exactly N times (once per mj_step,
// as MuJoCo calls it) with the program's model and data, and the motors still reach their targets (1e-6
// after one step, held). With the bridge gone, mj_step still calls it.
TEST(OwnedRowsCallback, AProgramsControlCallbackIsChained) {
  const ControlCallbackGuard guard;
  const ScratchDir dir;
  ArmChain arm;
  arm.links = kThreadLinks;
  arm.effort = kUnsaturated;
  const fs::path xml = emit(dir, write_model(dir, arm_chain(arm)), kThreadStep);
  PlainModel model(xml);
  ASSERT_TRUE(model.ok()) << model.error();
  g_program_model = model.m();
  g_program_data = model.d();
  mjcb_control = program_control;
  constexpr long kSteps = 100;
  {
    std::optional<rt::SignalBridge> bridge;
    try {
      bridge.emplace(rt::SignalBridge::attach(manifest_of(xml).string(), model.m(), model.d()));
    } catch (const std::exception& e) {
      FAIL() << "attach: " << e.what();
    }
    g_program_calls = 0;  // attaching may run mj_forward, which calls it too: count the steps' calls only
    g_program_foreign_calls = 0;
    guarded([&] {
      for (int j = 0; j < kThreadLinks; ++j) bridge->input(speed_input(j)).set(0.5);
      double first = 0, worst = 0;
      for (long n = 0; n < kSteps; ++n) {
        bridge->before_step();
        mj_step(model.m(), model.d());
        bridge->after_step();
        for (int j = 0; j < kThreadLinks; ++j) {
          const double error = std::abs(joint_qvel(model.m(), model.d(), hinge(j)) - 0.5);
          worst = std::max(worst, error);
          if (n == 0) first = std::max(first, error);
        }
      }
      std::printf(
          "measured: program callback calls over %ld steps: %ld (%ld for others); max |v - 0.5| after "
          "one step %.3g, over all %.3g\n",
          kSteps, g_program_calls.load(), g_program_foreign_calls.load(), first, worst);
      EXPECT_EQ(g_program_calls.load(), kSteps);
      EXPECT_EQ(g_program_foreign_calls.load(), 0);
      EXPECT_LT(first, 1e-6);
      EXPECT_LT(worst, 1e-6);
    });
  }
  g_program_calls = 0;
  mj_step(model.m(), model.d());
  EXPECT_EQ(g_program_calls.load(), 1)
      << "the program's callback is no longer called once the bridge is gone";
}

// ---------------------------------------------------------------------------------------------------------
// Springs, ranges, gears

// AGXUnity's LinearSpringTest (tests/corpus README): after 2 s `falling_rod.rod1` rests at world z = -0.5
// within 1 mm, its vertical speed within 1 mm/s, through a bridge in a plain mj_step loop as through
// Simulation; the two agree (Simulation is the bridge stepped split, which under Euler is mj_step).
TEST(OwnedRowsSpring, LinearSpringTestRestsThroughABridgeAsThroughSimulation) {
  const fs::path corpus = fs::path(OPENPLX_CORPUS_DIR) / "agxunity" / "LinearSpringTest.openplx";
  for (const double h : {0.002, 0.005, 0.02}) {
    double z[2] = {NAN, NAN};
    for (const Path path : kBothPaths) {
      SCOPED_TRACE(name(path) + ", dt " + arm_number(h));
      const ScratchDir dir;
      std::ifstream in(corpus);
      ASSERT_TRUE(in) << corpus;
      const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      const fs::path file = dir / "LinearSpringTest.openplx";
      std::ofstream(file) << text;
      auto r = load(path, dir, file, h, "FallingRodScene");
      if (!r) continue;
      const int rod = mj_name2id(r->model(), mjOBJ_BODY, "falling_rod.rod1");
      ASSERT_GE(rod, 0);
      guarded([&] {
        for (long n = std::lround(2.0 / h); n > 0; --n) r->step();
        const double height = r->data()->xpos[3 * rod + 2], speed = r->qvel("falling_rod.prismatic");
        std::printf("measured: LinearSpringTest, %s, dt %g: z %.9f m, speed %.3g m/s at t = %g s\n",
                    name(path).c_str(), h, height, speed, r->time());
        EXPECT_NEAR(height, -0.5, 1e-3);
        EXPECT_NEAR(speed, 0.0, 1e-3);
        z[path == Path::Simulation ? 0 : 1] = height;
      });
    }
    SCOPED_TRACE("dt " + arm_number(h));
    EXPECT_NEAR(z[0], z[1], 1e-9) << "the bridge in a plain mj_step loop and Simulation differ";
  }
}

// One link on a hinge with a RotationalRange [-0.5, 0.5] and a velocity motor of +-5e4 N m pushing toward
// +1 rad/s, dt 0.02: after 1 s it rests at the range's end within 1e-3 rad. (MuJoCo's own limit row gives
// (1 - d)/d a (2 d h)^2 = 0.27 rad under that push: a = 5e4 / 0.0301 rad/s^2.)
TEST(OwnedRowsRange, RangeHoldsAStrongMotorAtItsEnd) {
  constexpr double kH = 0.02;
  for (const Path path : kBothPaths) {
    SCOPED_TRACE(name(path));
    const ScratchDir dir;
    ArmChain arm;
    arm.links = 1;
    arm.effort = 5e4;
    arm.range_start = -0.5;
    arm.range_end = 0.5;
    auto r = load_text(path, dir, arm_chain(arm), kH);
    if (!r) continue;
    guarded([&] {
      r->set("speed0", 1.0);
      for (long n = std::lround(1.0 / kH); n > 0; --n) r->step();
      const double angle = r->output("angle0");
      std::printf("measured: range [-0.5, 0.5] against 5e4 N m, %s, dt %g: angle %.9f rad after %g s\n",
                  name(path).c_str(), kH, angle, r->time());
      EXPECT_NEAR(angle, r->qpos("hinge0"), 1e-12);  // the AngleOutput reads the joint
      EXPECT_NEAR(angle, 0.5, 1e-3);
    });
  }
}

// A 1-D drivetrain: a velocity motor on an input shaft (1 kg m^2) at 1 rad/s, a DriveTrain.Gear of ratio 2 to
// an output shaft (1 kg m^2). The convention (tests/runtime/rigid_coupling_test.cpp,
// drivetrain_parts_test.cpp): the output turns at input / ratio, the same way. After one step from rest: the
// input at 1 rad/s and the output at 0.5 within 1e-6 of the ratio: output / input = 1 / 2.
TEST(OwnedRowsGear, GearTurnsItsOutputAtTheRatioAfterOneStep) {
  constexpr double kRatio = 2;
  const std::string text = gear_pair(kRatio);
  for (const Path path : kBothPaths) {
    for (const double h : {0.002, 0.02}) {
      SCOPED_TRACE(name(path) + ", dt " + arm_number(h));
      const ScratchDir dir;
      auto r = load_text(path, dir, text, h);
      if (!r) continue;
      guarded([&] {
        r->set("speed", 1.0);
        r->step();
        const double input = r->output("in.angular_velocity_output");
        const double output = r->output("out.angular_velocity_output");
        std::printf(
            "measured: gear ratio 2, %s, dt %g: input %.12g rad/s, output %.12g rad/s, output / input "
            "%.12g after one step\n",
            name(path).c_str(), h, input, output, output / input);
        EXPECT_NEAR(input, 1.0, 1e-6);
        EXPECT_NEAR(output / input, 1 / kRatio, 1e-6);
      });
    }
  }
}

// ---------------------------------------------------------------------------------------------------------
// Elastic wheels

// The car on elastic wheels, standing: 0.5 on `steering` gives 0.5 on the Ackermann's steering output (and
// on the left wheel's steering joint) within 1e-6 after 1 s, at dt 0.0005, 0.002 and 0.02, with no
// SimulationError (today the tires' 300 kN m/rad radial turns diverge at dt 0.02).
TEST(OwnedRowsElasticWheel, AckermannSteersElasticWheelsAtEveryStep) {
  for (const double h : {0.0005, 0.002, 0.02}) {
    SCOPED_TRACE("dt " + arm_number(h));
    const ScratchDir dir;
    auto r = load_text(Path::Simulation, dir, car(elastic_steered_car()), h);
    if (!r) continue;
    guarded([&] {
      EXPECT_EQ(r->output("steering_system.interaction.steering_angle_output"), 0.0);
      r->set("steering", 0.5);
      for (long n = std::lround(1.0 / h); n > 0; --n) r->step();
      const double out = r->output("steering_system.interaction.steering_angle_output");
      const double left = r->qpos("front_left_suspension.mate.steering");
      std::printf("measured: elastic car, dt %g: steering output %.12g, left wheel %.12g rad at t = %g s\n",
                  h, out, left, r->time());
      EXPECT_NEAR(out, 0.5, 1e-6);
      EXPECT_NEAR(left, 0.5, 1e-6);
    });
  }
}

// The assembly test's elastic car (wheels half inside a 1.6 m wide chassis) driven by its rear wheels at
// 4 rad/s for 5 s at dt 0.02: no SimulationError, and it does drive (over 2 m; 1.6 m/s at the tires' radius
// less the start), upright.
TEST(OwnedRowsElasticWheel, CarOnElasticWheelsDrivesFiveSecondsAtDt002) {
  constexpr double kH = 0.02;
  const ScratchDir dir;
  Car c = elastic_steered_car();
  c.chassis_width = 1.6;
  auto r = load_text(Path::Simulation, dir, car(c), kH);
  ASSERT_NE(r, nullptr);
  const int chassis = mj_name2id(r->model(), mjOBJ_BODY, "chassis");
  ASSERT_GE(chassis, 0);
  const double start = r->data()->xpos[3 * chassis];
  guarded([&] {
    r->set("speed", 4.0);
    for (long n = std::lround(5.0 / kH); n > 0; --n) r->step();
    const double moved = r->data()->xpos[3 * chassis] - start, up = r->data()->xmat[9 * chassis + 8];
    std::printf("measured: elastic car, dt %g: moved %.4g m in %g s, chassis z axis . world z = %.6f\n", kH,
                moved, r->time(), up);
    EXPECT_GT(std::abs(moved), 2.0);
    EXPECT_GT(up, 0.9);
  });
}

// ---------------------------------------------------------------------------------------------------------
// Integrators, and what attaching changes

// The emitted 3-link arm with its <option integrator> replaced, loaded by plain MuJoCo.
fs::path arm_with_integrator(const ScratchDir& dir, const std::string& integrator, double h) {
  ArmChain arm;
  arm.links = 3;
  arm.effort = kUnsaturated;
  const fs::path xml = emit(dir, write_model(dir, arm_chain(arm)), h);
  std::ifstream in(xml);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string euler = "integrator=\"Euler\"";
  const size_t at = text.find(euler);
  EXPECT_NE(at, std::string::npos) << "the emitted model names its integrator";
  if (at != std::string::npos) text.replace(at, euler.size(), "integrator=\"" + integrator + "\"");
  std::ofstream(xml) << text;
  return xml;
}

// RK4 calls the control callback four times a step, which the rows' law is not written for: attaching is a
// LoadError that says so. Under `implicit` (no joint damping, the stand-ins' taken away) the rows hold as
// under Euler: 2.2.2's implicit step differs from Euler's only by the velocity derivatives of the forces,
// which at rest and on the first step from rest are zero, and small while the arm moves slowly.
TEST(OwnedRowsIntegrator, RungeKuttaIsRefusedAndImplicitHolds) {
  for (const double h : {0.002, 0.02}) {
    SCOPED_TRACE("dt " + arm_number(h));
    const ScratchDir dir;
    {
      const fs::path xml = arm_with_integrator(dir, "RK4", h);
      PlainModel rk4(xml);
      ASSERT_TRUE(rk4.ok()) << rk4.error();
      try {
        rt::SignalBridge::attach(manifest_of(xml).string(), rk4.m(), rk4.d());
        ADD_FAILURE() << "RK4 attached";
      } catch (const rt::LoadError& e) {
        EXPECT_NE(std::string(e.what()).find("RK4"), std::string::npos) << e.what();
      }
    }
    BridgeRunner implicit(arm_with_integrator(dir, "implicit", h));
    ASSERT_TRUE(implicit.ok()) << implicit.error();
    ASSERT_EQ(implicit.model()->opt.integrator, mjINT_IMPLICIT);
    const double first = one_step_error(implicit, 3, 0.5);
    for (int k = 0; k < 3; ++k) implicit.set(speed_input(k), 0.0);
    double drift = 0;
    std::vector<double> start(3);
    for (int k = 0; k < 3; ++k) start[k] = joint_qpos(implicit.model(), implicit.data(), hinge(k));
    for (int n = 0; n < static_cast<int>(std::lround(1.0 / h)); ++n) {
      implicit.step();
      for (int k = 0; k < 3; ++k)
        drift = std::max(drift, std::abs(joint_qpos(implicit.model(), implicit.data(), hinge(k)) - start[k]));
    }
    std::printf(
        "measured: 3 links, implicit, dt %g: one step to 0.5 off by %.3g rad/s; held 1 s within %.3g\n", h,
        first, drift);
    EXPECT_LT(first, 1e-6);
    // Holding, the implicit step's velocity derivatives are not the rows' (Euler: 8e-12 rad over 5 s at
    // 0.02).
    EXPECT_LT(drift, h == 0.002 ? 1e-7 : 1e-4) << "measured 4.7e-8 (dt 0.002), 4.7e-5 (dt 0.02)";
  }
}

// Attaching hands the model's motors to the runtime (the stand-in's gain and damper, the tendon's friction
// loss); the last bridge to go gives them back, so the model runs as its MJCF says again.
TEST(OwnedRowsAttach, TheLastBridgeGivesTheModelBack) {
  const ScratchDir dir;
  ArmChain arm;
  arm.links = 2;
  const fs::path xml = emit(dir, write_model(dir, arm_chain(arm)), 0.002);
  PlainModel plain(xml);
  ASSERT_TRUE(plain.ok()) << plain.error();
  mjModel* m = plain.m();
  const std::vector<mjtNum> gains(m->actuator_gainprm, m->actuator_gainprm + m->nu * mjNGAIN);
  const std::vector<mjtNum> dampings(m->dof_damping, m->dof_damping + m->nv);
  const std::vector<mjtNum> frictions(m->tendon_frictionloss, m->tendon_frictionloss + m->ntendon);
  mjData* second = plain.another_data();
  {
    rt::SignalBridge one = rt::SignalBridge::attach(manifest_of(xml).string(), m, plain.d());
    EXPECT_EQ(m->actuator_gainprm[0], 0);
    {
      rt::SignalBridge two = rt::SignalBridge::attach(manifest_of(xml).string(), m, second);
      EXPECT_EQ(m->actuator_gainprm[0], 0);
    }
    EXPECT_EQ(m->actuator_gainprm[0], 0) << "another bridge still drives the model";
  }
  EXPECT_EQ(std::vector<mjtNum>(m->actuator_gainprm, m->actuator_gainprm + m->nu * mjNGAIN), gains);
  EXPECT_EQ(std::vector<mjtNum>(m->dof_damping, m->dof_damping + m->nv), dampings);
  EXPECT_EQ(std::vector<mjtNum>(m->tendon_frictionloss, m->tendon_frictionloss + m->ntendon), frictions);
}

}  // namespace
