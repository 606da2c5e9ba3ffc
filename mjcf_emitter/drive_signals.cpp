// Lowering pass, signals of drivetrain parts beyond gears, clutches and brakes: gearboxes (gear number,
// ratio), flexible and viscous gears (tendon torque), differential lock-up, torque converters and engines.
#include "mjcf_emitter/lowering.h"

namespace openplx::mjcf {

namespace {
constexpr double kRpmPerRadPerSecond = 60.0 / (2 * 3.14159265358979323846);
}

// nullopt: not one of these parts' signals (bind_coupling goes on).
std::optional<SignalBinding> Lowering::bind_drive_part(SignalBinding b, std::string_view stem, int k) {
  const sn::DriveCoupling& c = view_.couplings[k];
  const bool enable = any_of(stem, {"EnableInteraction", "InteractionEnabled"});
  if (gearboxes_.count(k)) {
    const std::string& equality = gear_equalities_.at(k);
    if (stem == "Int") {
      b = mapped(std::move(b), Quantity::GearSelect, MjObject::Equality, equality);
      b.initial = c.initial_gear;
      b.initial_vector = c.forward_gears;
      b.initial_vector.insert(b.initial_vector.end(), c.reverse_gears.begin(), c.reverse_gears.end());
      b.low = static_cast<double>(c.forward_gears.size());
      b.high = c.has_neutral_gear ? 1.0 : 0.0;
      return b;
    }
    if (stem == "Ratio" && !b.input)
      return mapped(std::move(b), Quantity::GearRatio, MjObject::Equality, equality);
  }
  if (enable) {
    if (auto gear = gear_equalities_.find(k); gear != gear_equalities_.end())
      return mapped(std::move(b), Quantity::EqualityActive, MjObject::Equality, gear->second);
  }
  if (auto tendon = tendon_gears_.find(k); tendon != tendon_gears_.end()) {
    if (stem == "Torque1D" && !b.input)
      return mapped(std::move(b), Quantity::TendonSpringForce, MjObject::Tendon, tendon->second);
    if (stem == "Fraction" && !b.input) {
      b.quantity = Quantity::Constant;
      b.initial = c.ratio;
      return b;
    }
    if (stem == "Fraction")
      return unmapped(std::move(b),
                      "`" + c.path + "` is a flexible or viscous gear, a tendon whose ratio is fixed");
  }
  if (auto lock = differential_locks_.find(k); lock != differential_locks_.end() && stem == "Bool")
    return mapped(std::move(b), Quantity::EqualityActive, MjObject::Equality, lock->second);
  if (auto converter = converters_.find(k); converter != converters_.end()) {
    const std::string& base = converter->second;
    if (stem == "RelativeVelocity1D" && !b.input)
      return mapped(std::move(b), Quantity::TendonVelocity, MjObject::Tendon, base);
    if (any_of(stem, {"TorqueConverterLockUp", "TorqueConverterLockedUp"}))
      return mapped(std::move(b), Quantity::EqualityActive, MjObject::Equality, base + "/lock_up");
    if (any_of(stem, {"TorqueConverterPumpTorque", "TorqueConverterTurbineTorque"}) && !b.input) {
      const bool pump = stem == "TorqueConverterPumpTorque";
      b = mapped(std::move(b), Quantity::ActuatorForce, MjObject::Actuator,
                 base + (pump ? "/pump" : "/turbine"));
      b.runtime = true;
      return b;
    }
  }
  if (auto engine = engines_.find(k); engine != engines_.end()) {
    if (stem == "Fraction") {  // the throttle
      b = mapped(std::move(b), Quantity::Ctrl, MjObject::Actuator, engine->second);
      b.initial = std::clamp(c.initial_throttle, 0.0, 1.0);
      b.runtime = true;
      return b;
    }
    if (stem == "Torque1D" && !b.input) {
      b = mapped(std::move(b), Quantity::ActuatorForce, MjObject::Actuator, engine->second);
      b.runtime = true;
      return b;
    }
    if (stem == "Rpm" && !b.input) {
      b = mapped(std::move(b), Quantity::JointVelocity, MjObject::Joint, shaft_joints_[c.shafts[0]]);
      b.sign = kRpmPerRadPerSecond;
      return b;
    }
    if (enable)
      return unmapped(std::move(b), "`" + c.path + "` is an engine, whose actuator cannot be switched off");
  }
  return std::nullopt;
}

}  // namespace openplx::mjcf
