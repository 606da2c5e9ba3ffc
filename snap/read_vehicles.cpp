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

}  // namespace openplx::snap
