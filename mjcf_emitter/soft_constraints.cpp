#include "mjcf_emitter/soft_constraints.h"

#include <cmath>

namespace openplx::mjcf {

namespace {

// MuJoCo 3's body_simple (2): a leaf body of the world (or of a fixed child of the world) whose inertial
// frame is its body frame and whose joints are all slides at its origin along a body axis. 3.x gives such a
// body dA = 1/m where 2.2.2 averages over three axes.
bool simple_in_mujoco3(const mjModel* m, int b) {
  const int parent = m->body_parentid[b];
  const bool under_world = parent == 0 || (m->body_parentid[parent] == 0 && m->body_dofnum[parent] == 0);
  if (!under_world) return false;
  for (int c = 1; c < m->nbody; ++c)
    if (m->body_parentid[c] == b) return false;
  const mjtNum* ipos = m->body_ipos + 3 * b;
  const mjtNum* iquat = m->body_iquat + 4 * b;
  if (ipos[0] != 0 || ipos[1] != 0 || ipos[2] != 0 || iquat[0] != 1) return false;
  for (int j = m->body_jntadr[b]; j >= 0 && j < m->body_jntadr[b] + m->body_jntnum[b]; ++j) {
    if (m->jnt_type[j] != mjJNT_SLIDE) return false;
    const mjtNum* pos = m->jnt_pos + 3 * j;
    const mjtNum* axis = m->jnt_axis + 3 * j;
    if (pos[0] != 0 || pos[1] != 0 || pos[2] != 0) return false;
    const int nonzero = (axis[0] != 0) + (axis[1] != 0) + (axis[2] != 0);
    if (nonzero != 1) return false;
  }
  return true;
}

}  // namespace

SoftEqualityResult apply_soft_equalities(const DraftModel& draft,
                                         const std::vector<PendingSoftEquality>& pending, double timestep,
                                         bool mujoco3) {
  SoftEqualityResult result;
  const mjModel* m = draft.model();
  const double d = kSoftImpedance;
  for (const PendingSoftEquality& p : pending) {
    double dA = 0, dA_rot = 0;
    for (const std::string& body : {p.body1, p.body2}) {
      const int id = body == "world" ? 0 : draft.body_id(body);
      if (id <= 0) continue;
      dA += mujoco3 && simple_in_mujoco3(m, id) ? 1 / m->body_mass[id] : m->body_invweight0[2 * id];
      dA_rot += m->body_invweight0[2 * id + 1];
    }
    const MateCompliance& c = p.compliance;
    const double ks = c.k_trans * (1 - d) * dA, bs = c.b_trans * (1 - d) * dA;
    p.equality->set("solref", number(-ks) + " " + number(-bs))
        .set("solimp", number(d) + " " + number(d) + " 0.001 0.5 2");
    if (p.weld && c.k_trans > 0) {
      // 2.2.2: k_rot = ts ks / (4 (1-d) dA); 3.x: k_rot = ts^2 ks / (4 (1-d) dA_rot).
      const double torquescale = mujoco3 && dA_rot > 0 && dA > 0
                                     ? 2 * std::sqrt(c.k_rot * dA_rot / (c.k_trans * dA))
                                     : 4 * c.k_rot / c.k_trans;
      p.equality->set("torquescale", torquescale);
    }
    if (timestep * std::sqrt(ks) > 1 || timestep * bs > 1)
      result.unstable.push_back(*p.equality->get("name"));
  }
  return result;
}

}  // namespace openplx::mjcf
