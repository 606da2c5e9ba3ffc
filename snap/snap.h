// SNAP, the automatic assembly of OpenPLX (docs/snap.md; the 0.17.8 pseudocode in ../shared/seed):
// computes the local transforms the model left undefined so that every mate's connector frames meet.
//
// Loop, as the pseudocode: for each unused mate, with G the closest common ancestor of its connectors'
// owners, count the undefined transforms on each connector's chain towards G. Exactly one on one side and
// none on the other: that transform C (the first on the chain, nearest the connector) is solved with
// S = P⁻¹ ∘ A ∘ N⁻¹ (P: C's parent frame, A: the target frame, N: the connector's frame seen from C) and the
// mate's free degree of freedom is recorded. None on either side: the mate is checked. When a pass places
// nothing, a recorded degree of freedom is given up, or an undefined transform is forced to the identity
// (a system's reference body first, then the first undefined transform of the first unused mate).
//
// Angle convention: connectors[1]'s frame relative to connectors[0]'s is J, right-handed about main_axis
// (see joint_offset). MuJoCo joints and signals use the same convention.
#pragma once

#include <vector>

#include "frontend/diagnostics/diagnostics.h"
#include "snap/resolved_system.h"

namespace openplx::snap {

// Solves `system` in place: undefined nodes get their local transforms, and the world frames go into
// `system.assembly`, which is returned. Over-determined or inconsistent mates are warnings at the mate's
// line with the residual.
const SnapResult& run_snap(ResolvedSystem& system, frontend::DiagnosticSink& sink);

// How far a mate's connectors are from rest, ignoring its free degrees of freedom: the distance (m) and
// the angle (rad) of what is constrained.
struct Residual {
  double distance = 0.0;
  double angle = 0.0;
};
Residual mate_residual(const Mate& mate, const Transform& frame0, const Transform& frame1);

}  // namespace openplx::snap
