// Lowering pass, drivetrain parts between shafts: gears (rigid, flexible, viscous), gearboxes, differentials
// (open, locked, torque-limited slip), torque converters and engines. Engines and converters follow laws MJCF
// cannot state: their actuators carry the closest static behaviour and the runtime's RuntimeLaw the rest.
#include <cmath>

#include "mjcf_emitter/lowering.h"

namespace openplx::mjcf {

namespace {

constexpr double kPi = 3.14159265358979323846;

void split_curve(const sn::Curve& curve, std::vector<double>& x, std::vector<double>& y) {
  for (const auto& [a, b] : curve) {
    x.push_back(a);
    y.push_back(b);
  }
}

}  // namespace

// A rigid gear: the output shaft (joint1) turns 1 / ratio times the input (joint2).
Element& Lowering::gear_equality(Element& equality, const sn::DriveCoupling& c, double ratio) {
  Element& e = equality.add("joint");
  e.set("name", name(c.path))
      .set("joint1", shaft_joints_[c.shafts[1]])
      .set("joint2", shaft_joints_[c.shafts[0]])
      .set("polycoef", "0 " + number(1 / ratio) + " 0 0 0");
  gear_equalities_[index_in(system_.couplings, c)] = name(c.path);
  drive_edges_.push_back({c.shafts[0], c.shafts[1], 1 / ratio, nullptr});
  return e;
}

// Gear, FlexibleGear, ViscousGear. A finite stiffness or viscosity makes the slip q_out - q_in / ratio a
// fixed tendon with that stiffness and damping; MuJoCo's Euler step integrates tendon springs and dampers
// explicitly, so one too stiff for the step (k h^2 > I / 4 or b h > I, I the slip's inertia) is emitted
// rigid, which is what it is at that step, with a warning.
void Lowering::emit_gear(Element& equality, Element& tendons, const sn::DriveCoupling& c) {
  if (c.ratio == 0) {
    warn(c.where, "`" + c.path + ".ratio` is 0; the gear was left out");
    return;
  }
  const bool viscous = std::isfinite(c.viscosity);
  if (!viscous && !std::isfinite(c.stiffness)) {
    gear_equality(equality, c, c.ratio);
    return;
  }
  const double i_in = std::max(system_.shafts[c.shafts[0]].inertia, 1e-9);
  const double i_out = std::max(system_.shafts[c.shafts[1]].inertia, 1e-9);
  const double inertia = 1 / (1 / i_out + 1 / (c.ratio * c.ratio * i_in));
  const double h = options_.timestep;
  const double k = viscous ? 0.0 : c.stiffness, b = viscous ? c.viscosity : c.damping;
  if (k * h * h > inertia / 4 || b * h > inertia) {
    const bool by_stiffness = k * h * h > inertia / 4;
    warn(c.where, "`" + c.path +
                      (by_stiffness ? ".flexibility.stiffness` (" + number(k) + " N*m/rad)"
                                    : "` damping (" + number(b) + " N*m*s/rad)") +
                      " is too stiff for MuJoCo's explicit tendon forces at time step " + number(h) +
                      " s with these shaft inertias; the gear was emitted rigid");
    gear_equality(equality, c, c.ratio);
    return;
  }
  Element& tendon = tendons.add("fixed");
  tendon.set("name", name(c.path));
  if (k > 0) tendon.set("stiffness", k);
  if (b > 0) tendon.set("damping", b);
  tendon.add("joint").set("joint", shaft_joints_[c.shafts[1]]).set("coef", 1.0);
  tendon.add("joint").set("joint", shaft_joints_[c.shafts[0]]).set("coef", -1 / c.ratio);
  tendon_gears_[index_in(system_.couplings, c)] = name(c.path);
  drive_edges_.push_back({c.shafts[0], c.shafts[1], 1 / c.ratio, nullptr});
}

// A gearbox is a gear whose ratio its gear input selects (the runtime re-anchors the equality, as for a
// gear's ratio input); neutral switches the equality off.
void Lowering::emit_gearbox(Element& equality, const sn::DriveCoupling& c) {
  const GearSelection initial =
      gearbox_ratio(c.forward_gears, c.reverse_gears, c.has_neutral_gear, c.initial_gear);
  if (!initial.valid) {
    warn(c.where, "`" + c.path + ".initial_gear` (" + std::to_string(c.initial_gear) +
                      ") selects no gear of its lists; it starts in neutral");
  }
  if (std::isfinite(c.stiffness)) {
    warn(c.where, "`" + c.path +
                      ".flexibility` has no mapping for a gearbox (its ratio changes at run time, a tendon's "
                      "cannot); the gearbox is rigid");
  }
  double any = 1.0;  // the equality's ratio while in neutral: any gear's, so that speeds stay plausible
  for (double r : c.forward_gears)
    if (r != 0) any = std::abs(r);
  Element& e = gear_equality(equality, c, initial.ratio != 0 ? initial.ratio : any);
  if (initial.ratio == 0) e.set("active", "false");
  gearboxes_.insert(index_in(system_.couplings, c));
}

void Lowering::emit_differential(Element& equality, Element& tendons, const sn::DriveCoupling& c) {
  const std::string& drive = shaft_joints_[c.shafts[0]];
  const std::string& left = shaft_joints_[c.shafts[1]];
  const std::string& right = shaft_joints_[c.shafts[2]];
  Element& tendon = tendons.add("fixed");
  tendon.set("name", name(c.path));
  const double half = c.ratio / 2;
  tendon.add("joint").set("joint", drive).set("coef", 1.0);
  tendon.add("joint").set("joint", left).set("coef", -half);
  tendon.add("joint").set("joint", right).set("coef", -half);
  equality.add("tendon").set("name", name(c.path)).set("tendon1", name(c.path));
  // Locked up, both axles turn together: an equality its lock-up input switches.
  const std::string lock = name(c.path) + "/lock";
  equality.add("joint")
      .set("name", lock)
      .set("joint1", left)
      .set("joint2", right)
      .set("polycoef", "0 1 0 0 0")
      .set("active", c.locked_up ? "true" : "false");
  differential_locks_[index_in(system_.couplings, c)] = lock;
  // Torque-limited slip: the axles stick until the torque between them passes the breakaway torque, dry
  // friction on their difference (rigid rows, like clutches).
  if (c.breakaway_torque >= 0) {
    Element& slip = tendons.add("fixed");
    slip.set("name", name(c.path) + "/slip")
        .set("frictionloss", c.breakaway_torque)
        .set("solreffriction", rigid_solref())
        .set("solimpfriction", rigid_solimp());
    slip.add("joint").set("joint", left).set("coef", 1.0);
    slip.add("joint").set("joint", right).set("coef", -1.0);
  }
  // For gain estimates: an axle turns about 1/gear_ratio as fast as the drive.
  drive_edges_.push_back({c.shafts[0], c.shafts[1], 1 / c.ratio, nullptr});
  drive_edges_.push_back({c.shafts[0], c.shafts[2], 1 / c.ratio, nullptr});
}

// Pump and turbine torques are <motor>s the runtime sets each step from the converter's tables; the MJCF
// alone transmits nothing through the fluid. A tendon gives the slip velocity, an equality the lock-up.
void Lowering::emit_torque_converter(Element& equality, Element& tendons, const sn::DriveCoupling& c) {
  const std::string& pump = shaft_joints_[c.shafts[0]];
  const std::string& turbine = shaft_joints_[c.shafts[1]];
  const std::string base = name(c.path);
  Element& slip = tendons.add("fixed");
  slip.set("name", base);
  slip.add("joint").set("joint", turbine).set("coef", 1.0);
  slip.add("joint").set("joint", pump).set("coef", -1.0);
  equality.add("joint")
      .set("name", base + "/lock_up")
      .set("joint1", turbine)
      .set("joint2", pump)
      .set("polycoef", "0 1 0 0 0")
      .set("active", "false");
  RuntimeLaw law;
  law.kind = RuntimeLaw::Kind::TorqueConverter;
  law.path = c.path;
  law.actuators = {base + "/pump", base + "/turbine"};
  split_curve(c.geometry_factors, law.curve_x, law.curve_y);
  split_curve(c.torque_multipliers, law.curve2_x, law.curve2_y);
  law.parameter = c.oil_density * std::pow(c.diameter, 5);
  for (size_t k = 0; k < 2; ++k) {
    Element motor("motor");
    motor.set("name", law.actuators[k]).set("joint", k == 0 ? pump : turbine);
    drive_actuators_.push_back({std::move(motor), 0.0});
  }
  laws_.push_back(std::move(law));
  converters_[index_in(system_.couplings, c)] = base;
  drive_edges_.push_back({c.shafts[0], c.shafts[1], 1.0, nullptr});
}

// An engine: a <general> actuator on its shaft whose control is the throttle. Statically its torque is
// throttle * peak torque falling linearly with speed to nothing where the curve ends; the runtime replaces
// gain and bias each step with the curve at the shaft's speed and the idle governor.
void Lowering::emit_engine(const sn::DriveCoupling& c) {
  double peak = 0, end_rpm = 0;
  for (const auto& [rpm, torque] : c.torque_curve) {
    peak = std::max(peak, torque);
    if (torque > 0 || end_rpm == 0) end_rpm = rpm;
  }
  for (const auto& [rpm, torque] : c.torque_curve) {  // the first zero past the last positive point
    if (rpm > end_rpm && torque <= 0) {
      end_rpm = rpm;
      break;
    }
  }
  const double end_speed = std::max(end_rpm, 1.0) * 2 * kPi / 60;
  const std::string actuator = name(c.path);
  Element engine("general");
  engine.set("name", actuator)
      .set("joint", shaft_joints_[c.shafts[0]])
      .set("gainprm", peak)
      .set("biastype", "affine")
      .set("biasprm", "0 0 " + number(-peak / end_speed))
      .set("ctrllimited", "true")
      .set("ctrlrange", "0 1");
  if (std::isfinite(c.min_effort) || std::isfinite(c.max_effort)) {
    engine.set("forcelimited", "true")
        .set("forcerange", number(std::isfinite(c.min_effort) ? c.min_effort : -kNoEffortLimit) + " " +
                               number(std::isfinite(c.max_effort) ? c.max_effort : kNoEffortLimit));
  }
  drive_actuators_.push_back({std::move(engine), std::clamp(c.initial_throttle, 0.0, 1.0)});
  RuntimeLaw law;
  law.kind = RuntimeLaw::Kind::Engine;
  law.path = c.path;
  law.actuators = {actuator};
  split_curve(c.torque_curve, law.curve_x, law.curve_y);
  law.parameter = c.idle_rpm;
  laws_.push_back(std::move(law));
  engines_[index_in(system_.couplings, c)] = actuator;
}

// Engines' and converters' actuators, after every other actuator (their indices follow them).
void Lowering::emit_drive_actuators(Element& actuators) {
  for (DriveActuator& a : drive_actuators_) {
    actuators.add(std::move(a.element));
    drive_ctrl_.emplace_back(static_cast<int>(actuator_count_++), a.ctrl);
  }
  drive_actuators_.clear();
}

}  // namespace openplx::mjcf
