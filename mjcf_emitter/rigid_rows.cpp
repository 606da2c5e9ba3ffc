// Lowering pass, the rows AGX solves as hard constraints (docs/mapping.md "Constraint rows the runtime
// owns"): ranges (joint limits), brakes, clutches and slip limits (tendon friction loss), gears, couplings,
// steering columns and distance mates (joint and tendon equalities). The MJCF alone gives them MuJoCo's
// stiffest softness; the runtime makes them exact (RuntimeLaw::RigidRows), so the manifest lists them.
#include <vector>

#include "mjcf_emitter/lowering.h"

namespace openplx::mjcf {

void Lowering::collect_rigid_rows(Element& root) {
  RuntimeLaw law;
  law.kind = RuntimeLaw::Kind::RigidRows;
  law.path = options_.model_name;  // the root model: its own path is empty
  for_each_joint(root, [&](const Element& joint) {
    const std::string* limited = joint.get("limited");
    if (joint.get("range") && !(limited && *limited == "false")) law.joints.push_back(*joint.get("name"));
  });
  if (Element* tendons = root.child("tendon")) {
    for (const auto& t : tendons->children()) {
      const std::string* friction = t->get("frictionloss");
      if (t->get("name") && friction && *friction != "0") law.tendons.push_back(*t->get("name"));
    }
  }
  for (const auto& [coupling, tendon] : friction_couplings_) {  // engaged later: no friction loss yet
    if (std::find(law.tendons.begin(), law.tendons.end(), tendon) == law.tendons.end())
      law.tendons.push_back(tendon);
  }
  if (Element* equality = root.child("equality")) {
    for (const auto& e : equality->children()) {
      const std::string* name = e->get("name");
      if (!name || (e->name() != "joint" && e->name() != "tendon") || compliant_equalities_.count(*name))
        continue;
      law.equalities.push_back(*name);
    }
  }
  if (!law.joints.empty() || !law.tendons.empty() || !law.equalities.empty()) laws_.push_back(std::move(law));
}

}  // namespace openplx::mjcf
