#include "snap/snap.h"

#include <cmath>
#include <sstream>
#include <utility>

#include "frontend/evaluation/value_format.h"

namespace openplx::snap {
namespace {

namespace fe = openplx::frontend;
using natives::affine_compose;
using natives::affine_inverse;

constexpr double kDistanceTolerance = 1e-6;  // m
constexpr double kAngleTolerance = 1e-6;     // rad

double rotation_angle(const Eigen::Quaterniond& q) {
  return 2.0 * std::atan2(q.vec().norm(), std::abs(q.w()));
}

double axis_angle(const Eigen::Quaterniond& q, const Eigen::Vector3d& axis) {
  const Eigen::Vector3d turned = q * axis;
  return std::atan2(turned.cross(axis).norm(), turned.dot(axis));
}

class Snapper {
 public:
  Snapper(ResolvedSystem& system, fe::DiagnosticSink& sink)
      : system_(system),
        sink_(sink),
        fixed_(system.nodes.size()),
        placed_by_(system.nodes.size(), -1),
        forced_(system.nodes.size(), false) {
    for (size_t i = 0; i < system.nodes.size(); ++i) fixed_[i] = system.nodes[i].defined;
  }

  SnapResult run() {
    std::vector<int> unused;
    for (size_t m = 0; m < system_.mates.size(); ++m) {
      const Mate& mate = system_.mates[m];
      if (mate.enable_snap && mate.connectors[0] >= 0 && mate.connectors[1] >= 0)
        unused.push_back(static_cast<int>(m));
    }
    size_t free_dofs = 0;  // degrees of freedom recorded by placed mates and not yet given up
    while (!unused.empty()) {
      const size_t before = unused.size();
      std::vector<int> remaining;
      for (int m : unused) {
        if (!try_mate(m, free_dofs)) remaining.push_back(m);
      }
      unused = std::move(remaining);
      if (unused.size() != before) continue;
      // Nothing progressed. Giving up a recorded degree of freedom changes no transform here (we do not
      // solve loops through them), so it only costs a pass; then force an undefined transform.
      if (free_dofs > 0) {
        --free_dofs;
        continue;
      }
      if (!force_one(unused)) break;
    }
    for (int m : unused) {
      const Mate& mate = system_.mates[m];
      sink_.report(fe::DiagCode::SnapUnplaced, mate.where,
                   "SNAP cannot place mate " + mate.path + " between " + connector_name(mate.connectors[0]) +
                       " and " + connector_name(mate.connectors[1]));
    }
    resolve_adaptive();
    resolve_redirected();
    SnapResult result;
    for (size_t i = 0; i < system_.nodes.size(); ++i) result.node_world.push_back(world(static_cast<int>(i)));
    for (size_t c = 0; c < system_.connectors.size(); ++c)
      result.connector_world.push_back(connector_world(static_cast<int>(c)));
    result.placed_by = placed_by_;
    result.forced = forced_;
    return result;
  }

 private:
  std::string connector_name(int c) const { return c < 0 ? "<missing>" : system_.connectors[c].path; }
  int parent(int node) const { return node == kWorld ? kWorld : system_.nodes[node].parent; }

  Transform world(int node) const {
    Transform t;
    std::vector<int> chain;
    for (int n = node; n != kWorld; n = parent(n)) chain.push_back(n);
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) t = affine_compose(t, system_.nodes[*it].local);
    return t;
  }
  Transform connector_world(int c) const {
    return affine_compose(world(system_.connectors[c].owner), system_.connectors[c].local);
  }

  int common_ancestor(int a, int b) const {
    std::vector<int> up;
    for (int n = a; n != kWorld; n = parent(n)) up.push_back(n);
    for (int n = b; n != kWorld; n = parent(n)) {
      if (std::find(up.begin(), up.end(), n) != up.end()) return n;
    }
    return kWorld;
  }
  // The nodes from `owner` up to `ancestor` (exclusive), nearest the connector first.
  std::vector<int> chain(int owner, int ancestor) const {
    std::vector<int> out;
    for (int n = owner; n != ancestor && n != kWorld; n = parent(n)) out.push_back(n);
    return out;
  }
  int first_undefined(const std::vector<int>& nodes, int* count) const {
    int first = -1;
    *count = 0;
    for (int n : nodes) {
      if (fixed_[n]) continue;
      if (first < 0) first = n;
      ++*count;
    }
    return first;
  }

