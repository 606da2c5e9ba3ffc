#include "snap/resolve_system.h"

#include "frontend/evaluation/large_stack.h"
#include "snap/unread_attributes.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <optional>
#include <tuple>
#include <unordered_map>

#include "frontend/urdf/package_uri.h"
#include "snap/attribute_reader.h"
#include "snap/read_drivetrain.h"
#include "snap/read_lidar.h"
#include "snap/read_parameters.h"
#include "snap/read_vehicles.h"

namespace openplx::snap {
namespace {

namespace fe = openplx::frontend;
static_assert(std::is_same_v<ObjectRef, fe::ObjectId> && kNoObjectRef == fe::kNoObject);

bool in_bundle(const fe::ModelInfo* m) {
  return m && m->doc && m->doc->bundle;
}

// Where source_of finds an object declared, from the object's owner `at` up: the nearest attribute declared
// outside the bundles, or the root model's declaration; nullopt where it falls back on the object's own
// attribute. The same for every object of one owner; `settled` is false when the climb ended at a free
// object, which the evaluator may yet adopt.
std::optional<fe::SourceRange> declared_above(const fe::ObjectGraph& graph, fe::ObjectId at, bool& settled) {
  settled = true;
  for (;;) {
    const fe::Object& obj = graph.at(at);
    if (obj.owner == fe::kNoObject) {
      settled = at == graph.root;
      if (in_bundle(obj.type)) return std::nullopt;
      return obj.type->decl ? obj.type->decl->range : fe::SourceRange{};
    }
    const fe::Slot* slot = graph.at(obj.owner).find(obj.name);
    if (!slot) return std::nullopt;
    if (!in_bundle(slot->declared_in())) return slot->declaration()->member->range;
    at = obj.owner;
  }
}

// Where an object is declared, as the user sees it: an attribute a bundle model declares (a suspension's
// `mate`, a wheel's `rim_alignment_mate`) is reported at the user's declaration of the instance holding it,
// the nearest enclosing attribute declared outside the bundles. `above` is declared_above, or a memo of it.
template <typename Above>
fe::SourceRange source_with(const fe::ObjectGraph& graph, fe::ObjectId id, Above&& above) {
  const fe::Object& obj = graph.at(id);
  if (obj.owner == fe::kNoObject) return obj.type->decl ? obj.type->decl->range : fe::SourceRange{};
  const fe::Slot* slot = graph.at(obj.owner).find(obj.name);
  if (!slot) return {};
  const fe::SourceRange own = slot->declaration()->member->range;
  if (!in_bundle(slot->declared_in())) return own;
  return above(obj.owner).value_or(own);
}

class SystemBuilder {
 public:
  SystemBuilder(fe::Evaluator& evaluator, fe::DiagnosticSink& sink)
      : ev_(evaluator), in_(evaluator, &sink), sink_(sink) {
    fe::Program& program = evaluator.program();
    // Roles are checked against models the evaluation loaded; a bundle it never loaded cannot be a base of
    // anything, and loading it here would only cost time (Terrain, Vehicles, DriveTrain for a simple arm).
    // Physics3D's core is always looked up (loaded if need be).
    system_ = program.builtin_model("Physics3D.System");
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
    for (const char* name :
         {"Terrain.Shovel", "Physics1D.Bodies.LinearBody", "Physics1D.Interactions.LinearVelocityMotor",
          "DriveTrain.InfinitePowerSource"}) {
      if (fe::ModelInfo* m = program.loaded_model(name)) unsupported_.push_back(m);
    }
    const std::pair<const char*, Geometry::Shape> shapes[] = {
        {"Box", Geometry::Shape::Box},           {"Sphere", Geometry::Shape::Sphere},
        {"Cylinder", Geometry::Shape::Cylinder}, {"Capsule", Geometry::Shape::Capsule},
        {"Plane", Geometry::Shape::Plane},       {"ConvexMesh", Geometry::Shape::ConvexMesh},
        {"TriMesh", Geometry::Shape::TriMesh},   {"ExternalTriMeshGeometry", Geometry::Shape::ExternalMesh}};
    for (const char* bundle : {"Physics3D.Geometries.", "Visuals.Geometries."}) {
      for (const auto& [name, shape] : shapes) {
        if (fe::ModelInfo* m = program.loaded_model(std::string(bundle) + name))
          shapes_.emplace_back(m, shape);
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

  ResolvedSystem build(fe::ObjectId root) {
    if (!system_ || !body_ || !connector_ || !mate_)
      return std::move(view_);  // no Physics3D: nothing to assemble
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
    for (Mate& mate : view_.mates) resolve_connectors(mate);
    for (Interaction1D& interaction : view_.interactions) attach(interaction);
    resolve_drivetrain();
    resolve_packages();
    for (Interaction1D& interaction : view_.interactions)
      read_interaction_parameters(in_, interaction.object, interaction);
    resolve_materials();
    for (size_t f = 0; f < view_.collision_filters.size(); ++f) {
      view_.collision_filters[f].group1 = collision_group(filter_groups_[f].first);
      view_.collision_filters[f].group2 = collision_group(filter_groups_[f].second);
    }
    for (size_t k = 0; k < view_.signals.size(); ++k) resolve_source(view_.signals[k], signal_sources_[k]);
    resolve_composites();
    resolve_sensor_attachments();
    view_.gravity = read_gravity(in_, view_.root >= 0 ? view_.nodes[view_.root].object : fe::kNoObject);
    return std::move(view_);
  }

 private:
  template <typename Stack>
  void visit(fe::ObjectId id, int enclosing, Stack& stack, bool is_root) {
    const fe::Object& obj = ev_.graph().at(id);
    int node = enclosing;
    const Role role = role_of(obj.type);
    if (role.unsupported && !is_root) {
      view_.unsupported.push_back({id, path_of(id), role.unsupported->qualified, where_of(id)});
      return;  // nothing inside maps either
    }
    switch (role.kind) {
      case Role::Kind::Shaft: {
        const fe::ObjectId inertia = object(id, "inertia");
        const double moment = inertia == fe::kNoObject ? 1.0 : real(inertia, "inertia", 1.0);
        if (inertia != fe::kNoObject)
          in_.require(std::isfinite(moment) && moment >= 0, inertia, "inertia", moment,
                      "a shaft's moment of inertia is a positive number of kg m^2");
        view_.shafts.push_back({id, path_of(id), moment, where_of(id)});
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
        view_.couplings.push_back(std::move(c));
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
        view_.visual_materials.push_back(read_visual_material(in_, id));
        break;
      case Role::Kind::ContactModel: {
        ContactModel model;
        model.object = id;
        model.path = path_of(id);
        model.material1 = material_index(object(id, "material_1"));
        model.material2 = material_index(object(id, "material_2"));
        model.where = where_of(id);
        read_contact_parameters(in_, id, model);
        view_.contact_models.push_back(std::move(model));
        break;
      }
      case Role::Kind::Mimic:
        view_.joint_couplings.push_back(
            {id, path_of(id), -1, -1, real(id, "multiplier", 1.0), real(id, "offset", 0.0), where_of(id)});
        break;
      case Role::Kind::JointProperties:
        view_.joint_properties.push_back({id, path_of(id), -1, real(id, "damping"), real(id, "friction"),
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
        view_.collision_filters.push_back({id, path_of(id), {}, {}, where_of(id)});
        filter_groups_.emplace_back(object(id, "group1"), object(id, "group2"));
        break;
      case Role::Kind::Lidar:
        view_.lidars.push_back(read_lidar(in_, id, where_of(id), sink_));
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
        view_.terrains.push_back(std::move(t));
        return;  // its material and soil have no MuJoCo counterpart (warned by the emitter)
      }
      case Role::Kind::TrackLinks:
        return;  // the links are made by the emitter from the description (resolve_tracks)
      case Role::Kind::None:
        break;
    }
    // Children pushed last first, so the stack pops them in declaration order. The evaluator left most
    // instances unevaluated (Evaluator::evaluate_layouts): a part is made here when it can hold anything
    // this view maps.
    for (uint32_t k = static_cast<uint32_t>(ev_.graph().at(id).slots.size()); k-- > 0;) {
      if (ev_.graph().at(id).slots[k].state == fe::Slot::State::Pending && holds_parts(id, k))
        ev_.value(id, k);
      const fe::Slot& slot = ev_.graph().at(id).slots[k];
      if (slot.owns && slot.value.kind == fe::Value::Kind::Object) stack.push_back({slot.value.object, node});
    }
  }

  // Whether the owned part slot `k` of `id` would make can hold anything with a role: answered on the
  // instance of its layout that was evaluated in full, once per layout and slot.
  bool holds_parts(fe::ObjectId id, uint32_t k) {
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

  bool subtree_has_roles(fe::ObjectId id) {
    const fe::Object& obj = ev_.graph().at(id);
    const Role role = role_of(obj.type);
    if (role.kind != Role::Kind::None || role.unsupported) return true;
    for (uint32_t k = 0; k < obj.slots.size(); ++k) {
      const fe::Slot& slot = obj.slots[k];
      if (slot.state == fe::Slot::State::Pending ? holds_parts(id, k)
                                                 : slot.owns && slot.value.kind == fe::Value::Kind::Object &&
                                                       subtree_has_roles(slot.value.object))
        return true;
    }
    return false;
  }

  // What a model is to the view, decided once per model (a large tree has few models and many objects).
  struct Role {
    enum class Kind {
      None,
      Shaft,
      Coupling,
      Node,
      Connector,
      Mate,
      Geometry,
      Interaction,
      Signal,
      VisualMaterial,
      ContactModel,
      Mimic,
      JointProperties,
      PackagePath,
      CollisionFilter,
      Lidar,
      Terrain,
      TrackLinks
    };
    Kind kind = Kind::None;
    const fe::ModelInfo* unsupported = nullptr;
    // A signal's model: which of the models add_signal reads differently it is.
    struct SignalModel {
      bool input = false, broadcast = false, affine_input = false, affine_output = false, imu = false;
    } signal;
  };
  Role role_of(const fe::ModelInfo* type) {
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
                : sub(system_) || sub(body_)                      ? K::Node
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

  static bool is(const fe::Object& obj, const fe::ModelInfo* model) {
    return model && obj.type->is_subtype_of(model);
  }

  // Typed reads go through the one AttributeReader the parameter readers use too.
  double real(fe::ObjectId id, std::string_view name, double fallback = 0.0) {
    return in_.real(id, name, fallback);
  }
  fe::ObjectId object(fe::ObjectId id, std::string_view name) { return in_.object(id, name); }
  // A count attribute, clamped to [0, 1e9] so that no value overflows an int (the passes bound it further).
  int count(fe::ObjectId id, std::string_view name) {
    const double v = real(id, name);
    return std::isfinite(v) ? static_cast<int>(std::clamp(v, 0.0, 1e9)) : 0;
  }

  void read_body(fe::ObjectId id, BodyProperties& body) {
    if (const fe::Value* d = ev_.value(id, "is_dynamic"); d && d->kind == fe::Value::Kind::Bool)
      body.dynamic = d->bool_value;
    if (fe::ObjectId inertia = object(id, "inertia"); inertia != fe::kNoObject) {
      body.mass = real(inertia, "mass");
      in_.require(std::isfinite(body.mass) && body.mass >= 0, inertia, "mass", body.mass,
                  "a mass is 0 (computed from the geometries) or a positive number of kg");
      if (std::optional<Eigen::Matrix3d> tensor = inertia_tensor(inertia)) {
        body.inertia = *tensor;
        check_inertia_tensor(inertia, *tensor);
      }
      body.tensor_where = in_.written_at(inertia, "tensor");
    }
    if (const fe::Value* law = ev_.value(id, "urdf_mass"); law && law->kind == fe::Value::Kind::String) {
      if (law->string_value() == "collisions") body.urdf_mass = BodyProperties::UrdfMass::Collisions;
      if (law->string_value() == "as_written") body.urdf_mass = BodyProperties::UrdfMass::AsWritten;
    }
    if (fe::ObjectId kinematics = object(id, "kinematics"); kinematics != fe::kNoObject) {
      if (std::optional<Transform> cm = transform_of(kinematics, std::string_view("local_cm_transform")))
        body.cm = *cm;
      body.initial_linear_velocity = vec3(kinematics, "initial_local_linear_velocity");
      body.initial_angular_velocity = vec3(kinematics, "initial_local_angular_velocity");
      for (const char* velocity : {"initial_local_linear_velocity", "initial_local_angular_velocity"}) {
        if (const fe::ObjectId v = object(kinematics, velocity); v != fe::kNoObject)
          in_.require_finite_components(v, "an initial velocity is finite");
      }
    }
  }

  void add_geometry(fe::ObjectId id, int owner) {
    const fe::Object& obj = ev_.graph().at(id);
    Geometry g;
    g.object = id;
    g.visual = is(obj, visual_geometry_);
    g.owner = owner;
    g.path = path_of(id);
    g.where = where_of(id);
    for (const auto& [model, shape] : shapes_) {
      if (obj.type->is_subtype_of(model)) g.shape = shape;
    }
    if (std::optional<Transform> t = transform_of(id, std::string_view("local_transform"))) g.local = *t;
    // A size is finite and 0 or more (0: the emitter leaves the geometry out, warned).
    auto size = [&](std::string_view name) {
      const double v = real(id, name);
      in_.require(std::isfinite(v) && v >= 0, id, name, v, "a geometry's size is a finite number, 0 or more");
      return v;
    };
    switch (g.shape) {
      case Geometry::Shape::Box:
        g.size = vec3(id, "size");
        if (!(g.size.allFinite() && g.size.minCoeff() >= 0)) {
          const fe::ObjectId v = object(id, "size");
          for (const char* axis : {"x", "y", "z"}) {
            const double c = v == fe::kNoObject ? 0 : real(v, axis);
            in_.require(std::isfinite(c) && c >= 0, v, axis, c, "a box's size is finite and 0 or more");
          }
        }
        break;
      case Geometry::Shape::Sphere:
        g.size.x() = size("radius");
        break;
      case Geometry::Shape::Cylinder:
      case Geometry::Shape::Capsule:
        g.size = {size("radius"), size("height"), 0.0};
        break;
      case Geometry::Shape::ConvexMesh:
      case Geometry::Shape::TriMesh:
        read_mesh_data(id, g);
        break;
      default:
        break;
    }
    if (const fe::Value* path = ev_.value(id, "path"); path && path->kind == fe::Value::Kind::String) {
      g.file = path->string_value();
    }
    if (const fe::Value* uri = ev_.value(id, "package_uri"); uri && uri->kind == fe::Value::Kind::String) {
      g.package_uri = uri->string_value();
    }
    if (const fe::Value* scale = ev_.value(id, "scale"); scale && scale->kind == fe::Value::Kind::Object) {
      g.scale = vec3(id, "scale");
    } else if (scale && scale->is_number()) {
      g.scale = Eigen::Vector3d::Constant(scale->as_real());
    }
    geometry_materials_.push_back(object(id, "material"));
    if (const fe::Value* c = ev_.value(id, "enable_collisions"); c && c->kind == fe::Value::Kind::Bool)
      g.collides = c->bool_value;
    if (const fe::Value* m = ev_.value(id, "include_in_mass_properties");
        m && m->kind == fe::Value::Kind::Bool) {
      g.in_mass = m->bool_value;
    }
    if (g.visual) g.collides = g.in_mass = false;
    view_.geometries.push_back(std::move(g));
  }

  void add_interaction(fe::ObjectId id) {
    Interaction1D interaction;
    interaction.object = id;
    interaction.path = path_of(id);
    interaction.where = where_of(id);
    for (const auto& [model, kind] : kinds1d_) {
      if (ev_.graph().at(id).type->is_subtype_of(model)) interaction.kind = kind;
    }
    if (steering_interaction_ && ev_.graph().at(id).type->is_subtype_of(steering_interaction_))
      interaction.kind = Interaction1D::Kind::Steering;
    view_.interactions.push_back(std::move(interaction));
  }

  // Drivetrain references: 1-D connectors belong to the shaft that owns them; actuators name a 3-D mate.
  // A URDF mesh named `package://P/rest` is read from `<path>/rest` when the model declares a
  // Urdf.PackagePath named P (anywhere: in the scene or in the robot); otherwise from where the import found
  // P.
  void resolve_packages() {
    for (Geometry& g : view_.geometries) {
      const std::optional<fe::PackageUri> uri = fe::parse_package_uri(g.package_uri);
      auto it = uri ? packages_.find(uri->package) : packages_.end();
      if (it == packages_.end()) continue;
      g.file = (std::filesystem::path(it->second) / uri->inside).lexically_normal().generic_string();
    }
  }

  // The index of the mate that is `object`, or -1 (the map is built once, after the walk found every mate).
  int mate_index(fe::ObjectId object) {
    if (mate_of_.empty()) {
      for (size_t m = 0; m < view_.mates.size(); ++m) mate_of_[view_.mates[m].object] = static_cast<int>(m);
    }
    auto it = mate_of_.find(object);
    return it == mate_of_.end() ? -1 : it->second;
  }

  void resolve_drivetrain() {
    std::unordered_map<fe::ObjectId, int> shaft_of;
    for (size_t k = 0; k < view_.shafts.size(); ++k) shaft_of[view_.shafts[k].object] = static_cast<int>(k);
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
    for (DriveCoupling& c : view_.couplings) {
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
    for (JointCoupling& c : view_.joint_couplings) {
      c.follower = mate_index(object(c.object, "follower"));
      c.leader = mate_index(object(c.object, "leader"));
    }
    for (JointProperties& p : view_.joint_properties) p.mate = mate_index(object(p.object, "mate"));
    for (Interaction1D& i : view_.interactions) {
      if (i.kind == Interaction1D::Kind::Steering)
        read_steering(in_, i.object, i, [&](fe::ObjectId mate) { return mate_index(mate); });
    }
    for (Interaction1D& i : view_.interactions) {
      const fe::Object& obj = ev_.graph().at(i.object);
      const bool drivetrain_motor = is(obj, motor1d_) || is(obj, torque_motor1d_);
      // A Physics3D rotational motor given a shaft's 1-D connector drives that shaft too.
      const bool rotational_motor = i.kind == Interaction1D::Kind::RotationalVelocityMotor ||
                                    i.kind == Interaction1D::Kind::TorqueMotor;
      if (!drivetrain_motor && !rotational_motor) continue;
      const std::vector<int> on = connectors(i.object);
      if (!drivetrain_motor && (on.size() != 1 || on[0] < 0)) continue;
      if (drivetrain_motor) {
        i.kind = is(obj, motor1d_) ? Interaction1D::Kind::RotationalVelocityMotor
                                   : Interaction1D::Kind::TorqueMotor;
      }
      i.shaft = on.size() == 1 ? on[0] : -1;
    }
  }

  // Physics3D.System.kinematically_controlled (deprecated for RigidBody.is_dynamic, still used): the bodies
  // it lists are kinematic, as `is_dynamic: false` makes them.
  void apply_kinematic_control() {
    std::unordered_map<fe::ObjectId, size_t> node_of;
    for (size_t k = 0; k < view_.nodes.size(); ++k) node_of[view_.nodes[k].object] = k;
    for (size_t k = 0; k < view_.nodes.size(); ++k) {
      if (view_.nodes[k].kind != FrameNode::Kind::System) continue;
      const fe::Value* list = ev_.value(view_.nodes[k].object, "kinematically_controlled");
      if (!list || list->kind != fe::Value::Kind::Array) continue;
      for (const fe::Value& v : list->array()) {
        auto it = v.kind == fe::Value::Kind::Object ? node_of.find(v.object) : node_of.end();
        if (it != node_of.end() && view_.nodes[it->second].kind == FrameNode::Kind::Body)
          view_.nodes[it->second].body.dynamic = false;
      }
    }
  }

  // A 1-dof interaction acts on the mate whose connectors it shares (in either order).
  void attach(Interaction1D& interaction) {
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
    if (auto it = mate_by_connectors_.find(connector_pair(a.object, b.object));
        it != mate_by_connectors_.end())
      interaction.mate = it->second;
  }

  // Either order of two connectors, as one key.
  static uint64_t connector_pair(fe::ObjectId x, fe::ObjectId y) {
    return static_cast<uint64_t>(std::min(x, y)) << 32 | std::max(x, y);
  }
  // The first mate of each pair of connectors: an interaction finds its mate by one lookup, not by a walk
  // over all mates (quadratic for a 10,000-joint URDF, one range per joint).
  void index_mates_by_connectors() {
    for (size_t m = 0; m < view_.mates.size(); ++m) {
      const fe::Value* mate_list = ev_.value(view_.mates[m].object, "connectors");
      if (!mate_list || mate_list->kind != fe::Value::Kind::Array || mate_list->array().size() != 2) continue;
      mate_by_connectors_.emplace(connector_pair(mate_list->array()[0].object, mate_list->array()[1].object),
                                  static_cast<int>(m));
    }
  }

  void add_signal(fe::ObjectId id, const Role::SignalModel& model) {
    const fe::Object& obj = ev_.graph().at(id);
    const size_t index = view_.signals.size();
    Signal& signal = view_.signals.emplace_back();  // filled in place
    signal.object = id;
    signal.input = model.input;
    signal.path = path_of(id);
    signal.type = obj.type->qualified;
    // The torque converter's own signal models name it `torque_converter`, not `source`; an affine output's
    // `source` is the signal it transforms.
    const SignalSlots::Slots slots = signal_slots_.of(obj);
    const fe::ObjectId source = model.affine_output ? fe::kNoObject : in_.object(id, slots[kSource]);
    signal_sources_.push_back(source != fe::kNoObject ? source : in_.object(id, slots[kTorqueConverter]));
    signal.where = where_of(id);
    signal.enabled = in_.boolean(id, slots[kEnabled]).value_or(signal.enabled);
    std::vector<fe::ObjectId>& parts = composite_parts_.emplace_back();
    for (size_t list : {kTargets, kJointSources, kObjectSources, kSources}) {
      if (!slots[list].present()) continue;
      signal.composite = true;
      for (fe::ObjectId part : in_.objects(id, slots[list])) parts.push_back(part);
    }
    using Composition = Signal::Composition;
    if (model.broadcast) signal.composition = Composition::Broadcast;
    if (model.affine_input || model.affine_output) {
      signal.composite = true;
      signal.composition = Composition::Affine;
      signal.scale = real(id, "scale", 1.0);
      signal.offset = real(id, "offset", 0.0);
      parts = {object(id, signal.input ? "target" : "source")};
    }
    if (slots[kSensors].present()) signal.sensors = in_.objects(id, slots[kSensors]).size();
    if (model.imu) {
      signal.imu = true;
      // A sensor without an attachment of its own sits where the IMU is attached.
      const fe::ObjectId imu = object(id, "source");
      const fe::ObjectId imu_attachment =
          imu == fe::kNoObject ? fe::kNoObject : object(imu, "mate_connector_attachment");
      for (fe::ObjectId field : in_.objects(id, "fields")) {
        Signal::SensorField f;
        f.axis = static_cast<int>(real(field, "field", 1.0)) - 1;
        const fe::ObjectId sensor = object(field, "sensor");
        if (sensor != fe::kNoObject) {
          const fe::Object& logic = ev_.graph().at(sensor);
          using Kind = Signal::SensorField::Kind;
          f.kind = is(logic, accelerometer_)  ? Kind::Accelerometer
                   : is(logic, gyroscope_)    ? Kind::Gyroscope
                   : is(logic, magnetometer_) ? Kind::Magnetometer
                                              : Kind::Unknown;
          f.sensor_path = path_of(sensor);
          const fe::ObjectId own = object(sensor, "mate_connector_attachment");
          sensor_attachments_.emplace_back(index, signal.sensor_fields.size(),
                                           own != fe::kNoObject ? own : imu_attachment);
        }
        signal.sensor_fields.push_back(std::move(f));
      }
    }
  }

  // Materials by index, shared by geometries and contact models (the same material, the same index).
  int material_index(fe::ObjectId id) {
    if (id == fe::kNoObject) return -1;
    auto [it, fresh] = material_of_.try_emplace(id, static_cast<int>(view_.materials.size()));
    if (fresh) {
      const double density = in_.real(id, "density", 1000.0);
      in_.require(std::isfinite(density) && density >= 0, id, "density", density,
                  "a density is a finite number of kg/m^3, 0 or more");
      view_.materials.push_back({id, density, where_of(id)});
    }
    return it->second;
  }

  // Geometries' materials: a contact material by index, a visual one as its visual material.
  void resolve_materials() {
    std::unordered_map<fe::ObjectId, int> visual;
    for (size_t k = 0; k < view_.visual_materials.size(); ++k)
      visual[view_.visual_materials[k].object] = static_cast<int>(k);
    for (size_t k = 0; k < view_.geometries.size(); ++k) {
      Geometry& g = view_.geometries[k];
      g.material = material_index(geometry_materials_[k]);
      if (auto it = visual.find(geometry_materials_[k]); it != visual.end()) g.visual_material = it->second;
    }
  }

  // A Simulation.CollisionGroup's lists as nodes and geometries of this system.
  CollisionGroup collision_group(fe::ObjectId group) {
    CollisionGroup out;
    if (group == fe::kNoObject) return out;
    for (fe::ObjectId body : in_.objects(group, "bodies"))
      if (auto it = node_of_.find(body); it != node_of_.end()) out.bodies.push_back(it->second);
    for (fe::ObjectId system : in_.objects(group, "systems"))
      if (auto it = node_of_.find(system); it != node_of_.end()) out.systems.push_back(it->second);
    const std::vector<fe::ObjectId> listed = in_.objects(group, "geometries");
    for (size_t k = 0; k < view_.geometries.size(); ++k) {
      if (std::find(listed.begin(), listed.end(), view_.geometries[k].object) != listed.end())
        out.geometries.push_back(static_cast<int>(k));
    }
    return out;
  }

  // IMU fields' and lidars' connectors by index.
  void resolve_sensor_attachments() {
    if (sensor_attachments_.empty() && view_.lidars.empty()) return;  // no index to build
    std::unordered_map<fe::ObjectId, int> index;
    for (size_t k = 0; k < view_.connectors.size(); ++k)
      index[view_.connectors[k].object] = static_cast<int>(k);
    for (const auto& [signal, field, connector] : sensor_attachments_) {
      auto it = index.find(connector);
      view_.signals[signal].sensor_fields[field].connector = it == index.end() ? -1 : it->second;
    }
    for (Lidar& lidar : view_.lidars) {
      auto it = index.find(lidar.attachment);
      lidar.connector = it == index.end() ? -1 : it->second;
    }
  }

  // A composite's parts are signals of the tree, found by object.
  void resolve_composites() {
    if (std::all_of(composite_parts_.begin(), composite_parts_.end(),
                    [](const std::vector<fe::ObjectId>& parts) { return parts.empty(); }))
      return;  // no index to build
    std::unordered_map<fe::ObjectId, int> index;
    for (size_t k = 0; k < view_.signals.size(); ++k) index[view_.signals[k].object] = static_cast<int>(k);
    for (size_t k = 0; k < view_.signals.size(); ++k) {
      for (fe::ObjectId part : composite_parts_[k]) {
        auto it = index.find(part);
        view_.signals[k].parts.push_back(it == index.end() ? -1 : it->second);
      }
    }
  }

  // What a signal's source is: the first of interaction, mate, body, shaft and connector it is.
  void resolve_source(Signal& signal, fe::ObjectId source) {
    if (source == fe::kNoObject) return;
    if (sources_.empty()) build_source_index();
    auto it = sources_.find(source);
    if (it != sources_.end()) {
      signal.source_kind = it->second.first;
      signal.source = it->second.second;
      return;
    }
    signal.source_kind = SignalSource::Other;
    signal.source_path = path_of(source);
  }
  void build_source_index() {
    sources_.reserve(view_.connectors.size() + view_.shafts.size() + view_.couplings.size() +
                     view_.nodes.size() + view_.mates.size() + view_.interactions.size() +
                     view_.lidars.size());  // no rehashing
    // Inserted in reverse priority, so an object that were two things would keep the first kind.
    auto add = [&](SignalSource kind, const auto& items, auto accept) {
      for (size_t k = 0; k < items.size(); ++k)
        if (accept(items[k])) sources_[items[k].object] = {kind, static_cast<int>(k)};
    };
    auto all = [](const auto&) { return true; };
    add(SignalSource::Connector, view_.connectors, all);
    add(SignalSource::Shaft, view_.shafts, all);
    add(SignalSource::Coupling, view_.couplings, all);
    add(SignalSource::Body, view_.nodes, [](const FrameNode& n) { return n.kind == FrameNode::Kind::Body; });
    add(SignalSource::Mate, view_.mates, all);
    add(SignalSource::Interaction, view_.interactions, all);
    add(SignalSource::Lidar, view_.lidars, all);
  }

  // source_of, with what lies above an owner found once (a body's signals and connectors share it).
  fe::SourceRange where_of(fe::ObjectId id) {
    return source_with(ev_.graph(), id, [&](fe::ObjectId owner) {
      if (auto it = declared_above_.find(owner); it != declared_above_.end()) return it->second;
      bool settled;
      const std::optional<fe::SourceRange> above = declared_above(ev_.graph(), owner, settled);
      if (settled) declared_above_.emplace(owner, above);
      return above;
    });
  }

  // ObjectGraph::path, built on the owner's path when that is kept (a body's signals and connectors share
  // it).
  std::string path_of(fe::ObjectId id) {
    const fe::Object& obj = ev_.graph().at(id);
    const std::string* owner = obj.owner == fe::kNoObject ? nullptr : owner_path(obj.owner);
    return owner ? joined_path(*owner, obj.name) : ev_.graph().path(id);
  }

  // rooted_path, the last owner's remembered: siblings (a body's signals) are visited in a row.
  const std::string* owner_path(fe::ObjectId owner) {
    if (owner == last_owner_ && last_owner_path_) return last_owner_path_;
    const std::string* path = rooted_path(owner);
    if (path) std::tie(last_owner_, last_owner_path_) = std::pair(owner, path);  // kept paths never move
    return path;
  }

  // The path of the root or of an object below it, kept: an owned object keeps its owner and name, so its
  // path never changes. Null under a free object (a value the evaluator may yet adopt).
  const std::string* rooted_path(fe::ObjectId id) {
    if (auto it = rooted_paths_.find(id); it != rooted_paths_.end()) return &it->second;
    const fe::Object& obj = ev_.graph().at(id);
    if (obj.owner == fe::kNoObject) {
      if (id != ev_.graph().root) return nullptr;
      return &rooted_paths_.emplace(id, ev_.graph().path(id)).first->second;
    }
    const std::string* owner = rooted_path(obj.owner);
    if (!owner) return nullptr;
    return &rooted_paths_.emplace(id, joined_path(*owner, obj.name)).first->second;
  }

  // ObjectGraph::path's rule: the owner's path, a dot and the name; no dot after an empty path (the root's).
  static std::string joined_path(const std::string& owner, const std::string& name) {
    std::string path;
    path.reserve(owner.size() + 1 + name.size());
    if (!owner.empty()) (path += owner) += '.';
    path += name;
    return path;
  }

  // ConvexMesh/TriMesh vertices (Math.Vec3 instances) and TriMesh triangle indices.
  void read_mesh_data(fe::ObjectId id, Geometry& g) {
    if (const fe::Value* v = ev_.value(id, "vertices"); v && v->kind == fe::Value::Kind::Array) {
      for (const fe::Value& item : v->array()) {
        if (item.kind != fe::Value::Kind::Object) continue;
        Eigen::Vector3d p;
        const char* axes[] = {"x", "y", "z"};
        for (int i = 0; i < 3; ++i) {
          const fe::Value* c = ev_.value(item.object, axes[i]);
          p[i] = c && c->is_number() ? c->as_real() : 0.0;
        }
        g.vertices.push_back(p);
      }
    }
    if (const fe::Value* v = ev_.value(id, "indices"); v && v->kind == fe::Value::Kind::Array) {
      for (const fe::Value& item : v->array()) {
        if (item.kind == fe::Value::Kind::Int) g.indices.push_back(static_cast<int>(item.int_value));
      }
    }
  }

  Eigen::Vector3d vec3(fe::ObjectId object, std::string_view name) { return in_.vec3(object, name); }

  Transform affine(fe::ObjectId transform) {
    const auto [position, rotation] = transform_slots_.of(ev_.graph().at(transform));
    Transform t;
    t.position = in_.vec3(transform, position);
    if (!t.position.allFinite()) {
      if (const fe::ObjectId p = in_.object(transform, position); p != fe::kNoObject)
        in_.require_finite_components(p, "a position is finite");
    }
    if (const fe::ObjectId q = in_.object(transform, rotation); q != fe::kNoObject) {
      const auto [x, y, z, w] = in_.xyzw(q);
      const double norm = std::sqrt(x * x + y * y + z * z + w * w);
      if (!std::isfinite(norm)) {
        in_.require_finite_components(q, "a rotation quaternion is finite");
      } else if (!(norm > 1e-12)) {
        // No rotation at all rather than the identity: taking one for the other would be silently wrong.
        in_.require(false, transform, "rotation", norm,
                    "a rotation quaternion has a length (it is normalised); {0, 0, 0, 0} is none, and the "
                    "identity is {0, 0, 0, 1}");
      }
      t.rotation = natives::quat_normal(natives::quat_from_xyzw(x, y, z, w));
    }
    return t;
  }

  // A transform attribute; one still to become its type's own default is read once per type
  // (AttributeReader::pending_default), so no instance is built for it.
  template <typename Attribute>
  std::optional<Transform> transform_of(fe::ObjectId holder, const Attribute& attribute) {
    const fe::ModelInfo* shared = in_.pending_default(holder, attribute);
    if (shared) {
      if (auto it = default_transforms_.find(shared); it != default_transforms_.end()) return it->second;
    }
    const fe::ObjectId transform = in_.object(holder, attribute);
    if (transform == fe::kNoObject) return std::nullopt;
    const Transform t = affine(transform);
    if (shared) default_transforms_.emplace(shared, t);
    return t;
  }

  // A tensor MuJoCo can hold: finite, principal moments 0 or positive and each at most the sum of the other
  // two (MuJoCo's own test, which it would otherwise fail at load, unlocated). A zero tensor means
  // "computed".
  void check_inertia_tensor(fe::ObjectId inertia, const Eigen::Matrix3d& tensor) {
    if (!tensor.allFinite()) {
      in_.require(false, inertia, "tensor", tensor.maxCoeff(), "an inertia tensor is finite");
      return;
    }
    if (tensor.isZero()) return;
    const Eigen::Matrix3d symmetric = (tensor + tensor.transpose()) / 2;
    const Eigen::Vector3d moments = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(symmetric).eigenvalues();
    const double largest = moments.cwiseAbs().maxCoeff(), slack = 1e-12 * largest;
    if (in_.require(moments.minCoeff() >= -slack, inertia, "tensor", moments.minCoeff(),
                    "its principal moments must be 0 or positive (the smallest is shown)"))
      in_.require(moments[0] + moments[1] + slack >= moments[2], inertia, "tensor", moments[2],
                  "its largest principal moment (shown) exceeds the sum of the other two, which no body has");
  }

  // An Inertia's tensor (Math.Matrix3x3), read once per type when it is a pending default.
  std::optional<Eigen::Matrix3d> inertia_tensor(fe::ObjectId inertia) {
    const std::string_view name = "tensor";
    const fe::ModelInfo* shared = in_.pending_default(inertia, name);
    if (shared) {
      if (auto it = default_tensors_.find(shared); it != default_tensors_.end()) return it->second;
    }
    const fe::ObjectId tensor = object(inertia, name);
    if (tensor == fe::kNoObject) return std::nullopt;
    const SlotTable<9>::Slots e = tensor_slots_.of(ev_.graph().at(tensor));
    Eigen::Matrix3d m;
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) m(r, c) = in_.real(tensor, e[3 * r + c]);
    }
    if (shared) default_tensors_.emplace(shared, m);
    return m;
  }

  // The local transform slot of a system (`local_transform`) or body (`kinematics.local_transform`).
  bool read_transform(fe::ObjectId id, Transform& out) {
    fe::ObjectId holder = id;
    if (ev_.graph().at(id).type->is_subtype_of(body_)) {
      const fe::Value* kinematics = ev_.value(id, "kinematics");
      if (!kinematics || kinematics->kind != fe::Value::Kind::Object) return false;
      holder = kinematics->object;
    }
    const AttributeSlot slot = local_transform_slot_.of(ev_.graph().at(holder))[0];
    const std::optional<Transform> transform = transform_of(holder, slot);
    if (!transform) return false;
    out = *transform;
    return ev_.graph().at(holder).slots[slot.index].explicit_value;
  }

  int add_node(fe::ObjectId id, int parent, bool is_root) {
    FrameNode node;
    node.kind =
        ev_.graph().at(id).type->is_subtype_of(system_) ? FrameNode::Kind::System : FrameNode::Kind::Body;
    node.object = id;
    node.parent = parent;
    node.path = path_of(id);
    node.defined = read_transform(id, node.local) || is_root;  // the root frame never moves
    node.where = where_of(id);
    if (node.kind == FrameNode::Kind::Body) read_body(id, node.body);
    const int index = static_cast<int>(view_.nodes.size());
    if (is_root) view_.root = index;
    node_of_[id] = index;
    view_.nodes.push_back(std::move(node));
    view_.order.emplace_back(true, index);
    // A system's reference body is forced first when SNAP has to choose.
    if (view_.nodes[index].kind == FrameNode::Kind::System) {
      const fe::Value* ref = ev_.value(id, "reference_body");
      if (ref && ref->kind == fe::Value::Kind::Object) reference_bodies_.push_back(ref->object);
    }
    for (fe::ObjectId ref : reference_bodies_) {
      if (ref == id) view_.nodes[index].reference = true;
    }
    return index;
  }

  void add_connector(fe::ObjectId id, int owner, bool in_tree = true) {
    Connector c;
    c.object = id;
    c.owner = owner;
    c.path = path_of(id);
    const fe::ModelInfo* type = ev_.graph().at(id).type;
    c.adaptive = (adaptive_ && type->is_subtype_of(adaptive_)) ||
                 (adaptive_trait_ && type->is_subtype_of(adaptive_trait_));
    c.where = where_of(id);
    c.local = connector_frame(id, c.where);
    if (in_tree) {
      if (const fe::ObjectId parent = object(id, "redirected_parent"); parent != fe::kNoObject)
        redirects_.emplace_back(static_cast<int>(view_.connectors.size()), parent);
    }
    connector_of_[id] = static_cast<int>(view_.connectors.size());
    if (in_tree) view_.order.emplace_back(false, static_cast<int>(view_.connectors.size()));
    view_.connectors.push_back(std::move(c));
  }

  Transform connector_frame(fe::ObjectId id, fe::SourceRange where) {
    const Eigen::Vector3d position = vec3(id, "position");
    const Eigen::Vector3d main_axis = vec3(id, "main_axis");
    const Eigen::Vector3d normal = vec3(id, "normal");
    if (!(position.allFinite() && main_axis.allFinite() && normal.allFinite())) {
      for (const char* name : {"position", "main_axis", "normal"}) {
        if (const fe::ObjectId v = object(id, name); v != fe::kNoObject)
          in_.require_finite_components(v, "a connector's position and axes are finite");
      }
      return Transform{};
    }
    std::optional<Transform> frame = natives::affine_from_axes(main_axis, normal, position);
    if (!frame) {
      sink_.report(fe::DiagCode::InvalidConnector, where,
                   "mate connector " + path_of(id) +
                       " has no frame: main_axis must be non-zero and normal must not be parallel to it");
      return Transform{position, Eigen::Quaterniond::Identity()};
    }
    return *frame;
  }

  void add_mate(fe::ObjectId id) {
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
      in_.require(std::isfinite(out), id, name, out,
                  "a mate's initial angle, position or distance is finite");
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
    view_.mates.push_back(std::move(mate));
  }

  // A redirected connector (RedirectedMateConnector, 0.31's ConnectorProperties.Redirected) is written in its
  // owner's frame and attached to `redirected_parent`. A parent below the owner through declared transforms
  // takes it here (a wheel's rim at the wheel's origin); any other body of the model (a vehicle's chassis
  // that SNAP places, a sibling system's body) takes it after assembly, keeping the world frame the
  // connector was assembled at (spec/snap.md 2.2: W(parent)⁻¹ ∘ W(owner) ∘ M). Until then it is on its
  // owner, as written: SNAP places the parts it joins from there.
  void resolve_redirects() {
    for (const auto& [k, body] : redirects_) {
      Connector& c = view_.connectors[k];
      auto it = node_of_.find(body);
      if (it == node_of_.end()) {
        sink_.report(fe::DiagCode::MjcfUnmapped, c.where,
                     "`" + c.path + ".redirected_parent` is not a body of this model (" + path_of(body) +
                         "); the connector stays on its owner");
        continue;
      }
      if (it->second == c.owner) continue;
      Transform chain;  // the body's frame in the owner's
      bool below = false, declared = true;
      for (int n = it->second; n != kWorld; n = view_.nodes[n].parent) {
        if (n == c.owner) {
          below = true;
          break;
        }
        declared = declared && view_.nodes[n].defined;
        chain = natives::affine_compose(view_.nodes[n].local, chain);
      }
      if (!below || !declared) {
        c.redirect_to = it->second;
        continue;
      }
      c.owner = it->second;
      c.local = natives::affine_compose(natives::affine_inverse(chain), c.local);
    }
  }

  void resolve_tracks() {
    if (!track_system_) return;
    for (const FrameNode& n : view_.nodes) {
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
      view_.tracks.push_back(std::move(t));
    }
  }

  void resolve_elastic_wheels() {
    if (!elastic_wheel_) return;
    for (const FrameNode& n : view_.nodes) {
      if (n.kind != FrameNode::Kind::System || !ev_.graph().at(n.object).type->is_subtype_of(elastic_wheel_))
        continue;
      const int m = mate_index(object(n.object, "tire_mate"));
      if (m >= 0) read_elastic_wheel(in_, n.object, view_.mates[m]);
    }
  }

  // Connectors are references to objects anywhere in the tree (or to the World singleton).
  void resolve_connectors(Mate& mate) {
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
        view_.connectors.back().path = obj.type->qualified;
        mate.connectors[side] = connector_of_[item.object];
        continue;
      }
      sink_.report(fe::DiagCode::InvalidMate, mate.where,
                   "connector " + path_of(item.object) + " of mate " + mate.path +
                       " belongs to no system or body of this model");
    }
  }

  fe::Evaluator& ev_;
  AttributeReader in_;
  fe::DiagnosticSink& sink_;
  ResolvedSystem view_;
  // Attributes read on every instance of a model, found once per layout (AttributeReader has Math.Vec3's
  // and Math.Quat's): a Math.AffineTransform's, a Math.Matrix3x3's, the transform of a system or of a
  // body's kinematics, and a signal's (an Input's or Output's, composites' and sources' included).
  SlotTable<2> transform_slots_{{"position", "rotation"}};
  SlotTable<9> tensor_slots_{{"e00", "e01", "e02", "e10", "e11", "e12", "e20", "e21", "e22"}};
  SlotTable<1> local_transform_slot_{{"local_transform"}};
  // Values of attributes that are their type's own default, by type (transform_of, inertia_tensor).
  std::unordered_map<const fe::ModelInfo*, Transform> default_transforms_;
  std::unordered_map<const fe::ModelInfo*, bool> default_holds_parts_;  // by pure default type (holds_parts)
  std::unordered_map<const fe::ModelInfo*, Eigen::Matrix3d> default_tensors_;
  enum SignalAttribute : size_t {
    kSource,
    kTorqueConverter,
    kEnabled,
    kTargets,
    kJointSources,
    kObjectSources,
    kSources,
    kSensors
  };
  using SignalSlots = SlotTable<8>;
  SignalSlots signal_slots_{{"source", "torque_converter", "enabled", "targets", "joint_sources",
                             "object_sources", "sources", "sensors"}};
  std::vector<fe::ObjectId> geometry_materials_;                      // per geometry: its `material`
  std::vector<std::vector<fe::ObjectId>> composite_parts_;            // per signal: a composite's parts
  std::vector<fe::ObjectId> signal_sources_;                          // per signal: its `source`
  std::vector<std::pair<fe::ObjectId, fe::ObjectId>> filter_groups_;  // per collision filter
  std::unordered_map<fe::ObjectId, int> material_of_;
  std::unordered_map<fe::ObjectId, std::pair<SignalSource, int>> sources_;
  fe::ModelInfo* system_ = nullptr;
  fe::ModelInfo* body_ = nullptr;
  fe::ModelInfo* connector_ = nullptr;
  fe::ModelInfo* adaptive_ = nullptr;
  fe::ModelInfo* adaptive_trait_ = nullptr;  // 0.30's ConnectorProperties.Adaptive
  fe::ModelInfo* mate_ = nullptr;
  fe::ModelInfo* suspension_mate_ = nullptr;       // Vehicles SingleMate suspension joint
  fe::ModelInfo* lidar_ = nullptr;                 // Sensors.LidarLogic
  fe::ModelInfo* terrain_ = nullptr;               // Terrain.Terrain
  fe::ModelInfo* elastic_wheel_ = nullptr;         // Vehicles.Wheels.ElasticWheel
  fe::ModelInfo* track_system_ = nullptr;          // Vehicles.TrackSystem.Base
  fe::ModelInfo* track_links_ = nullptr;           // Vehicles.TrackSystem.Components.Tracks.Base
  fe::ModelInfo* steering_trait_ = nullptr;        // Vehicles.Suspensions.Properties.Steering
  fe::ModelInfo* steering_interaction_ = nullptr;  // Vehicles kinematic steering interaction
  fe::ModelInfo* rigid_body_ = nullptr;
  fe::ModelInfo* contact_geometry_ = nullptr;
  fe::ModelInfo* visual_geometry_ = nullptr;
  fe::ModelInfo* interaction1d_ = nullptr;
  fe::ModelInfo* input_ = nullptr;
  fe::ModelInfo* output_ = nullptr;
  fe::ModelInfo* contact_model_ = nullptr;
  fe::ModelInfo* visual_material_ = nullptr;
  std::vector<fe::ModelInfo*> unsupported_;
  std::vector<std::pair<fe::ModelInfo*, MateType>> mate_kinds_;
  std::vector<std::pair<fe::ModelInfo*, Geometry::Shape>> shapes_;
  std::vector<std::pair<fe::ModelInfo*, Interaction1D::Kind>> kinds1d_;
  std::unordered_map<const fe::ModelInfo*, Role> roles_;
  std::map<std::pair<uint32_t, uint32_t>, bool> holds_parts_;
  fe::ModelInfo* shaft_ = nullptr;
  fe::ModelInfo* torque_motor1d_ = nullptr;
  fe::ModelInfo* clutch_ = nullptr;
  fe::ModelInfo* brake_ = nullptr;
  fe::ModelInfo* gearbox_ = nullptr;
  fe::ModelInfo* converter_ = nullptr;
  fe::ModelInfo* mean_value_engine_ = nullptr;
  fe::ModelInfo* empirical_engine_ = nullptr;
  fe::ModelInfo* broadcast_ = nullptr;
  fe::ModelInfo* imu_output_ = nullptr;
  fe::ModelInfo* accelerometer_ = nullptr;
  fe::ModelInfo* gyroscope_ = nullptr;
  fe::ModelInfo* magnetometer_ = nullptr;
  // IMU fields' sensors: (signal, field, the sensor's connector object), resolved to connector indices.
  std::vector<std::tuple<size_t, size_t, fe::ObjectId>> sensor_attachments_;
  fe::ModelInfo* affine_input_ = nullptr;
  fe::ModelInfo* affine_output_ = nullptr;
  fe::ModelInfo* gear_ = nullptr;
  fe::ModelInfo* differential_ = nullptr;
  fe::ModelInfo* drive_actuator_ = nullptr;
  fe::ModelInfo* motor1d_ = nullptr;
  fe::ModelInfo* mimic_ = nullptr;
  fe::ModelInfo* joint_properties_ = nullptr;
  fe::ModelInfo* package_path_ = nullptr;
  fe::ModelInfo* collision_filter_ = nullptr;
  std::map<std::string, std::string> packages_;
  std::unordered_map<fe::ObjectId, int>
      mate_of_;  // see mate_index  // Urdf.PackagePath: package name -> folder
  std::unordered_map<fe::ObjectId, int> node_of_;
  std::vector<std::pair<int, fe::ObjectId>> redirects_;  // connector index, its redirected_parent
  std::unordered_map<fe::ObjectId, int> connector_of_;
  std::unordered_map<uint64_t, int> mate_by_connectors_;  // see index_mates_by_connectors
  std::vector<fe::ObjectId> reference_bodies_;
  fe::ObjectId last_owner_ = fe::kNoObject;  // see owner_path
  const std::string* last_owner_path_ = nullptr;
  std::unordered_map<fe::ObjectId, std::string> rooted_paths_;                       // see rooted_path
  std::unordered_map<fe::ObjectId, std::optional<fe::SourceRange>> declared_above_;  // see where_of
};

}  // namespace

frontend::SourceRange source_of(const frontend::ObjectGraph& graph, frontend::ObjectId id) {
  bool settled;
  return source_with(graph, id, [&](fe::ObjectId owner) { return declared_above(graph, owner, settled); });
}

ResolvedSystem resolve_system(frontend::Evaluator& evaluator, frontend::ObjectId root,
                              frontend::DiagnosticSink& sink) {
  evaluator.track_reads(true);  // what the builder reads is what the pipeline honours
  ResolvedSystem system;
  // Reading evaluates what the evaluator left for later: on its stack, as evaluation always runs.
  frontend::run_with_large_stack([&] { system = SystemBuilder(evaluator, sink).build(root); });
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
