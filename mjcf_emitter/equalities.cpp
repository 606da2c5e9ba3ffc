// Lowering pass, loop closures and couplings: <equality> weld/connect/joint, their soft parameters, loop
// excludes.
#include "mjcf_emitter/lowering.h"

namespace openplx::mjcf {

using natives::affine_compose;
using natives::affine_inverse;

// Mates outside the tree: loop closures, and disabled mates as inactive equalities (`active="false"`,
// switched by their enable input through eq_active).
void Lowering::emit_loop_closures(Element& root) {
  Element& equality = root.add("equality");
  Element& contact = root.add("contact");
  std::set<std::pair<std::string, std::string>> excluded;
  for (const auto& e : adjacency_) {
    if (tree_mates_.count(e.mate)) continue;
    const sn::Mate& mate = system_.mates[e.mate];
    const std::string a = e.a >= 0 ? name(system_.nodes[e.a].path) : "world";
    const std::string b = e.b >= 0 ? name(system_.nodes[e.b].path) : "world";
    // The anchor: connector 0 in its body's frame (MuJoCo derives body2's point from the assembled pose).
    // A connector on the world side (World, or one owned by a system) is given in world coordinates.
    const sn::Transform frame0 =
        e.a >= 0 ? system_.connectors[mate.connectors[0]].local : snap_.connector_world[mate.connectors[0]];
    const sn::Transform frame1 =
        e.b >= 0 ? system_.connectors[mate.connectors[1]].local : snap_.connector_world[mate.connectors[1]];
    const Eigen::Vector3d anchor = frame0.position;
    const std::optional<MateCompliance> soft = compliance(mate);
    if (!soft) warn_mate_softness(mate, true);
    switch (mate.type) {
      case sn::MateType::Lock: {
        Element& weld = equality.add("weld").set("name", name(mate.path)).set("body1", a);
        if (e.b >= 0) weld.set("body2", b);
        weld.set("anchor",
                 frame1.position);  // where the error is measured: the weld point, in body2's frame
        if (!mate.enabled) weld.set("active", "false");
        equalities_of_mate_[e.mate].push_back(*weld.get("name"));
        if (soft) soft_equalities_.push_back({&weld, a, b, *soft, true});
        break;
      }
      case sn::MateType::Ball:
      case sn::MateType::Hinge: {
        // A hinge closing a loop: two points on its axis (one would leave the axis free to tilt).
        const Eigen::Vector3d axis = frame0.rotation * Eigen::Vector3d::UnitZ();
        const int count = mate.type == sn::MateType::Hinge ? 2 : 1;
        for (int k = 0; k < count; ++k) {
          const Eigen::Vector3d point =
              count == 1 ? anchor : Eigen::Vector3d(anchor + (k == 0 ? 0.05 : -0.05) * axis);
          Element& connect = equality.add("connect");
          connect.set("name", name(mate.path) + (count == 1 ? "" : (k == 0 ? ".a" : ".b"))).set("body1", a);
          if (e.b >= 0) connect.set("body2", b);
          connect.set("anchor", point);
          if (!mate.enabled) connect.set("active", "false");
          equalities_of_mate_[e.mate].push_back(*connect.get("name"));
          if (soft) soft_equalities_.push_back({&connect, a, b, *soft, false});
        }
        if (soft && soft->k_rot > 0) {
          warn(mate.where, "`" + mate.path + ".flexibility`: the rotational stiffness of a " +
                               sn::mate_type_name(mate.type) +
                               " closing a loop is not mapped (MuJoCo's connect constrains points only); its "
                               "translational stiffness is");
        }
        break;
      }
      default:
        if (!mate.enabled) {
          warn(mate.where, "`" + mate.path +
                               "` is disabled (`enabled: false`) and MuJoCo 2.2.2 has no equality "
                               "for a " +
                               sn::mate_type_name(mate.type) +
                               " that its enable input could switch on; it was left out");
          continue;
        }
        warn(mate.where, "`" + mate.path + "` closes a kinematic loop as a " + sn::mate_type_name(mate.type) +
                             "; MuJoCo 2.2.2 has no exact equality for it, so it was left out");
        continue;
    }
    if (e.a >= 0 && e.b >= 0 && excluded.insert({std::min(a, b), std::max(a, b)}).second) {
      contact.add("exclude").set("body1", a).set("body2", b);
    }
    for (const sn::Interaction1D& i : system_.interactions) {
      if (i.mate == e.mate) {
        warn(i.where, "`" + i.path + "` acts on `" + mate.path + "`, which " +
                          (mate.enabled ? "closes a loop" : "is disabled (`enabled: false`)") +
                          " and has no MuJoCo joint; it was left out");
      }
    }
  }
}

// A loop-closing mate's elastic flexibility (LinearElastic per direction) and its dissipation, as physical
// stiffness and damping: the mean over the translational and over the rotational directions (one weld has
// one value each; differing directions are warned). Damping: MechanicalDamping as given, a relaxation time
// t as t k, else AGX's default of two time steps. nullopt when the mate is rigid.
std::optional<MateCompliance> Lowering::compliance(const sn::Mate& mate) {
  if (!mate.flexible) return std::nullopt;
  MateCompliance c;
  bool differs = false;
  auto directions = [&](size_t from, double& k_mean, double& b_mean) {
    int count = 0;
    double first = -1;
    for (size_t axis = from; axis < from + 3; ++axis) {
      const sn::DofCompliance& dof = mate.dofs[axis];
      const double k = dof.stiffness;
      if (!(k > 0)) continue;
      double b = 2 * options_.timestep * k;
      if (dof.damping_constant) b = *dof.damping_constant;
      if (dof.relaxation_time) b = *dof.relaxation_time * k;
      differs = differs || (first >= 0 && k != first);
      first = k;
      k_mean += k;
      b_mean += b;
      ++count;
    }
    if (count > 0) {
      k_mean /= count;
      b_mean /= count;
    }
  };
  directions(0, c.k_trans, c.b_trans);  // along main, normal, cross
  directions(3, c.k_rot, c.b_rot);      // around them
  if (!(c.k_trans > 0)) return std::nullopt;
  if (differs) {
    warn(mate.where, "`" + mate.path +
                         ".flexibility` differs between directions; a MuJoCo equality has one stiffness for "
                         "its translations (and one for its rotations), so their means were used");
  }
  return c;
}

// Rigid equalities (loop closures, drivetrain couplings, mimic joints) as stiff as MuJoCo holds them: time
// constant 2 h (the shortest refsafe keeps), damping ratio 1/2, impedance 0.9999 (the largest it accepts).
// That gives stiffness 1/h^2 and damping 1/h, which under semi-implicit Euler is deadbeat: an error in
// position and velocity is gone after two steps (critical damping, ratio 1, keeps 3/4 of a position error per
// step). What remains is the impedance's leak, (1 - d) of what the row carries in each step (docs/mapping.md
// "Couplings"). Flexible ones are set by finish_with_draft.
void Lowering::stiffen_equalities(Element& root) {
  Element* equality = root.child("equality");
  if (!equality) return;
  std::set<const Element*> soft;
  for (const PendingSoftEquality& p : soft_equalities_) soft.insert(p.equality);
  for (const std::unique_ptr<Element>& e : equality->children()) {
    const std::string* name = e->get("name");
    if (soft.count(e.get()) || (name && compliant_equalities_.count(*name))) continue;
    e->set("solref", number(2 * options_.timestep) + " 0.5").set("solimp", rigid_solimp());
  }
}

// Rigid friction rows (motors, clutches, brakes): a friction row has no position error, so only its damping
// 1/h counts, which makes its velocity deadbeat.
std::string Lowering::rigid_solref() const {
  return number(2 * options_.timestep) + " 1";
}

std::string Lowering::rigid_solimp() {
  return number(kRigidImpedance) + " " + number(kRigidImpedance) + " 0.001 0.5 2";
}

// What only MuJoCo's compiler knows, from one draft compile: mesh bodies' mass properties (written as
// explicit inertials, so the file needs no exactmeshinertia, which 3.2.5 removed), for flexible loop
// closures, bodies' inverse-inertia estimates (dA), and velocity motors' servo stand-ins the mass matrix.
void Lowering::finish_with_draft(Element& root) {
  std::vector<Element*> mesh_bodies, legacy_bodies;  // exact mesh volumes; MuJoCo's default (legacy) ones
  for (const auto& [node, mass] : mass_on_geoms_)
    (legacy_mesh_mass_.count(node) ? legacy_bodies : mesh_bodies).push_back(body_element_.at(node));
  const bool servos = stand_in_servos_;
  if (sink_.has_errors()) return;
  auto compile = [&](bool exact) {
    auto draft = std::make_unique<DraftModel>(root, options_.output_dir, exact);
    for (const std::string& text : draft->warnings()) {  // MuJoCo's own words, at the root model
      sink_.report(fe::DiagCode::MuJoCoWarning,
                   system_.root >= 0 ? system_.nodes[system_.root].where : fe::SourceRange{},
                   "MuJoCo warns while compiling the draft model: " + text);
    }
    if (!draft->model()) {
      warn({}, "the draft model did not load in MuJoCo (" + draft->error() +
                   "); mesh bodies keep MuJoCo's own mass computation and flexible loop closures its default "
                   "softness");
      return std::unique_ptr<DraftModel>();
    }
    return draft;
  };
  // The legacy bodies first, so that a draft for the rest already holds their final inertials.
  if (!legacy_bodies.empty()) {
    const std::unique_ptr<DraftModel> legacy = compile(false);
    if (!legacy) return;
    legacy->write_inertials(legacy_bodies);
  }
  if (soft_equalities_.empty() && mesh_bodies.empty() && !servos) return;
  const std::unique_ptr<DraftModel> compiled = compile(true);
  if (!compiled) return;
  const DraftModel& draft = *compiled;
  draft.write_inertials(mesh_bodies);
  finish_servo_gains(draft);
  const SoftEqualityResult r = apply_soft_equalities(draft, soft_equalities_, options_.timestep,
                                                     options_.mujoco == EmitOptions::MuJoCo::V3);
  for (const std::string& e : r.unstable) {
    warn({}, "equality " + e + " is stiffer than explicit integration at " + number(options_.timestep) +
                 " s resolves (h sqrt(k/m) > 1); it may oscillate");
  }
}

// A Distance mate holds its connectors target_distance apart: a spatial tendon between sites at the two
// connectors, held by a tendon equality at target - (its length as assembled), since MuJoCo measures tendon
// equalities from the initial configuration. A target of zero with coincident connectors is a `connect`
// (a tendon of length zero has no direction).
void Lowering::emit_distance_mates(Element& root) {
  Element& equality = *root.child("equality");
  for (size_t m = 0; m < system_.mates.size(); ++m) {
    const sn::Mate& mate = system_.mates[m];
    if (mate.type != sn::MateType::Distance || mate.connectors[0] < 0 || mate.connectors[1] < 0) continue;
    const int a = vertex_of_connector(mate.connectors[0]), b = vertex_of_connector(mate.connectors[1]);
    if (a == b) {
      warn(mate.where, "`" + mate.path + "` joins two connectors of one body; it was left out");
      continue;
    }
    const double assembled = (snap_.connector_world[mate.connectors[1]].position -
                              snap_.connector_world[mate.connectors[0]].position)
                                 .norm();
    const std::string element = name(mate.path);
    if (assembled < 1e-9 && std::abs(mate.target_distance) < 1e-9) {
      const sn::Transform local = system_.connectors[mate.connectors[0]].local;
      equality.add("connect")
          .set("name", element)
          .set("body1", mujoco_body(a))
          .set("body2", mujoco_body(b))
          .set("anchor", a >= 0 ? local.position : snap_.connector_world[mate.connectors[0]].position)
          .set("active", mate.enabled ? "true" : "false");
      equalities_of_mate_[static_cast<int>(m)] = {element};
      continue;
    }
    Element* tendons = root.child("tendon");
    if (!tendons) tendons = &root.add("tendon");
    Element& tendon = tendons->add("spatial");
    tendon.set("name", element);
    tendon.add("site").set("site", site_for(mate.connectors[0]));
    tendon.add("site").set("site", site_for(mate.connectors[1]));
    equality.add("tendon")
        .set("name", element)
        .set("tendon1", element)
        .set("polycoef", number(mate.target_distance - assembled) + " 0 0 0 0")
        .set("active", mate.enabled ? "true" : "false");
    equalities_of_mate_[static_cast<int>(m)] = {element};
    distance_mates_[static_cast<int>(m)] = element;
  }
}

// A drivetrain as MuJoCo joints and constraints: every shaft is a rotor body spinning about z at the world
// origin (no geometry, its inertia about the axis), hinge/prismatic actuators tie a shaft's angle to the
// mate's joint and gears tie two shafts with joint equalities (MuJoCo measures both from their initial
// values), a differential ties its three shafts with a fixed tendon held at its initial length:
// w_drive = gear_ratio (w_left + w_right) / 2. Gears: ratio = input speed / output speed (UNCONFIRMED for
// AGX; the corpus only uses -1, where both readings agree).
// Joints that follow another (URDF mimic): a joint equality, follower = offset + multiplier * leader in
// joint values (a joint's value includes its mate's initial angle or position).
void Lowering::emit_joint_couplings(Element& root) {
  Element* equality = root.child("equality");
  for (const sn::JointCoupling& c : system_.joint_couplings) {
    auto joint = [&](int mate) -> Element* {
      if (mate < 0 || !tree_mates_.count(mate)) return nullptr;
      return joint_for(mate, system_.mates[mate].type != sn::MateType::Prismatic);
    };
    Element* follower = joint(c.follower);
    Element* leader = joint(c.leader);
    if (!follower || !leader || follower == leader) {
      warn(c.where, "`" + c.path +
                        "` does not couple two hinge or prismatic joints of MuJoCo's tree; it was "
                        "left out");
      continue;
    }
    // MuJoCo measures both joints from their qpos0 (`ref`): follower = offset + multiplier leader in joint
    // values is, from there, a constant term offset + multiplier leader0 - follower0.
    auto ref = [](const Element* j) { return j->get("ref") ? std::stod(*j->get("ref")) : 0.0; };
    const double constant = c.offset + c.multiplier * ref(leader) - ref(follower);
    equality->add("joint")
        .set("name", name(c.path))
        .set("joint1", *follower->get("name"))
        .set("joint2", *leader->get("name"))
        .set("polycoef", number(constant) + " " + number(c.multiplier) + " 0 0 0");
  }
}

}  // namespace openplx::mjcf
