#include "mujoco_support/instability.h"

#include <cmath>
#include <cstdio>

namespace openplx::mjcf {

namespace {

constexpr double kPi = 3.14159265358979323846;

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.6g", value);
  return text;
}

// A MuJoCo name without the model's prefix; "" when the element has none.
std::string_view stripped(const mjModel* m, const int* address, int id, std::string_view prefix) {
  std::string_view name = m->names + address[id];
  if (!prefix.empty() && name.substr(0, prefix.size()) == prefix) name.remove_prefix(prefix.size());
  return name;
}

std::string named(std::string_view kind, std::string_view name, int id) {
  if (name.empty()) return std::string(kind) + " #" + std::to_string(id);
  return std::string(kind) + " `" + std::string(name) + "`";
}

int qpos_count(int type) {
  return type == mjJNT_FREE ? 7 : type == mjJNT_BALL ? 4 : 1;
}

// "the rotation of", "the x translation of", ...: which motion of the joint the DOF is.
std::string motion(const mjModel* m, int joint, int dof) {
  const int k = dof - m->jnt_dofadr[joint];
  static const char* const kAxis[] = {"x", "y", "z"};
  switch (m->jnt_type[joint]) {
    case mjJNT_FREE:
      return std::string("the ") + kAxis[k % 3] + (k < 3 ? " translation" : " rotation") + " of free";
    case mjJNT_BALL:
      return std::string("the ") + kAxis[k % 3] + " rotation of ball";
    case mjJNT_SLIDE:
      return "the translation of slide";
    default:
      return "the rotation of hinge";
  }
}

std::string values_text(const mjModel* m, const WarningFacts& f, int joint, int dof) {
  std::string text;
  auto add = [&](const std::string& piece) { text += (text.empty() ? "" : ", ") + piece; };
  if (f.qpos && joint >= 0) {
    const int adr = m->jnt_qposadr[joint], n = qpos_count(m->jnt_type[joint]);
    std::string q;
    for (int i = 0; i < n; ++i) q += (i ? " " : "") + number(f.qpos[adr + i]);
    add("qpos " + (n > 1 ? "{" + q + "}" : q));
  }
  if (f.qvel && dof >= 0) add("qvel " + number(f.qvel[dof]));
  if (f.qacc && dof >= 0) add("qacc " + number(f.qacc[dof]));
  return text.empty() ? "" : " (" + text + ")";
}

// Actuators that drive `joint` directly, with no control range: an input nothing bounds.
std::string unbounded_inputs(const mjModel* m, const WarningFacts& f, int joint) {
  std::string text;
  for (int a = 0; a < m->nu; ++a) {
    const bool on_joint =
        (m->actuator_trntype[a] == mjTRN_JOINT || m->actuator_trntype[a] == mjTRN_JOINTINPARENT) &&
        m->actuator_trnid[2 * a] == joint;
    // Force motors only: a spring (affine bias) pulls back whatever its control.
    if (!on_joint || m->actuator_ctrllimited[a] || m->actuator_biastype[a] != mjBIAS_NONE) continue;
    text += (text.empty() ? "" : ", ") + named("actuator", stripped(m, m->name_actuatoradr, a, f.prefix), a);
    if (f.ctrl) text += " (control " + number(f.ctrl[a]) + ")";
  }
  return text;
}

// The joint's own stiffness and that of springs emitted as actuators on it (an affine bias pulling back
// in proportion to the position: force = gain ctrl + b0 + b1 length, b1 < 0; length = gear q).
double stiffness(const mjModel* m, int joint) {
  double k = m->jnt_stiffness[joint];
  for (int a = 0; a < m->nu; ++a) {
    const bool on_joint =
        (m->actuator_trntype[a] == mjTRN_JOINT || m->actuator_trntype[a] == mjTRN_JOINTINPARENT) &&
        m->actuator_trnid[2 * a] == joint;
    if (!on_joint || m->actuator_biastype[a] != mjBIAS_AFFINE) continue;
    const double gear = m->actuator_gear[6 * a], b1 = m->actuator_biasprm[a * mjNBIAS + 1];
    if (b1 < 0) k += -b1 * gear * gear;
  }
  return k;
}

std::string hint(const mjModel* m, const WarningFacts& f, int joint, int dof) {
  const double h = m->opt.timestep;
  std::string text = "hint: ";
  if (f.emitted_timestep > 0 && std::abs(f.emitted_timestep - h) > 1e-12 * f.emitted_timestep) {
    text += "the time step is " + number(h) + " s but the model was emitted for " +
            number(f.emitted_timestep) + " s: run it at that step or emit it for this one (--timestep); ";
  } else {
    text += "a smaller time step (now " + number(h) + " s) may keep it stable; ";
  }
  const double k = joint >= 0 ? stiffness(m, joint) : 0;
  if (dof >= 0 && k > 0 && m->dof_M0[dof] > 0) {
    const double period = 2 * kPi * std::sqrt(m->dof_M0[dof] / k);
    text += "its springs (stiffness " + number(k) + ") swing with a period of " + number(period) +
            " s, which needs a time step below about " + number(period / 10) + " s; ";
  } else {
    text += "look for stiff springs or compliance (periods near the time step) on or near it; ";
  }
  if (joint >= 0) {
    const std::string inputs = unbounded_inputs(m, f, joint);
    if (!inputs.empty()) text += "it is driven by " + inputs + " with no control range: a large input; ";
  }
  text += "an input beyond what the model allows, or bodies that start interpenetrating";
  return text;
}

std::string instability(const mjModel* m, const WarningFacts& f, const char* what) {
  int joint = -1, dof = -1;
  std::string where;
  if (f.warning == mjWARN_BADQPOS) {
    joint = joint_of_qpos(m, f.info);
    if (joint >= 0) dof = m->jnt_dofadr[joint];
    where = joint >= 0 ? "qpos " + std::to_string(f.info) + ", " + describe_dof(m, dof, f.prefix)
                       : "qpos " + std::to_string(f.info) + " (the model has " + std::to_string(m->nq) + ")";
  } else if (f.info >= 0 && f.info < m->nv) {
    dof = f.info;
    joint = m->dof_jntid[dof];
    where = "DOF " + std::to_string(dof) + ", " + describe_dof(m, dof, f.prefix);
  } else {
    where = "DOF " + std::to_string(f.info) + " (the model has " + std::to_string(m->nv) + ")";
  }
  return "at t = " + number(f.time) + " s MuJoCo found a NaN, infinite or huge " + what + " at " + where +
         values_text(m, f, joint, dof) +
         "; MuJoCo reset the simulation to its initial state (time 0), so what follows is not the model's "
         "motion. " +
         hint(m, f, joint, dof);
}

}  // namespace

