#include "tools/urdf_survey/survey_file.h"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "tools/urdf_survey/child_process.h"
#include "tools/urdf_survey/mujoco_urdf.h"
#include "tools/urdf_survey/stub_meshes.h"

namespace openplx::urdf_survey {

namespace fs = std::filesystem;

namespace {

// One line, so the parent can split on tabs and newlines.
std::string one_line(std::string text) {
  for (char& c : text) {
    if (c == '\n' || c == '\r' || c == '\t') c = ' ';
  }
  while (!text.empty() && text.back() == ' ') text.pop_back();
  return text;
}

void report(const char* what, const std::string& state, const std::string& detail) {
  std::printf("%s\t%s\t%s\n", what, state.c_str(), one_line(detail).c_str());
  std::fflush(stdout);
}

// The converter's first error line (the one a user reads first), else its first line.
std::string first_error(const std::string& output) {
  std::stringstream lines(output);
  std::string first;
  for (std::string line; std::getline(lines, line);) {
    if (line.find(": error") != std::string::npos || line.rfind("error", 0) == 0) return line;
    if (first.empty() && !line.empty()) first = line;
  }
  return first;
}

mjModel* load_ours(const fs::path& urdf, const fs::path& work_dir, const FileOptions& options) {
  const fs::path out = work_dir / (urdf.stem().string() + ".ours.xml");
  const ChildResult run =
      run_child({options.converter, urdf.string(), "-o", out.string(), "--check"}, options.converter_timeout);
  if (run.timed_out) {
    char seconds[32];
    std::snprintf(seconds, sizeof(seconds), "%g s", options.converter_timeout);
    report("OURS", "refused", std::string("timeout after ") + seconds);
    return nullptr;
  }
  if (run.signal != 0) {
    report("OURS", "refused", "converter crashed (signal " + std::to_string(run.signal) + ")");
    return nullptr;
  }
  if (run.exit_code != 0) {
    report("OURS", "refused", first_error(run.output));
    return nullptr;
  }
  char error[1000] = "";
  mjModel* m = mj_loadXML(out.c_str(), nullptr, error, sizeof(error));
  if (!m) {
    report("OURS", "refused", std::string("MuJoCo rejects our output: ") + error);
    return nullptr;
  }
  report("OURS", "loaded", "");
  return m;
}

// Body b's world pose at the zero configuration: every hinge and slide at 0, free and ball joints where
// the model puts them.
struct Pose {
  std::array<double, 3> pos;
  std::array<double, 9> rot;
};

std::vector<Pose> zero_configuration(const mjModel* m) {
  mjData* d = mj_makeData(m);
  for (int j = 0; j < m->njnt; ++j) {
    if (m->jnt_type[j] == mjJNT_HINGE || m->jnt_type[j] == mjJNT_SLIDE) d->qpos[m->jnt_qposadr[j]] = 0;
  }
  mj_kinematics(m, d);
  std::vector<Pose> poses(m->nbody);
  for (int b = 0; b < m->nbody; ++b) {
    std::copy_n(d->xpos + 3 * b, 3, poses[b].pos.begin());
    std::copy_n(d->xmat + 9 * b, 9, poses[b].rot.begin());
  }
  mj_deleteData(d);
  return poses;
}

bool relative_near(double a, double b, double tolerance) {
  return std::abs(a - b) <= tolerance * std::max({std::abs(a), std::abs(b), 1e-300});
}

std::string number(double x) {
  char text[40];
  std::snprintf(text, sizeof(text), "%.10g", x);
  return text;
}

// Every body of MuJoCo's model found by name in ours, with the same mass (relative 1e-9), the same
// principal moments (relative 1e-9), and the same world pose at the zero configuration (1e-9).
void compare(const mjModel* ours, const mjModel* theirs) {
  const std::vector<Pose> our_poses = zero_configuration(ours), their_poses = zero_configuration(theirs);
  bool mass_ok = true, pose_ok = true, inertia_ok = true;
  std::string first_mass, first_pose, first_inertia, missing;
  double worst_pose = 0;
  int compared = 0;
  for (int b = 1; b < theirs->nbody; ++b) {
    const char* name = mj_id2name(theirs, mjOBJ_BODY, b);
    const int o = name ? mj_name2id(ours, mjOBJ_BODY, name) : -1;
    if (o < 0) {
      if (missing.empty()) missing = name ? name : "(unnamed)";
      pose_ok = mass_ok = inertia_ok = false;
      continue;
    }
    ++compared;
    const double a = ours->body_mass[o], c = theirs->body_mass[b];
    if (!relative_near(a, c, 1e-9) && std::abs(a - c) > 1e-300) {
      if (mass_ok) first_mass = std::string(name) + " " + number(a) + " vs " + number(c);
      mass_ok = false;
    }
    std::array<double, 3> ia{}, ic{};
    std::copy_n(ours->body_inertia + 3 * o, 3, ia.begin());
    std::copy_n(theirs->body_inertia + 3 * b, 3, ic.begin());
    std::sort(ia.begin(), ia.end());
    std::sort(ic.begin(), ic.end());
    for (int k = 0; k < 3; ++k) {
      if (!relative_near(ia[k], ic[k], 1e-9) && std::abs(ia[k] - ic[k]) > 1e-300) {
        if (inertia_ok) {
          first_inertia = std::string(name) + " (" + number(ia[0]) + " " + number(ia[1]) + " " +
                          number(ia[2]) + ") vs (" + number(ic[0]) + " " + number(ic[1]) + " " +
                          number(ic[2]) + ")";
        }
        inertia_ok = false;
        break;
      }
    }
    double distance = 0, turn = 0;
    for (int k = 0; k < 3; ++k) distance += std::pow(our_poses[o].pos[k] - their_poses[b].pos[k], 2);
    for (int k = 0; k < 9; ++k) turn += std::pow(our_poses[o].rot[k] - their_poses[b].rot[k], 2);
    const double error = std::max(std::sqrt(distance), std::sqrt(turn));
    if (error > 1e-9 && error > worst_pose) {
      worst_pose = error;
      first_pose = std::string(name) + " off by " + number(std::sqrt(distance)) + " m, " +
                   number(std::sqrt(turn)) + " (rotation)";
      pose_ok = false;
    }
  }
  std::string detail = std::to_string(compared) + " bodies";
  if (!missing.empty()) detail += "; missing in ours: " + missing;
  if (!mass_ok) detail += "; mass: " + first_mass;
  if (!inertia_ok) detail += "; inertia: " + first_inertia;
  if (!pose_ok && !first_pose.empty()) detail += "; pose: " + first_pose;
  std::printf("PARITY\t%s\t%d\t%d\t%d\t%s\n", mass_ok && pose_ok && inertia_ok ? "ok" : "mismatch", mass_ok,
              pose_ok, inertia_ok, one_line(detail).c_str());
  std::fflush(stdout);
}

}  // namespace

void survey_file(const fs::path& original, const fs::path& work_dir, const FileOptions& options) {
  fs::path urdf = original;
  if (options.stub_missing_meshes) {
    int stubbed = 0;
    urdf = stub_missing_meshes(original, work_dir, stubbed);
    if (stubbed > 0) report("STUBS", std::to_string(stubbed), "");
  }
  mjModel* ours = load_ours(urdf, work_dir, options);
  std::string error;
  mjModel* theirs = load_with_mujoco(urdf, work_dir, error);
  report("MUJOCO", theirs ? "loaded" : "refused", error);
  if (ours && theirs) compare(ours, theirs);
  if (ours) mj_deleteModel(ours);
  if (theirs) mj_deleteModel(theirs);
}

}  // namespace openplx::urdf_survey
