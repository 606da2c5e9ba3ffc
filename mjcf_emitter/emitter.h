// OpenPLX resolved system (after SNAP) to an MJCF document for MuJoCo 2.2.2 (docs/mapping.md).
//
// A spanning tree rooted at the world becomes the body tree: tree mates become joints in the child body at
// its connector (Hinge: hinge, Prismatic: slide, Cylindrical: slide + hinge, Ball: ball, Lock: no joint),
// a dynamic body no mate reaches gets a free joint, a static body (`is_dynamic: false`) hangs jointless from
// the world. Mates that close loops become equality constraints with a contact exclude. Joint `ref` holds the
// initial value, so MuJoCo joint readings equal OpenPLX angles and positions (connectors[1] relative to
// connectors[0], right-handed about main_axis). Anything MuJoCo cannot express is a warning naming the
// OpenPLX attribute and what was done instead.
#pragma once

#include <memory>
#include <string>

#include "contract/signal_binding.h"
#include "frontend/diagnostics/diagnostics.h"
#include "mjcf_emitter/mesh_conversion.h"
#include "mjcf_emitter/xml.h"
#include "snap/snap.h"

namespace openplx::mjcf {

struct EmitOptions {
  std::string model_name;   // <mujoco model="...">
  std::string prefix;       // prepended to every MuJoCo name (--prefix)
  std::string output_dir;   // mesh files are written relative to it; empty: absolute paths
  double timestep = 0.002;  // <option timestep> (--timestep): OpenPLX has no time-step setting
  // The MuJoCo the file is for (--mujoco): soft welds' solref and torquescale follow laws that changed in
  // 3.0, and V3 adds a collision flag only 3.x loads (mujoco3_collision.h; docs/mapping.md "MuJoCo
  // versions").
  enum class MuJoCo { V2, V3 };
  MuJoCo mujoco = MuJoCo::V2;
  // The "initial" keyframe (initial controls and free bodies' velocities). A keyframe must cover the whole
  // model, so a file <include>d into a bigger scene goes without (--no-keyframe); a SignalBridge sets the
  // initial controls instead.
  bool keyframe = true;
  // A directional light when the model has none (viewer_defaults.h). A file made for a bigger scene goes
  // without: every included file's light adds up, and the scene brings its own (--lights).
  bool light = true;
  // Emitted::manifest_json filled in; the converter leaves it empty and writes the manifest to its file in
  // pieces from `signals` and `laws` (write_manifest_json), never holding the whole text.
  bool manifest_text = true;
  // --exclude-initial-overlaps: an <exclude> for every pair of bodies whose collision geometry overlaps at
  // the initial state, found by compiling and forwarding a draft of the document in MuJoCo (a note for each).
  bool exclude_initial_overlaps = false;
  // --urdf-exact-mesh-mass: a URDF link without <inertial> takes its mesh volumes exactly, as OpenPLX bodies
  // do, instead of as MuJoCo 2.2.2's URDF importer computes them (its legacy formula; docs/urdf.md).
  bool urdf_exact_mesh_mass = false;
  // A COLLADA file's <up_axis> turned onto +Z, as the COLLADA standard defines it. Off by default: RViz and
  // Gazebo take the coordinates as written, and robots are drawn (and checked by their authors) there.
  bool collada_up_axis = false;
};

// A <mesh> asset read from a file MuJoCo cannot read (mesh_conversion.h): `document` holds it inline.
struct ConvertedMesh {
  std::string asset;                         // the <mesh> element's name
  std::string source;                        // the file it was read from
  std::shared_ptr<const TriangleMesh> mesh;  // shared by the assets of one file (one per scale)
};

struct Emitted {
  Element document{"mujoco"};
  // Written to a file, the converter moves these into files beside it (mesh_files.h).
  std::vector<ConvertedMesh> converted_meshes;
  std::vector<SignalBinding> signals;  // every OpenPLX input/output and how MuJoCo reaches it
  std::vector<RuntimeLaw> laws;        // what the runtime computes each step (engines, torque converters)
  std::string manifest_json;           // the same, as the signal manifest file (EmitOptions::manifest_text)
};

// MuJoCo 2.2.2's XML reader stops near 100 nested elements; deeper body chains are an error here.
inline constexpr int kMaxBodyDepth = 90;

// `system` must have been through SNAP (run_snap fills its assembly).
Emitted emit_mjcf(const snap::ResolvedSystem& system, const EmitOptions& options,
                  frontend::DiagnosticSink& sink);

}  // namespace openplx::mjcf
