// Lowering pass, last: MuJoCo 2.2.2's rule for the mass and inertia of moving bodies, applied to the finished
// document, so that nothing written is refused. Measured against mj_loadXML (tests/mjcf/moving_body_inertia_
// test.cpp): a body with a joint, together with the jointless bodies welded below it, must have a summed mass
// and summed principal moments (added per index, as MuJoCo adds them) of at least mjMINVAL each. A moment
// below it (a thin rod's 1e-23 about its axis) is raised to mjMINVAL on the moving body itself, warned.
#include <mujoco/mujoco.h>

#include <array>

#include "mjcf_emitter/attribute_numbers.h"
#include "mjcf_emitter/lowering.h"

namespace openplx::mjcf {
namespace {

struct WeldSum {
  double mass = 0;
  std::array<double, 3> moments{};
  bool mass_known = true;  // false when a body leaves its mass to MuJoCo (no <inertial>)
  bool known = true;       // the moments too: false also for a fullinertia, whose moments MuJoCo finds
};

bool has_joint(const Element& body) {
  for (const auto& c : body.children())
    if (c->name() == "joint" || c->name() == "freejoint") return true;
  return false;
}

// Adds `body`'s inertial and those of the jointless bodies below it (its weld group).
void add_weld_group(const Element& body, WeldSum& sum) {
  const Element* inertial = nullptr;
  for (const auto& c : body.children())
    if (c->name() == "inertial") inertial = c.get();
  const std::optional<Eigen::Vector3d> moments =
      inertial ? attribute_vector(*inertial, "diaginertia") : std::nullopt;
  if (!inertial) {
    sum.mass_known = sum.known = false;  // geoms: MuJoCo sums them
  } else {
    // A fullinertia's moments pass (bodies.cpp writes one only then), but its mass still counts: a
    // 1e-308 kg body with a written tensor was once written and refused by MuJoCo.
    const std::vector<double> mass = attribute_numbers(*inertial, "mass");
    sum.mass += mass.empty() ? 0.0 : mass[0];
    if (!moments) {
      sum.known = false;
    } else {
      for (int k = 0; k < 3; ++k) sum.moments[k] += (*moments)[k];
    }
  }
  for (const auto& c : body.children())
    if (c->name() == "body" && !has_joint(*c)) add_weld_group(*c, sum);
}

}  // namespace

void Lowering::enforce_moving_body_inertia() {
  for (const auto& [node, body] : body_element_) {
    if (!has_joint(*body)) continue;
    WeldSum sum;
    add_weld_group(*body, sum);
    const bool light = sum.mass_known && sum.mass < mjMINVAL;
    if (!light && (!sum.known || (sum.mass >= mjMINVAL && sum.moments[0] >= mjMINVAL &&
                                  sum.moments[1] >= mjMINVAL && sum.moments[2] >= mjMINVAL)))
      continue;
    Element* inertial = body->child("inertial");
    const sn::FrameNode& n = system_.nodes[static_cast<size_t>(node)];
    if (light) {
      sink_.report(fe::DiagCode::MjcfBadAsset, n.where,
                   "`" + n.path + "` moves but its mass (" + number(sum.mass) +
                       " kg with the bodies fixed to it) is below MuJoCo's smallest, " + number(mjMINVAL) +
                       " kg; MuJoCo refuses such a body: give it a mass");
      continue;
    }
    Eigen::Vector3d own = *attribute_vector(*inertial, "diaginertia");
    std::string raised;
    for (int k = 0; k < 3; ++k) {
      if (sum.moments[k] >= mjMINVAL) continue;
      raised += (raised.empty() ? "" : ", ") + number(own[k]);
      own[k] += mjMINVAL - sum.moments[k];
      if (own[k] < mjMINVAL) own[k] = mjMINVAL;  // rounding of the sum
    }
    inertial->set("diaginertia", own);
    warn(n.where, "`" + n.path + "` moves but its principal moment of inertia " + raised +
                      " kg m^2 is below " + number(mjMINVAL) +
                      ", the smallest MuJoCo accepts for a moving body (it refuses the model); it was raised "
                      "to that");
  }
}

}  // namespace openplx::mjcf