  bool try_mate(int m, size_t& free_dofs) {
    const Mate& mate = system_.mates[m];
    const Connector& c0 = system_.connectors[mate.connectors[0]];
    const Connector& c1 = system_.connectors[mate.connectors[1]];
    const int g = common_ancestor(c0.owner, c1.owner);
    int u0 = 0, u1 = 0;
    const int first0 = first_undefined(chain(c0.owner, g), &u0);
    const int first1 = first_undefined(chain(c1.owner, g), &u1);
    if (u0 == 1 && u1 == 0) {
      place(m, 0, first0);
    } else if (u0 == 0 && u1 == 1) {
      place(m, 1, first1);
    } else if (u0 == 0 && u1 == 0) {
      check(m);
      return true;
    } else {
      return false;
    }
    if (mate.type != MateType::Lock) ++free_dofs;
    return true;
  }

  // Solves node C's local transform so that connector `side` of the mate meets its partner at rest.
  void place(int m, int side, int node) {
    const Mate& mate = system_.mates[m];
    const Connector& moving = system_.connectors[mate.connectors[side]];
    const Transform partner = connector_world(mate.connectors[1 - side]);
    const Transform j = joint_offset(mate);
    // Rest: F1 = F0 ∘ J. The target of the moving connector's world frame:
    const Transform target =
        side == 1 ? affine_compose(partner, j) : affine_compose(partner, affine_inverse(j));
    // N: the moving connector's frame seen from C (the defined transforms between C and the connector).
    Transform below;
    std::vector<int> between;
    for (int n = moving.owner; n != node; n = parent(n)) between.push_back(n);
    for (auto it = between.rbegin(); it != between.rend(); ++it)
      below = affine_compose(below, system_.nodes[*it].local);
    const Transform n_frame = affine_compose(below, moving.local);
    const Transform p_frame = world(parent(node));
    // S = P⁻¹ ∘ A ∘ N⁻¹
    system_.nodes[node].local =
        affine_compose(affine_compose(affine_inverse(p_frame), target), affine_inverse(n_frame));
    system_.nodes[node].local.rotation.normalize();
    fixed_[node] = true;
    placed_by_[node] = m;
  }

  void check(int m) {
    const Mate& mate = system_.mates[m];
    const Residual r =
        mate_residual(mate, connector_world(mate.connectors[0]), connector_world(mate.connectors[1]));
    if (r.distance <= kDistanceTolerance && r.angle <= kAngleTolerance) return;
    sink_.report(fe::DiagCode::SnapInconsistent, mate.where,
                 "mate " + mate.path + " is over-determined: after SNAP its connectors " +
                     connector_name(mate.connectors[0]) + " and " + connector_name(mate.connectors[1]) +
                     " are " + fe::format_real(r.distance) + " m and " +
                     fe::format_real(r.angle * 180.0 / M_PI) +
                     " degrees apart; the simulation will pull them together");
  }

