#include "snap/resolve_system.h"

#include "frontend/evaluation/large_stack.h"
#include "snap/system_builder.h"
#include "snap/unread_attributes.h"

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "snap/read_drivetrain.h"
#include "snap/read_lidar.h"
#include "snap/read_parameters.h"

namespace openplx::snap {
namespace detail {

static_assert(std::is_same_v<ObjectRef, fe::ObjectId> && kNoObjectRef == fe::kNoObject);

SystemBuilder::SystemBuilder(fe::Evaluator& evaluator, fe::DiagnosticSink& sink)
    : ev_(evaluator), in_(evaluator, &sink), sink_(sink) {
  fe::Program& program = evaluator.program();
  // Roles are checked against models the evaluation loaded; a bundle it never loaded cannot be a base of
  // anything, and loading it here would only cost time (Terrain, Vehicles, DriveTrain for a simple arm).
  // Physics3D's core is always looked up (loaded if need be).
  system_model_ = program.builtin_model("Physics3D.System");
  body_ = program.builtin_model("Physics3D.Bodies.Body");
  connector_ = program.builtin_model("Physics3D.Interactions.MateConnector");
  adaptive_ = program.loaded_model("Physics3D.Interactions.AdaptiveMateConnector");
  adaptive_trait_ = program.loaded_model("Physics3D.Interactions.ConnectorProperties.Adaptive");
  mate_ = program.builtin_model("Physics3D.Interactions.Mate");
  rigid_body_ = program.builtin_model("Physics3D.Bodies.RigidBody");
  contact_geometry_ = program.loaded_model("Physics3D.Geometries.ContactGeometry");
  visual_geometry_ = program.loaded_model("Visuals.Geometries.Geometry");
  interaction1d_ = program.loaded_model("Physics.Interactions.Interaction1DOF");
  input_ = program.loaded_model("Physics.Signals.Input");
  output_ = program.loaded_model("Physics.Signals.Output");
  contact_model_ = program.loaded_model("Physics.Interactions.SurfaceContact.Model");
  visual_material_ = program.loaded_model("Visuals.Materials.Material");
  shaft_ = program.loaded_model("Physics1D.Bodies.RotationalBody");
  gear_ = program.loaded_model("DriveTrain.Gear");
  differential_ = program.loaded_model("DriveTrain.Differential");
  drive_actuator_ = program.loaded_model("DriveTrain.Actuator");
  motor1d_ = program.loaded_model("Physics1D.Interactions.RotationalVelocityMotor");
  torque_motor1d_ = program.loaded_model("DriveTrain.TorqueMotor");
  clutch_ = program.loaded_model("DriveTrain.ManualClutch");
  brake_ = program.loaded_model("DriveTrain.ManualBrake");
  gearbox_ = program.loaded_model("DriveTrain.GearBox");
  converter_ = program.loaded_model("DriveTrain.EmpiricalTorqueConverter");
  mean_value_engine_ = program.loaded_model("DriveTrain.MeanValueEngine");
  empirical_engine_ = program.loaded_model("DriveTrain.EmpiricalEngine");
  broadcast_ = program.loaded_model("Control.Virtual.BroadcastInput");
  imu_output_ = program.loaded_model("Sensors.Signals.IMUOutput");
  accelerometer_ = program.loaded_model("Sensors.AccelerometerLogic");
  gyroscope_ = program.loaded_model("Sensors.GyroscopeLogic");
  magnetometer_ = program.loaded_model("Sensors.MagnetometerLogic");
  affine_input_ = program.loaded_model("Control.Virtual.AffineTransform1DInput");
  affine_output_ = program.loaded_model("Control.Virtual.AffineTransform1DOutput");
  mimic_ = program.loaded_model("Urdf.Mimic");
  joint_properties_ = program.loaded_model("Urdf.JointProperties");
  package_path_ = program.loaded_model("Urdf.PackagePath");
  collision_filter_ = program.loaded_model("Simulation.DisableCollisionPair");
  // Models with no MuJoCo counterpart get a warning instead of vanishing: shovels, linear 1-D bodies and
  // motors, and power sources without a torque law (InfinitePowerSource).
  for (const char* name : {"Terrain.Shovel", "Physics1D.Bodies.LinearBody",
                           "Physics1D.Interactions.LinearVelocityMotor", "DriveTrain.InfinitePowerSource"}) {
    if (fe::ModelInfo* m = program.loaded_model(name)) unsupported_.push_back(m);
  }
  const std::pair<const char*, Geometry::Shape> shapes[] = {
      {"Box", Geometry::Shape::Box},           {"Sphere", Geometry::Shape::Sphere},
      {"Cylinder", Geometry::Shape::Cylinder}, {"Capsule", Geometry::Shape::Capsule},
      {"Plane", Geometry::Shape::Plane},       {"ConvexMesh", Geometry::Shape::ConvexMesh},
      {"TriMesh", Geometry::Shape::TriMesh},   {"ExternalTriMeshGeometry", Geometry::Shape::ExternalMesh}};
  for (const char* bundle : {"Physics3D.Geometries.", "Visuals.Geometries."}) {
    for (const auto& [name, shape] : shapes) {
      if (fe::ModelInfo* m = program.loaded_model(std::string(bundle) + name)) shapes_.emplace_back(m, shape);
    }
  }
  using K = Interaction1D::Kind;
  const std::pair<const char*, K> kinds1d[] = {{"LinearSpring", K::LinearSpring},
                                               {"TorsionSpring", K::TorsionSpring},
                                               {"LinearRange", K::LinearRange},
                                               {"RotationalRange", K::RotationalRange},
                                               {"LinearVelocityMotor", K::LinearVelocityMotor},
                                               {"RotationalVelocityMotor", K::RotationalVelocityMotor},
                                               {"ForceMotor", K::ForceMotor},
                                               {"TorqueMotor", K::TorqueMotor},
                                               {"DistanceRange", K::DistanceRange},
                                               {"DistanceMotor", K::DistanceMotor}};
  for (const auto& [name, kind] : kinds1d) {
    if (fe::ModelInfo* m = program.loaded_model(std::string("Physics3D.Interactions.") + name)) {
      kinds1d_.emplace_back(m, kind);
    }
  }
  const std::pair<const char*, MateType> kinds[] = {{"Lock", MateType::Lock},
                                                    {"Hinge", MateType::Hinge},
                                                    {"Prismatic", MateType::Prismatic},
                                                    {"Cylindrical", MateType::Cylindrical},
                                                    {"Ball", MateType::Ball},
                                                    {"Distance", MateType::Distance},
                                                    {"ConstantVelocity", MateType::ConstantVelocity}};
  for (const auto& [name, type] : kinds) {
    if (fe::ModelInfo* m = program.loaded_model(std::string("Physics3D.Interactions.") + name)) {
      mate_kinds_.emplace_back(m, type);
    }
  }
  if (fe::ModelInfo* m = program.loaded_model("Urdf.Planar")) mate_kinds_.emplace_back(m, MateType::Planar);
  suspension_mate_ = program.loaded_model("Vehicles.Suspensions.SingleMate.Interactions.Base");
  lidar_ = program.loaded_model("Sensors.LidarLogic");
  terrain_ = program.loaded_model("Terrain.Terrain");
  elastic_wheel_ = program.loaded_model("Vehicles.Wheels.ElasticWheel");
  track_system_ = program.loaded_model("Vehicles.TrackSystem.Base");
  track_links_ = program.loaded_model("Vehicles.TrackSystem.Components.Tracks.Base");
  steering_trait_ = program.loaded_model("Vehicles.Suspensions.Properties.Steering");
  steering_interaction_ = program.loaded_model("Vehicles.Steering.Kinematic.Interactions.Base");
}

ResolvedSystem SystemBuilder::build(fe::ObjectId root) {
  if (!system_model_ || !body_ || !connector_ || !mate_)
    return std::move(system_);  // no Physics3D: nothing to assemble
  // Depth-first in declaration order, parents before children.
  struct Item {
    fe::ObjectId object;
    int node;  // nearest enclosing frame node
  };
  std::vector<Item> stack;
  visit(root, kWorld, stack, true);
  while (!stack.empty()) {
    Item item = stack.back();
    stack.pop_back();
    visit(item.object, item.node, stack, false);
  }
  apply_kinematic_control();
  resolve_redirects();
  resolve_elastic_wheels();
  resolve_tracks();
  for (Mate& mate : system_.mates) resolve_connectors(mate);
  for (Interaction1D& interaction : system_.interactions) attach(interaction);
  resolve_drivetrain();
  resolve_packages();
  for (Interaction1D& interaction : system_.interactions)
    read_interaction_parameters(in_, interaction.object, interaction);
  resolve_materials();
  for (size_t f = 0; f < system_.collision_filters.size(); ++f) {
    system_.collision_filters[f].group1 = collision_group(filter_groups_[f].first);
    system_.collision_filters[f].group2 = collision_group(filter_groups_[f].second);
  }
  for (size_t k = 0; k < system_.signals.size(); ++k) resolve_source(system_.signals[k], signal_sources_[k]);
  resolve_composites();
  resolve_sensor_attachments();
  resolve_signal_references();
  system_.gravity = read_gravity(in_, system_.root >= 0 ? system_.nodes[system_.root].object : fe::kNoObject);
  return std::move(system_);
}

template <typename Stack>
void SystemBuilder::visit(fe::ObjectId id, int enclosing, Stack& stack, bool is_root) {
  const fe::Object& obj = ev_.graph().at(id);
  int node = enclosing;
  const Role role = role_of(obj.type);
  if (role.unsupported && !is_root) {
    system_.unsupported.push_back({id, path_of(id), role.unsupported->qualified, where_of(id)});
    return;  // nothing inside maps either
  }
  switch (role.kind) {
    case Role::Kind::Shaft: {
      const fe::ObjectId inertia = object(id, "inertia");
      const double moment = inertia == fe::kNoObject ? 1.0 : real(inertia, "inertia", 1.0);
      if (inertia != fe::kNoObject)
        in_.require(std::isfinite(moment) && moment >= 0, inertia, "inertia", moment,
                    "a shaft's moment of inertia is a positive number of kg m^2");
      system_.shafts.push_back({id, path_of(id), moment, where_of(id)});
      break;
    }
    case Role::Kind::Coupling: {
      using Kind = DriveCoupling::Kind;
      DriveCoupling c;
      c.kind = is(obj, gear_)                                              ? Kind::Gear
               : is(obj, differential_)                                    ? Kind::Differential
               : is(obj, clutch_)                                          ? Kind::Clutch
               : is(obj, brake_)                                           ? Kind::Brake
               : is(obj, gearbox_)                                         ? Kind::GearBox
               : is(obj, converter_)                                       ? Kind::TorqueConverter
               : is(obj, mean_value_engine_) || is(obj, empirical_engine_) ? Kind::Engine
                                                                           : Kind::Actuator;
      c.object = id;
      c.path = path_of(id);
      c.where = where_of(id);
      read_drive_parameters(in_, id, c);
      system_.couplings.push_back(std::move(c));
      break;
    }
    case Role::Kind::Node:
      node = add_node(id, enclosing, is_root);
      break;
    case Role::Kind::Connector:
      add_connector(id, enclosing);
      break;
    case Role::Kind::Mate:
      add_mate(id);
      break;
    case Role::Kind::Geometry:
      add_geometry(id, enclosing);
      break;
    case Role::Kind::Interaction:
      add_interaction(id);
      break;
    case Role::Kind::Signal:
      add_signal(id, role.signal);
      break;
    case Role::Kind::VisualMaterial:
      system_.visual_materials.push_back(read_visual_material(in_, id));
      break;
    case Role::Kind::ContactModel: {
      ContactModel model;
      model.object = id;
      model.path = path_of(id);
      model.material1 = material_index(object(id, "material_1"));
      model.material2 = material_index(object(id, "material_2"));
      model.where = where_of(id);
      read_contact_parameters(in_, id, model);
      system_.contact_models.push_back(std::move(model));
      break;
    }
    case Role::Kind::Mimic:
      system_.joint_couplings.push_back(
          {id, path_of(id), -1, -1, real(id, "multiplier", 1.0), real(id, "offset", 0.0), where_of(id)});
      break;
    case Role::Kind::JointProperties:
      system_.joint_properties.push_back({id, path_of(id), -1, real(id, "damping"), real(id, "friction"),
                                          real(id, "effort"), real(id, "velocity"), where_of(id)});
      break;
    case Role::Kind::PackagePath:
      if (const fe::Value* name = ev_.value(id, "name"); name && name->kind == fe::Value::Kind::String) {
        const fe::Value* dir = ev_.value(id, "path");
        packages_[name->string_value()] =
            dir && dir->kind == fe::Value::Kind::String ? dir->string_value() : "";
      }
      break;
    case Role::Kind::CollisionFilter:
      system_.collision_filters.push_back({id, path_of(id), {}, {}, where_of(id)});
      filter_groups_.emplace_back(object(id, "group1"), object(id, "group2"));
      break;
    case Role::Kind::Lidar:
      system_.lidars.push_back(read_lidar(in_, id, where_of(id), sink_));
      break;
    case Role::Kind::Terrain: {
      Terrain t;
      t.object = id;
      t.path = path_of(id);
      t.parent = enclosing;
      read_transform(id, t.local);
      t.num_x = count(id, "num_elements_x");
      t.num_y = count(id, "num_elements_y");
      t.element_size = real(id, "element_size");
      t.max_depth = real(id, "max_depth");
      t.where = where_of(id);
      system_.terrains.push_back(std::move(t));
      return;  // its material and soil have no MuJoCo counterpart (warned by the emitter)
    }
    case Role::Kind::TrackLinks:
      return;  // the links are made by the emitter from the description (resolve_tracks)
    case Role::Kind::None:
      break;
  }
  // Children pushed last first, so the stack pops them in declaration order. The evaluator left most
  // instances unevaluated (Evaluator::evaluate_layouts): a part is made here when it can hold anything
  // this system maps.
  for (uint32_t k = static_cast<uint32_t>(ev_.graph().at(id).slots.size()); k-- > 0;) {
    if (ev_.graph().at(id).slots[k].state == fe::Slot::State::Pending && holds_parts(id, k)) ev_.value(id, k);
    const fe::Slot& slot = ev_.graph().at(id).slots[k];
    if (slot.owns && slot.value.kind == fe::Value::Kind::Object) stack.push_back({slot.value.object, node});
  }
}

// Whether the owned part slot `k` of `id` would make can hold anything with a role: answered on the
// instance of its layout that was evaluated in full, once per layout and slot.
bool SystemBuilder::holds_parts(fe::ObjectId id, uint32_t k) {
  const fe::Object& obj = ev_.graph().at(id);
  const fe::Slot& slot = obj.slots[k];
  if (!slot.type() || slot.type()->kind != fe::TypeKind::Model || slot.type()->is_array || slot.optional())
    return false;  // no owned part (arrays and references are not parts)
  if (const fe::ModelInfo* type = ev_.pending_default(id, k)) {
    // A pure default has its type's parts: answered on the checked default of that type.
    if (const fe::ObjectId same = ev_.checked_default(type); same != fe::kNoObject) {
      auto [it, fresh] = default_holds_parts_.try_emplace(type, true);  // true while being decided
      if (!fresh) return it->second;
      const bool holds = subtree_has_roles(same);  // may add entries: `it` is not kept
      default_holds_parts_[type] = holds;
      return holds;
    }
  }
  // Entries on its parts may add anything, but the same entries bind every instance of a layout.
  const fe::ObjectId checked = ev_.checked_instance(obj);
  if (checked == fe::kNoObject || checked == id) return true;
  // An enclosing model's assignment laid over this instance alone may give the part another type.
  if (slot.binding.entry != ev_.graph().at(checked).slots[k].binding.entry) return true;
  auto [it, fresh] = holds_parts_.try_emplace({obj.layout, k}, true);  // true while being decided
  if (!fresh) return it->second;
  const fe::Slot& model = ev_.graph().at(checked).slots[k];
  const bool holds =
      model.state != fe::Slot::State::Done ||
      (model.owns && model.value.kind == fe::Value::Kind::Object && subtree_has_roles(model.value.object));
  holds_parts_[{obj.layout, k}] = holds;
  return holds;
}

bool SystemBuilder::subtree_has_roles(fe::ObjectId id) {
  const fe::Object& obj = ev_.graph().at(id);
  const Role role = role_of(obj.type);
  if (role.kind != Role::Kind::None || role.unsupported) return true;
  for (uint32_t k = 0; k < obj.slots.size(); ++k) {
    const fe::Slot& slot = obj.slots[k];
    if (slot.state == fe::Slot::State::Pending
            ? holds_parts(id, k)
            : slot.owns && slot.value.kind == fe::Value::Kind::Object && subtree_has_roles(slot.value.object))
      return true;
  }
  return false;
}

SystemBuilder::Role SystemBuilder::role_of(const fe::ModelInfo* type) {
  auto [it, fresh] = roles_.try_emplace(type);
  if (!fresh) return it->second;
  Role& role = it->second;
  for (const fe::ModelInfo* m : unsupported_) {
    if (type->is_subtype_of(m)) {
      role.unsupported = m;
      break;
    }
  }
  auto sub = [&](const fe::ModelInfo* m) { return m && type->is_subtype_of(m); };
  using K = Role::Kind;
  role.kind = sub(mimic_)              ? K::Mimic
              : sub(joint_properties_) ? K::JointProperties
              : sub(package_path_)     ? K::PackagePath
              : sub(collision_filter_) ? K::CollisionFilter
              : sub(lidar_)            ? K::Lidar
              : sub(terrain_)          ? K::Terrain
              : sub(track_links_)      ? K::TrackLinks
              : sub(shaft_)            ? K::Shaft
              : sub(gear_) || sub(differential_) || sub(drive_actuator_) || sub(clutch_) || sub(brake_) ||
                      sub(gearbox_) || sub(converter_) || sub(mean_value_engine_) || sub(empirical_engine_)
                  ? K::Coupling
              : sub(system_model_) || sub(body_)                ? K::Node
              : sub(connector_)                                 ? K::Connector
              : sub(mate_)                                      ? K::Mate
              : sub(contact_geometry_) || sub(visual_geometry_) ? K::Geometry
              : sub(interaction1d_)                             ? K::Interaction
              : sub(input_) || sub(output_)                     ? K::Signal
              : sub(visual_material_)                           ? K::VisualMaterial
              : sub(contact_model_)                             ? K::ContactModel
                                                                : K::None;
  if (role.kind == K::Signal) {
    role.signal = {sub(input_), sub(broadcast_), sub(affine_input_), sub(affine_output_), sub(imu_output_)};
  }
  return role;
}

}  // namespace detail

ResolvedSystem resolve_system(frontend::Evaluator& evaluator, frontend::ObjectId root,
                              frontend::DiagnosticSink& sink) {
  evaluator.track_reads(true);  // what the builder reads is what the pipeline honours
  ResolvedSystem system;
  // Reading evaluates what the evaluator left for later: on its stack, as evaluation always runs.
  frontend::run_with_large_stack([&] { system = detail::SystemBuilder(evaluator, sink).build(root); });
  evaluator.track_reads(false);
  warn_unread_attributes(evaluator, root, system, sink);
  return system;
}

Transform joint_offset(const Mate& mate) {
  Transform j;
  const Eigen::Vector3d z = Eigen::Vector3d::UnitZ();
  switch (mate.type) {
    case MateType::Hinge:
      j.rotation = natives::quat_angle_axis(mate.initial_angle, z);
      break;
    case MateType::Prismatic:
      j.position = mate.initial_position * z;
      break;
    case MateType::Cylindrical:
      j.rotation = natives::quat_angle_axis(mate.initial_angle, z);
      j.position = mate.initial_position * z;
      break;
    case MateType::Distance:
      j.position = mate.initial_position * z;
      break;
    default:
      break;
  }
  return j;
}

std::string mate_type_name(MateType type) {
  switch (type) {
    case MateType::Lock:
      return "Lock";
    case MateType::Hinge:
      return "Hinge";
    case MateType::Prismatic:
      return "Prismatic";
    case MateType::Cylindrical:
      return "Cylindrical";
    case MateType::Ball:
      return "Ball";
    case MateType::Distance:
      return "Distance";
    case MateType::ConstantVelocity:
      return "ConstantVelocity";
    case MateType::Planar:
      return "Planar";
    case MateType::Suspension:
      return "Suspension";
    case MateType::ElasticTire:
      return "ElasticTire";
    case MateType::Other:
      return "Mate";
  }
  return "Mate";
}

}  // namespace openplx::snap
