// What stepping costs once the runtime owns MuJoCo's constraint rows (AGX's SPOOK law for velocity motors,
// springs, ranges and gears, written from the process-wide mjcb_control a SignalBridge installs:
// runtime/constraint_rows.h, runtime/row_hook.h, ../shared/design/owned-rows.md). Ratios measured side by
// side in one run, interleaved, best of kRepetitions; nothing here asserts a time.
//
// 1. The 7-link arm holding itself horizontal (tests/support/arm_chain.h: 1 kg boxes 0.3 m long, hinges
//    about y, a RotationalVelocityMotor of +-200 N m and target 0 per hinge), emitted by openplx2mjcf and
//    stepped through a SignalBridge, against a hand-written MJCF of the same bodies, geoms and hinges with
//    an explicit <velocity> servo per hinge (kv = 1 / (n h (M^-1)_jj), forcelimited +-200) under plain
//    mj_step. Target: the bridge at >= 0.6x the servo's steps/s. The hold error shows the servo cannot
//    hold the arm (its kv must stay small for explicit Euler to be stable) while the rows do.
// 2. Samples with runtime laws: "before" is the emitted MJCF alone under plain mj_step (what a user without
//    the runtime gets: its stand-in actuators), "after" the same MJCF with a SignalBridge attached, and the
//    same model through Simulation::load + step().
//
//   cmake --build build --target stepping_bench && build/bench/stepping_bench
//
// Plain mj_step runs clear mjcb_control while they step (and restore it after): a program without the
// runtime has no hook, and the bridge's hook, once installed, stays installed for the whole process.
#include <stdlib.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "openplx/runtime/signal_bridge.h"
#include "openplx/runtime/simulation.h"
#include "tests/support/arm_chain.h"
#include "tools/cli/cli.h"

namespace rt = openplx::runtime;
namespace fs = std::filesystem;

