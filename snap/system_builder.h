// The builder behind resolve_system (resolve_system.h): one walk over the evaluated tree that reads every
// attribute the resolved system maps. One class, its member functions defined by job in the
// snap/resolve_*.cpp files and snap/object_paths.cpp; private to the snap library.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <tuple>
#include <unordered_map>
#include <utility>
#include <vector>

#include "frontend/diagnostics/diagnostics.h"
#include "frontend/evaluation/evaluator.h"
#include "snap/attribute_reader.h"
#include "snap/resolved_system.h"

namespace openplx::snap::detail {

namespace fe = openplx::frontend;

class SystemBuilder {
 public:
  SystemBuilder(fe::Evaluator& evaluator, fe::DiagnosticSink& sink);

  ResolvedSystem build(fe::ObjectId root);

 private:
  // What a model is to the system, decided once per model (a large tree has few models and many objects).
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

  // The walk over the tree, and what each model is to the system. (resolve_system.cpp)
  template <typename Stack>
  void visit(fe::ObjectId id, int enclosing, Stack& stack, bool is_root);
  bool holds_parts(fe::ObjectId id, uint32_t k);
  bool subtree_has_roles(fe::ObjectId id);
  Role role_of(const fe::ModelInfo* type);

  // Systems, bodies and connectors: the frames SNAP places. (resolve_frames.cpp)
  void read_body(fe::ObjectId id, BodyProperties& body);
  void apply_kinematic_control();
  Transform affine(fe::ObjectId transform);
  void check_inertia_tensor(fe::ObjectId inertia, const Eigen::Matrix3d& tensor);
  std::optional<Eigen::Matrix3d> inertia_tensor(fe::ObjectId inertia);
  bool read_transform(fe::ObjectId id, Transform& out);
  int add_node(fe::ObjectId id, int parent, bool is_root);
  void add_connector(fe::ObjectId id, int owner, bool in_tree = true);
  Transform connector_frame(fe::ObjectId id, fe::SourceRange where);
  void resolve_redirects();

  // Geometries, their meshes and materials, collision groups. (resolve_geometries.cpp)
  void add_geometry(fe::ObjectId id, int owner);
  void read_mesh_data(fe::ObjectId id, Geometry& g);
  void resolve_packages();
  int material_index(fe::ObjectId id);
  void resolve_materials();
  CollisionGroup collision_group(fe::ObjectId group);

  // Mates, 1-D interactions, the drivetrain, tracks and elastic wheels. (resolve_interactions.cpp)
  void add_interaction(fe::ObjectId id);
  int mate_index(fe::ObjectId object);
  void resolve_drivetrain();
  void attach(Interaction1D& interaction);
  void index_mates_by_connectors();
  void add_mate(fe::ObjectId id);
  void resolve_connectors(Mate& mate);
  void resolve_elastic_wheels();
  void resolve_tracks();

  // Signals, their sources, composites and sensor attachments. (resolve_signals.cpp)
  void add_signal(fe::ObjectId id, const Role::SignalModel& model);
  void resolve_sensor_attachments();
  void resolve_signal_references();
  void read_sensor_noise(fe::ObjectId sensor, Signal::SensorField& f);
  void read_relative_to(fe::ObjectId id, size_t index);
  void resolve_composites();
  void resolve_source(Signal& signal, fe::ObjectId source);
  void build_source_index();

  // Paths and source locations of objects. (object_paths.cpp)
  fe::SourceRange where_of(fe::ObjectId id);
  std::string path_of(fe::ObjectId id);
  const std::string* owner_path(fe::ObjectId owner);
  const std::string* rooted_path(fe::ObjectId id);
  static std::string joined_path(const std::string& owner, const std::string& name);

  // Shared by every job.
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

  // Either order of two connectors, as one key.
  static uint64_t connector_pair(fe::ObjectId x, fe::ObjectId y) {
    return static_cast<uint64_t>(std::min(x, y)) << 32 | std::max(x, y);
  }

  Eigen::Vector3d vec3(fe::ObjectId object, std::string_view name) { return in_.vec3(object, name); }

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

  fe::Evaluator& ev_;
  AttributeReader in_;
  fe::DiagnosticSink& sink_;
  ResolvedSystem system_;
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
  fe::ModelInfo* system_model_ = nullptr;
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
  std::vector<std::pair<size_t, fe::ObjectId>> signal_references_;  // (signal, its relative_to connector)
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

}  // namespace openplx::snap::detail
