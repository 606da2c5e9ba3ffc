// Lowering pass, joints: the <joint>s of tree mates at their connectors, friction, URDF damping and friction.
#include "mjcf_emitter/lowering.h"

namespace openplx::mjcf {

void Lowering::emit_joints(Element& body, int node, int m) {
  const sn::Mate& mate = system_.mates[m];
  warn_mate_softness(mate, false);
  if (mate.type == sn::MateType::Lock) return;  // a rigid child: no joint
  const int side = vertex_of_connector(mate.connectors[1]) == node ? 1 : 0;
  const sn::Connector& c = system_.connectors[mate.connectors[side]];
  // The connector in the body frame (its owner is this body).
  const Eigen::Vector3d pos = c.local.position;
  // connectors[1] relative to connectors[0] about +main_axis: on side 0 the body turns the other way.
  const Eigen::Vector3d axis = (side == 1 ? 1.0 : -1.0) * (c.local.rotation * Eigen::Vector3d::UnitZ());
  auto joint = [&](const char* type, const std::string& suffix, double ref,
                   const Eigen::Vector3d& along = Eigen::Vector3d::Zero()) {
    const Eigen::Vector3d direction = along.isZero() ? axis : along;
    Element& j = body.add("joint");
    j.set("name", name(mate.path) + suffix).set("type", type).set("pos", pos);
    if (std::string(type) != "ball") j.set("axis", direction);
    if (ref != 0.0) j.set("ref", ref);
    joint_of_mate_[m].push_back(&j);
    joint_info_[&j] = {node, pos, direction.normalized(), std::string(type) == "hinge"};
    return &j;
  };
  switch (mate.type) {
    case sn::MateType::Hinge:
      apply_friction(*joint("hinge", "", mate.initial_angle), mate, mate.friction, "friction");
      break;
    case sn::MateType::Prismatic:
      apply_friction(*joint("slide", "", mate.initial_position), mate, mate.friction, "friction");
      break;
    case sn::MateType::Cylindrical:
      apply_friction(*joint("slide", ".slide", mate.initial_position), mate, mate.friction_translational,
                     "friction_translational");
      apply_friction(*joint("hinge", ".hinge", mate.initial_angle), mate, mate.friction_rotational,
                     "friction_rotational");
      break;
    case sn::MateType::Ball:
      joint("ball", "", 0.0);
      break;
    case sn::MateType::Suspension: {
      // Travel along the suspension's direction (connector 0's normal unless the suspension says otherwise),
      // then steering about it, then spin about main_axis: MuJoCo turns each joint's axis by the joints
      // before it, so the spin axis steers with the wheel. The connector frames coincide at rest.
      const double sign = side == 1 ? 1.0 : -1.0;
      const sn::Connector& chassis = system_.connectors[mate.connectors[0]];
      const Eigen::Vector3d along0 =
          mate.travel.isZero() ? Eigen::Vector3d::UnitX()
                               : Eigen::Vector3d(chassis.local.rotation.inverse() * mate.travel.normalized());
      const Eigen::Vector3d along = sign * (c.local.rotation * along0);
      if (!travel_held_rigid(mate, node)) {
        Element* travel = joint("slide", ".travel", 0.0, along);
        if (mate.travel_stiffness > 0) travel->set("stiffness", mate.travel_stiffness);
        if (mate.travel_damping > 0) travel->set("damping", mate.travel_damping);
      }
      if (mate.steerable) joint("hinge", ".steering", 0.0, along);
      joint("hinge", ".spin", 0.0);
      break;
    }
    case sn::MateType::ElasticTire: {
      // The tire on its rim: a slide along and a hinge about each of the connector's axes (z the axle), each
      // with the wheel's stiffness and damping for that direction (a compliance row); a direction without
      // stiffness is rigid.
      const double sign = side == 1 ? 1.0 : -1.0;
      const char* axes[3] = {".axial", ".radial_normal", ".radial_cross"};
      const Eigen::Vector3d unit[3] = {Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitX(),
                                       Eigen::Vector3d::UnitY()};
      for (int rotational = 0; rotational < 2; ++rotational) {
        for (int k = 0; k < 3; ++k) {
          const sn::DofCompliance& dof = mate.dofs[3 * rotational + k];
          if (!(dof.stiffness > 0)) continue;  // a rigid direction
          Element* j =
              joint(rotational ? "hinge" : "slide", std::string(rotational ? ".turn" : ".shift") + axes[k],
                    0.0, sign * (c.local.rotation * unit[k]));
          // AGX's compliance row (emit_compliant_dofs), not joint stiffness: MuJoCo integrates that
          // explicitly and a tire's is far too stiff for it.
          const double tau = dof.damping_constant  ? *dof.damping_constant / dof.stiffness
                             : dof.relaxation_time ? *dof.relaxation_time
                                                   : kDefaultRelaxationTime;
          const sn::BodyProperties& body = system_.nodes[node].body;
          compliant_dofs_.push_back({*j->get("name"), dof.stiffness, tau,
                                     rotational ? body.inertia.diagonal().maxCoeff() : body.mass,
                                     mate.path + (rotational ? " (rotational" : " (translational") +
                                         std::string(", ") + (axes[k] + 1) + ")",
                                     mate.where});
        }
      }
      break;
    }
    case sn::MateType::Planar: {  // MuJoCo's URDF importer's names; the connector's x is the _TX direction
      const Eigen::Vector3d tx = (side == 1 ? 1.0 : -1.0) * (c.local.rotation * Eigen::Vector3d::UnitX());
      const Eigen::Vector3d ty = (side == 1 ? 1.0 : -1.0) * (c.local.rotation * Eigen::Vector3d::UnitY());
      joint("slide", "_TX", 0.0, tx);
      joint("slide", "_TY", 0.0, ty);
      joint("hinge", "_RZ", 0.0);
      break;
    }
    default:
      break;
  }
}

// A suspension's travel is a slide with the spring and damper as joint stiffness and damping (MuJoCo's
// Euler integrates joint damping implicitly, stiffness explicitly). A spring too stiff for the step (ω h >
// 0.5 on the wheel's mass: AGX's default 1e8 N/m is one) would make explicit integration blow up; its
// travel is held rigid instead, which is what such a spring does to within m g / k, and said so.
bool Lowering::travel_held_rigid(const sn::Mate& mate, int node) {
  const double k = mate.travel_stiffness, mass = system_.nodes[node].body.mass;
  if (!too_stiff_for_step(k, mass)) return false;
  warn(mate.where, "`" + mate.path + ".spring_constant` (" + number(k) + " N/m on " + number(mass) +
                       " kg) is stiffer than MuJoCo integrates at a " + number(options_.timestep) +
                       " s step; the travel was held rigid (its static deflection, m g / k = " +
                       number(mass * 9.81 / k) + " m, is lost)");
  return true;
}

// A spring k on inertia m whose period is under about 4π steps (ω h > 0.5): MuJoCo integrates joint
// stiffness explicitly, so it would blow up. Unknown inertia (0) is not judged.
bool Lowering::too_stiff_for_step(double k, double inertia) const {
  return k > 0 && inertia > 0 && options_.timestep * std::sqrt(k / inertia) > 0.5;
}

// Flexibility and dissipation of a mate's constrained degrees of freedom: tree joints are exactly rigid in
// MuJoCo and equalities take MuJoCo's default softness, so a non-default model is reported, not dropped.
void Lowering::warn_mate_softness(const sn::Mate& mate, bool loop) {
  for (const auto& [attribute, type] :
       {std::pair<const char*, const std::string&>{"flexibility", mate.flexibility_type},
        {"dissipation", mate.dissipation_type}}) {
    if (type.empty() || type.find(".Default") != std::string::npos) continue;
    warn(mate.where, "`" + mate.path + "." + attribute + "` (" + type +
                         ") has no MuJoCo 2.2.2 mapping here; " +
                         (loop ? "the loop-closing equality keeps MuJoCo's default softness"
                               : "the joint's constrained directions are rigid"));
  }
}

// Dry friction of a mate's free degree of freedom. MuJoCo's joint friction is a constant limit
// (`frictionloss`), so only a friction given a constant normal force maps: limit = coefficient x normal
// force (N for slides; read as N m for hinges, UNCONFIRMED). Friction that scales with the constraint force
// has no 2.2.2 counterpart and is warned.
void Lowering::apply_friction(Element& joint, const sn::Mate& mate, const sn::MateFriction& friction,
                              const char* attribute) {
  const std::string& type = friction.type;
  if (type.empty() || type == "Physics.Interactions.Dissipation.DefaultFriction") return;
  if (type == "Physics.Interactions.Dissipation.DryConstantNormalForceFriction") {
    const double limit = friction.coefficient * friction.normal_force;
    if (limit > 0) joint.set("frictionloss", limit);
    return;
  }
  warn(mate.where,
       "`" + mate.path + "." + attribute + "` (" + type +
           ") depends on the constraint force, which MuJoCo 2.2.2 joint friction cannot; the joint "
           "was emitted without friction");
}

Element* Lowering::joint_for(int mate, bool rotational) {
  auto it = joint_of_mate_.find(mate);
  if (it == joint_of_mate_.end()) return nullptr;
  // A suspension's rotational degree of freedom for motors, ranges and signals is its wheel's spin (the
  // steering angle belongs to the steering mechanism).
  const bool suspension = system_.mates[mate].type == sn::MateType::Suspension;
  if (suspension && rotational) return it->second.back();
  for (Element* j : it->second) {
    const bool hinge = *j->get("type") == "hinge";
    if (hinge == rotational && *j->get("type") != "ball") return j;
  }
  return nullptr;
}

// URDF <dynamics>: damping adds to the springs' own; friction becomes frictionloss (a constant Coulomb
// friction is exactly what MuJoCo's joint friction is), added to a mate friction already there.
void Lowering::apply_joint_properties(std::map<Element*, double>& dampings) {
  for (const sn::JointProperties& p : system_.joint_properties) {
    if (p.mate < 0 || !tree_mates_.count(p.mate)) {
      if (p.damping > 0 || p.friction > 0)
        warn(p.where, "`" + p.path + "` (URDF dynamics) is on a mate that closes a loop or joins nothing; " +
                          "MuJoCo's equality constraints have no damping or friction, so it was left out");
      continue;
    }
    // A planar mate's three joints all take the URDF dynamics, as MuJoCo's importer gives them.
    std::vector<Element*> joints;
    if (system_.mates[p.mate].type == sn::MateType::Planar) {
      joints = joint_of_mate_[p.mate];
    } else if (Element* j = joint_for(p.mate, system_.mates[p.mate].type != sn::MateType::Prismatic)) {
      joints.push_back(j);
    }
    for (Element* joint : joints) {  // none for a Lock: nothing moves
      if (p.damping > 0) dampings[joint] += p.damping;
      if (p.friction > 0) {
        const std::string* had = joint->get("frictionloss");
        joint->set("frictionloss", p.friction + (had ? std::stod(*had) : 0.0));
      }
    }
  }
}

}  // namespace openplx::mjcf