WarningSeverity warning_severity(int warning) {
  switch (warning) {
    case mjWARN_CONTACTFULL:
    case mjWARN_CNSTRFULL:
    case mjWARN_BADQPOS:
    case mjWARN_BADQVEL:
    case mjWARN_BADQACC:
    case mjWARN_BADCTRL:
      return WarningSeverity::Wrong;
    case mjWARN_INERTIA:
      return WarningSeverity::Note;
    default:
      return WarningSeverity::Ignore;
  }
}

bool warning_resets(int warning) {
  return warning == mjWARN_BADQPOS || warning == mjWARN_BADQVEL || warning == mjWARN_BADQACC;
}

int joint_of_qpos(const mjModel* m, int qpos_index) {
  for (int j = 0; j < m->njnt; ++j) {
    const int adr = m->jnt_qposadr[j];
    if (qpos_index >= adr && qpos_index < adr + qpos_count(m->jnt_type[j])) return j;
  }
  return -1;
}

std::string describe_dof(const mjModel* m, int dof, std::string_view prefix) {
  if (dof < 0 || dof >= m->nv) return "DOF " + std::to_string(dof);
  const int joint = m->dof_jntid[dof], body = m->dof_bodyid[dof];
  return motion(m, joint, dof) + " " + named("joint", stripped(m, m->name_jntadr, joint, prefix), joint) +
         " in " + named("body", stripped(m, m->name_bodyadr, body, prefix), body);
}

std::string describe_warning(const mjModel* m, const WarningFacts& f) {
  const double h = m->opt.timestep;
  switch (f.warning) {
    case mjWARN_BADQACC:
      return instability(m, f, "acceleration (qacc)");
    case mjWARN_BADQVEL:
      return instability(m, f, "velocity (qvel)");
    case mjWARN_BADQPOS:
      return instability(m, f, "position (qpos)");
    case mjWARN_BADCTRL: {
      std::string who = f.info >= 0 && f.info < m->nu
                            ? named("actuator", stripped(m, m->name_actuatoradr, f.info, f.prefix), f.info)
                            : "actuator #" + std::to_string(f.info);
      if (f.ctrl && f.info >= 0 && f.info < m->nu) who += " (control " + number(f.ctrl[f.info]) + ")";
      return "at t = " + number(f.time) + " s MuJoCo found a NaN, infinite or huge control on " + who +
             " and zeroed every control for the step. hint: bound the input (a control range) or check what "
             "computes it";
    }
    case mjWARN_CONTACTFULL:
      return "at t = " + number(f.time) +
             " s MuJoCo's contact buffer was full (nconmax = " + std::to_string(m->nconmax) +
             "): contacts beyond it were dropped, so bodies may pass through each other. hint: raise "
             "<size nconmax> in the MJCF, or look for bodies that start interpenetrating";
    case mjWARN_CNSTRFULL:
      return "at t = " + number(f.time) +
             " s MuJoCo's constraint buffer was full (njmax = " + std::to_string(m->njmax) +
             "): the step's constraints (joint limits, contacts, equalities, motors) were dropped. hint: "
             "raise <size njmax> in the MJCF, or look for bodies that start interpenetrating";
    case mjWARN_INERTIA:
      return "at t = " + number(f.time) + " s MuJoCo found the inertia matrix near singular at " +
             (f.info >= 0 && f.info < m->nv
                  ? "DOF " + std::to_string(f.info) + ", " + describe_dof(m, f.info, f.prefix)
                  : "DOF " + std::to_string(f.info)) +
             ". hint: a body with (almost) no mass or inertia on a joint; time step " + number(h) + " s";
    case mjWARN_VGEOMFULL:
      return "MuJoCo's visual geom buffer was full (visualisation only)";
    default:
      return "MuJoCo warning " + std::to_string(f.warning) + " (info " + std::to_string(f.info) + ")";
  }
}

void WarnedState::capture(const mjModel* m, const mjData* d) {
  if (valid) return;
  valid = true;
  time = d->time;
  qpos.assign(d->qpos, d->qpos + m->nq);
  qvel.assign(d->qvel, d->qvel + m->nv);
  qacc.assign(d->qacc, d->qacc + m->nv);
  ctrl.assign(d->ctrl, d->ctrl + m->nu);
}

WarningFacts WarnedState::facts(const mjData* d, int warning, double time_before) const {
  WarningFacts facts;
  facts.warning = warning;
  facts.info = d->warning[warning].lastinfo;
  facts.time = valid ? time : time_before;
  if (valid) {
    facts.qpos = qpos.data();
    facts.qvel = qvel.data();
    facts.qacc = qacc.data();
    facts.ctrl = ctrl.data();
  }
  return facts;
}

}  // namespace openplx::mjcf
