// Lowering pass, signals of shafts and of drivetrain parts beyond gears, clutches and brakes: gearboxes (gear
// number, ratio), flexible and viscous gears (tendon torque), differential lock-up, torque converters and
// engines.
#include "mjcf_emitter/lowering.h"

namespace openplx::mjcf {

namespace {
constexpr double kRpmPerRadPerSecond = 60.0 / (2 * 3.14159265358979323846);
}

// A shaft's angle and speed outputs: its joint's, or for a folded shaft the joint of its group less that
// joint's initial value (JointPosition's polynomial {qpos0, 1}). False, `b` untouched: not one of these.
bool Lowering::bind_shaft(SignalBinding& b, std::string_view stem, int shaft) {
  if (b.input || !any_of(stem, {"Angle", "AngularVelocity1D"})) return false;
  const bool angle = stem == "Angle";
  mapped(b, angle ? Quantity::JointPosition : Quantity::JointVelocity, MjObject::Joint, shaft_joints_[shaft]);
  if (angle && shaft_offsets_[shaft] != 0) b.initial_vector = {shaft_offsets_[shaft], 1.0};
  return true;
}

// False, `b` untouched: not one of these parts' signals (bind_coupling goes on).
bool Lowering::bind_drive_part(SignalBinding& b, std::string_view stem, int k) {
  const sn::DriveCoupling& c = system_.couplings[k];
  const bool enable = any_of(stem, {"EnableInteraction", "InteractionEnabled"});
  if (gearboxes_.count(k)) {
    const std::string& equality = gear_equalities_.at(k);
    if (stem == "Int") {
      mapped(b, Quantity::GearSelect, MjObject::Equality, equality);
      b.initial = c.initial_gear;
      b.initial_vector = c.forward_gears;
      b.initial_vector.insert(b.initial_vector.end(), c.reverse_gears.begin(), c.reverse_gears.end());
      b.low = static_cast<double>(c.forward_gears.size());
      b.high = c.has_neutral_gear ? 1.0 : 0.0;
      return true;
    }
    if (stem == "Ratio" && !b.input) {
      mapped(b, Quantity::GearRatio, MjObject::Equality, equality);
      return true;
    }
  }
  if (enable) {
    if (auto gear = gear_equalities_.find(k); gear != gear_equalities_.end()) {
      mapped(b, Quantity::EqualityActive, MjObject::Equality, gear->second);
      return true;
    }
  }
  if (auto tendon = tendon_gears_.find(k); tendon != tendon_gears_.end()) {
    if (stem == "Torque1D" && !b.input) {
      mapped(b, Quantity::TendonSpringForce, MjObject::Tendon, tendon->second);
      return true;
    }
    if (stem == "Fraction" && !b.input) {
      b.quantity = Quantity::Constant;
      b.initial = c.ratio;
      return true;
    }
    if (stem == "Fraction") {
      unmapped(b, "`" + c.path + "` is a flexible or viscous gear, a tendon whose ratio is fixed");
      return true;
    }
  }
  if (auto lock = differential_locks_.find(k); lock != differential_locks_.end() && stem == "Bool") {
    mapped(b, Quantity::EqualityActive, MjObject::Equality, lock->second);
    return true;
  }
  if (auto converter = converters_.find(k); converter != converters_.end()) {
    const std::string& base = converter->second;
    if (stem == "RelativeVelocity1D" && !b.input) {
      mapped(b, Quantity::TendonVelocity, MjObject::Tendon, base);
      return true;
    }
    if (any_of(stem, {"TorqueConverterLockUp", "TorqueConverterLockedUp"})) {
      mapped(b, Quantity::EqualityActive, MjObject::Equality, base + "/lock_up");
      return true;
    }
    if (any_of(stem, {"TorqueConverterPumpTorque", "TorqueConverterTurbineTorque"}) && !b.input) {
      const bool pump = stem == "TorqueConverterPumpTorque";
      mapped(b, Quantity::ActuatorForce, MjObject::Actuator, base + (pump ? "/pump" : "/turbine"));
      b.runtime = true;
      return true;
    }
  }
  if (auto engine = engines_.find(k); engine != engines_.end()) {
    if (stem == "Fraction") {  // the throttle
      mapped(b, Quantity::Ctrl, MjObject::Actuator, engine->second);
      b.initial = std::clamp(c.initial_throttle, 0.0, 1.0);
      b.runtime = true;
      return true;
    }
    if (stem == "Torque1D" && !b.input) {
      mapped(b, Quantity::ActuatorForce, MjObject::Actuator, engine->second);
      b.runtime = true;
      return true;
    }
    if (stem == "Rpm" && !b.input) {
      mapped(b, Quantity::JointVelocity, MjObject::Joint, shaft_joints_[c.shafts[0]]);
      b.sign = kRpmPerRadPerSecond;
      return true;
    }
    if (enable) {
      unmapped(b, "`" + c.path + "` is an engine, whose actuator cannot be switched off");
      return true;
    }
  }
  return false;
}

}  // namespace openplx::mjcf
