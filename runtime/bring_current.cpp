// After a user's own mj_step, qpos and qvel are the new state, but MuJoCo's derived fields (xpos, site_xpos,
// cvel, tendon lengths, position- and velocity-stage sensors) were computed by mj_step1 before integration:
// one step old. A bridge brings them up to date lazily, the first time an output that reads them is read,
// with the same MuJoCo stages a Simulation's next mj_step1 runs, and none that touch contacts or
// constraint rows (efc_*), so the numbers equal a Simulation's bit for bit and the user's constraint data
// is left as mj_step left it.
#include <algorithm>

#include "mujoco_support/mujoco_compat.h"
#include "runtime/simulation_state.h"

namespace openplx::runtime {

using mjcf::Quantity;

bool reads_derived_state(Quantity q) {
  switch (q) {
    case Quantity::BodyPosition:
    case Quantity::BodyRPY:
    case Quantity::BodyLinearVelocity:
    case Quantity::BodyAngularVelocity:
    case Quantity::SitePosition:
    case Quantity::SiteRPY:
    case Quantity::SiteLinearVelocity:
    case Quantity::SiteAngularVelocity:
    case Quantity::SiteRelativePosition:
    case Quantity::SiteRelativeRPY:
    case Quantity::SiteRelativeLinearVelocity:
    case Quantity::SiteRelativeAngularVelocity:
    case Quantity::TendonLength:
    case Quantity::TendonVelocity:
    case Quantity::TendonSpringForce:
    case Quantity::SensorFields:
      return true;
    default:
      return false;
  }
}

namespace {

// mj_fwdVelocity's tendon and actuator velocities, without its passive forces and constraint references.
void velocities_of_transmissions(const mjModel* m, mjData* d) {
  if (mj_isSparse(m)) {
    for (int t = 0; t < m->ntendon; ++t) {
      const int start = d->ten_J_rowadr[t];
      mjtNum v = 0;
      for (int k = 0; k < d->ten_J_rownnz[t]; ++k)
        v += d->ten_J[start + k] * d->qvel[d->ten_J_colind[start + k]];
      d->ten_velocity[t] = v;
    }
  } else if (m->ntendon > 0) {
    mju_mulMatVec(d->ten_velocity, d->ten_J, d->qvel, m->ntendon, m->nv);
  }
  if (m->nu > 0) mju_mulMatVec(d->actuator_velocity, d->actuator_moment, d->qvel, m->nu, m->nv);
}

}  // namespace

void SimulationState::bring_current() const {
  derived_state_behind = false;
  // mj_kinematics normalizes the quaternions of qpos in place; mj_step's own mj_step1 normalizes them again,
  // and a quaternion normalized twice can differ from one normalized once in the last bit, which contacts
  // amplify. Keeping qpos as mj_step left it keeps the user's trajectory the same whether outputs are read.
  qpos_kept.assign(d->qpos, d->qpos + m->nq);
  mj_kinematics(m, d);
  mj_comPos(m, d);
  mj_tendon(m, d);
  mj_transmission(m, d);
  mj_sensorPos(m, d);
  velocities_of_transmissions(m, d);
  mj_comVel(m, d);
  mj_sensorVel(m, d);
  std::copy(qpos_kept.begin(), qpos_kept.end(), d->qpos);
}

}  // namespace openplx::runtime
