// The `openplx2mjcf` command line, callable in-process so tests run it under the sanitizers.
//
//   openplx2mjcf FILE [options] (usage() lists them all; README "Command line" too)
//
// Exit status: 0 success (warnings allowed), 1 input errors (diagnostics on `err`), 2 usage errors.
#pragma once

#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "mjcf_emitter/placement.h"

namespace openplx::cli {

enum class DumpKind { None, Tokens, Ast, Values, Snap };

struct CliOptions {
  std::string input;
  std::optional<std::string> model;
  std::optional<std::string> output;  // "-" is stdout
  std::vector<std::string> bundle_dirs;
  bool strict = false;
  bool check = false;                     // --check: load the MJCF in MuJoCo, compare with SNAP, simulate it
  double check_time = 1.0;                // --check-time T: how long --check simulates, s
  bool exclude_initial_overlaps = false;  // --exclude-initial-overlaps: <exclude> bodies overlapping at t = 0
  bool collada_up_axis = false;           // --collada-up-axis: COLLADA's <up_axis> turned onto +Z
  bool urdf_exact_mesh_mass = false;      // --urdf-exact-mesh-mass: exact mesh volumes for URDF links
  std::string prefix;                     // --prefix P: prepended to every MuJoCo name
  double timestep = 0.002;                // --timestep S: MuJoCo's time step (OpenPLX has no setting for it)
  bool mujoco3 = false;                   // --mujoco 3: soft-weld laws of MuJoCo 3.x
  bool keyframe = true;                   // --no-keyframe: leave the initial keyframe out
  std::optional<bool> lights;             // --lights on|off; auto (unset): a light unless --no-keyframe
  bool default_bundles = true;            // --no-default-bundles: only -B and OPENPLX_BUNDLE_PATH bundles
  std::optional<mjcf::Placement> pose;    // --pose "x y z [qw qx qy qz]": the model placed in a scene
  std::optional<std::string> depfile;     // --depfile FILE: a Make-style list of every file read
  DumpKind dump = DumpKind::None;
  bool help = false;
  bool version = false;
};

inline constexpr int kExitOk = 0;
inline constexpr int kExitInputError = 1;
inline constexpr int kExitUsageError = 2;

// Parses argv[1..]. On a usage error returns nullopt and writes the reason to `error`.
std::optional<CliOptions> parse_options(const std::vector<std::string>& args, std::string& error);

std::string usage();
// "model.xml" -> "model.signals.json"
std::string manifest_path(const std::string& output);

int run(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

// For a process that exits right after run(): its model is left to the exit rather than freed.
void end_process_after_run();

// For the executable: when stderr is a terminal, --check shows how far its simulation is (a line rewritten
// in place); in a pipe or a file, and for in-process callers that do not call this, it stays quiet.
void show_progress_on_terminal();

}  // namespace openplx::cli
