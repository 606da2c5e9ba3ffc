// What the converter's MJCF does on its own, without the runtime: the same models and steps as the owned-rows
// acceptance tests (tests/runtime/owned_rows_test.cpp), loaded with plain mj_loadXML, started from the
// "initial" keyframe, driven by writing d->ctrl (or m->eq_data) where the manifest's binding says, and
// stepped with plain mj_step: no SignalBridge, no Simulation, no mjcb_control. There the rows the runtime
// owns (docs/mapping.md, "Constraint rows the runtime owns") are MuJoCo's own stand-ins: a velocity motor is
// a <velocity> servo on its joint (kv = 1 / (n h (M^-1)_jj), forcerange the effort band), a spring a clamped
// <general>, an elastic tire direction a joint held by a soft joint <equality>, ranges and gears MuJoCo's
// stiffest rows (time constant 2h, impedance 0.9999).
//
// The requirement (issue 41): what the file says on its own must be stable wherever the runtime is (same
// models, same steps) and as close as MuJoCo's own elements allow. So every case here holds the MJCF alone
// to: no MuJoCo warning (every d->warning[k].number 0, and MuJoCo's warning handler never called), time
// never going back (MuJoCo resets the data on a bad state), every qpos and qvel finite, on every step. The
// figures it reaches are asserted as they are, with a bound derived from the stand-in's law or a little
// looser than measured; each says what the runtime makes exact and the figure the runtime gets
// (owned_rows_test). Each figure is printed on a line starting "measured (MJCF alone):", for docs/mapping.md.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tests/support/arm_chain.h"
#include "tests/support/owned_rows_models.h"
#include "tests/support/scratch_dir.h"

namespace {

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

constexpr double kUnsaturated = 1e6;  // N m: an effort limit no one-step target here comes near
constexpr double kGravity = 9.81;     // MuJoCo's default, which the converter keeps
// A 1 kg, 0.3 m link about its end: weight m g L / 2, inertia m (L^2 + w^2) / 12 + m (L / 2)^2.
constexpr double kLinkWeightTorque = openplx::testing::kArmLinkMass * kGravity * 0.15;  // 1.4715 N m
constexpr double kLinkInertia = 1.0 * (0.3 * 0.3 + 0.04 * 0.04) / 12 + 1.0 * 0.15 * 0.15;

// ---------------------------------------------------------------------------------------------------------
// MuJoCo's warnings

// Every text MuJoCo's warning handler got while a WarningRecorder was alive (tests run one at a time in a
// process, and MuJoCo steps on this thread only).
std::vector<std::string> g_warnings;

void record_warning(const char* text) {
  g_warnings.emplace_back(text);
}

// Sets mju_user_warning to record_warning (so nothing writes MUJOCO_LOG.TXT) and puts back the handler it
// found when it goes.
class WarningRecorder {
 public:
  WarningRecorder() : saved_(mju_user_warning) {
    g_warnings.clear();
    mju_user_warning = record_warning;
  }
  ~WarningRecorder() { mju_user_warning = saved_; }
  WarningRecorder(const WarningRecorder&) = delete;
  WarningRecorder& operator=(const WarningRecorder&) = delete;

  std::string texts() const {
    std::string all;
    for (const std::string& w : g_warnings) all += w + "\n";
    return all;
  }

 private:
  void (*saved_)(const char*);
};

// ---------------------------------------------------------------------------------------------------------
// The MJCF alone

// A model as a program with only the converter's files has it: mj_loadXML, the "initial" keyframe when there
// is one, inputs written where the manifest (OUT.signals.json) binds them, plain mj_step. Every step is
// checked: once a warning, a step back in time or a non-finite qpos or qvel shows, trouble() says what and
// when and step() steps no more.
class BareModel {
 public:
  explicit BareModel(const fs::path& xml) {
    char error[1000] = "";
    m_ = mj_loadXML(xml.c_str(), nullptr, error, sizeof(error));
    if (!m_) {
      error_ = xml.string() + ": " + error;
      return;
    }
    d_ = mj_makeData(m_);
    const int key = mj_name2id(m_, mjOBJ_KEY, "initial");
    if (key >= 0) mj_resetDataKeyframe(m_, d_, key);
    mj_forward(m_, d_);
    std::ifstream in(manifest_of(xml));
    if (!in) {
      error_ = manifest_of(xml).string() + ": cannot read the manifest";
      return;
    }
    const nlohmann::json manifest = nlohmann::json::parse(in);
    for (const nlohmann::json& s : manifest.at("signals")) signals_[s.at("path").get<std::string>()] = s;
    check("at the start");
  }
  ~BareModel() {
    if (d_) mj_deleteData(d_);
    if (m_) mj_deleteModel(m_);
  }
  BareModel(const BareModel&) = delete;
  BareModel& operator=(const BareModel&) = delete;

