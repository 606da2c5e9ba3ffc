#include "mjcf_emitter/timestep_dependence.h"

#include <algorithm>
#include <array>
#include <set>
#include <sstream>
#include <utility>

namespace openplx::mjcf {

namespace {

// The choices, by the trace each leaves in the document (the lowering passes that make them in brackets).
enum Choice {
  Equalities,  // every equality: solref 2h rigid, or softened to what explicit Euler holds at h (equalities)
  HardLimits,  // solreflimit 2h: joint and tendon ranges (actuators)
  FrictionRows,     // solreffriction 2h: velocity motors, clutches, brakes, slip limits (velocity_motors,
                    // drive_parts, drivetrain)
  References,       // a velocity motor's stand-in, its damper or servo gain from h (velocity_motors.cpp)
  Gains,            // <general> with a velocity term: springs' and dampers' damping capped below the inertia
                    // per step, distance motors' gain 0.5 / (inverse mass h) (springs, actuators)
  ExplicitSprings,  // joint or tendon stiffness kept because ω h <= 0.5 at h (else held rigid: joints,
                    // drive_parts)
  SpringRows,       // the runtime's spring rows, with SPOOK parameters computed from h
                    // (runtime/constraint_rows)
  kChoices
};

// What each is, and how it follows h (the count goes between them).
constexpr std::array<std::pair<const char*, const char*>, kChoices> kPhrases = {{
    {"equality constraints", "solref 2h, softness bounded for h"},
    {"hard limits", "solreflimit 2h"},
    {"friction-row drives", "solreffriction 2h"},
    {"velocity-motor stand-ins", "damper I / h, or servo kv = 1 / (n h (M^-1)_jj)"},
    {"actuator damping and gains", "capped for h"},
    {"joint and tendon springs", "judged stable at h"},
    {"spring rows", "the runtime builds them for h"},
}};

// A <general> actuator's velocity term (biasprm[2]): the damping of springs and dampers kept explicit while
// below the inertia per step, a distance motor's gain. A velocity motor's bias actuator has none.
bool velocity_feedback(const Element& general) {
  const std::string* bias = general.get("biasprm");
  if (!bias) return false;
  std::istringstream terms(*bias);
  double term[3] = {0, 0, 0};
  terms >> term[0] >> term[1] >> term[2];
  return term[2] != 0;
}

void count(const Element& e, std::array<size_t, kChoices>& counts, bool in_equality, bool in_actuator,
           const std::set<std::string>& stand_ins) {
  const std::string& name = e.name();
  if (in_equality) ++counts[Equalities];
  if (e.get("solreflimit")) ++counts[HardLimits];
  if (e.get("solreffriction")) ++counts[FrictionRows];
  const std::string* element = e.get("name");
  const bool stand_in = element && stand_ins.count(*element);  // counted as velocity-motor stand-ins
  if (in_actuator && name == "general" && !stand_in && velocity_feedback(e)) ++counts[Gains];
  if ((name == "joint" || name == "fixed" || name == "spatial") && e.get("stiffness") &&
      *e.get("stiffness") != "0")
    ++counts[ExplicitSprings];
  for (const auto& child : e.children()) {
    // <default> classes hold settings, not elements; a <joint> inside a <tendon>'s <fixed> is a coefficient.
    if (child->name() == "default") continue;
    if (name == "fixed" && child->name() == "joint") continue;
    count(*child, counts, name == "equality", name == "actuator", stand_ins);
  }
}

}  // namespace

std::vector<std::string> timestep_choices(const Element& document, const std::vector<RuntimeLaw>& laws) {
  std::array<size_t, kChoices> counts{};
  std::set<std::string> stand_ins;
  for (const RuntimeLaw& l : laws)
    if (l.kind == RuntimeLaw::Kind::VelocityMotor) stand_ins.insert(l.actuators.begin(), l.actuators.end());
  count(document, counts, false, false, stand_ins);
  counts[References] = static_cast<size_t>(std::count_if(laws.begin(), laws.end(), [](const RuntimeLaw& l) {
    return l.kind == RuntimeLaw::Kind::VelocityMotor;
  }));
  counts[SpringRows] = static_cast<size_t>(std::count_if(
      laws.begin(), laws.end(), [](const RuntimeLaw& l) { return l.kind == RuntimeLaw::Kind::Spring; }));
  std::vector<std::string> choices;
  for (size_t k = 0; k < kChoices; ++k) {
    if (counts[k] > 0)
      choices.push_back(std::string(kPhrases[k].first) + " (" + std::to_string(counts[k]) + ", " +
                        kPhrases[k].second + ")");
  }
  return choices;
}

}  // namespace openplx::mjcf
