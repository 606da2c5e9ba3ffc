// Lowering pass, drivetrain: shafts as rotor bodies, actuator/gear joint equalities, differential tendons,
// shaft motors.
#include "mjcf_emitter/lowering.h"

namespace openplx::mjcf {

using natives::affine_compose;
using natives::affine_inverse;

// Shafts held rigidly 1:1 to a 3-D joint (HingeActuator, PrismaticActuator) or to each other (a brake's
// power line) turn as one: each such group is folded into one MuJoCo joint, the 3-D joint of its first
// actuator (else its first shaft's own), which carries the others' inertia as armature. What acts on a folded
// shaft acts on that joint; no equality holds the group, so it is exact at every step (a rigid equality leaks
// (1 - d) of what it carries in the step it starts carrying it: docs/mapping.md "Couplings"). Gears and
// gearboxes are not folded: their ratio changes at run time and their torque output is their equality's
// force.
void Lowering::fold_rigid_shafts() {
  const size_t n = system_.shafts.size();
  shaft_group_.resize(n);
  for (size_t k = 0; k < n; ++k) shaft_group_[k] = static_cast<int>(k);
  auto group = [&](int s) {
    while (shaft_group_[s] != s) s = shaft_group_[s] = shaft_group_[shaft_group_[s]];
    return s;
  };
  using Kind = sn::DriveCoupling::Kind;
  for (const sn::DriveCoupling& c : system_.couplings) {
    if (c.kind == Kind::Brake && c.shafts.size() == 2 && c.shafts[0] >= 0 && c.shafts[1] >= 0)
      shaft_group_[group(c.shafts[1])] = group(c.shafts[0]);
  }
  for (size_t k = 0; k < n; ++k) shaft_group_[k] = group(static_cast<int>(k));
  for (const sn::DriveCoupling& c : system_.couplings) {
    if (c.kind != Kind::Actuator || c.shafts.size() != 1 || c.shafts[0] < 0) continue;
    if (Element* joint = actuator_joint(c)) group_joint_.try_emplace(shaft_group_[c.shafts[0]], joint);
  }
}

// Whether two of a coupling's shafts are folded into one joint.
bool Lowering::joins_one_joint(const sn::DriveCoupling& c) const {
  std::set<std::string_view> joints;
  for (int s : c.shafts) {
    if (s >= 0 && !joints.insert(shaft_joints_[s]).second) return true;
  }
  return false;
}

// The 3-D joint a HingeActuator/PrismaticActuator drives, nullptr when its mate has none in MuJoCo's tree.
Element* Lowering::actuator_joint(const sn::DriveCoupling& c) {
  if (c.mate < 0 || !tree_mates_.count(c.mate)) return nullptr;
  return joint_for(c.mate, system_.mates[c.mate].type != sn::MateType::Prismatic);
}

void Lowering::emit_drivetrain(Element& root) {
  if (system_.shafts.empty()) return;
  fold_rigid_shafts();
  std::vector<double> crank(system_.shafts.size(), 0.0);  // engines' own inertia turns with their shaft
  for (const sn::DriveCoupling& c : system_.couplings) {
    if (c.kind == sn::DriveCoupling::Kind::Engine && c.shafts.size() == 1 && c.shafts[0] >= 0)
      crank[static_cast<size_t>(c.shafts[0])] += std::max(c.crank_inertia, 0.0);
  }
  // A group's inertia beyond its own joint's: every folded shaft's, and engines' cranks.
  std::map<int, double> armature;
  for (size_t k = 0; k < system_.shafts.size(); ++k) {
    const int g = shaft_group_[k];
    const bool own_body = g == static_cast<int>(k) && !group_joint_.count(g);
    armature[g] += crank[k] + (own_body ? 0.0 : std::max(system_.shafts[k].inertia, 1e-9));
  }
  shaft_joints_.resize(system_.shafts.size());
  shaft_offsets_.assign(system_.shafts.size(), 0.0);
  for (size_t k = 0; k < system_.shafts.size(); ++k) {
    if (shaft_group_[k] != static_cast<int>(k) || group_joint_.count(static_cast<int>(k))) continue;
    const sn::Shaft& shaft = system_.shafts[k];
    Element& body = world_->add("body");
    body.set("name", name(shaft.path)).set("pos", "0 0 0");
    Element& joint = body.add("joint");
    joint.set("name", name(shaft.path)).set("type", "hinge").set("axis", "0 0 1");
    if (armature[static_cast<int>(k)] > 0) joint.set("armature", armature[static_cast<int>(k)]);
    const double inertia = std::max(shaft.inertia, 1e-9);
    body.add("inertial")
        .set("pos", "0 0 0")
        .set("mass", 1.0)
        .set("diaginertia", Eigen::Vector3d::Constant(inertia));
  }
  for (auto& [g, joint] : group_joint_) {
    const std::string* given = joint->get("armature");
    joint->set("armature", armature[g] + (given ? std::stod(*given) : 0.0));
  }
  for (size_t k = 0; k < system_.shafts.size(); ++k) {
    const int g = shaft_group_[k];
    auto folded = group_joint_.find(g);
    if (folded == group_joint_.end()) {
      shaft_joints_[k] = name(system_.shafts[g].path);
      continue;
    }
    shaft_joints_[k] = *folded->second->get("name");
    // A shaft starts at angle 0, the joint at its `ref` (MuJoCo's qpos0).
    const std::string* ref = folded->second->get("ref");
    shaft_offsets_[k] = ref ? std::stod(*ref) : 0.0;
  }
  Element& equality = *root.child("equality");
  Element& tendons = root.add("tendon");
  using Kind = sn::DriveCoupling::Kind;
  for (const sn::DriveCoupling& c : system_.couplings) {
    if (c.kind != Kind::Actuator && c.kind != Kind::Brake && joins_one_joint(c)) {
      warn(c.where, "`" + c.path +
                        "` joins shafts that turn as one (held together rigidly by hinge/prismatic actuators "
                        "or a brake's power line); it was left out");
      continue;
    }
    if (c.kind == Kind::Clutch || c.kind == Kind::Brake) {
      emit_friction_coupling(equality, tendons, c);
      continue;
    }
    const bool complete = std::none_of(c.shafts.begin(), c.shafts.end(), [](int k) { return k < 0; });
    const size_t needed = c.kind == Kind::Actuator || c.kind == Kind::Engine ? 1
                          : c.kind == Kind::Differential                     ? 3
                                                                             : 2;
    if (!complete || c.shafts.size() != needed) {
      warn(c.where, "`" + c.path + "` does not connect drivetrain shafts; it was left out");
      continue;
    }
    switch (c.kind) {
      case Kind::Actuator: {
        Element* joint = actuator_joint(c);
        if (!joint) {
          warn(c.where, "`" + c.path +
                            ".mate_3d` is not a hinge or prismatic joint of MuJoCo's tree; the "
                            "actuator was left out");
          continue;
        }
        drive_edges_.push_back({c.shafts[0], -1, 1.0, joint});
        // The group's first joint carries the shaft; another joint the group drives follows that one.
        const std::string& carrier = shaft_joints_[c.shafts[0]];
        if (*joint->get("name") == carrier) break;
        equality.add("joint")
            .set("name", name(c.path))
            .set("joint1", *joint->get("name"))
            .set("joint2", carrier)
            .set("polycoef", "0 1 0 0 0");
        break;
      }
      case Kind::Gear:
        emit_gear(equality, tendons, c);
        break;
      case Kind::GearBox:
        emit_gearbox(equality, c);
        break;
      case Kind::Differential:
        emit_differential(equality, tendons, c);
        break;
      case Kind::TorqueConverter:
        emit_torque_converter(equality, tendons, c);
        break;
      case Kind::Engine:
        emit_engine(c);
        break;
      case Kind::Clutch:
      case Kind::Brake:
        break;  // emit_friction_coupling
    }
  }
}

// A clutch or brake: dry friction of torque_capacity * engagement as a fixed tendon whose friction loss is
// that torque (rigid rows, like the motors'). A clutch's tendon is the slip between its two shafts. A brake
// holds its shaft against the ground; a brake between two shafts sits in the power line: it passes the
// motion rigidly (a joint equality) and brakes both against the ground (AGX's drive_train_brake: disengaged
// the motor turns the hinge through it, engaged it holds). An automatic one starts at 1 or 0 as initially
// engaged; the runtime ramps it when its engage input switches.
void Lowering::emit_friction_coupling(Element& /*equality*/, Element& tendons, const sn::DriveCoupling& c) {
  std::vector<int> shafts;
  for (int s : c.shafts) {
    if (s >= 0) shafts.push_back(s);
  }
  const bool clutch = c.kind == sn::DriveCoupling::Kind::Clutch;
  if (shafts.empty() || (clutch && shafts.size() != 2) || shafts.size() > 2) {
    warn(c.where, "`" + c.path + "` does not connect " +
                      (clutch ? "two drivetrain shafts" : "a drivetrain shaft") + "; it was left out");
    return;
  }
  if (!clutch && shafts.size() == 2) {  // the power line is folded into one joint (fold_rigid_shafts)
    drive_edges_.push_back({shafts[0], shafts[1], 1.0, nullptr});
    shafts.pop_back();
  }
  const double engagement = c.automatic ? (c.initially_engaged ? 1.0 : 0.0) : c.engagement_fraction;
  Element& tendon = tendons.add("fixed");
  tendon.set("name", name(c.path))
      .set("frictionloss", c.torque_capacity * std::clamp(engagement, 0.0, 1.0))
      .set("solreffriction", rigid_solref())
      .set("solimpfriction", rigid_solimp());
  for (size_t k = 0; k < shafts.size(); ++k)
    tendon.add("joint").set("joint", shaft_joints_[shafts[k]]).set("coef", k == 0 ? 1.0 : -1.0);
  friction_couplings_[index_in(system_.couplings, c)] = name(c.path);
}

// A motor on a shaft: a velocity motor is a motor constraint (velocity_motors.cpp) on the shaft's joint, its
// reference outweighing the whole drivetrain the shaft drives; a torque motor a <motor> on that joint.
void Lowering::emit_shaft_motor(Element& root, const sn::Interaction1D& i) {
  if (i.kind == sn::Interaction1D::Kind::TorqueMotor) {
    emit_effort_motor(*root.child("actuator"), i, shaft_joints_[i.shaft]);
    return;
  }
  emit_velocity_motor(root, i, shaft_joints_[i.shaft], drivetrain_inertia(i.shaft));
}

// Inertia reflected to shaft `start`: every shaft's inertia and every driven joint's subtree inertia, times
// the square of its speed relative to the start (gears scale speeds by their ratio; an even differential
// split is assumed).
double Lowering::drivetrain_inertia(int start) {
  std::map<int, double> speed{{start, 1.0}};
  std::vector<int> todo{start};
  double total = 0;
  while (!todo.empty()) {
    const int s = todo.back();
    todo.pop_back();
    total += std::max(system_.shafts[s].inertia, 1e-9) * speed[s] * speed[s];
    for (const DriveEdge& e : drive_edges_) {
      if (e.joint && e.from == s) total += effective_inertia(*e.joint) * speed[s] * speed[s];
      if (e.to < 0 || (e.from != s && e.to != s)) continue;
      const int next = e.from == s ? e.to : e.from;
      if (speed.count(next)) continue;
      speed[next] = e.from == s ? speed[s] * e.factor : speed[s] / e.factor;
      todo.push_back(next);
    }
  }
  return total;
}

}  // namespace openplx::mjcf