  bool ok() const { return m_ && d_ && error_.empty(); }
  const std::string& error() const { return error_; }
  mjModel* m() const { return m_; }
  mjData* d() const { return d_; }

  // Writes `value` to input `path` as its binding in the manifest says: a control (a velocity motor's target
  // speed: the <velocity> servo's ctrl), a steering column's equality target (m->eq_data, as the runtime
  // writes it), or each target of a broadcast.
  void set(const std::string& path, double value) {
    const auto found = signals_.find(path);
    if (found == signals_.end()) {
      ADD_FAILURE() << "no signal `" << path << "` in the manifest";
      return;
    }
    const nlohmann::json& s = found->second;
    const std::string quantity = s.at("quantity");
    const std::vector<std::string> names = s.at("names");
    if (quantity == "broadcast") {
      for (const std::string& target : names) set(target, value);
    } else if (quantity == "ctrl") {
      for (const std::string& name : names) {
        const int id = mj_name2id(m_, mjOBJ_ACTUATOR, name.c_str());
        ASSERT_GE(id, 0) << "no actuator `" << name << "` for input `" << path << "`";
        d_->ctrl[id] = value;
      }
    } else if (quantity == "equality_target") {
      ASSERT_TRUE(s.at("initial_vector").empty()) << path << ": a polynomial target, not written here";
      const int id = mj_name2id(m_, mjOBJ_EQUALITY, names.at(0).c_str());
      ASSERT_GE(id, 0) << "no equality `" << names.at(0) << "` for input `" << path << "`";
      m_->eq_data[id * mjNEQDATA] = value - m_->qpos0[m_->jnt_qposadr[m_->eq_obj1id[id]]];
    } else {
      ADD_FAILURE() << "input `" << path << "` is bound to `" << quantity
                    << "`, which this test does not write";
    }
  }

  // One mj_step, then the checks; false (and no step) once there was trouble.
  bool step() {
    if (!trouble_.empty()) return false;
    const double before = d_->time;
    mj_step(m_, d_);
    ++steps_;
    if (!(d_->time > before)) {
      trouble_ = "time went from " + arm_number(before) + " to " + arm_number(d_->time) + " s on step " +
                 std::to_string(steps_);
    }
    check("on step " + std::to_string(steps_));
    sound_until_ = trouble_.empty() ? d_->time : before;
    return trouble_.empty();
  }
  // `seconds` of steps (rounded to whole steps); false once there was trouble.
  bool run(double seconds) {
    for (long n = std::lround(seconds / m_->opt.timestep); n > 0; --n) {
      if (!step()) return false;
    }
    return true;
  }

  // Empty while every step was sound.
  const std::string& trouble() const { return trouble_; }
  // The time of the last sound state: the end of the run when trouble() is empty.
  double sound_until() const { return sound_until_; }

  int joint(const std::string& name) const {
    const int id = mj_name2id(m_, mjOBJ_JOINT, name.c_str());
    EXPECT_GE(id, 0) << "no MuJoCo joint named " << name;
    return id;
  }
  double qpos(const std::string& name) const {
    const int id = joint(name);
    return id < 0 ? NAN : d_->qpos[m_->jnt_qposadr[id]];
  }
  double qvel(const std::string& name) const {
    const int id = joint(name);
    return id < 0 ? NAN : d_->qvel[m_->jnt_dofadr[id]];
  }
  int body(const std::string& name) const {
    const int id = mj_name2id(m_, mjOBJ_BODY, name.c_str());
    EXPECT_GE(id, 0) << "no MuJoCo body named " << name;
    return id;
  }

