#include "snap/read_vehicles.h"

#include <cmath>

namespace openplx::snap {

void read_suspension(AttributeReader& in, const frontend::ModelInfo* steering_trait, frontend::ObjectId id,
                     Mate& mate) {
  mate.type = MateType::Suspension;
  // Written to the travel joint's stiffness and damping, which MuJoCo takes as given: a negative one pushes
  // the wheel away and gains energy, an infinite one is no number.
  if (const frontend::ObjectId spring = in.object(id, "spring_constant"); spring != frontend::kNoObject) {
    mate.travel_stiffness = in.real(spring, "stiffness");
    in.require(std::isfinite(mate.travel_stiffness) && mate.travel_stiffness >= 0, spring, "stiffness",
               mate.travel_stiffness, "a suspension's stiffness is a finite number, 0 or positive");
  }
  if (const frontend::ObjectId damper = in.object(id, "spring_damping"); damper != frontend::kNoObject) {
    mate.travel_damping = in.real(damper, "damping_constant");
    in.require(std::isfinite(mate.travel_damping) && mate.travel_damping >= 0, damper, "damping_constant",
               mate.travel_damping, "a suspension's damping is a finite number, 0 or positive");
  }
  const frontend::ObjectId suspension = in.graph().at(id).owner;
  if (suspension == frontend::kNoObject) return;
  mate.steerable = steering_trait && in.graph().at(suspension).type->is_subtype_of(steering_trait);
  mate.travel = in.vec3(suspension, "chassis_local_direction");
}

void read_elastic_wheel(AttributeReader& in, frontend::ObjectId id, Mate& tire_mate) {
  tire_mate.type = MateType::ElasticTire;
  tire_mate.enabled = true;
  const frontend::ObjectId flexibility = in.object(id, "flexibility");
  const frontend::ObjectId dissipation = in.object(id, "dissipation");
  auto part = [&](frontend::ObjectId of, const char* direction) {
    return of == frontend::kNoObject ? frontend::kNoObject : in.object(of, direction);
  };
  // Mate::kDirections order: along main, normal, cross; around main, normal, cross.
  const char* wheel_directions[6] = {"along_axial",  "along_radial",  "along_radial",
                                     "around_axial", "around_radial", "around_radial"};
  for (int k = 0; k < 6; ++k) {
    DofCompliance& dof = tire_mate.dofs[k];
    if (const frontend::ObjectId f = part(flexibility, wheel_directions[k]); f != frontend::kNoObject)
      dof.stiffness = in.real(f, "stiffness");
    if (const frontend::ObjectId d = part(dissipation, wheel_directions[k]); d != frontend::kNoObject)
      dof.damping_constant = in.number(d, "damping_constant");
  }
}

}  // namespace openplx::snap
