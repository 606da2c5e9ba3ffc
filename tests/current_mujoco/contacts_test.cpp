// Contacts in MuJoCo 2.2.2 and current 3.x (mujoco-js, MuJoCo 3.3.8): three cases emitted by openplx2mjcf,
// run with plain mj_step in 2.2.2 here and in 3.x through run_contacts.mjs, with and without --mujoco 3.
// - samples/vehicle_circle driven as its manifest says (speed 8 rad/s, steering 0.3 rad) for 3 s: four
//   cylinders on a box ground, the pairs 3.3's native GJK/EPA collides differently from 2.2.2's MPR.
// - a box sliding down a slope (box-box): a = g (sin t - mu cos t).
// - a solid wheel rolling down a slope (cylinder-box): a = 2/3 g sin t, spin = speed / radius.
// docs/mapping.md "Contacts in 3.x" has the measured table. ./test.sh installs Node and the module
// (tools/install-deps.sh --tests); without them these tests fail and say so.
#include <mujoco/mujoco.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/scratch_dir.h"
#include "tools/cli/cli.h"

namespace {

namespace fs = std::filesystem;

constexpr double kG = 9.81;
constexpr double kSlope = M_PI / 6;  // both slope models

// A body's state at one step: position, its free joint's velocity (linear in world axes, angular in the
// body's), the most contacts seen so far.
struct State {
  std::array<double, 3> x{}, v{}, w{};
  int ncon = 0;
};
using Trace = std::map<int, State>;  // by step

// `ctrl:NAME=VALUE` / `eq:NAME=VALUE`, applied once before the first step (run_contacts.mjs reads the same).
struct Setting {
  std::string kind, name;
  double value;
};

Trace run_in_2_2(const std::string& file, const std::string& body, const std::vector<int>& steps,
                 const std::vector<Setting>& settings, std::string& failure) {
  char error[1000] = "";
  mjModel* m = mj_loadXML(file.c_str(), nullptr, error, sizeof(error));
  if (!m) {
    failure = error;
    return {};
  }
  mjData* d = mj_makeData(m);
  for (const Setting& s : settings) {
    if (s.kind == "ctrl") d->ctrl[mj_name2id(m, mjOBJ_ACTUATOR, s.name.c_str())] = s.value;
    if (s.kind == "eq") m->eq_data[mjNEQDATA * mj_name2id(m, mjOBJ_EQUALITY, s.name.c_str())] = s.value;
  }
  const int b = mj_name2id(m, mjOBJ_BODY, body.c_str());
  const int dof = m->jnt_dofadr[m->body_jntadr[b]];
  mj_forward(m, d);
  Trace run;
  int ncon = d->ncon;
  for (int k = 0; k <= steps.back(); ++k) {
    if (std::find(steps.begin(), steps.end(), k) != steps.end()) {
      State& s = run[k];
      for (int i = 0; i < 3; ++i) {
        s.x[i] = d->xpos[3 * b + i];
        s.v[i] = d->qvel[dof + i];
        s.w[i] = d->qvel[dof + 3 + i];
      }
      s.ncon = ncon;
    }
    mj_step(m, d);
    ncon = std::max(ncon, d->ncon);
  }
  mj_deleteData(d);
  mj_deleteModel(m);
  return run;
}

// Each file in current MuJoCo, in one Node process; by file.
std::map<std::string, Trace> run_in_3(const std::vector<std::string>& files, const std::string& body,
                                      const std::vector<int>& steps, const std::vector<Setting>& settings,
                                      std::string& failure) {
  const fs::path dir = fs::path(OPENPLX_TEST_DATA_DIR) / "current_mujoco";
  if (!fs::exists(dir / "node_modules" / "mujoco-js" / "package.json")) {
    failure = "mujoco-js is not installed in " + dir.string() + ": run tools/install-deps.sh --tests";
    return {};
  }
  std::string list;
  for (int k : steps) list += (list.empty() ? "" : ",") + std::to_string(k);
  std::string command = "node '" + (dir / "run_contacts.mjs").string() + "' '" + body + "' " + list;
  for (const std::string& file : files) command += " '" + file + "'";
  for (const Setting& s : settings) {
    std::ostringstream value;
    value.precision(17);
    value << s.value;
    command += " '" + s.kind + ":" + s.name + "=" + value.str() + "'";
  }
  command += " 2>&1";
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
  if (!pipe) {
    failure = "cannot run node";
    return {};
  }
  std::string output;
  char buffer[4096];
  while (size_t n = fread(buffer, 1, sizeof(buffer), pipe.get())) output.append(buffer, n);
  std::map<std::string, Trace> runs;
  std::istringstream lines(output);
  for (std::string line; std::getline(lines, line);) {
    std::istringstream in(line);
    std::string tag, file;
    int k = 0;
    State s;
    if (!(in >> tag >> file >> k) || tag != "AT") continue;
    for (double* v : {&s.x[0], &s.x[1], &s.x[2], &s.v[0], &s.v[1], &s.v[2], &s.w[0], &s.w[1], &s.w[2]})
      in >> *v;
    in >> s.ncon;
    runs[file][k] = s;
  }
  for (const std::string& file : files)
    if (runs[file].size() != steps.size()) failure = "run_contacts.mjs: " + output;
  return runs;
}

// The model emitted for 2.2 (the default) and with --mujoco 3 into `dir`.
struct Files {
  std::string for2, for3, failure;
};

Files emit_both(const fs::path& model, const fs::path& dir) {
  Files files{(dir / (model.stem().string() + "_2.xml")).string(),
              (dir / (model.stem().string() + "_3.xml")).string(), ""};
  for (const auto& args : {std::vector<std::string>{model.string(), "-o", files.for2},
                           std::vector<std::string>{model.string(), "-o", files.for3, "--mujoco", "3"}}) {
    std::ostringstream text, errors;
    if (openplx::cli::run(args, text, errors) != 0) files.failure += errors.str();
  }
  return files;
}

// One case in both versions: 2.2.2 on the 2.2 file; 3.x on the --mujoco 3 file and on the 2.2 file (what
// --mujoco 3 changes).
struct Compared {
  Trace mujoco2, mujoco3, mujoco3_without;
  std::string failure;
};

Compared compare(const fs::path& model, const fs::path& dir, const std::string& body,
                 const std::vector<int>& steps, const std::vector<Setting>& settings = {}) {
  Compared c;
  const Files files = emit_both(model, dir);
  c.failure = files.failure;
  if (!c.failure.empty()) return c;
  c.mujoco2 = run_in_2_2(files.for2, body, steps, settings, c.failure);
  std::map<std::string, Trace> now = run_in_3({files.for3, files.for2}, body, steps, settings, c.failure);
  c.mujoco3 = now[files.for3];
  c.mujoco3_without = now[files.for2];
  return c;
}

double distance(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
}

// Down the slope: both slopes are turned by kSlope about y, descending along +x.
double along(const std::array<double, 3>& v) {
  return v[0] * std::cos(kSlope) - v[2] * std::sin(kSlope);
}

fs::path contact_model(const char* name) {
  return fs::path(OPENPLX_TEST_DATA_DIR) / "current_mujoco" / "contacts" / name;
}

// The file --mujoco 3 writes carries the flag only 3.x reads, and --check (MuJoCo 2.2.2) still passes.
TEST(MuJoCo3Contacts, TheFlagIsInTheMuJoCo3FileOnlyAndCheckStillLoadsIt) {
  const openplx::testing::ScratchDir dir;
  const fs::path model = fs::path(OPENPLX_SAMPLES_DIR) / "vehicle_circle.openplx";
  const Files files = emit_both(model, dir.path());
  ASSERT_TRUE(files.failure.empty()) << files.failure;
  auto text = [](const std::string& file) {
    std::ostringstream s;
    s << std::ifstream(file).rdbuf();
    return s.str();
  };
  EXPECT_EQ(text(files.for2).find("nativeccd"), std::string::npos);
  EXPECT_NE(text(files.for3).find("<flag nativeccd=\"disable\"/>"), std::string::npos);
  std::ostringstream out, errors;
  EXPECT_EQ(
      openplx::cli::run({model.string(), "--mujoco", "3", "--check", "-o", (dir / "checked.xml").string()},
                        out, errors),
      0)
      << errors.str();
  EXPECT_EQ(errors.str().find("rejects"), std::string::npos) << errors.str();
  EXPECT_EQ(text((dir / "checked.xml").string()), text(files.for3));  // --check wrote what it did not load
}

// vehicle_circle for 3 s at steering 0.3 and speed 8 (the manifest's `steering` holds the steering equality's
// target, `speed` both rear drives' controls). With --mujoco 3 both versions collide the wheels with libccd's
// MPR, and only round-off separates them: the bound is that of the contact-free models after 1 s
// (current_mujoco_test.cpp), 1e-6 m on a path of about 7 m.
TEST(MuJoCo3Contacts, VehicleCircleFollowsTheSamePathInBothVersions) {
  const openplx::testing::ScratchDir dir;
  const int steps = 1500;
  const Compared c =
      compare(fs::path(OPENPLX_SAMPLES_DIR) / "vehicle_circle.openplx", dir.path(), "chassis", {0, steps},
              {{"ctrl", "rear_left_drive", 8},
               {"ctrl", "rear_right_drive", 8},
               {"eq", "steering_system.interaction.angle", 0.3}});
  ASSERT_TRUE(c.failure.empty()) << c.failure;
  const State &old = c.mujoco2.at(steps), &now = c.mujoco3.at(steps), &without = c.mujoco3_without.at(steps);
  EXPECT_GT(distance(old.x, c.mujoco2.at(0).x), 5.0);  // it drove
  EXPECT_LE(distance(now.x, old.x), 1e-6);
  // The case shows the difference: 3.x's own collision takes the car elsewhere.
  EXPECT_GT(distance(without.x, old.x), 0.1);
  std::cout.precision(10);
  std::cout << "vehicle_circle at 3 s: 2.2.2 (" << old.x[0] << ", " << old.x[1] << ", " << old.x[2]
            << "); 3.3.8 with --mujoco 3 (" << now.x[0] << ", " << now.x[1] << ", " << now.x[2] << "), "
            << distance(now.x, old.x) << " m apart; 3.3.8 without (" << without.x[0] << ", " << without.x[1]
            << ", " << without.x[2] << "), " << distance(without.x, old.x) << " m apart\n";
}

// A 1 kg box slides down a 30 degree slope at mu = 0.3: a = g (sin 30 - 0.3 cos 30) = 2.3563 m/s^2, taken
// from the distance it slid in 2 s from rest, a = 2 s / t^2 (Euler's step adds h / t = 0.1 %). MuJoCo's
// pyramidal friction lifts a sliding box (each edge of the pyramid is damped on v_n +- mu v_slip): it rocks
// and hops by about 1 mm, its acceleration over 0.5 s windows swings from -4 % to +3 %, and the distance
// averages that to within 1 % (0.16 % measured). Box-box contacts take the same path in both versions, with
// or without --mujoco 3: the same round-off bound as the car's.
TEST(MuJoCo3Contacts, BoxSlidesDownTheSlopeAtTheAnalyticAccelerationInBothVersions) {
  const openplx::testing::ScratchDir dir;
  const double seconds = 2;
  const int steps = 1000;
  const Compared c = compare(contact_model("box_on_slope.openplx"), dir.path(), "block", {0, steps});
  ASSERT_TRUE(c.failure.empty()) << c.failure;
  const double expected = kG * (std::sin(kSlope) - 0.3 * std::cos(kSlope));
  auto acceleration = [&](const Trace& r) {
    return 2 * (along(r.at(steps).x) - along(r.at(0).x)) / (seconds * seconds);
  };
  const double old = acceleration(c.mujoco2), now = acceleration(c.mujoco3),
               without = acceleration(c.mujoco3_without);
  EXPECT_NEAR(old, expected, 0.01 * expected);
  EXPECT_LE(distance(c.mujoco3.at(steps).x, c.mujoco2.at(steps).x), 1e-6);
  EXPECT_LE(distance(c.mujoco3_without.at(steps).x, c.mujoco2.at(steps).x), 1e-6);
  std::cout.precision(10);
  std::cout << "box on a 30 degree slope, mu 0.3 (g (sin - mu cos) = " << expected << " m/s^2): 2.2.2 " << old
            << ", 3.3.8 with --mujoco 3 " << now << ", without " << without << "; positions at 2 s "
            << distance(c.mujoco3.at(steps).x, c.mujoco2.at(steps).x) << " m apart with, "
            << distance(c.mujoco3_without.at(steps).x, c.mujoco2.at(steps).x) << " m without\n";
}

// A solid 10 kg wheel of radius 0.3 m rolls down the 30 degree slope: rolling without slipping,
// v = 2/3 g sin 30 t = 6.54 m/s at 2 s (0.5 %: Euler's error) and the spin times the radius is that speed,
// less MuJoCo's creep: its soft friction row lets the contact slip at (1 - d) a0 dmax tc / (2 d) = 5.2 mm/s
// (a0 = g sin 30 the slip's acceleration without friction, d = 0.9, dmax = 0.95, tc = 0.02 s; within twice
// that). One contact holds the wheel up at the middle of its line contact, a balance round-off tips (the two
// versions part at 0.3 s, from 1e-17 m): with --mujoco 3 the paths down the slope stay within 3e-4 m (1e-4 of
// the distance rolled; 4.2e-5 measured). Without it 3.x's EPA puts the contact on a rim edge: the wheel
// wobbles, slips at 26 mm/s and ends 2.6e-3 m off.
TEST(MuJoCo3Contacts, WheelRollsDownTheSlopeWithoutSlippingInBothVersions) {
  const openplx::testing::ScratchDir dir;
  const double radius = 0.3, seconds = 2;
  const int steps = 1000;
  const Compared c = compare(contact_model("wheel_on_slope.openplx"), dir.path(), "wheel", {0, steps});
  ASSERT_TRUE(c.failure.empty()) << c.failure;
  const double expected = 2.0 / 3 * kG * std::sin(kSlope) * seconds;
  const double creep = 0.1 * kG * std::sin(kSlope) * 0.95 * 0.02 / (2 * 0.9);
  for (const Trace* r : {&c.mujoco2, &c.mujoco3}) {
    const State& s = r->at(steps);
    EXPECT_NEAR(along(s.v), expected, 5e-3 * expected);
    EXPECT_NEAR(s.w[1] * radius, along(s.v), 2 * creep);  // the spin about the wheel's axis, its local y
  }
  auto rolled = [&](const Trace& r) { return along(r.at(steps).x) - along(r.at(0).x); };
  EXPECT_NEAR(rolled(c.mujoco3), rolled(c.mujoco2), 3e-4);
  std::cout.precision(10);
  std::cout << "wheel on a 30 degree slope at 2 s (2/3 g sin t = " << expected << " m/s): speed 2.2.2 "
            << along(c.mujoco2.at(steps).v) << ", 3.3.8 with --mujoco 3 " << along(c.mujoco3.at(steps).v)
            << ", without " << along(c.mujoco3_without.at(steps).v) << "; spin x radius 2.2.2 "
            << c.mujoco2.at(steps).w[1] * radius << ", with " << c.mujoco3.at(steps).w[1] * radius
            << ", without " << c.mujoco3_without.at(steps).w[1] * radius << "; rolled 2.2.2 "
            << rolled(c.mujoco2) << " m, with " << rolled(c.mujoco3) << ", without "
            << rolled(c.mujoco3_without) << "; roll rate 2.2.2 " << c.mujoco2.at(steps).w[0]
            << " rad/s, with " << c.mujoco3.at(steps).w[0] << ", without " << c.mujoco3_without.at(steps).w[0]
            << "\n";
}

}  // namespace
