// The few mjModel/mjData fields the runtime touches whose place changed in MuJoCo 3.0, behind one accessor
// each, so the runtime compiles against 2.2.2 and 3.x headers (docs/runtime.md "MuJoCo versions"):
// - an equality's on/off switch moved from mjModel::eq_active to mjData::eq_active (3.0.0; the model keeps
//   eq_active0, the value mj_resetData restores);
// - a tendon's spring rest length became a (low, high) dead band, mjModel::tendon_lengthspring[2 * id].
#pragma once

#include <mujoco/mujoco.h>

namespace openplx::runtime {

#if defined(mjVERSION_HEADER) && mjVERSION_HEADER >= 300
inline mjtByte& equality_active(mjModel*, mjData* d, int id) {
  return d->eq_active[id];
}
inline mjtNum tendon_rest_length(const mjModel* m, const mjData* d, int id) {
  // The spring pulls toward the nearer end of its dead band, and not at all inside it.
  const mjtNum low = m->tendon_lengthspring[2 * id], high = m->tendon_lengthspring[2 * id + 1];
  const mjtNum length = d->ten_length[id];
  return length < low ? low : length > high ? high : length;
}
#else
inline mjtByte& equality_active(mjModel* m, mjData*, int id) {
  return m->eq_active[id];
}
inline mjtNum tendon_rest_length(const mjModel* m, const mjData*, int id) {
  return m->tendon_lengthspring[id];
}
#endif

}  // namespace openplx::runtime
