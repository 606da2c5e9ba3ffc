#include "snap/read_vehicles.h"

namespace openplx::snap {

void read_suspension(AttributeReader& in, const frontend::ModelInfo* steering_trait, frontend::ObjectId id,
                     Mate& mate) {
  mate.type = MateType::Suspension;
  if (const frontend::ObjectId spring = in.object(id, "spring_constant"); spring != frontend::kNoObject)
    mate.travel_stiffness = in.real(spring, "stiffness");
  if (const frontend::ObjectId damper = in.object(id, "spring_damping"); damper != frontend::kNoObject)
    mate.travel_damping = in.real(damper, "damping_constant");
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
