#include "runtime/drive_laws.h"

#include <algorithm>
#include <cmath>

namespace openplx::runtime {

namespace {
constexpr double kRpmPerRadPerSecond = 60.0 / (2 * 3.14159265358979323846);
// Below idle the governor opens the throttle fully over the last tenth of the idle speed.
constexpr double kGovernorBand = 0.1;
}  // namespace

double interpolate(const std::vector<double>& x, const std::vector<double>& y, double at) {
  if (x.empty() || x.size() != y.size()) return 0;
  if (at <= x.front()) return y.front();
  if (at >= x.back()) return y.back();
  const size_t hi = static_cast<size_t>(std::upper_bound(x.begin(), x.end(), at) - x.begin());
  const size_t lo = hi - 1;
  const double span = x[hi] - x[lo];
  return span > 0 ? y[lo] + (y[hi] - y[lo]) * (at - x[lo]) / span : y[hi];
}

void DriveLaws::resolve(mjModel* m, const std::vector<mjcf::RuntimeLaw>& laws) {
  for (const mjcf::RuntimeLaw& source : laws) {
    if (source.kind != mjcf::RuntimeLaw::Kind::Engine &&
        source.kind != mjcf::RuntimeLaw::Kind::TorqueConverter)
      continue;
    Law law{source.kind,     {}, {}, source.curve_x, source.curve_y, source.curve2_x, source.curve2_y,
            source.parameter};
    for (const std::string& name : source.actuators) {
      const int a = mj_name2id(m, mjOBJ_ACTUATOR, name.c_str());
      if (a < 0 || m->actuator_trntype[a] != mjTRN_JOINT) break;
      law.actuators.push_back(a);
      law.dofs.push_back(m->jnt_dofadr[m->actuator_trnid[2 * a]]);
    }
    if (law.actuators.size() != source.actuators.size()) continue;
    if (law.kind == mjcf::RuntimeLaw::Kind::Engine) m->actuator_biasprm[law.actuators[0] * mjNBIAS + 2] = 0;
    laws_.push_back(std::move(law));
  }
}

void DriveLaws::apply(mjModel* m, mjData* d) {
  for (const Law& law : laws_) {
    switch (law.kind) {
      case mjcf::RuntimeLaw::Kind::Engine: {
        // torque = curve(speed) * max(throttle, governor)
        const int a = law.actuators[0];
        const double rpm = d->qvel[law.dofs[0]] * kRpmPerRadPerSecond, idle = law.parameter;
        const double full = interpolate(law.x, law.y, rpm);
        const double governor = idle > 0 ? std::clamp((idle - rpm) / (kGovernorBand * idle), 0.0, 1.0) : 0.0;
        const double throttle = std::clamp(d->ctrl[a], 0.0, 1.0);
        m->actuator_gainprm[a * mjNGAIN] = full;
        m->actuator_biasprm[a * mjNBIAS] = full * std::max(0.0, governor - throttle);
        break;
      }
      case mjcf::RuntimeLaw::Kind::TorqueConverter: {
        const double pump = d->qvel[law.dofs[0]], turbine = d->qvel[law.dofs[1]];
        double pump_torque = 0, turbine_torque = 0;
        if (std::abs(pump) > 1e-9) {
          const double nu = turbine / pump;
          const double factor = interpolate(law.x, law.y, nu), multiplier = interpolate(law.x2, law.y2, nu);
          pump_torque = -factor * law.parameter * pump * std::abs(pump);
          turbine_torque = -multiplier * pump_torque;
        }
        d->ctrl[law.actuators[0]] = pump_torque;
        d->ctrl[law.actuators[1]] = turbine_torque;
        break;
      }
      default:
        break;  // constraint rows (constraint_rows.h)
    }
  }
}

}  // namespace openplx::runtime
