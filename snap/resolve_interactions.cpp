// Mates and their connectors, 1-D interactions, the drivetrain's references, tracks and elastic wheels.
#include <cmath>
#include <string>

#include "snap/read_drivetrain.h"
#include "snap/read_parameters.h"
#include "snap/read_vehicles.h"
#include "snap/system_builder.h"

namespace openplx::snap::detail {

void SystemBuilder::add_interaction(fe::ObjectId id) {
  Interaction1D interaction;
  interaction.object = id;
  interaction.path = path_of(id);
  interaction.where = where_of(id);
  for (const auto& [model, kind] : kinds1d_) {
    if (ev_.graph().at(id).type->is_subtype_of(model)) interaction.kind = kind;
  }
  if (steering_interaction_ && ev_.graph().at(id).type->is_subtype_of(steering_interaction_))
    interaction.kind = Interaction1D::Kind::Steering;
  system_.interactions.push_back(std::move(interaction));
}

// The index of the mate that is `object`, or -1 (the map is built once, after the walk found every mate).
int SystemBuilder::mate_index(fe::ObjectId object) {
  if (mate_of_.empty()) {
    for (size_t m = 0; m < system_.mates.size(); ++m) mate_of_[system_.mates[m].object] = static_cast<int>(m);
  }
  auto it = mate_of_.find(object);
  return it == mate_of_.end() ? -1 : it->second;
}

// Drivetrain references: 1-D connectors belong to the shaft that owns them; actuators name a 3-D mate.
void SystemBuilder::resolve_drivetrain() {
  std::unordered_map<fe::ObjectId, int> shaft_of;
  for (size_t k = 0; k < system_.shafts.size(); ++k) shaft_of[system_.shafts[k].object] = static_cast<int>(k);
  auto shaft = [&](fe::ObjectId ref) {
    if (ref == fe::kNoObject) return -1;
    if (auto it = shaft_of.find(ref); it != shaft_of.end()) return it->second;  // the shaft itself
    auto it = shaft_of.find(ev_.graph().at(ref).owner);                         // one of its connectors
    return it == shaft_of.end() ? -1 : it->second;
  };
  auto connectors = [&](fe::ObjectId id) {
    std::vector<int> out;
    if (const fe::Value* list = ev_.value(id, "connectors"); list && list->kind == fe::Value::Kind::Array) {
      for (const fe::Value& c : list->array())
        out.push_back(c.kind == fe::Value::Kind::Object ? shaft(c.object) : -1);
    }
    return out;
  };
  for (DriveCoupling& c : system_.couplings) {
    switch (c.kind) {
      case DriveCoupling::Kind::Gear:
      case DriveCoupling::Kind::Clutch:
      case DriveCoupling::Kind::Brake:
      case DriveCoupling::Kind::GearBox:
      case DriveCoupling::Kind::TorqueConverter:
      case DriveCoupling::Kind::Engine:
        c.shafts = connectors(c.object);
        break;
      case DriveCoupling::Kind::Differential:
        for (const char* name : {"drive_shaft", "left_axle_shaft", "right_axle_shaft"})
          c.shafts.push_back(shaft(object(c.object, name)));
        break;
      case DriveCoupling::Kind::Actuator: {
        c.shafts.push_back(shaft(object(c.object, "connector_1d")));
        c.mate = mate_index(object(c.object, "mate_3d"));
        break;
      }
    }
  }
  for (JointCoupling& c : system_.joint_couplings) {
    c.follower = mate_index(object(c.object, "follower"));
    c.leader = mate_index(object(c.object, "leader"));
  }
  for (JointProperties& p : system_.joint_properties) p.mate = mate_index(object(p.object, "mate"));
  for (Interaction1D& i : system_.interactions) {
    if (i.kind == Interaction1D::Kind::Steering)
      read_steering(in_, i.object, i, [&](fe::ObjectId mate) { return mate_index(mate); });
  }
  for (Interaction1D& i : system_.interactions) {
    const fe::Object& obj = ev_.graph().at(i.object);
    const bool drivetrain_motor = is(obj, motor1d_) || is(obj, torque_motor1d_);
    // A Physics3D rotational motor given a shaft's 1-D connector drives that shaft too.
    const bool rotational_motor =
        i.kind == Interaction1D::Kind::RotationalVelocityMotor || i.kind == Interaction1D::Kind::TorqueMotor;
    if (!drivetrain_motor && !rotational_motor) continue;
    const std::vector<int> on = connectors(i.object);
    if (!drivetrain_motor && (on.size() != 1 || on[0] < 0)) continue;
    if (drivetrain_motor) {
      i.kind =
          is(obj, motor1d_) ? Interaction1D::Kind::RotationalVelocityMotor : Interaction1D::Kind::TorqueMotor;
    }
    i.shaft = on.size() == 1 ? on[0] : -1;
  }
}

// A 1-dof interaction acts on the mate whose connectors it shares (in either order).
void SystemBuilder::attach(Interaction1D& interaction) {
  const fe::Value* list = ev_.value(interaction.object, "connectors");
  if (!list || list->kind != fe::Value::Kind::Array || list->array().size() != 2) return;
  const fe::Value& a = list->array()[0];
  const fe::Value& b = list->array()[1];
  if (interaction.kind == Interaction1D::Kind::DistanceRange ||
      interaction.kind == Interaction1D::Kind::DistanceMotor) {  // between any two connectors
    for (int side = 0; side < 2; ++side) {
      const fe::Value& end = side == 0 ? a : b;
      if (end.kind != fe::Value::Kind::Object) continue;
      if (auto it = connector_of_.find(end.object); it != connector_of_.end())
        interaction.connectors[side] = it->second;
    }
    return;
  }
  if (a.kind != fe::Value::Kind::Object || b.kind != fe::Value::Kind::Object) return;
  if (mate_by_connectors_.empty()) index_mates_by_connectors();
  if (auto it = mate_by_connectors_.find(connector_pair(a.object, b.object)); it != mate_by_connectors_.end())
    interaction.mate = it->second;
}

// The first mate of each pair of connectors: an interaction finds its mate by one lookup, not by a walk
// over all mates (quadratic for a 10,000-joint URDF, one range per joint).
void SystemBuilder::index_mates_by_connectors() {
  for (size_t m = 0; m < system_.mates.size(); ++m) {
    const fe::Value* mate_list = ev_.value(system_.mates[m].object, "connectors");
    if (!mate_list || mate_list->kind != fe::Value::Kind::Array || mate_list->array().size() != 2) continue;
    mate_by_connectors_.emplace(connector_pair(mate_list->array()[0].object, mate_list->array()[1].object),
                                static_cast<int>(m));
  }
}

void SystemBuilder::add_mate(fe::ObjectId id) {
  Mate mate;
  mate.object = id;
  mate.path = path_of(id);
  // A URDF joint renamed in OpenPLX (it shares its name with a link) keeps its URDF name in MuJoCo.
  if (const fe::Value* urdf = ev_.value(id, "urdf_name"); urdf && urdf->kind == fe::Value::Kind::String) {
    const size_t dot = mate.path.rfind('.');
    mate.path = (dot == std::string::npos ? "" : mate.path.substr(0, dot + 1)) + urdf->string_value();
  }
  mate.where = where_of(id);
  const fe::ModelInfo* type = ev_.graph().at(id).type;
  for (const auto& [model, kind] : mate_kinds_) {
    if (type->is_subtype_of(model)) mate.type = kind;
  }
  auto real = [&](std::string_view name, double& out) {
    const fe::Value* v = ev_.value(id, name);
    if (v && v->is_number()) out = v->as_real();
    in_.require(std::isfinite(out), id, name, out, "a mate's initial angle, position or distance is finite");
  };
  real("initial_angle", mate.initial_angle);
  real("initial_position", mate.initial_position);
  real("initial_normal_angle", mate.initial_normal_angle);
  real("initial_cross_angle", mate.initial_cross_angle);
  if (mate.type == MateType::Distance) {  // SNAP places it at its initial distance along main_axis
    real("initial_distance", mate.initial_position);
    mate.target_distance = mate.initial_position;
    real("target_distance", mate.target_distance);
  }
  if (const fe::Value* snap = ev_.value(id, "enable_snap"); snap && snap->kind == fe::Value::Kind::Bool) {
    mate.enable_snap = snap->bool_value;
  }
  read_mate_parameters(in_, id, mate);
  if (suspension_mate_ && type->is_subtype_of(suspension_mate_))
    read_suspension(in_, steering_trait_, id, mate);
  system_.mates.push_back(std::move(mate));
}

// Connectors are references to objects anywhere in the tree (or to the World singleton).
void SystemBuilder::resolve_connectors(Mate& mate) {
  const fe::Value* list = ev_.value(mate.object, "connectors");
  const size_t count = list && list->kind == fe::Value::Kind::Array ? list->array().size() : 0;
  if (count != 2) {
    sink_.report(fe::DiagCode::InvalidMate, mate.where,
                 "mate " + mate.path + " needs exactly two connectors, has " + std::to_string(count));
    return;
  }
  for (int side = 0; side < 2; ++side) {
    const fe::Value& item = list->array()[side];
    if (item.kind != fe::Value::Kind::Object) continue;
    auto it = connector_of_.find(item.object);
    if (it != connector_of_.end()) {
      mate.connectors[side] = it->second;
      continue;
    }
    // Not owned by anything in the tree: the World connector, or a const connector that lives in the world.
    const fe::Object& obj = ev_.graph().at(item.object);
    if (obj.is_const_singleton && obj.type->is_subtype_of(connector_)) {
      add_connector(item.object, kWorld, false);
      system_.connectors.back().path = obj.type->qualified;
      mate.connectors[side] = connector_of_[item.object];
      continue;
    }
    sink_.report(fe::DiagCode::InvalidMate, mate.where,
                 "connector " + path_of(item.object) + " of mate " + mate.path +
                     " belongs to no system or body of this model");
  }
}

void SystemBuilder::resolve_elastic_wheels() {
  if (!elastic_wheel_) return;
  for (const FrameNode& n : system_.nodes) {
    if (n.kind != FrameNode::Kind::System || !ev_.graph().at(n.object).type->is_subtype_of(elastic_wheel_))
      continue;
    const int m = mate_index(object(n.object, "tire_mate"));
    if (m >= 0) read_elastic_wheel(in_, n.object, system_.mates[m]);
  }
}

void SystemBuilder::resolve_tracks() {
  if (!track_system_) return;
  for (const FrameNode& n : system_.nodes) {
    if (n.kind != FrameNode::Kind::System || !ev_.graph().at(n.object).type->is_subtype_of(track_system_))
      continue;
    TrackSystem t;
    t.object = n.object;
    t.path = n.path;
    t.where = n.where;
    const fe::ObjectId links = object(n.object, "tracks");
    const fe::ObjectId description =
        links == fe::kNoObject ? fe::kNoObject : object(links, "link_description");
    t.link_count = links == fe::kNoObject ? 0 : count(links, "link_count");
    if (links != fe::kNoObject) {
      // Each link is a body with contacts: MuJoCo 2.2.2 allocates its constraint rows dense (rows^2), so
      // a few hundred links is what it can hold.
      const double written = real(links, "link_count");
      constexpr int kMaxTrackLinks = 300;  // mjcf_emitter/tracks.cpp: the same bound (kMaxLinks)
      in_.require(written >= 3 && written <= kMaxTrackLinks, links, "link_count", written,
                  "a track has 3 to " + std::to_string(kMaxTrackLinks) +
                      " links (more would not fit the constraint memory MuJoCo 2.2.2 allocates)");
    }
    if (description != fe::kNoObject) {
      t.link_width = real(description, "width");
      t.link_height = real(description, "height");
      if (const fe::ObjectId inertia = object(description, "inertia"); inertia != fe::kNoObject) {
        t.link_mass = real(inertia, "mass");
        in_.require(std::isfinite(t.link_mass) && t.link_mass >= 0, inertia, "mass", t.link_mass,
                    "a mass is 0 (computed from the geometries) or a positive number of kg");
      }
      fe::ObjectId material = links == fe::kNoObject ? fe::kNoObject : object(links, "material");
      if (const fe::ObjectId box = object(description, "contact_geometry");
          material == fe::kNoObject && box != fe::kNoObject)
        material = object(box, "material");
      if (material != fe::kNoObject) t.link_density = real(material, "density", 1000.0);
    }
    for (fe::ObjectId w : in_.objects(n.object, "track_wheels")) {
      TrackSystem::Wheel wheel;
      if (auto it = node_of_.find(object(w, "body")); it != node_of_.end()) wheel.body = it->second;
      if (auto it = connector_of_.find(object(w, "center_connector")); it != connector_of_.end())
        wheel.connector = it->second;
      wheel.radius = real(w, "radius");
      in_.require(std::isfinite(wheel.radius), w, "radius", wheel.radius, "a wheel's radius is finite");
      t.wheels.push_back(wheel);
    }
    if (auto it = node_of_.find(object(n.object, "chassis_body")); it != node_of_.end())
      t.chassis = it->second;
    system_.tracks.push_back(std::move(t));
  }
}

}  // namespace openplx::snap::detail
