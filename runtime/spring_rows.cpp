#include "runtime/spring_rows.h"

#include <algorithm>
#include <string>

namespace openplx::runtime {

namespace {

// The fraction of MuJoCo's softness a hardened friction row keeps. A row leaks h (1 - d) of the acceleration
// a0 it holds back per step, 1 - d = 1e-4 at MuJoCo's stiffest; this leaves 1e-8. Harder rows (1e-6 and
// below, measured on a 7-link arm of motors) gain nothing: the Newton solver's Hessian, beside the motors'
// 1e9 reference inertias, loses that precision.
constexpr double kHardenedSoftness = 1e-4;

}  // namespace

bool SpringRows::resolve(mjModel* m, const mjcf::RuntimeLaw& law) {
  if (law.actuators.size() != 1 || mjDISABLED(mjDSBL_FRICTIONLOSS) || mjDISABLED(mjDSBL_CONSTRAINT))
    return false;
  const std::string& name = law.actuators.front();
  const int a = mj_name2id(m, mjOBJ_ACTUATOR, name.c_str()), t = mj_name2id(m, mjOBJ_TENDON, name.c_str());
  if (a < 0 || t < 0 || m->actuator_trntype[a] != mjTRN_JOINT || m->tendon_num[t] != 1) return false;
  const int wrap = m->tendon_adr[t], joint = m->actuator_trnid[2 * a];
  if (m->wrap_type[wrap] != mjWRAP_JOINT || m->wrap_objid[wrap] != joint || m->wrap_prm[wrap] != 1.0)
    return false;
  const double k = m->actuator_gainprm[a * mjNGAIN];
  if (!(k > 0)) return false;
  Spring s;
  s.actuator = a;
  s.tendon = t;
  s.stiffness = k;
  s.relaxation_time = law.parameter;
  for (int i = 0; i < m->nsensor; ++i) {
    if (m->sensor_type[i] == mjSENS_ACTUATORFRC && m->sensor_objid[i] == a) s.sensors.push_back(i);
  }
  // The actuator keeps only the range's centre (written each step); the row is the spring.
  m->actuator_gainprm[a * mjNGAIN] = 0;
  m->actuator_biasprm[a * mjNBIAS + 1] = 0;
  m->actuator_biasprm[a * mjNBIAS + 2] = 0;
  const int dof = m->jnt_dofadr[joint];
  m->dof_damping[dof] = std::max(0.0, m->dof_damping[dof] - law.joint_damping);
  m->tendon_frictionloss[t] =
      1;  // any positive value makes mj_step1 build the row; write_rows sets its bound
  if (spring_of_tendon_.empty()) spring_of_tendon_.assign(static_cast<size_t>(m->ntendon), -1);
  spring_of_tendon_[static_cast<size_t>(t)] = static_cast<int>(springs_.size());
  springs_.push_back(std::move(s));
  return true;
}

void SpringRows::take_over_noslip(mjModel* m) {
  if (m->opt.noslip_iterations <= 0 || springs_.empty()) return;
  harden_other_friction_rows_ = true;
  m->opt.noslip_iterations = 0;
}

// SPOOK (Lacoursiere): with relaxation time tau, Y = 1 / (1 + 4 tau / h), the row satisfies
//   G v+ + S lambda = -(4 Y / h) g + Y G v,   S = 4 Y / (h^2 k),   lambda = h f,
// which for MuJoCo's row (J a + R f = aref, v+ = v + h a) is R = S and aref = -(4 Y / h^2) g - (1 - Y) / h v.
// The solver clamps f to the friction bound: the range's half width about its centre c, which the actuator
// pushes; aref - R c makes the row's unclamped force f - c, so the sum is clamp(f, min, max).
void SpringRows::write_rows(mjModel* m, mjData* d) {
  for (Spring& s : springs_) s.row = -1;
  for (int r = d->ne; r < d->ne + d->nf; ++r) {
    const bool tendon = d->efc_type[r] == mjCNSTR_FRICTION_TENDON && !spring_of_tendon_.empty();
    const int spring = tendon ? spring_of_tendon_[static_cast<size_t>(d->efc_id[r])] : -1;
    if (spring >= 0) {
      springs_[static_cast<size_t>(spring)].row = r;
    } else if (harden_other_friction_rows_ && d->efc_R[r] > kHardenedSoftness * d->efc_diagApprox[r]) {
      // Noslip's work, nearly: the row without most of its softness (once per mj_step1: MuJoCo's own R is
      // 1e-4 of diagApprox, a hardened one well below kHardenedSoftness of it).
      d->efc_R[r] *= kHardenedSoftness;
      d->efc_D[r] = 1 / d->efc_R[r];
    }
  }
  const double h = m->opt.timestep;
  for (Spring& s : springs_) {
    const int a = s.actuator, r = s.row;
    double low = -mjMAXVAL, high = mjMAXVAL;
    if (m->actuator_forcelimited[a]) {
      low = m->actuator_forcerange[2 * a];
      high = m->actuator_forcerange[2 * a + 1];
    }
    const double centre = (low + high) / 2, half_width = std::max(0.0, (high - low) / 2);
    m->actuator_biasprm[a * mjNBIAS] = centre;
    if (r < 0) continue;
    const double upsilon = 1 / (1 + 4 * s.relaxation_time / h);
    const double softness = 4 * upsilon / (h * h * s.stiffness);
    const double stretch = d->ten_length[s.tendon] - d->ctrl[a];
    d->efc_aref[r] =
        -4 * upsilon / (h * h) * stretch - (1 - upsilon) / h * d->ten_velocity[s.tendon] - softness * centre;
    d->efc_R[r] = softness;
    d->efc_D[r] = 1 / softness;
    d->efc_frictionloss[r] = m->actuator_gear[6 * a] != 0 ? half_width : 0.0;  // gear 0: switched off
  }
}

void SpringRows::add_row_forces(const mjModel* m, mjData* d) const {
  for (const Spring& s : springs_) {
    if (s.row < 0 || s.row >= d->nefc) continue;
    d->actuator_force[s.actuator] += d->efc_force[s.row];
    for (int i : s.sensors) {
      double value = d->actuator_force[s.actuator];
      if (m->sensor_cutoff[i] > 0) value = std::clamp(value, -m->sensor_cutoff[i], m->sensor_cutoff[i]);
      d->sensordata[m->sensor_adr[i]] = value;
    }
  }
}

}  // namespace openplx::runtime
