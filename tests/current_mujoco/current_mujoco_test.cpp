// Every corpus model, URDF robot and sample, as openplx2mjcf emits it, loads in current MuJoCo (the official
// WebAssembly build, mujoco-js pinned in package.json, MuJoCo 3.3.8) with the body poses MuJoCo 2.2.2 gives
// (1e-9), and contact-free models follow the same trajectory for 1 s (the largest difference is printed:
// round-off grows through 500 steps, 1e-6 bounds it). ./test.sh installs Node and the module
// (tools/install-deps.sh --tests); without them this test fails and says so.
#include <mujoco/mujoco.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>

#include "tests/support/scratch_dir.h"
#include "tests/support/soft_lock_scene.h"
#include "tools/cli/cli.h"

namespace {

namespace fs = std::filesystem;

constexpr int kSteps = 500;  // 1 s at the emitted 0.002 s step

struct Outcome {
  bool ok = false;
  std::string error;
  int nbody = 0, ncon = 0;
  std::vector<double> start, end;  // xpos then xquat, after mj_forward and after kSteps
};

std::vector<double> poses(const mjModel* m, const mjData* d) {
  std::vector<double> v(d->xpos, d->xpos + 3 * m->nbody);
  v.insert(v.end(), d->xquat, d->xquat + 4 * m->nbody);
  return v;
}

Outcome run_mujoco2(const std::string& file, int steps = kSteps) {
  Outcome r;
  char error[1000] = "";
  mjModel* m = mj_loadXML(file.c_str(), nullptr, error, sizeof(error));
  if (!m) {
    r.error = error;
    return r;
  }
  mjData* d = mj_makeData(m);
  mj_forward(m, d);
  r.start = poses(m, d);
  r.ncon = d->ncon;
  for (int k = 0; k < steps; ++k) {
    mj_step(m, d);
    r.ncon = std::max(r.ncon, d->ncon);
  }
  r.end = poses(m, d);
  r.nbody = m->nbody;
  r.ok = true;
  mj_deleteData(d);
  mj_deleteModel(m);
  return r;
}

// All files in one Node process (the module takes a while to start).
std::map<std::string, Outcome> run_mujoco3(const std::vector<std::string>& files, std::string& failure,
                                           int steps = kSteps) {
  const fs::path dir = fs::path(OPENPLX_TEST_DATA_DIR) / "current_mujoco";
  if (!fs::exists(dir / "node_modules" / "mujoco-js" / "package.json")) {
    failure = "mujoco-js is not installed in " + dir.string() + ": run tools/install-deps.sh --tests";
    return {};
  }
  std::string command = "node '" + (dir / "run_models.mjs").string() + "' " + std::to_string(steps);
  for (const std::string& f : files) command += " '" + f + "'";
  command += " 2>&1";
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
  if (!pipe) {
    failure = "cannot run node";
    return {};
  }
  std::string output;
  char buffer[65536];
  while (size_t n = fread(buffer, 1, sizeof(buffer), pipe.get())) output.append(buffer, n);
  std::map<std::string, Outcome> runs;
  std::istringstream lines(output);
  std::string line;
  while (std::getline(lines, line)) {
    std::istringstream in(line);
    std::string status, file;
    in >> status >> file;
    Outcome r;
    if (status == "ERR") {
      std::getline(in, r.error);
    } else if (status == "OK") {
      r.ok = true;
      in >> r.nbody >> r.ncon;
      for (double v; in >> v;) r.end.push_back(v);
      const size_t half = r.end.size() / 2;
      r.start.assign(r.end.begin(), r.end.begin() + static_cast<long>(half));
      r.end.erase(r.end.begin(), r.end.begin() + static_cast<long>(half));
    } else {
      continue;
    }
    runs[file] = r;
  }
  if (runs.empty()) failure = "node printed no results:\n" + output;
  return runs;
}

// The largest difference of positions and of orientations (quaternions up to sign).
double difference(const std::vector<double>& a, const std::vector<double>& b, int nbody) {
  double most = 0;
  for (int k = 0; k < 3 * nbody; ++k) most = std::max(most, std::abs(a[k] - b[k]));
  for (int body = 0; body < nbody; ++body) {
    double same = 0, flipped = 0;
    for (int c = 0; c < 4; ++c) {
      const size_t i = static_cast<size_t>(3 * nbody + 4 * body + c);
      same = std::max(same, std::abs(a[i] - b[i]));
      flipped = std::max(flipped, std::abs(a[i] + b[i]));
    }
    most = std::max(most, std::min(same, flipped));
  }
  return most;
}

TEST(CurrentMuJoCo, EveryOutputLoadsWithTheSamePosesAndMoves) {
  std::vector<fs::path> sources;
  for (const auto& entry : fs::directory_iterator(fs::path(OPENPLX_CORPUS_DIR) / "agxunity"))
    if (entry.path().extension() == ".openplx") sources.push_back(entry.path());
  for (const auto& entry : fs::recursive_directory_iterator(fs::path(OPENPLX_VENDORED_CORPUS_DIR) / "urdf"))
    if (entry.path().extension() == ".urdf") sources.push_back(entry.path());
  for (const auto& entry : fs::directory_iterator(fs::path(OPENPLX_SAMPLES_DIR)))
    if (entry.path().extension() == ".openplx") sources.push_back(entry.path());
  std::sort(sources.begin(), sources.end());
  const openplx::testing::ScratchDir dir;
  std::vector<std::string> files;
  size_t refused = 0;
  for (const fs::path& source : sources) {
    const std::string out =
        (dir / (std::to_string(files.size()) + "_" + source.stem().string() + ".xml")).string();
    std::vector<std::string> args{source.string(), "-o", out};
    if (source.stem() == "simple_lidar") args.insert(args.end(), {"--model", "ValidLidar"});
    if (source.stem() == "use_test_bundle")
      args.insert(args.end(), {"-B", (source.parent_path() / "TestBundle").string()});
    std::ostringstream text, errors;
    if (openplx::cli::run(args, text, errors) != 0) {
      ++refused;  // errors by design, which other tests check
      continue;
    }
    files.push_back(out);
  }
  std::string failure;
  const std::map<std::string, Outcome> current = run_mujoco3(files, failure);
  ASSERT_TRUE(failure.empty()) << failure;
  size_t contact_free = 0;
  double worst_start = 0, worst_end = 0;
  for (const std::string& file : files) {
    SCOPED_TRACE(file);
    const Outcome old = run_mujoco2(file);
    ASSERT_TRUE(old.ok) << old.error;
    auto it = current.find(file);
    ASSERT_NE(it, current.end());
    const Outcome& now = it->second;
    ASSERT_TRUE(now.ok) << "MuJoCo 3 refused it: " << now.error;
    ASSERT_EQ(now.nbody, old.nbody);
    const double start = difference(old.start, now.start, old.nbody);
    EXPECT_LE(start, 1e-9);
    worst_start = std::max(worst_start, start);
    if (old.ncon == 0 && now.ncon == 0) {
      const double end = difference(old.end, now.end, old.nbody);
      EXPECT_LE(end, 1e-6);
      worst_end = std::max(worst_end, end);
      ++contact_free;
      std::cout << fs::path(file).stem().string() << ": contact-free, 1 s apart by " << end << "\n";
    }
  }
  std::cout << files.size() << " outputs compared (" << refused << " sources refused by design), "
            << contact_free << " contact-free; largest pose difference at t=0: " << worst_start
            << ", after 1 s (contact-free): " << worst_end << "\n";
  EXPECT_GE(files.size(), 35u);
}

// A model emitted with the 2.2 law and with --mujoco 3, each run 5 s: in MuJoCo 2.2.2 (the 2.2 file) and in
// 3.3.8 (both files, so the test can show what the wrong law gives).
struct InBothVersions {
  bool ok = false;
  std::string failure;
  Outcome mujoco2, mujoco3, mujoco3_with_22_law;
};

InBothVersions simulate_in_both_versions(const fs::path& model, const fs::path& dir) {
  InBothVersions run;
  const std::string for2 = (dir / (model.stem().string() + "_2.xml")).string();
  const std::string for3 = (dir / (model.stem().string() + "_3.xml")).string();
  for (const auto& args : {std::vector<std::string>{model.string(), "-o", for2},
                           std::vector<std::string>{model.string(), "-o", for3, "--mujoco", "3"}}) {
    std::ostringstream text, errors;
    if (openplx::cli::run(args, text, errors) != 0) {
      run.failure = errors.str();
      return run;
    }
  }
  constexpr int kFiveSeconds = 2500;
  run.mujoco2 = run_mujoco2(for2, kFiveSeconds);
  const std::map<std::string, Outcome> now = run_mujoco3({for2, for3}, run.failure, kFiveSeconds);
  if (!run.mujoco2.ok) run.failure += run.mujoco2.error;
  if (!run.failure.empty()) return run;
  run.mujoco3 = now.at(for3);
  run.mujoco3_with_22_law = now.at(for2);
  run.ok = run.mujoco3.ok && run.mujoco3_with_22_law.ok;
  if (!run.ok) run.failure = run.mujoco3.error + run.mujoco3_with_22_law.error;
  return run;
}

// docs/mapping.md "MuJoCo versions": a 2 kg box on a vertical slide hung from a 2000 N/m flexible Lock
// settles m g / k = 9.81 mm low in 2.2.2 with the default law, and in 3.x only with --mujoco 3 (3.x gives
// this "simple" body dA = 1/m, three times 2.2.2's). Within 1 % after 5 s in both.
TEST(CurrentMuJoCo, SoftLockSettlesAtItsSpringLengthInBothVersions) {
  const openplx::testing::ScratchDir dir;
  const auto model = dir / "soft_lock.openplx";
  std::ofstream(model) << openplx::testing::kSoftLockScene;
  const InBothVersions run = simulate_in_both_versions(model, dir.path());
  ASSERT_TRUE(run.ok) << run.failure;
  const double expected = -2 * 9.81 / 2000;
  auto sag = [](const Outcome& r) { return r.end[5] - r.start[5]; };  // the box's (body 1) z
  EXPECT_NEAR(sag(run.mujoco2), expected, 0.01 * std::abs(expected));
  EXPECT_NEAR(sag(run.mujoco3), expected, 0.01 * std::abs(expected));
  std::cout << "soft Lock sag (m g / k = " << expected << " m): MuJoCo 2.2.2 " << sag(run.mujoco2)
            << ", 3.3.8 with --mujoco 3 " << sag(run.mujoco3) << ", 3.3.8 with the 2.2 law "
            << sag(run.mujoco3_with_22_law) << "\n";
}

// docs/mapping.md "MuJoCo versions": a 2 kg, 0.4 m arm on a hinge about y, held level by a 2000 N m/rad
// flexible Lock at the hinge, sags m g r / k = 2 * 9.81 * 0.2 / 2000 = 1.962 mrad (MuJoCo's rotational row
// gets k_rot from torquescale; 3.x squares it against its rotational dA, hence --mujoco 3's torquescale).
// Within 1 %.
TEST(CurrentMuJoCo, SoftLockHoldsItsRotationalStiffnessInBothVersions) {
  const openplx::testing::ScratchDir dir;
  const auto model = dir / "soft_lock_rot.openplx";
  std::ofstream(model)
      << "Arm is Physics3D.Bodies.RigidBody:\n"
         "    inertia.mass: 2\n"
         "    geometry is Physics3D.Geometries.Box:\n"
         "        size: {0.4, 0.05, 0.05}\n"
         "    c is Physics3D.Interactions.MateConnector:\n"
         "        position.x: -0.2\n"
         "        main_axis: Math.Vec3.Y_AXIS()\n"
         "        normal: Math.Vec3.X_AXIS()\n"
         "Scene is Physics3D.System:\n"
         "    w is Physics3D.Interactions.MateConnector:\n"
         "        main_axis: Math.Vec3.Y_AXIS()\n"
         "        normal: Math.Vec3.X_AXIS()\n"
         "    arm is Arm\n"
         "    hinge is Physics3D.Interactions.Hinge:\n"
         "        connectors: [w, arm.c]\n"
         "    lock is Physics3D.Interactions.Lock:\n"
         "        connectors: [w, arm.c]\n"
         "        flexibility becomes Physics3D.Interactions.Flexibility.LinearElasticLockFlexibility:\n"
         "            default_stiffness: 2000\n";
  const InBothVersions run = simulate_in_both_versions(model, dir.path());
  ASSERT_TRUE(run.ok) << run.failure;
  const double expected = 2 * 9.81 * 0.2 / 2000;
  auto angle = [](const Outcome& r) {  // the arm's (body 1) turn about y, from its quaternion
    const size_t q = static_cast<size_t>(3 * r.nbody + 4);
    return 2 * std::atan2(r.end[q + 2], r.end[q]);
  };
  EXPECT_NEAR(angle(run.mujoco2), expected, 0.01 * expected);
  EXPECT_NEAR(angle(run.mujoco3), expected, 0.01 * expected);
  std::cout << "soft Lock rotation (m g r / k = " << expected << " rad): MuJoCo 2.2.2 " << angle(run.mujoco2)
            << ", 3.3.8 with --mujoco 3 " << angle(run.mujoco3) << ", 3.3.8 with the 2.2 law "
            << angle(run.mujoco3_with_22_law) << "\n";
}

}  // namespace