 private:
  void check(const std::string& when) {
    if (!trouble_.empty()) return;
    for (int k = 0; k < mjNWARNING; ++k) {
      if (d_->warning[k].number != 0) {
        trouble_ = "MuJoCo warning " + std::to_string(k) + " (" + std::to_string(d_->warning[k].number) +
                   " times, info " + std::to_string(d_->warning[k].lastinfo) + ") " + when +
                   ", t = " + arm_number(d_->time) + " s";
        return;
      }
    }
    for (int i = 0; i < m_->nq; ++i) {
      if (!std::isfinite(d_->qpos[i])) {
        trouble_ = "qpos[" + std::to_string(i) + "] not finite " + when;
        return;
      }
    }
    for (int i = 0; i < m_->nv; ++i) {
      if (!std::isfinite(d_->qvel[i])) {
        trouble_ = "qvel[" + std::to_string(i) + "] not finite " + when;
        return;
      }
    }
  }

  mjModel* m_ = nullptr;
  mjData* d_ = nullptr;
  std::string error_, trouble_;
  long steps_ = 0;
  double sound_until_ = 0;
  std::map<std::string, nlohmann::json> signals_;
};

// The converter's MJCF for `text` (or `source`) at time step h, loaded bare; null, with the failure recorded,
// when it does not convert or load.
std::unique_ptr<BareModel> load(const ScratchDir& dir, const fs::path& source, double h,
                                const std::string& model = "") {
  const fs::path xml = emit(dir, source, h, model);
  auto bare = std::make_unique<BareModel>(xml);
  if (!bare->ok()) {
    ADD_FAILURE() << bare->error();
    return nullptr;
  }
  return bare;
}
std::unique_ptr<BareModel> load_text(const ScratchDir& dir, const std::string& text, double h) {
  return load(dir, write_model(dir, text), h);
}

// What every case asserts of its run: no trouble on any step, no warning text, and the runtime not involved.
void expect_sound(const BareModel& bare, const WarningRecorder& warnings) {
  EXPECT_EQ(bare.trouble(), "") << "the MJCF alone is not stable";
  EXPECT_EQ(warnings.texts(), "") << "MuJoCo warned";
  EXPECT_EQ(mjcb_control, nullptr) << "a control callback is set: this is not the MJCF alone";
}

std::string hinge(int k) {
  return "hinge" + std::to_string(k);
}
std::string speed_input(int k) {
  return "speed" + std::to_string(k);
}

// Holds every motor's target at 0 for `seconds` (or until the run is no longer sound) and returns the largest
// |angle - its start| over every joint and step (the arm starts straight out, every angle 0).
double hold_drift(BareModel& bare, int links, double seconds) {
  for (int k = 0; k < links; ++k) {
    bare.set(speed_input(k), 0.0);
    EXPECT_NEAR(bare.qpos(hinge(k)), 0.0, 1e-12) << hinge(k) << ": the arm starts straight out, horizontal";
  }
  double worst = 0;
  for (long n = std::lround(seconds / bare.m()->opt.timestep); n > 0; --n) {
    if (!bare.step()) break;
    for (int k = 0; k < links; ++k) worst = std::max(worst, std::abs(bare.qpos(hinge(k))));
  }
  return worst;
}

// The gain of a velocity motor's stand-in `actuator`: its damper b, or its servo's kv.
double stand_in_gain(const mjModel* m, const std::string& actuator) {
  const int id = mj_name2id(m, mjOBJ_ACTUATOR, actuator.c_str());
  EXPECT_GE(id, 0) << "no actuator " << actuator;
  return id < 0 ? NAN : m->actuator_gainprm[id * mjNGAIN];
}

// ---------------------------------------------------------------------------------------------------------
// Arms

// The 7-link arm, +-200 N m motors, every target 0, for 5 s (the runtime holds it within 1e-6 rad: 8e-14 at
// dt 0.002, 8e-12 at dt 0.02). Alone, in a model without equalities, each motor is a damper b = I / h on its
// joint (I what it drives about its axis: 10.3 kg m^2 at the shoulder) pulling it toward its target; a
// damper carries a load tau only while moving at tau / b (the shoulder's 72 N m: 0.014 rad/s at dt 0.002), so
// the arm sags slowly instead of holding. Asserted: stable on every step, the sag within 30 % above what was
// measured (0.383 rad at dt 0.002, 0.451 at dt 0.02). (A bounded <velocity> servo stable under explicit Euler
// let this arm fall 2.4 rad, and MuJoCo diverged on the falling chain at dt 0.02.)
TEST(BareMjcfArm, SevenLinksHoldingThemselvesSagButStayStable) {
  for (const double h : {0.002, 0.02}) {
    SCOPED_TRACE("dt " + arm_number(h));
    const ScratchDir dir;
    const WarningRecorder warnings;  // before loading: nothing writes MUJOCO_LOG.TXT
    auto bare = load_text(dir, arm_chain(ArmChain{}), h);
    if (!bare) continue;
    // Link k's weight acts (k + 1/2) L from the shoulder: m g L / 2 (2k + 1), summed 7^2 m g L / 2 = 72 N m.
    const double kv = stand_in_gain(bare->m(), "motor0"), shoulder_load = 49 * kLinkWeightTorque;
    const double drift = hold_drift(*bare, 7, 5.0);
    std::printf(
        "measured (MJCF alone): 7 links, dt %g: shoulder stand-in b %.4g N m s (its %.4g N m load needs %.3g "
        "rad/s); max |angle - start| %.3g rad until t = %g s of 5%s%s\n",
        h, kv, shoulder_load, shoulder_load / kv, drift, bare->sound_until(),
        bare->trouble().empty() ? "" : ": ", bare->trouble().c_str());
    expect_sound(*bare, warnings);
    EXPECT_LT(drift, 1.3 * (h == 0.002 ? 0.383 : 0.451)) << "measured 0.383 (dt 0.002), 0.451 (dt 0.02)";
  }
}

// The unsaturated 7-link arm from rest to 0.5 rad/s on every joint (the runtime: within 1e-6 after one step,
// 5e-9 measured, and on every step after). Alone each motor is a damper b = I / h pulling toward its target,
// integrated implicitly by Euler with the chain's coupling and its weight: far from the target after one step
// (1.41 rad/s at dt 0.002, 1.46 at 0.02, on the distal joints the proximal ones swing), 0.14 and 0.97 rad/s
// after 1 s. Asserted: stable, within 20 % above those.
TEST(BareMjcfArm, SevenLinksTowardATargetSpeedAreStable) {
  for (const double h : {0.002, 0.02}) {
    SCOPED_TRACE("dt " + arm_number(h));
    const ScratchDir dir;
    const WarningRecorder warnings;  // before loading: nothing writes MUJOCO_LOG.TXT
    ArmChain arm;
    arm.effort = kUnsaturated;
    auto bare = load_text(dir, arm_chain(arm), h);
    if (!bare) continue;
    for (int k = 0; k < 7; ++k) bare->set(speed_input(k), 0.5);
    bare->step();
    double first = 0;
    for (int k = 0; k < 7; ++k) first = std::max(first, std::abs(bare->qvel(hinge(k)) - 0.5));
    bare->run(1.0 - h);
    double last = 0;
    for (int k = 0; k < 7; ++k) last = std::max(last, std::abs(bare->qvel(hinge(k)) - 0.5));
    std::printf(
        "measured (MJCF alone): 7 links, dt %g: max |v - 0.5| after one step = %.3g rad/s, after 1 s = %.3g "
        "rad/s\n",
        h, first, last);
    expect_sound(*bare, warnings);
    EXPECT_LT(first, 1.2 * (h == 0.002 ? 1.41 : 1.46)) << "measured 1.41 (dt 0.002), 1.46 (dt 0.02)";
    EXPECT_LT(last, 1.2 * (h == 0.002 ? 0.138 : 0.973)) << "measured 0.138 (dt 0.002), 0.973 (dt 0.02)";
  }
}

// ---------------------------------------------------------------------------------------------------------
// Families: chain length x time step

const int kChainLengths[] = {1, 2, 3, 5, 10};
const double kFamilySteps[] = {0.0005, 0.002, 0.02};

// Every chain, +-200 N m motors, held for 1 s (the runtime: within 1e-6 rad, 4.2e-10 measured). Alone: stable
// on every step. One link: the damper b = I / h carries its weight W cos(angle) (W = m g L / 2) at a speed
// of at most h W / I, so it sags at most h W / I in 1 s: 0.0244, 0.0977, 0.977 rad at dt 0.0005, 0.002, 0.02
// (less as its load's arm shortens). Longer chains sag alike (each joint's damper carries what hangs beyond
// it); their drift is asserted within 15 % of what was measured.
TEST(BareMjcfFamily, ChainsHoldingThemselvesForOneSecondAreStable) {
  // Measured max |angle - start| over 1 s, [links][step] (dt 0.0005, 0.002, 0.02).
  const std::map<int, std::vector<double>> measured{{2, {0.0244, 0.0969, 0.723}},
                                                    {3, {0.0244, 0.0965, 0.635}},
                                                    {5, {0.0243, 0.0957, 0.518}},
                                                    {10, {0.0242, 0.0938, 0.364}}};
  for (const int links : kChainLengths) {
    for (size_t i = 0; i < std::size(kFamilySteps); ++i) {
      const double h = kFamilySteps[i];
      SCOPED_TRACE(std::to_string(links) + " links, dt " + arm_number(h));
      const ScratchDir dir;
      const WarningRecorder warnings;  // before loading: nothing writes MUJOCO_LOG.TXT
      ArmChain arm;
      arm.links = links;
      auto bare = load_text(dir, arm_chain(arm), h);
      if (!bare) continue;
      const double drift = hold_drift(*bare, links, 1.0);
      std::printf("measured (MJCF alone): %d links, dt %g: max |angle - start| over 1 s = %.3g rad\n", links,
                  h, drift);
      expect_sound(*bare, warnings);
      if (links == 1) {
        const double sag = h * kLinkWeightTorque / kLinkInertia;  // rad in 1 s at the horizontal's speed
        EXPECT_LE(drift, sag * 1.001);
        EXPECT_GE(drift, 0.85 * sag);
      } else {
        EXPECT_NEAR(drift, measured.at(links)[i], 0.15 * measured.at(links)[i]);
      }
    }
  }
}

// ---------------------------------------------------------------------------------------------------------
// Springs, ranges, gears

// AGXUnity's LinearSpringTest at dt 0.002, 0.005, 0.02 for 2 s (the runtime: rests at z = -0.5000981 with
// 0 m/s, within 1 mm and 1 mm/s). Alone the spring is a <general> of 1e6 N/m clamped to +-200 N, its damping
// (4e-4 s x k) inside the clamp: it never pushes beyond 200 N, cannot brake as the row does, and the rod
// swings about the rest. Asserted: stable, within 0.11 m and 1 m/s of the rest (measured at most 0.103 m,
// 0.82 m/s).
TEST(BareMjcfSpring, LinearSpringTestIsStable) {
  fs::path corpus = fs::path(OPENPLX_VENDORED_CORPUS_DIR) / "agxunity" / "LinearSpringTest.openplx";
  if (!fs::exists(corpus)) corpus = fs::path(OPENPLX_CORPUS_DIR) / "agxunity" / "LinearSpringTest.openplx";
  for (const double h : {0.002, 0.005, 0.02}) {
    SCOPED_TRACE("dt " + arm_number(h));
    const ScratchDir dir;
    std::ifstream in(corpus);
    ASSERT_TRUE(in) << corpus;
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const fs::path file = dir / "LinearSpringTest.openplx";
    std::ofstream(file) << text;
    const WarningRecorder warnings;  // before loading: nothing writes MUJOCO_LOG.TXT
    auto bare = load(dir, file, h, "FallingRodScene");
    if (!bare) continue;
    const int rod = bare->body("falling_rod.rod1");
    ASSERT_GE(rod, 0);
    bare->run(2.0);
    mj_forward(bare->m(), bare->d());  // after mj_step, MuJoCo's positions are those the step started from
    mjtNum velocity[6];                // world frame: rotation, then translation
    mj_objectVelocity(bare->m(), bare->d(), mjOBJ_BODY, rod, velocity, 0);
    const double z = bare->d()->xpos[3 * rod + 2], vz = velocity[5];
    std::printf("measured (MJCF alone): LinearSpringTest, dt %g: z %.6f m, vz %.4g m/s at t = %g s\n", h, z,
                vz, bare->d()->time);
    expect_sound(*bare, warnings);
    EXPECT_NEAR(z, -0.5, 0.11);
    EXPECT_NEAR(vz, 0.0, 1.0);
  }
}

// One link with a RotationalRange [-0.5, 0.5] and a +-5e4 N m motor toward +1 rad/s, dt 0.02, 1 s (the
// runtime: at 0.5 within 1e-3, 0.500000000 measured; MuJoCo's limit row under the full 5e4 N m: 0.5075).
// Alone the motor is a damper b = I / h pulling toward 1 rad/s, which Euler integrates implicitly: it scales
// the joint's share of the limit row's correction down by I / (I + h b) = 1/2 each step, so the joint rests
// past the end by more than MuJoCo's row law gives (1.6e-5 rad for this push): 6.6e-3 measured. Asserted:
// stable, within 30 % above that.
TEST(BareMjcfRange, RangeAgainstAStrongMotorIsStable) {
  constexpr double kH = 0.02;
  const ScratchDir dir;
  const WarningRecorder warnings;  // before loading: nothing writes MUJOCO_LOG.TXT
  ArmChain arm;
  arm.links = 1;
  arm.effort = 5e4;
  arm.range_start = -0.5;
  arm.range_end = 0.5;
  auto bare = load_text(dir, arm_chain(arm), kH);
  ASSERT_NE(bare, nullptr);
  bare->set("speed0", 1.0);
  bare->run(1.0);
  const double angle = bare->qpos("hinge0");
  std::printf("measured (MJCF alone): range [-0.5, 0.5] against 5e4 N m, dt %g: angle %.9f rad after %g s\n",
              kH, angle, bare->d()->time);
  expect_sound(*bare, warnings);
  EXPECT_GT(angle, 0.5);
  EXPECT_LT(angle - 0.5, 1.3 * 6.6e-3);
}

// The gear pair of ratio 2, the input's motor set to 1 rad/s, one step from rest (the runtime: input 1 and
// output / input = 0.5 within 1e-6). Alone the motor is a servo of kv = I_in / h (its (M^-1)_jj = 1 / I_in),
// which a rigid gear makes drive I_in + I_out / ratio^2: the input reaches I_in / (I_in + I_out / 4) = 0.8 of
// its target. The gear is MuJoCo's stiffest joint equality: from rest its row leaves R / (A + R) of the
// unconstrained step's violation (out - in / 2 = -0.5: the input at 1, the output at 0), A = 1 + 1/4 and R
// the row's softness (efc_R): output / input = 0.5 - 1e-4.
TEST(BareMjcfGear, GearAfterOneStep) {
  constexpr double kRatio = 2, kInertia = 1;  // both shafts' (gear_pair)
  for (const double h : {0.002, 0.02}) {
    SCOPED_TRACE("dt " + arm_number(h));
    const ScratchDir dir;
    const WarningRecorder warnings;  // before loading: nothing writes MUJOCO_LOG.TXT
    auto bare = load_text(dir, gear_pair(kRatio), h);
    if (!bare) continue;
    bare->set("speed", 1.0);
    bare->step();
    const double input = bare->qvel("in"), output = bare->qvel("out");
    ASSERT_EQ(bare->d()->nefc, 1);
    ASSERT_EQ(bare->d()->efc_type[0], mjCNSTR_EQUALITY);
    const double a = 1 / kInertia + 1 / (kRatio * kRatio * kInertia), r = bare->d()->efc_R[0];
    const double leak = -0.5 * r / (a + r);
    std::printf(
        "measured (MJCF alone): gear ratio 2, dt %g: input %.6g rad/s, output %.6g rad/s, output / input "
        "%.6g after one step (out - in/2 = %.3g; the row law: %.3g)\n",
        h, input, output, output / input, output - input / kRatio, leak);
    bare->run(1.0);
    expect_sound(*bare, warnings);
    EXPECT_NEAR(input, kInertia / (kInertia + kInertia / (kRatio * kRatio)), 1e-4);
    EXPECT_NEAR(output - input / kRatio, leak, 1e-3 * std::abs(leak));
    EXPECT_NEAR(output / input, 1 / kRatio, 2e-4);
  }
}

// ---------------------------------------------------------------------------------------------------------
// Elastic wheels

// The car on elastic wheels, standing, 0.5 on `steering` for 1 s at dt 0.0005, 0.002, 0.02 (the runtime:
// 0.5 within 1e-6, no SimulationError). Alone the tires' directions are joints held by soft joint equalities
// and the steering column MuJoCo's stiffest joint equality (its target written to eq_data, as the runtime
// writes it): stable, at 0.5 within 1e-7 (1.8e-8 measured at dt 0.02).
TEST(BareMjcfElasticWheel, AckermannSteeringElasticWheelsIsStable) {
  for (const double h : {0.0005, 0.002, 0.02}) {
    SCOPED_TRACE("dt " + arm_number(h));
    const ScratchDir dir;
    const WarningRecorder warnings;  // before loading: nothing writes MUJOCO_LOG.TXT
    auto bare = load_text(dir, car(elastic_steered_car()), h);
    if (!bare) continue;
    bare->set("steering", 0.5);
    bare->run(1.0);
    const double left = bare->qpos("front_left_suspension.mate.steering");
    const double right = bare->qpos("front_right_suspension.mate.steering");
    std::printf(
        "measured (MJCF alone): elastic car, dt %g: steering 0.5 -> left wheel %.9f rad (right %.6f) at t = "
        "%g s\n",
        h, left, right, bare->d()->time);
    expect_sound(*bare, warnings);
    EXPECT_NEAR(left, 0.5, 1e-7);
  }
}

// The assembly test's elastic car (1.6 m chassis) driven at 4 rad/s for 5 s at dt 0.02 (the runtime: over
// 2 m, 7.2 m measured, upright, no SimulationError). Alone the rear motors are servos of kv = 1 / (n h
// (M^-1)_jj): stable, over 2 m (4.33 measured), upright.
TEST(BareMjcfElasticWheel, CarOnElasticWheelsDrivingFiveSecondsAtDt002IsStable) {
  constexpr double kH = 0.02;
  const ScratchDir dir;
  Car c = elastic_steered_car();
  c.chassis_width = 1.6;
  const WarningRecorder warnings;  // before loading: nothing writes MUJOCO_LOG.TXT
  auto bare = load_text(dir, car(c), kH);
  ASSERT_NE(bare, nullptr);
  const int chassis = bare->body("chassis");
  ASSERT_GE(chassis, 0);
  const double start = bare->d()->xpos[3 * chassis];
  bare->set("speed", 4.0);
  bare->run(5.0);
  mj_forward(bare->m(), bare->d());  // after mj_step, MuJoCo's positions are those the step started from
  const double moved = bare->d()->xpos[3 * chassis] - start, up = bare->d()->xmat[9 * chassis + 8];
  std::printf(
      "measured (MJCF alone): elastic car, dt %g: moved %.4g m in %g s (rear wheels %.3g, %.3g rad/s), "
      "chassis "
      "z axis . world z = %.6f\n",
      kH, moved, bare->d()->time, bare->qvel("rear_left_suspension.mate.spin"),
      bare->qvel("rear_right_suspension.mate.spin"), up);
  expect_sound(*bare, warnings);
  EXPECT_GT(std::abs(moved), 2.0);
  EXPECT_GT(up, 0.9);
}

}  // namespace