namespace {

constexpr double kTimestep = 0.002;
constexpr int kRepetitions = 9;
constexpr int kArmSteps = 10000;  // 20 s held

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// A fresh folder for the emitted files, removed at exit.
struct TempDir {
  fs::path path;
  TempDir() {
    std::string pattern = (fs::temp_directory_path() / "openplx_stepping_bench_XXXXXX").string();
    if (!mkdtemp(pattern.data())) throw std::runtime_error("cannot create a folder " + pattern);
    path = pattern;
  }
  ~TempDir() {
    std::error_code ignored;
    fs::remove_all(path, ignored);
  }
};

// openplx2mjcf FILE -o XML --timestep 0.002, in process; the manifest lands beside it as XML's
// .signals.json.
void emit(const fs::path& file, const fs::path& xml) {
  std::ostringstream out, err;
  if (openplx::cli::run({file.string(), "-o", xml.string(), "--timestep", std::to_string(kTimestep)}, out,
                        err) != 0) {
    throw std::runtime_error("openplx2mjcf " + file.string() + " failed:\n" + err.str());
  }
}

fs::path manifest_of(const fs::path& xml) {
  fs::path manifest = xml;
  return manifest.replace_extension(".signals.json");
}

mjModel* load_xml(const fs::path& xml) {
  char error[1000] = "";
  mjModel* m = mj_loadXML(xml.c_str(), nullptr, error, sizeof(error));
  if (!m) throw std::runtime_error(xml.string() + ": " + error);
  return m;
}

mjModel* load_xml_text(const fs::path& xml, const std::string& text) {
  std::ofstream(xml) << text;
  return load_xml(xml);
}

// The initial state a Simulation starts from: the emitter's "initial" keyframe when there is one.
void reset(const mjModel* m, mjData* d) {
  const int key = mj_name2id(m, mjOBJ_KEY, "initial");
  if (key >= 0) {
    mj_resetDataKeyframe(m, d, key);
  } else {
    mj_resetData(m, d);
  }
}

// One way of stepping one model: the best time over the repetitions and what its steps did.
struct Result {
  const char* label = "";
  double seconds = 1e300;  // best of the timed repetitions
  int steps = 0, nv = 0;
  double iterations = 0;      // mean d->solver_iter per step: the step's final solve only
  double all_iterations = 0;  // mean iterations per step over every solve (the counting pass)
  double solves = 0;          // mean mj_fwdConstraint calls per step that had rows to solve
  double hold = 0;            // after the run: max |qpos| over the hinges
  double rate() const { return steps / seconds; }
};

double hinge_hold_error(const mjModel* m, const mjData* d) {
  double worst = 0;
  for (int j = 0; j < m->njnt; ++j) {
    if (m->jnt_type[j] == mjJNT_HINGE) worst = std::max(worst, std::abs(d->qpos[m->jnt_qposadr[j]]));
  }
  return worst;
}

// The counting pass: every solve's iterations, the rows' extra solves inside mjcb_control included. MuJoCo
// 2.2.2 calls mjcb_time at the start and end of each timed stage; mj_fwdConstraint is one, and counts
// mjTIMER_CONSTRAINT after a solve of rows. A solve's d->solver_iter stands until the next solve clears
// it, which is after that solve's own first mjcb_time call: so the call that first sees the count risen
// still reads the finished solve's iterations. Untimed, as mjcb_time makes MuJoCo time every stage.
mjData* counted = nullptr;
int counted_solves = 0;
long counted_iterations = 0;

mjtNum count_solves() {
  if (counted && counted->timer[mjTIMER_CONSTRAINT].number != counted_solves) {
    counted_solves = counted->timer[mjTIMER_CONSTRAINT].number;
    counted_iterations += counted->solver_iter;
  }
  return 0;
}

enum class Pass { Timed, Counted };

// `steps` calls of `step` on (m, d), from the state they are in, into `r`.
void run_steps(Pass pass, Result& r, const mjModel* m, mjData* d, int steps,
               const std::function<void()>& step) {
  if (pass == Pass::Counted) {
    counted = d;
    counted_solves = d->timer[mjTIMER_CONSTRAINT].number;
    counted_iterations = 0;
    mjcb_time = count_solves;
    for (int k = 0; k < steps; ++k) step();
    count_solves();
    mjcb_time = nullptr;
    counted = nullptr;
    r.all_iterations = static_cast<double>(counted_iterations) / steps;
    return;
  }
  long iterations = 0;
  const int solves = d->timer[mjTIMER_CONSTRAINT].number;
  const auto start = std::chrono::steady_clock::now();
  for (int k = 0; k < steps; ++k) {
    step();
    iterations += d->solver_iter;
  }
  r.seconds = std::min(r.seconds, seconds_since(start));
  r.steps = steps;
  r.nv = m->nv;
  r.iterations = static_cast<double>(iterations) / steps;
  r.solves = static_cast<double>(d->timer[mjTIMER_CONSTRAINT].number - solves) / steps;
  r.hold = hinge_hold_error(m, d);
}

// Plain mj_step on fresh data, with no hook.
void run_plain(Pass pass, Result& r, const mjModel* m, int steps) {
  mjData* d = mj_makeData(m);
  reset(m, d);
  const mjfGeneric hook = mjcb_control;
  mjcb_control = nullptr;
  run_steps(pass, r, m, d, steps, [m, d] { mj_step(m, d); });
  mjcb_control = hook;
  mj_deleteData(d);
}

// The user's own mj_step with a bridge attached to fresh data (the bridge goes before its data).
void run_bridge(Pass pass, Result& r, mjModel* m, const fs::path& manifest, int steps) {
  mjData* d = mj_makeData(m);
  reset(m, d);
  {
    rt::SignalBridge bridge = rt::SignalBridge::attach(manifest.string(), m, d);
    run_steps(pass, r, m, d, steps, [&bridge, m, d] {
      bridge.before_step();
      mj_step(m, d);
      bridge.after_step();
    });
  }
  mj_deleteData(d);
}

// A freshly loaded Simulation (its load is not timed).
void run_simulation(Pass pass, Result& r, const fs::path& file, int steps) {
  rt::LoadOptions options;
  options.timestep = kTimestep;
  rt::Simulation sim = rt::Simulation::load(file.string(), options);
  run_steps(pass, r, sim.model(), sim.data(), steps, [&sim] { sim.step(); });
}

// The arm of tests/support/arm_chain.h written by hand; `kv` empty: no actuators.
std::string servo_arm_xml(const std::vector<double>& kv) {
  using openplx::testing::arm_number;
  const int n = 7;
  const std::string half = arm_number(openplx::testing::kArmLinkLength / 2);
  const std::string width = arm_number(openplx::testing::kArmLinkWidth / 2);
  std::string x = "<mujoco model=\"servo_arm\">\n  <option timestep=\"" + arm_number(kTimestep) +
                  "\" gravity=\"0 0 -9.81\" integrator=\"Euler\"/>\n  <worldbody>\n";
  std::string close;
  for (int k = 0; k < n; ++k) {
    const std::string indent(4 + 2 * k, ' ');
    x += indent + "<body name=\"link" + std::to_string(k) + "\" pos=\"" +
         (k == 0 ? half : arm_number(openplx::testing::kArmLinkLength)) + " 0 0\">\n";
    x += indent + "  <joint name=\"hinge" + std::to_string(k) + "\" type=\"hinge\" pos=\"-" + half +
         " 0 0\" axis=\"0 1 0\"/>\n";
    x += indent + "  <geom type=\"box\" size=\"" + half + " " + width + " " + width + "\" mass=\"" +
         arm_number(openplx::testing::kArmLinkMass) + "\"/>\n";
    close = indent + "</body>\n" + close;
  }
  x += close + "  </worldbody>\n";
  if (!kv.empty()) {
    x += "  <actuator>\n";
    for (int k = 0; k < n; ++k) {
      x += "    <velocity joint=\"hinge" + std::to_string(k) + "\" kv=\"" + arm_number(kv[k]) +
           "\" forcelimited=\"true\" forcerange=\"-200 200\"/>\n";
    }
    x += "  </actuator>\n";
  }
  return x + "</mujoco>\n";
}

// kv_j = 1 / (n h (M^-1)_jj) at qpos0, the emitter's stand-in gain: explicit Euler stays stable with all n
// servos together, as h times the largest eigenvalue of M^-1 diag(kv) is at most h trace(M^-1 diag(kv)) = 1.
std::vector<double> servo_gains(const fs::path& dir) {
  mjModel* m = load_xml_text(dir / "servo_arm_bare.xml", servo_arm_xml({}));
  mjData* d = mj_makeData(m);
  mj_forward(m, d);
  std::vector<double> kv(m->nv), unit(m->nv), column(m->nv);
  for (int j = 0; j < m->nv; ++j) {
    std::fill(unit.begin(), unit.end(), 0.0);
    unit[j] = 1;
    mj_solveM(m, d, column.data(), unit.data(), 1);
    kv[j] = 1 / (m->nv * m->opt.timestep * column[j]);
  }
  mj_deleteData(d);
  mj_deleteModel(m);
  return kv;
}

void print_header(const char* first) {
  std::printf("%-40s %3s %9s %7s %10s %9s %7s %9s\n", first, "nv", "steps/s", "ratio", "final iter",
              "all iter", "solves", "hold rad");
}

void print_row(const Result& r, const Result& base, bool hold) {
  std::printf("%-40s %3d %9.0f %6.3fx %10.2f %9.2f %7.2f", r.label, r.nv, r.rate(), r.rate() / base.rate(),
              r.iterations, r.all_iterations, r.solves);
  if (hold) {
    std::printf(" %9.3g\n", r.hold);
  } else {
    std::printf(" %9s\n", "-");
  }
}

struct Sample {
  Sample(const char* sample, fs::path source, int n) : name(sample), file(std::move(source)), steps(n) {}
  const char* name;
  fs::path file;
  int steps;  // per repetition: about 0.1 s or more of stepping
  fs::path xml;
  mjModel* before = nullptr;  // stepped alone
  mjModel* after = nullptr;   // a separate copy: attaching takes over its stand-ins
  Result plain, bridge, simulation;
};

int run() {
  const TempDir dir;

  // 1. The arm.
  const fs::path arm_file = dir.path / "arm.openplx";
  std::ofstream(arm_file) << openplx::testing::arm_chain(openplx::testing::ArmChain{});
  const fs::path arm_xml = dir.path / "arm.xml";
  emit(arm_file, arm_xml);
  mjModel* arm = load_xml(arm_xml);
  const std::vector<double> kv = servo_gains(dir.path);
  mjModel* servo = load_xml_text(dir.path / "servo_arm.xml", servo_arm_xml(kv));
  Result arm_servo{"hand-written <velocity> servo, mj_step"};
  Result arm_bridge{"emitted + SignalBridge (rows), mj_step"};
  Result arm_simulation{"Simulation::load + step()"};

  // 2. The samples.
  const fs::path source(OPENPLX_SOURCE_DIR);
  std::vector<Sample> samples = {
      {"vehicle_circle", source / "samples/vehicle_circle.openplx", 10000},
      {"drivetrain_machine", source / "samples/drivetrain_machine.openplx", 10000},
      {"LinearSpringTest", source / "tests/corpus/agxunity/LinearSpringTest.openplx", 20000},
  };
  for (Sample& s : samples) {
    s.xml = dir.path / (std::string(s.name) + ".xml");
    emit(s.file, s.xml);
    s.before = load_xml(s.xml);
    s.after = load_xml(s.xml);
    s.plain.label = "before: emitted MJCF alone, mj_step";
    s.bridge.label = "after: + SignalBridge (rows), mj_step";
    s.simulation.label = "after: Simulation::load + step()";
  }

  const auto start = std::chrono::steady_clock::now();
  // The timed repetitions, interleaved (the best of each), then one untimed counting pass.
  for (int round = 0; round <= kRepetitions; ++round) {
    const Pass pass = round < kRepetitions ? Pass::Timed : Pass::Counted;
    run_plain(pass, arm_servo, servo, kArmSteps);
    run_bridge(pass, arm_bridge, arm, manifest_of(arm_xml), kArmSteps);
    run_simulation(pass, arm_simulation, arm_file, kArmSteps);
    for (Sample& s : samples) {
      run_plain(pass, s.plain, s.before, s.steps);
      run_bridge(pass, s.bridge, s.after, manifest_of(s.xml), s.steps);
      run_simulation(pass, s.simulation, s.file, s.steps);
    }
  }
  const double total = seconds_since(start);

  std::printf(
      "stepping_bench: MuJoCo %s, h = %g s, best of %d interleaved repetitions from the initial state\n",
      mj_versionString(), kTimestep, kRepetitions);
  std::printf(
      "columns: nv = degrees of freedom; steps/s = steps / best wall time (steady clock); ratio = steps/s\n"
      "  over the section's first row; per step, means: final iter = d->solver_iter (the step's final solve\n"
      "  only: the rows' extra solves inside mjcb_control are not in it), all iter = iterations of every\n"
      "  solve (an untimed pass counting each mj_fwdConstraint through mjcb_time), solves = solves of rows\n"
      "  (MuJoCo's constraint timer count; 0: no rows); hold rad = max |hinge angle| after the run\n\n");
  std::printf(
      "1. 7-link arm holding itself horizontal, +-200 N m velocity motors at target 0, %d steps (%g s)\n",
      kArmSteps, kArmSteps * kTimestep);
  std::printf("   servo kv = 1 / (7 h (M^-1)_jj) = %.3g .. %.3g N m s; target: rows >= 0.6x the servo\n",
              *std::min_element(kv.begin(), kv.end()), *std::max_element(kv.begin(), kv.end()));
  print_header("");
  for (const Result* r : {&arm_servo, &arm_bridge, &arm_simulation}) print_row(*r, arm_servo, true);

  std::printf("\n2. Samples with runtime laws; ratio = after / before\n");
  for (const Sample& s : samples) {
    char title[80];
    std::snprintf(title, sizeof(title), "%s, %d steps (%g s)", s.name, s.steps, s.steps * kTimestep);
    print_header(title);
    for (const Result* r : {&s.plain, &s.bridge, &s.simulation}) print_row(*r, s.plain, false);
  }
  std::printf("\n(%.1f s for all the passes, Simulation loads included)\n", total);

  for (Sample& s : samples) {
    mj_deleteModel(s.before);
    mj_deleteModel(s.after);
  }
  mj_deleteModel(servo);
  mj_deleteModel(arm);
  return 0;
}

}  // namespace

int main() {
  try {
    return run();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "stepping_bench: %s\n", e.what());
    return 1;
  }
}
