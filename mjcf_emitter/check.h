// `--check`: loads emitted MJCF with MuJoCo's own mj_loadXML, runs mj_forward, and compares every body's
// world pose with SNAP's and every equality constraint's residual with zero (mujoco-compile exits 0 on
// failure, so loading through the library is the only trustworthy test). Then, from the "initial"
// keyframe (with its controls), it lists the collision geometry that already overlaps and simulates the
// model for a short span, watching MuJoCo's warning counters after every step: a bad qpos/qvel/qacc (MuJoCo
// resets mjData), a bad control or a full contact/constraint buffer is reported at the joint or body it
// concerns. MuJoCo's own messages are kept (MuJoCoMessages), never written to MUJOCO_LOG.TXT.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "frontend/diagnostics/source.h"
#include "mjcf_emitter/mujoco_library.h"
#include "snap/snap.h"

namespace openplx::mjcf {

struct CheckOptions {
  double tolerance = 1e-9;      // pose error allowed, m and rad
  double simulate_time = 1.0;   // s simulated from the initial keyframe; 0: none
  double emitted_timestep = 0;  // the time step the model was emitted for (the hint compares it); 0: unknown
  // Called after each simulated step with the time simulated and simulate_time (openplx2mjcf shows it on a
  // terminal); may be empty.
  std::function<void(double simulated, double total)> progress;
};

// Two bodies whose collision geometry overlaps at the initial state (MuJoCo has already left out parent and
// child, excluded pairs and bodies welded together).
struct InitialOverlap {
  std::string body1, body2;  // MuJoCo names, body1 < body2; "world" for the world's geometry
  std::string geom1, geom2;  // the deepest contact's geoms (of body1 and body2); "" when unnamed
  double depth = 0;          // how deep they overlap, m (> 0)
  // When one hangs from the other (MuJoCo leaves out a parent and child unless the parent is fixed to the
  // world): the child's first joint, "" when it has none or they are not parent and child.
  bool parent_and_child = false;
  std::string joint;
};

// Overlaps deeper than this are reported: touching shapes (a box resting on the ground) give depths of
// rounding size.
inline constexpr double kOverlapTolerance = 1e-5;

// MuJoCo's contacts at `d`'s state (after mj_forward): one per pair of bodies, its deepest, deeper than
// `min_depth`; sorted by body names (deterministic output).
std::vector<InitialOverlap> overlapping_bodies(const MuJoCoLibrary& mj, const mjModel* m, const mjData* d,
                                               double min_depth = kOverlapTolerance);

// A length for a reader: "3.4 cm", "0.12 mm", "1.5 m" (three significant digits).
std::string length_text(double metres);

// Resets `d` to the keyframe `key_name` (its qpos, qvel and controls) when the model has it, else to the
// model's defaults, and runs mj_forward.
void reset_to_initial_state(const MuJoCoLibrary& mj, const mjModel* m, mjData* d,
                            const std::string& key_name);

// A finding at the user's source: `where` is the OpenPLX (or URDF) declaration of the joint or body it
// concerns, or has no file (the caller puts it on the root model).
struct LocatedProblem {
  std::string message;
  frontend::SourceRange where;
};

struct CheckResult {
  bool loaded = false;
  std::string load_error;             // MuJoCo's message when loading failed
  std::vector<std::string> problems;  // pose or constraint mismatches, one line each
  // Where each of `problems` points (same order): the body's or equality's declaration, or no file.
  std::vector<frontend::SourceRange> problem_where;
  // The declaration of the element MuJoCo names in `load_error` ("Object name = arm"), or no file.
  frontend::SourceRange load_error_where;
  double max_position_error = 0.0;
  double max_rotation_error = 0.0;
  double max_equality_residual = 0.0;
  std::vector<InitialOverlap> overlaps;         // at the initial state
  std::vector<LocatedProblem> overlap_reports;  // one per overlap, in the same order
  std::vector<LocatedProblem> instabilities;    // the simulation is not the model's motion (errors)
  std::vector<LocatedProblem> mujoco_warnings;  // MuJoCo's other messages (warnings)
  double simulated_time = 0;                    // s simulated before the first instability (or in all)
  int steps = 0;                                // mj_step calls taken
};

// `xml_path` must be a file (mesh paths in it resolve against its folder). Body names are `prefix` + path.
CheckResult check_mjcf(const std::string& xml_path, const snap::ResolvedSystem& system,
                       const snap::SnapResult& snap, const std::string& prefix, const std::string& root_name,
                       const CheckOptions& options = {});

}  // namespace openplx::mjcf
