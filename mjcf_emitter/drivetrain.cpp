// Lowering pass, drivetrain: shafts as rotor bodies, actuator/gear joint equalities, differential tendons,
// shaft motors.
#include "mjcf_emitter/lowering.h"

namespace openplx::mjcf {

using natives::affine_compose;
using natives::affine_inverse;

void Lowering::emit_drivetrain(Element& root) {
  if (view_.shafts.empty()) return;
  std::vector<double> crank(view_.shafts.size(), 0.0);  // engines' own inertia turns with their shaft
  for (const sn::DriveCoupling& c : view_.couplings) {
    if (c.kind == sn::DriveCoupling::Kind::Engine && c.shafts.size() == 1 && c.shafts[0] >= 0)
      crank[static_cast<size_t>(c.shafts[0])] += std::max(c.crank_inertia, 0.0);
  }
  for (size_t k = 0; k < view_.shafts.size(); ++k) {
    const sn::Shaft& shaft = view_.shafts[k];
    Element& body = world_->add("body");
    body.set("name", name(shaft.path)).set("pos", "0 0 0");
    Element& joint = body.add("joint");
    joint.set("name", name(shaft.path)).set("type", "hinge").set("axis", "0 0 1");
    if (crank[k] > 0) joint.set("armature", crank[k]);
    const double inertia = std::max(shaft.inertia, 1e-9);
    body.add("inertial")
        .set("pos", "0 0 0")
        .set("mass", 1.0)
        .set("diaginertia", Eigen::Vector3d::Constant(inertia));
    shaft_joints_.push_back(name(shaft.path));
  }
  Element& equality = *root.child("equality");
  Element& tendons = root.add("tendon");
  using Kind = sn::DriveCoupling::Kind;
  for (const sn::DriveCoupling& c : view_.couplings) {
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
        Element* joint = c.mate >= 0 && tree_mates_.count(c.mate)
                             ? joint_for(c.mate, view_.mates[c.mate].type != sn::MateType::Prismatic)
                             : nullptr;
        if (!joint) {
          warn(c.where, "`" + c.path +
                            ".mate_3d` is not a hinge or prismatic joint of MuJoCo's tree; the "
                            "actuator was left out");
          continue;
        }
        equality.add("joint")
            .set("name", name(c.path))
            .set("joint1", *joint->get("name"))
            .set("joint2", shaft_joints_[c.shafts[0]])
            .set("polycoef", "0 1 0 0 0");
        drive_edges_.push_back({c.shafts[0], -1, 1.0, joint});
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
void Lowering::emit_friction_coupling(Element& equality, Element& tendons, const sn::DriveCoupling& c) {
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
  if (!clutch && shafts.size() == 2) {
    equality.add("joint")
        .set("name", name(c.path) + "/line")
        .set("joint1", shaft_joints_[shafts[1]])
        .set("joint2", shaft_joints_[shafts[0]])
        .set("polycoef", "0 1 0 0 0");
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
  friction_couplings_[index_in(view_.couplings, c)] = name(c.path);
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
    total += std::max(view_.shafts[s].inertia, 1e-9) * speed[s] * speed[s];
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