  // Forces one undefined transform to what the model says: a reference body first, then a static body (it
  // never moves, so assembly must not move it either: a URDF's massless root), else the first undefined
  // transform of the first unused mate (side 0's chain, then side 1's).
  bool force_one(const std::vector<int>& unused) {
    for (size_t i = 0; i < system_.nodes.size(); ++i) {
      if (!fixed_[i] && system_.nodes[i].reference) {
        fixed_[i] = forced_[i] = true;
        return true;
      }
    }
    for (size_t i = 0; i < system_.nodes.size(); ++i) {
      const FrameNode& n = system_.nodes[i];
      if (!fixed_[i] && n.kind == FrameNode::Kind::Body && !n.body.dynamic) {
        fixed_[i] = forced_[i] = true;
        return true;
      }
    }
    for (int m : unused) {
      const Mate& mate = system_.mates[m];
      const Connector& c0 = system_.connectors[mate.connectors[0]];
      const Connector& c1 = system_.connectors[mate.connectors[1]];
      const int g = common_ancestor(c0.owner, c1.owner);
      int count = 0;
      int node = first_undefined(chain(c0.owner, g), &count);
      if (node < 0) node = first_undefined(chain(c1.owner, g), &count);
      if (node < 0) continue;
      fixed_[node] = forced_[node] = true;  // its local transform stays what the model says (the identity)
      return true;
    }
    return false;
  }

  // An adaptive connector moves itself onto its partner once everything else is placed.
  void resolve_adaptive() {
    for (const Mate& mate : system_.mates) {
      if (mate.connectors[0] < 0 || mate.connectors[1] < 0) continue;
      for (int side = 0; side < 2; ++side) {
        Connector& c = system_.connectors[mate.connectors[side]];
        if (!c.adaptive) continue;
        const Transform partner = connector_world(mate.connectors[1 - side]);
        const Transform j = joint_offset(mate);
        const Transform target =
            side == 1 ? affine_compose(partner, j) : affine_compose(partner, affine_inverse(j));
        c.local = affine_compose(affine_inverse(world(c.owner)), target);
        break;
      }
    }
  }

  // A redirected connector whose parent needed assembly moves onto it now, keeping its world frame.
  void resolve_redirected() {
    for (Connector& c : system_.connectors) {
      if (c.redirect_to < 0) continue;
      c.local = affine_compose(affine_compose(affine_inverse(world(c.redirect_to)), world(c.owner)), c.local);
      c.local.rotation.normalize();
      c.owner = std::exchange(c.redirect_to, -1);
    }
  }

  ResolvedSystem& system_;
  fe::DiagnosticSink& sink_;
  std::vector<bool> fixed_;
  std::vector<int> placed_by_;
  std::vector<bool> forced_;
};

}  // namespace

Residual mate_residual(const Mate& mate, const Transform& frame0, const Transform& frame1) {
  // frame1 seen from frame0, compared with the rest offset J where J is fixed by the mate.
  const Transform relative = affine_compose(affine_inverse(frame0), frame1);
  const Transform deviation = affine_compose(affine_inverse(joint_offset(mate)), relative);
  const Eigen::Vector3d z = Eigen::Vector3d::UnitZ();
  Residual r;
  switch (mate.type) {
    case MateType::Lock:
    case MateType::Suspension:   // assembled at rest: travel, steering and spin at zero
    case MateType::ElasticTire:  // at rest: undeflected
      r.distance = deviation.position.norm();
      r.angle = rotation_angle(deviation.rotation);
      break;
    case MateType::Hinge:  // free: rotation about z
      r.distance = relative.position.norm();
      r.angle = axis_angle(relative.rotation, z);
      break;
    case MateType::Prismatic:  // free: translation along z
      r.distance = relative.position.head<2>().norm();
      r.angle = rotation_angle(relative.rotation);
      break;
    case MateType::Cylindrical:  // free: both along and about z
      r.distance = relative.position.head<2>().norm();
      r.angle = axis_angle(relative.rotation, z);
      break;
    case MateType::Ball:
    case MateType::ConstantVelocity:  // free: rotations
      r.distance = relative.position.norm();
      break;
    case MateType::Planar:  // free: translation across z, rotation about it
      r.distance = std::abs(relative.position.z());
      r.angle = axis_angle(relative.rotation, z);
      break;
    case MateType::Distance:
    case MateType::Other:
      break;
  }
  return r;
}

const SnapResult& run_snap(ResolvedSystem& system, frontend::DiagnosticSink& sink) {
  system.assembly = Snapper(system, sink).run();
  return system.assembly;
}

}  // namespace openplx::snap
