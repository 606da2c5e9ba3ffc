// Vehicles bundle parts the resolved system carries: SingleMate suspensions (travel, spring, steering) and
// kinematic steering mechanisms.
#pragma once

#include "snap/attribute_reader.h"
#include "snap/resolved_system.h"

namespace openplx::snap {

// A Vehicles.Suspensions.SingleMate.Interactions.Base mate `id`: its travel direction (the owning
// suspension's chassis_local_direction, in the chassis body's frame), whether the suspension has the
// Properties.Steering trait, and a LinearSpringDamper's spring and damper on the travel.
void read_suspension(AttributeReader& in, const frontend::ModelInfo* steering_trait, frontend::ObjectId id,
                     Mate& mate);

// A Vehicles.Steering.Kinematic.Interactions.Base interaction: its mechanism and linkage geometry, and the
// mates of the suspensions its owning Steering.Kinematic.Base steers (`mate_of` maps a mate object to its
// index, -1 when none).
template <typename MateIndex>
void read_steering(AttributeReader& in, frontend::ObjectId id, Interaction1D& steering, MateIndex&& mate_of) {
  steering.kind = Interaction1D::Kind::Steering;
  const std::string& type = in.type_name(id);
  for (const char* mechanism : {"Ackermann", "BellCrank", "RackAndPinion"}) {
    if (type.find(mechanism) != std::string::npos) steering.mechanism = mechanism;
  }
  steering.knuckle_angle = in.real(id, "knuckle_angle");
  steering.knuckle_length = in.real(id, "knuckle_length");
  if (steering.mechanism == "BellCrank" || steering.mechanism == "RackAndPinion") {
    steering.tie_rod_angle = in.real(id, "initial_angle_right_tie_rod");
    steering.column_distance = in.real(id, "steering_column_distance");
    steering.gear = in.real(id, "gear", 1.0);
    if (steering.mechanism == "RackAndPinion") steering.rack_length = in.real(id, "rack_length");
  }
  const frontend::ObjectId system = in.graph().at(id).owner;
  // Where the user wrote each geometry attribute, on the steering system (the bundle forwards it to the
  // interaction) or on the interaction itself, for warnings at the user's line.
  auto written_by_user = [&](frontend::ObjectId object, const char* name) -> const frontend::Slot* {
    if (object == frontend::kNoObject) return nullptr;
    const frontend::Slot* slot = in.graph().at(object).find(name);
    const bool user = slot && slot->binding.entry && slot->binding.entry->member && slot->binding.model &&
                      !(slot->binding.model->doc && slot->binding.model->doc->bundle);
    return user ? slot : nullptr;
  };
  for (const char* name : {"knuckle_angle", "knuckle_length", "initial_angle_right_tie_rod",
                           "steering_column_distance", "rack_length", "gear"}) {
    const frontend::Slot* slot = written_by_user(system, name);
    if (!slot) slot = written_by_user(id, name);
    if (slot) steering.written.emplace_back(name, slot->binding.entry->member->range);
  }
  if (system == frontend::kNoObject) return;
  const char* sides[2] = {"left_suspension", "right_suspension"};
  for (int side = 0; side < 2; ++side) {
    const frontend::ObjectId suspension = in.object(system, sides[side]);
    if (suspension != frontend::kNoObject) steering.steered[side] = mate_of(in.object(suspension, "mate"));
  }
}

// A Vehicles.Wheels.ElasticWheel system `id` makes its tire_mate (disabled in the bundle: AGX replaces it by
// its wheel joint) the tire's compliant joint: enabled, of type ElasticTire, with the wheel's flexibility and
// dissipation per direction (the mate's main axis is the axle: axial = along/around main, radial = along/
// around normal and cross).
void read_elastic_wheel(AttributeReader& in, frontend::ObjectId id, Mate& tire_mate);

}  // namespace openplx::snap
