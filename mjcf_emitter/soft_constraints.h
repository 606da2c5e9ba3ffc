// Flexible loop-closing mates as soft MuJoCo equalities (docs/mapping.md "Mate softness"). MuJoCo's solref is
// mass-normalised: with direct solref (-ks, -bs) and flat impedance d, a constraint row behaves like a spring
// k = ks / ((1 - d) dA) and a damper b = bs / ((1 - d) dA), dA being MuJoCo's inverse-inertia estimate of the
// row (body_invweight0, translational, summed over both bodies). So solref = (-k (1-d) dA, -b (1-d) dA). A
// weld has one solref for all six rows (its rotational rows also use the translational dA), and its
// rotational stiffness is torquescale ks / (4 (1-d) dA): torquescale = 4 k_rot / k_trans.
#pragma once

#include <mujoco/mujoco.h>

#include <string>
#include <vector>

#include "mjcf_emitter/draft_model.h"
#include "mjcf_emitter/xml.h"

namespace openplx::mjcf {

// Physical stiffness (N/m, N m/rad) and damping (N s/m, N m s/rad) of a mate's constrained directions.
struct MateCompliance {
  double k_trans = 0, b_trans = 0;
  double k_rot = 0, b_rot = 0;
};

// An equality waiting for MuJoCo's dA before its solref can be written.
struct PendingSoftEquality {
  Element* equality = nullptr;  // <weld> or <connect>
  std::string body1, body2;     // MuJoCo body names ("world" for the world)
  MateCompliance compliance;
  bool weld = false;
};

// The impedance of flexible equalities: small, so the row is nearly a pure spring (added inertia d / (1 -
// d)).
inline constexpr double kSoftImpedance = 0.05;

struct SoftEqualityResult {
  std::vector<std::string> unstable;  // equalities whose stiffness needs h sqrt(ks) > 1 (warn)
};

// Writes solref/solimp (and torquescale) on every pending equality from the draft's body_invweight0, by the
// law of the target MuJoCo (docs/mapping.md "MuJoCo versions"): 3.x takes dA = 1/m for "simple" bodies and
// applies torquescale squared against the rotational dA, where 2.2.2 used the translational dA for all rows.
SoftEqualityResult apply_soft_equalities(const DraftModel& draft,
                                         const std::vector<PendingSoftEquality>& pending, double timestep,
                                         bool mujoco3);

}  // namespace openplx::mjcf
