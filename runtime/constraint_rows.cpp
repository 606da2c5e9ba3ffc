#include "runtime/constraint_rows.h"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <unordered_map>
#include <utility>

namespace openplx::runtime {

namespace {

using Kind = mjcf::RuntimeLaw::Kind;

// The share of a rigid position row's error (a range passed, a gear's or coupling's offset) taken back per
// step. Its velocity is exact every step (AGX's rigid rows: a gear at its ratio after one step); taking
// the whole error back at once (deadbeat) would throw an assembly error's correction into one step.
constexpr double kPositionCorrection = 0.5;
// How near its end (rad or m) a ranged joint gets its limit row.
constexpr double kLimitMargin = 1e-3;

// The models whose stand-ins some ConstraintRows took over, with the values they had: the last one to let
// go (a bridge destroyed) puts them back, so the model behaves as its MJCF says again.
struct TakenModel {
  int users = 0;
  std::vector<std::pair<mjtNum*, mjtNum>> saved;
  int noslip_iterations = 0;
};
std::mutex taken_mutex;
std::unordered_map<const mjModel*, TakenModel>& taken_models() {
  static std::unordered_map<const mjModel*, TakenModel> models;
  return models;
}

// Several mjData may step one mjModel in parallel threads: a model field they all compute alike is written
// only when it changes, so steady stepping only reads it.
void set_if_changed(mjtNum& field, mjtNum value) {
  if (field != value) field = value;
}

// SPOOK's Upsilon for relaxation time tau at step h.
double upsilon(double tau, double h) {
  return 1 / (1 + 4 * tau / h);
}

}  // namespace

void set_row_softness(const mjModel* m, mjData* d, int i, double softness) {
  if (mj_isDual(m)) {  // PGS (or noslip) reads A + R, formed before the callback: patch its diagonal
    if (mj_isSparse(m)) {
      for (int a = d->efc_AR_rowadr[i]; a < d->efc_AR_rowadr[i] + d->efc_AR_rownnz[i]; ++a) {
        if (d->efc_AR_colind[a] == i) {
          d->efc_AR[a] += softness - d->efc_R[i];
          break;
        }
      }
    } else {
      d->efc_AR[i * (d->nefc + 1)] += softness - d->efc_R[i];
    }
  }
  d->efc_R[i] = softness;
  d->efc_D[i] = 1 / softness;
}

void ConstraintRows::add_rigid(int type, int id, int actuator) {
  std::vector<int>& map = by_type_[static_cast<size_t>(type)];
  if (map[static_cast<size_t>(id)] >= 0) return;  // named twice
  Rigid r;
  r.type = type;
  r.id = id;
  r.actuator = actuator;
  std::vector<Rigid>& list = actuator >= 0 ? motors_ : rigid_;
  list.push_back(r);
  // Motors first: rigid_ indices are offset by a large constant so both fit one map.
  map[static_cast<size_t>(id)] =
      actuator >= 0 ? static_cast<int>(list.size()) - 1 : (1 << 24) + static_cast<int>(list.size()) - 1;
}

std::vector<std::string> ConstraintRows::resolve(mjModel* m, const std::vector<mjcf::RuntimeLaw>& laws) {
  std::vector<std::string> problems;
  const bool any = std::any_of(laws.begin(), laws.end(), [](const mjcf::RuntimeLaw& l) {
    return l.kind == Kind::Spring || l.kind == Kind::VelocityMotor || l.kind == Kind::Compliance ||
           l.kind == Kind::RigidRows;
  });
  if (!any) return problems;
  release();
  if (m->opt.integrator == mjINT_RK4) {
    problems.push_back(
        "the model integrates with RK4, which calls the control callback four times a step; the constraint "
        "rows "
        "AGX's law needs (velocity motors, springs, ranges, gears) are written for one solve a step: use "
        "integrator=\"Euler\" or \"implicit\"");
    return problems;
  }
  if (mjDISABLED(mjDSBL_CONSTRAINT)) {
    problems.push_back("the model disables constraints, which carry its motors, springs, ranges and gears");
    return problems;
  }
  by_type_.assign(5, {});
  by_type_[mjCNSTR_EQUALITY].assign(static_cast<size_t>(m->neq), -1);
  by_type_[mjCNSTR_FRICTION_DOF].assign(static_cast<size_t>(m->nv), -1);
  by_type_[mjCNSTR_FRICTION_TENDON].assign(static_cast<size_t>(m->ntendon), -1);
  by_type_[mjCNSTR_LIMIT_JOINT].assign(static_cast<size_t>(m->njnt), -1);
  by_type_[mjCNSTR_LIMIT_TENDON].assign(static_cast<size_t>(m->ntendon), -1);
  spring_of_tendon_.assign(static_cast<size_t>(m->ntendon), -1);
  compliance_of_equality_.assign(static_cast<size_t>(m->neq), -1);

  const std::lock_guard<std::mutex> lock(taken_mutex);
  TakenModel& taken = taken_models()[m];
  const bool first = taken.users++ == 0;
  model_ = m;
  if (first) taken.noslip_iterations = m->opt.noslip_iterations;
  auto take = [&](mjtNum& field, mjtNum value) {
    if (first) taken.saved.emplace_back(&field, field);
    field = value;
  };
  // The fixed tendon of an actuator's name that holds the actuator's joint alone, -1 when there is none.
  auto own_tendon = [&](const std::string& name, int a) {
    const int t = mj_name2id(m, mjOBJ_TENDON, name.c_str());
    if (a < 0 || t < 0 || m->actuator_trntype[a] != mjTRN_JOINT || m->tendon_num[t] != 1) return -1;
    const int wrap = m->tendon_adr[t];
    if (m->wrap_type[wrap] != mjWRAP_JOINT || m->wrap_objid[wrap] != m->actuator_trnid[2 * a] ||
        m->wrap_prm[wrap] != 1.0)
      return -1;
    return t;
  };
  // A law's stand-in actuator and the tendon of its name (-1 and a problem when they do not fit).
  auto stand_in = [&](const mjcf::RuntimeLaw& law, const std::string& about, const char* what) {
    const std::string& name = law.actuators.front();
    const int a = mj_name2id(m, mjOBJ_ACTUATOR, name.c_str()), t = own_tendon(name, a);
    if (t < 0)
      problems.push_back(about + "its " + what + " needs actuator and fixed tendon `" + name +
                         "` on the same joint");
    return std::pair{a, t};
  };
  // A stand-in gives way to its row: its gain, bias and the damper it put on its joint go (once per model,
  // while its gain is not yet 0: another mjData of the model may have taken it), and its tendon gets a
  // friction row (any positive friction loss makes MuJoCo build it; write sets its bound).
  auto take_stand_in = [&](int a, int t, double joint_damping) {
    if (m->actuator_gainprm[a * mjNGAIN] != 0) {
      const int dof = m->jnt_dofadr[m->actuator_trnid[2 * a]];
      take(m->dof_damping[dof], std::max(0.0, m->dof_damping[dof] - joint_damping));
      take(m->actuator_gainprm[a * mjNGAIN], 0);
      for (int k = 0; k < 3; ++k) take(m->actuator_biasprm[a * mjNBIAS + k], 0);
    }
    take(m->tendon_frictionloss[t], 1);
  };
  for (const mjcf::RuntimeLaw& law : laws) {
    const std::string about = "`" + law.path + "`: ";
    switch (law.kind) {
      case Kind::VelocityMotor: {
        const auto [a, t] = stand_in(law, about, "velocity motor");
        if (t < 0) continue;
        take_stand_in(a, t, law.joint_damping);  // its force becomes the band's centre (write)
        m->actuator_forcelimited[a] = 1;         // the centre stays within the band
        m->actuator_biastype[a] = mjBIAS_AFFINE;
        add_rigid(mjCNSTR_FRICTION_TENDON, t, a);
        break;
      }
      case Kind::Spring: {
        const auto [a, t] = stand_in(law, about, "spring");
        if (t < 0) continue;
        const double model_k = m->actuator_gainprm[a * mjNGAIN];
        const double k = law.stiffness > 0 ? law.stiffness : model_k;
        if (!(k > 0)) continue;  // taken over by an earlier resolve without the law's stiffness: skip
        take_stand_in(a, t, law.joint_damping);
        Spring s;
        s.actuator = a;
        s.tendon = t;
        s.stiffness = k;
        s.relaxation_time = law.parameter;
        for (int i = 0; i < m->nsensor; ++i) {
          if (m->sensor_type[i] == mjSENS_ACTUATORFRC && m->sensor_objid[i] == a) s.sensors.push_back(i);
        }
        spring_of_tendon_[static_cast<size_t>(t)] = static_cast<int>(springs_.size());
        springs_.push_back(std::move(s));
        break;
      }
      case Kind::Compliance: {
        const int e = mj_name2id(m, mjOBJ_EQUALITY, law.equalities.front().c_str());
        if (e < 0 || m->eq_type[e] != mjEQ_JOINT) {
          problems.push_back(about + "its compliance needs joint equality `" + law.equalities.front() + "`");
          continue;
        }
        compliance_of_equality_[static_cast<size_t>(e)] = static_cast<int>(compliances_.size());
        compliances_.push_back({e, law.stiffness, law.parameter});
        break;
      }
      case Kind::RigidRows: {
        for (const std::string& name : law.joints) {
          const int j = mj_name2id(m, mjOBJ_JOINT, name.c_str());
          if (j < 0) {
            problems.push_back(about + "no joint `" + name + "`");
            continue;
          }
          // MuJoCo builds a limit row once the joint is within the margin of its end: without one, a joint
          // resting exactly at its end (where the row's shift puts it) has its row on one step and off the
          // next, and a push into the end chatters.
          take(m->jnt_margin[j], std::max(m->jnt_margin[j], kLimitMargin));
          add_rigid(mjCNSTR_LIMIT_JOINT, j, -1);
        }
        auto rigid = [&](const std::vector<std::string>& names, mjtObj object, int type, const char* kind) {
          for (const std::string& name : names) {
            const int id = mj_name2id(m, object, name.c_str());
            if (id < 0)
              problems.push_back(about + "no " + kind + " `" + name + "`");
            else
              add_rigid(type, id, -1);
          }
        };
        rigid(law.tendons, mjOBJ_TENDON, mjCNSTR_FRICTION_TENDON, "tendon");
        rigid(law.equalities, mjOBJ_EQUALITY, mjCNSTR_EQUALITY, "equality");
        break;
      }
      default:
        break;
    }
  }
  // Noslip re-solves friction rows without their softness (springs would turn rigid); the rows it was there
  // to harden are now exact themselves.
  if (!empty()) m->opt.noslip_iterations = 0;
  return problems;
}

void ConstraintRows::release() {
  if (!model_) return;
  const std::lock_guard<std::mutex> lock(taken_mutex);
  auto it = taken_models().find(model_);
  if (it != taken_models().end() && --it->second.users == 0) {
    // Backwards, so a field taken twice ends with its first value.
    for (auto s = it->second.saved.rbegin(); s != it->second.saved.rend(); ++s) *s->first = s->second;
    model_->opt.noslip_iterations = it->second.noslip_iterations;
    taken_models().erase(it);
  }
  model_ = nullptr;
}

void ConstraintRows::write_rigid(const mjModel* m, mjData* d, Rigid& r, int i, int k) {
  const double h = m->opt.timestep;
  const double softness = kRigidSoftness * d->efc_diagApprox[i];
  if (static_cast<int>(r.force.size()) <= k) r.force.resize(static_cast<size_t>(k) + 1, 0.0);
  if (k >= r.previous_rows) {  // a row new this step (a limit reached again): its old force says nothing
    r.force[static_cast<size_t>(k)] = 0;
    changed_ = true;
  }
  const double estimate = r.force[static_cast<size_t>(k)];
  double aref = 0;
  if (r.type == mjCNSTR_FRICTION_TENDON) {  // a velocity: the motor's target, else held (a brake, a clutch)
    double target = 0;
    if (r.actuator >= 0) {
      const int a = r.actuator;
      target = d->ctrl[a];
      if (m->actuator_ctrllimited[a])
        target = std::clamp(target, m->actuator_ctrlrange[2 * a], m->actuator_ctrlrange[2 * a + 1]);
      changed_ = changed_ || target != r.target;
      r.target = target;
      const bool on = m->actuator_gear[6 * a] != 0;
      const double low = m->actuator_forcerange[2 * a], high = m->actuator_forcerange[2 * a + 1];
      // The band [low, high] = its centre, pushed by the stand-in, and the row's bound about it.
      set_if_changed(m->actuator_biasprm[a * mjNBIAS], on ? (low + high) / 2 : 0.0);
      d->efc_frictionloss[i] = on ? std::max(0.0, (high - low) / 2) : 0.0;
    }
    aref = (target - d->efc_vel[i]) / h;
  } else {  // a position: its velocity error gone in the step, the position error halved each step
    // A limit row within its margin but short of the end lets the joint approach at up to pos / (2h): it
    // reaches the end without passing it.
    aref = -kPositionCorrection / (h * h) * d->efc_pos[i] - d->efc_vel[i] / h;
  }
  // In the quadratic zone the solver gives J a = aref - R f; the shift cancels that with the estimate.
  d->efc_aref[i] = aref + softness * estimate;
  set_row_softness(m, d, i, softness);
  r.rows.push_back(i);
}

void ConstraintRows::write(const mjModel* m, mjData* d) {
  const double h = m->opt.timestep;
  // Noslip, switched on again after the rows were taken over, would re-solve them without their law.
  if (m->opt.noslip_iterations > 0) const_cast<mjModel*>(m)->opt.noslip_iterations = 0;
  for (std::vector<Rigid>* list : {&motors_, &rigid_}) {
    for (Rigid& r : *list) {
      r.previous_rows = static_cast<int>(r.rows.size());
      r.rows.clear();
    }
  }
  for (Spring& s : springs_) s.row = -1;
  changed_ = false;
  for (int i = 0; i < d->nefc; ++i) {
    const int type = d->efc_type[i], id = d->efc_id[i];
    if (type > mjCNSTR_LIMIT_TENDON) break;  // contacts come last
    if (type == mjCNSTR_FRICTION_TENDON && spring_of_tendon_[static_cast<size_t>(id)] >= 0) {
      springs_[static_cast<size_t>(spring_of_tendon_[static_cast<size_t>(id)])].row = i;
      continue;
    }
    if (type == mjCNSTR_EQUALITY && compliance_of_equality_[static_cast<size_t>(id)] >= 0) {
      // SPOOK (Lacoursiere): G v+ + S lambda = -(4 Y / h) g + Y G v with S = 4 Y / (h^2 k), lambda = h f; for
      // MuJoCo's row (J a + R f = aref, v+ = v + h a): R = S, aref = -(4 Y / h^2) g - (1 - Y) / h v.
      const Compliance& c =
          compliances_[static_cast<size_t>(compliance_of_equality_[static_cast<size_t>(id)])];
      const double y = upsilon(c.relaxation_time, h);
      d->efc_aref[i] = -4 * y / (h * h) * d->efc_pos[i] - (1 - y) / h * d->efc_vel[i];
      set_row_softness(m, d, i, 4 * y / (h * h * c.stiffness));
      continue;
    }
    const int index = by_type_[static_cast<size_t>(type)][static_cast<size_t>(id)];
    if (index < 0) continue;
    Rigid& r = index >= (1 << 24) ? rigid_[static_cast<size_t>(index - (1 << 24))]
                                  : motors_[static_cast<size_t>(index)];
    write_rigid(m, d, r, i, static_cast<int>(r.rows.size()));
  }
  // Springs: the SPOOK row about the rest (the actuator's control), its force clamped to the effort range
  // about the range's centre c, which the actuator pushes; aref - R c makes the row's unclamped force f - c.
  for (Spring& s : springs_) {
    const int a = s.actuator, i = s.row;
    double low = -mjMAXVAL, high = mjMAXVAL;
    if (m->actuator_forcelimited[a]) {
      low = m->actuator_forcerange[2 * a];
      high = m->actuator_forcerange[2 * a + 1];
    }
    const double centre = (low + high) / 2, half_width = std::max(0.0, (high - low) / 2);
    set_if_changed(m->actuator_biasprm[a * mjNBIAS], centre);
    if (i < 0) continue;
    const double y = upsilon(s.relaxation_time, h), softness = 4 * y / (h * h * s.stiffness);
    const double stretch = d->ten_length[s.tendon] - d->ctrl[a];
    d->efc_aref[i] = -4 * y / (h * h) * stretch - (1 - y) / h * d->ten_velocity[s.tendon] - softness * centre;
    set_row_softness(m, d, i, softness);
    d->efc_frictionloss[i] = m->actuator_gear[6 * a] != 0 ? half_width : 0.0;  // gear 0: switched off
  }
}

double ConstraintRows::refine(const mjModel* m, mjData* d) {
  double change = 0;
  for (std::vector<Rigid>* list : {&motors_, &rigid_}) {
    for (Rigid& r : *list) {
      for (size_t k = 0; k < r.rows.size(); ++k) {
        const int i = r.rows[k];
        const double f = d->efc_force[i], shift = d->efc_R[i] * (f - r.force[k]);
        d->efc_aref[i] += shift;
        r.force[k] = f;
        change = std::max(change, std::abs(shift));
      }
    }
  }
  return change * m->opt.timestep;
}

bool ConstraintRows::write_step(const mjModel* m, mjData* d) {
  if (empty()) return false;
  write(m, d);
  if (motors_.empty() && rigid_.empty()) return false;
  const bool refinement = needs_refinement_ || changed_;
  needs_refinement_ = true;  // after_step clears it when this step's forces stay steady
  return refinement;
}

void ConstraintRows::control(const mjModel* m, mjData* d, ConstraintRows* const* all, size_t count) {
  bool refinement = false;
  for (size_t k = 0; k < count; ++k) refinement = all[k]->write_step(m, d) || refinement;
  if (!refinement) return;
  for (int pass = 0; pass < kRefinements; ++pass) {  // one solve refines every set of rows on this data
    mj_fwdActuation(m, d);
    mj_fwdAcceleration(m, d);
    mj_fwdConstraint(m, d);
    double change = 0;
    for (size_t k = 0; k < count; ++k) change = std::max(change, all[k]->refine(m, d));
    if (change < kRefineTolerance) break;
  }
}

void ConstraintRows::control(const mjModel* m, mjData* d) {
  ConstraintRows* self = this;
  control(m, d, &self, 1);
}

void ConstraintRows::after_step(const mjModel* m, mjData* d) {
  if (empty()) return;
  for (const Spring& s : springs_) {
    if (s.row < 0 || s.row >= d->nefc) continue;
    d->actuator_force[s.actuator] += d->efc_force[s.row];
    for (int i : s.sensors) {
      double value = d->actuator_force[s.actuator];
      if (m->sensor_cutoff[i] > 0) value = std::clamp(value, -m->sensor_cutoff[i], m->sensor_cutoff[i]);
      d->sensordata[m->sensor_adr[i]] = value;
    }
  }
  // The final solve's forces are the next step's estimates. The next step may skip the extra solves when
  // this one's estimate was good (its error, R h |f - f^|, is known now) and the forces did not move since
  // the step before (the next step's error is about R h times that move: owned-rows.md, exp7).
  double change = 0;
  for (std::vector<Rigid>* list : {&motors_, &rigid_}) {
    for (Rigid& r : *list) {
      if (r.last_final.size() < r.force.size()) r.last_final.resize(r.force.size(), 0.0);
      for (size_t k = 0; k < r.rows.size(); ++k) {
        const int i = r.rows[k];
        if (i >= d->nefc) continue;
        const double f = d->efc_force[i];
        const double moved = std::max(std::abs(f - r.force[k]), std::abs(f - r.last_final[k]));
        change = std::max(change, d->efc_R[i] * moved);
        r.force[k] = r.last_final[k] = f;
      }
    }
  }
  needs_refinement_ = change * m->opt.timestep >= kRefineTolerance;
}

}  // namespace openplx::runtime
