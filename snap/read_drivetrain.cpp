#include "snap/read_drivetrain.h"

#include <algorithm>
#include <cmath>

namespace openplx::snap {

namespace fe = openplx::frontend;

namespace {

// A list of gear ratios: each finite and not 0 (a ratio of 0 would hold the output still, or divide by 0).
std::vector<double> ratios(AttributeReader& in, fe::ObjectId id, std::string_view name) {
  std::vector<double> out;
  const fe::Value* v = in.evaluator().value(id, name);
  if (v && v->kind == fe::Value::Kind::Array) {
    for (const fe::Value& item : v->array()) {
      if (!item.is_number()) continue;
      out.push_back(item.as_real());
      in.require(std::isfinite(out.back()) && out.back() != 0, id, name, out.back(),
                 "a gear ratio is a finite number other than 0");
    }
  }
  return out;
}

double ratio(AttributeReader& in, fe::ObjectId id, std::string_view name) {
  const double r = in.real(id, name, 1.0);
  in.require(std::isfinite(r) && r != 0, id, name, r, "a gear ratio is a finite number other than 0");
  return r;
}

// A number that must be finite and 0 or positive (capacities, durations, densities).
double nonnegative(AttributeReader& in, fe::ObjectId id, std::string_view name, double fallback,
                   std::string_view what) {
  const double v = in.real(id, name, fallback);
  in.require(std::isfinite(v) && v >= 0, id, name, v,
             std::string(what) + " is a finite number, 0 or positive");
  return v;
}

// Pairs (x, y) read from a list of objects, sorted by x.
Curve pairs(AttributeReader& in, fe::ObjectId id, std::string_view list, std::string_view x,
            std::string_view y) {
  Curve out;
  for (fe::ObjectId item : in.objects(id, list)) out.emplace_back(in.real(item, x), in.real(item, y));
  std::stable_sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  return out;
}

void read_friction_coupling(AttributeReader& in, fe::ObjectId id, DriveCoupling& c) {
  c.torque_capacity = nonnegative(in, id, "torque_capacity", 0.0, "a torque capacity");
  c.engagement_fraction = in.real(id, "initial_engagement_fraction", 1.0);
  in.require(c.engagement_fraction >= 0 && c.engagement_fraction <= 1, id, "initial_engagement_fraction",
             c.engagement_fraction, "an engagement fraction is from 0 to 1");
  // AGX's threshold for locking the plates (docs/mapping.md "Clutches and brakes"): MuJoCo's friction rows
  // stick and slip by the solver alone, so it has nothing to set. Read, so it is not reported as ignored.
  (void)in.number(id, "min_relative_slip_ratio");
  c.automatic = in.graph().at(id).has("engagement_duration");
  if (!c.automatic) return;
  c.initially_engaged = in.boolean(id, "initially_engaged").value_or(false);
  c.engagement_duration = nonnegative(in, id, "engagement_duration", 0.1, "a duration");
  c.disengagement_duration = nonnegative(in, id, "disengagement_duration", 0.1, "a duration");
}

// Flexibility (LinearElastic stiffness), damping (MechanicalDamping) and viscosity (viscous friction).
void read_compliance(AttributeReader& in, fe::ObjectId id, DriveCoupling& c) {
  if (const fe::ObjectId f = in.object(id, "flexibility"); f != fe::kNoObject) {
    c.stiffness = in.real(f, "stiffness", kInf);
    in.require(c.stiffness >= 0, f, "stiffness", c.stiffness,
               "a stiffness is 0 or positive (Math.INF: rigid)");
  }
  if (const fe::ObjectId d = in.object(id, "dissipation"); d != fe::kNoObject) {
    c.damping = nonnegative(in, d, "damping_constant", 0.0, "a damping constant");
    c.viscosity = in.real(d, "viscosity", kInf);
    in.require(c.viscosity >= 0, d, "viscosity", c.viscosity,
               "a viscosity is 0 or positive (Math.INF: none)");
  }
}

}  // namespace

double interpolate(const Curve& curve, double x) {
  if (curve.empty()) return 0;
  if (x <= curve.front().first) return curve.front().second;
  if (x >= curve.back().first) return curve.back().second;
  auto hi = std::upper_bound(curve.begin(), curve.end(), x,
                             [](double v, const std::pair<double, double>& p) { return v < p.first; });
  auto lo = hi - 1;
  const double span = hi->first - lo->first;
  return span > 0 ? lo->second + (hi->second - lo->second) * (x - lo->first) / span : hi->second;
}

Curve mean_value_torque_curve(double max_torque, double max_torque_rpm, double max_power_rpm, double idle_rpm,
                              double max_rpm) {
  const double nt = std::max(max_torque_rpm, 1.0);
  // T = Tmax (1 - k (n - nt)^2); d(T n)/dn = 0 at np gives k = 1 / ((np - nt)(3 np - nt)).
  const double k =
      max_power_rpm > nt ? 1.0 / ((max_power_rpm - nt) * (3 * max_power_rpm - nt)) : 1.0 / (nt * nt);
  auto parabola = [&](double n) { return max_torque * std::max(0.0, 1.0 - k * (n - nt) * (n - nt)); };
  const double top = max_rpm > 0 ? max_rpm : nt + 1.0 / std::sqrt(k);
  const double floor = parabola(std::clamp(idle_rpm, 0.0, nt));
  Curve curve;
  constexpr int kSamples = 40;
  std::vector<double> speeds{nt, idle_rpm, max_power_rpm};  // the rated points exactly
  for (int i = 0; i <= kSamples; ++i) speeds.push_back(top * i / kSamples);
  std::sort(speeds.begin(), speeds.end());
  for (double n : speeds) {
    if (n < 0 || n > top || (!curve.empty() && n - curve.back().first < 1e-9)) continue;
    curve.emplace_back(n, n < nt ? std::max(parabola(n), floor) : parabola(n));
  }
  curve.emplace_back(top * (1 + 1e-9), 0.0);  // the rev limiter
  return curve;
}

void read_drive_parameters(AttributeReader& in, fe::ObjectId id, DriveCoupling& c) {
  using Kind = DriveCoupling::Kind;
  switch (c.kind) {
    case Kind::Gear:
      c.ratio = ratio(in, id, "ratio");
      read_compliance(in, id, c);
      break;
    case Kind::Differential:
      c.ratio = ratio(in, id, "gear_ratio");
      c.locked_up = in.boolean(id, "locked_up").value_or(false);
      c.breakaway_torque = in.real(id, "breakaway_torque", -1.0);
      break;
    case Kind::Clutch:
    case Kind::Brake:
      read_friction_coupling(in, id, c);
      break;
    case Kind::GearBox:
      c.forward_gears = ratios(in, id, "forward_gears");
      c.reverse_gears = ratios(in, id, "reverse_gears");
      // Clamped into an int (2^31 would not fit); a gear the lists lack is warned by the emitter.
      {
        const double gear = in.real(id, "initial_gear", 0.0);  // NaN would make the cast undefined
        c.initial_gear = std::isnan(gear) ? 0 : static_cast<int>(std::clamp(gear, -1e9, 1e9));
      }
      c.has_neutral_gear = in.boolean(id, "has_neutral_gear").value_or(true);
      read_compliance(in, id, c);
      break;
    case Kind::Engine:
      c.initial_throttle = in.real(id, "initial_throttle", 0.0);
      c.min_effort = in.real(id, "min_effort", -kInf);
      c.max_effort = in.real(id, "max_effort", kInf);
      if (in.graph().at(id).has("rpm_torque_list")) {
        c.torque_curve = pairs(in, id, "rpm_torque_list", "rpm", "torque");
        // An empty table gives no torque at any throttle: a silent dead engine.
        if (c.torque_curve.empty())
          in.refuse(id, "rpm_torque_list", "is empty; an engine's torque table has at least one point");
        c.idle_rpm = in.real(id, "idle_rpm", 0.0);
      } else {
        // The curve is built from these speeds; 0 or less describes no engine (a curve of 1 rev/min).
        for (const char* rated : {"max_torque_RPM", "max_power_RPM", "max_RPM"}) {
          const double v = in.real(id, rated, 1.0);
          in.require(std::isfinite(v) && v > 0, id, rated, v, "an engine's rated speed is a positive RPM");
        }
        c.idle_rpm = in.real(id, "idle_RPM", 0.0);
        in.require(std::isfinite(c.idle_rpm) && c.idle_rpm >= 0, id, "idle_RPM", c.idle_rpm,
                   "an engine's idle speed is 0 or a positive RPM");
        c.crank_inertia = in.real(id, "crank_shaft_inertia", 0.0);
        c.torque_curve =
            mean_value_torque_curve(in.real(id, "max_torque"), in.real(id, "max_torque_RPM"),
                                    in.real(id, "max_power_RPM"), c.idle_rpm, in.real(id, "max_RPM", 0.0));
      }
      break;
    case Kind::TorqueConverter:
      c.geometry_factors =
          pairs(in, id, "velocity_ratio_geometry_factor_list", "velocity_ratio", "geometry_factor");
      c.torque_multipliers =
          pairs(in, id, "velocity_ratio_torque_multiplier_list", "velocity_ratio", "multiplier");
      c.oil_density = in.real(id, "oil_density");
      c.diameter = in.real(id, "diameter");
      c.lock_up_time = in.real(id, "lock_up_time");
      break;
    case Kind::Actuator:
      break;
  }
}

}  // namespace openplx::snap
