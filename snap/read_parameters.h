// The numbers and flags of mates, 1-DOF interactions, materials, contact models and the environment, read
// once into the resolved system (the structural walk is in resolve_system.cpp).
#pragma once

#include "snap/attribute_reader.h"
#include "snap/resolved_system.h"

namespace openplx::snap {

// enabled, flexibility and dissipation per direction, friction of the free degrees of freedom.
void read_mate_parameters(AttributeReader& in, frontend::ObjectId id, Mate& mate);

// Ranges, springs and motors: what each kind's mapping reads (call after its kind is final).
void read_interaction_parameters(AttributeReader& in, frontend::ObjectId id, Interaction1D& interaction);

// Where the user wrote `object.name`'s value and what to call it there: the assignment of it, or of an
// object holding it (a vector written whole), named by the declaration whose text holds that assignment
// (`Paint.metallic_map` for every instance of Paint; the converted root's own ones by their path). A value
// no user wrote is named by the instance's path, at the user's declaration of the object.
WrittenValue written_value(const AttributeReader& in, frontend::ObjectId object, std::string_view name);
// The name of the attribute a user's assignment binds, as written_value gives it (nullopt: no user's entry).
std::optional<std::string> written_name(const frontend::ObjectGraph& graph, const frontend::Slot& slot);

// A Visuals.Materials.Material: tint, roughness, metallic, and which texture maps carry inline pixels.
VisualMaterial read_visual_material(AttributeReader& in, frontend::ObjectId id);

// A SurfaceContact model's enabled flag, friction coefficient and restitutions (materials are the caller's).
void read_contact_parameters(AttributeReader& in, frontend::ObjectId id, ContactModel& model);

// The root's Simulation gravity field.
Gravity read_gravity(AttributeReader& in, frontend::ObjectId root);

}  // namespace openplx::snap
