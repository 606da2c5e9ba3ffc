// The MJCF emitter's shared state, internal to mjcf_emitter/: one Lowering object runs the passes in order
// (run, in emitter.cpp). Most files hold one pass for one MJCF concern; some are entered from several
// passes (equalities.cpp: README.md says which). Later passes read what earlier ones recorded (the tree, the
// elements of bodies and joints, the actuators). Inputs are only the resolved system, the options and the
// diagnostic sink. See mjcf_emitter/README.md for which file writes which element.
#pragma once

#include <algorithm>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include "mjcf_emitter/draft_model.h"
#include "mjcf_emitter/emitter.h"
#include "mjcf_emitter/mass_properties.h"
#include "mjcf_emitter/soft_constraints.h"

namespace openplx::mjcf {

namespace fe = openplx::frontend;
namespace sn = openplx::snap;

inline constexpr int kWorldVertex = -1;
inline constexpr double kNoEffortLimit = 1e10;  // an effort range's stand-in for "no limit"
// AGX's constraint damping when a model gives none: a SPOOK relaxation time of 2/60 s, the value AGX's native
// constraints start with (two steps at AGX's default 60 Hz, whatever the time step).
inline constexpr double kDefaultRelaxationTime = 2.0 / 60.0;
inline constexpr double kRigidImpedance = 0.9999;  // the largest solimp MuJoCo accepts: rigid constraints

struct TreeEdge {
  int mate = -1;              // -1: a free joint or a static body
  int parent = kWorldVertex;  // node index of the parent body, or the world
};

class Lowering {
 public:
  Lowering(const sn::ResolvedSystem& system, const EmitOptions& options, fe::DiagnosticSink& sink)
      : system_(system), snap_(system.assembly), options_(options), sink_(sink) {}

  Emitted run();

 private:
  // ------------------------------------------------------------------------------------------ helpers
  std::string name(const std::string& path) const {
    return options_.prefix + (path.empty() ? options_.model_name : path);
  }
  bool is_body(int node) const { return node >= 0 && system_.nodes[node].kind == sn::FrameNode::Kind::Body; }
  bool is_static(int node) const { return is_body(node) && !system_.nodes[node].body.dynamic; }
  // The graph vertex a connector hangs on: its body, or the world for system connectors and World.
  int vertex_of_connector(int connector) const {
    const int owner = system_.connectors[connector].owner;
    return is_body(owner) ? owner : kWorldVertex;
  }
  void warn(fe::SourceRange where, const std::string& message) {
    sink_.report(fe::DiagCode::MjcfUnmapped, where, message);
  }
  // Calls f(joint) for every named <joint> of the body tree below <worldbody>, walked without recursion (a
  // chain may be as deep as MuJoCo reads).
  template <typename F>
  static void for_each_joint(Element& root, F&& f) {
    std::vector<Element*> pending{root.child("worldbody")};
    while (!pending.empty() && pending.back()) {
      Element* e = pending.back();
      pending.pop_back();
      for (const auto& child : e->children()) {
        if (child->name() == "body") pending.push_back(child.get());
        if (child->name() == "joint" && child->get("name")) f(*child);
      }
    }
  }
  static void drop_empty(Element& root, std::string_view section) {
    auto& kids = root.children();
    kids.erase(std::remove_if(kids.begin(), kids.end(),
                              [&](const std::unique_ptr<Element>& e) {
                                return e->name() == section && e->children().empty();
                              }),
               kids.end());
  }
  // The index of an element of `items` held by reference.
  template <typename T>
  static int index_in(const std::vector<T>& items, const T& item) {
    return static_cast<int>(&item - items.data());
  }
  // Bindings are filled in place (bind_signals): a binding moved costs as much as one made.
  static void unmapped(SignalBinding& b, std::string reason) {
    b.quantity = Quantity::None;
    // Reasons quote paths; the root model's own path is empty (a bundle file converted on its own).
    for (size_t at; (at = reason.find("``")) != std::string::npos;) reason.replace(at, 2, "the root model");
    b.reason = std::move(reason);
  }
  static void mapped(SignalBinding& b, Quantity quantity, MjObject object, std::string element) {
    b.quantity = quantity;
    b.object = object;
    b.names.clear();
    b.names.push_back(std::move(element));  // moved: a braced list would copy it
  }
  // Text joined with one allocation (a reason for each of thousands of signals).
  static std::string concat(std::initializer_list<std::string_view> parts) {
    size_t size = 0;
    for (std::string_view part : parts) size += part.size();
    std::string text;
    text.reserve(size);
    for (std::string_view part : parts) text += part;
    return text;
  }
  static bool any_of(std::string_view stem, std::initializer_list<std::string_view> stems) {
    for (std::string_view s : stems) {  // a loop the compiler unrolls, where std::find is a call
      if (s == stem) return true;
    }
    return false;
  }

  // ------------------------------------------------------------------------- emitter.cpp
  Eigen::Vector3d gravity();

  // ------------------------------------------------------------------------------ tree_choice.cpp
  static int edge_cost(const sn::Mate& mate, bool carries_interactions);
  bool joint_mapped(const sn::Mate& mate) const;
  void choose_tree();

  // ----------------------------------------------------------------------------------- bodies.cpp
  std::string geom_class(const char* kind) const;
  bool has_visuals(int owner);
  void emit_geom_classes(Element& root);
  void emit_world_geoms(Element& world);
  void emit_bodies(Element& world);
  Element& emit_body(Element& parent, int node);
  const std::vector<const sn::Geometry*>& geometries_of(int node);
  double density_of(const sn::Geometry& g);
  void emit_inertial(Element& body, int node);
  // <inertial> with `tensor` (about `com`, in axes turned by `axes` from the body's), written as MuJoCo 2.2.2
  // will read it and repaired where its compiler would refuse it (bodies.cpp).
  void write_inertial(Element& body, double mass, const Eigen::Vector3d& com, const Eigen::Quaterniond& axes,
                      const Eigen::Matrix3d& tensor, fe::SourceRange where, const std::string& what);
  void emit_geom(Element& parent, const sn::Geometry& g, const sn::Transform& pose, bool on_static);

  // ----------------------------------------------------------------------------------- joints.cpp
  void emit_joints(Element& body, int node, int m);
  bool travel_held_rigid(const sn::Mate& mate, int node);
  bool too_stiff_for_step(double stiffness, double inertia) const;
  void warn_mate_softness(const sn::Mate& mate, bool loop);
  void apply_friction(Element& joint, const sn::Mate& mate, const sn::MateFriction& friction,
                      const char* attribute);
  Element* joint_for(int mate, bool rotational);
  void apply_joint_properties(std::map<Element*, double>& dampings);

  // ------------------------------------------------------------------------------- equalities.cpp
  void emit_loop_closures(Element& root);
  void emit_distance_mates(Element& root);
  std::optional<MateCompliance> compliance(const sn::Mate& mate);
  void finish_with_draft(Element& root);
  void enforce_moving_body_inertia();  // moving_body_inertia.cpp: MuJoCo's mjMINVAL rule, last
  void size_contact_buffers(Element& root, int extra_contacts, int extra_rows);  // contact_buffers.cpp
  void finish_velocity_stand_ins(Element& root);                                 // velocity_motors.cpp
  void finish_servo_gains(const DraftModel& draft);                              // velocity_motors.cpp
  void collect_rigid_rows(Element& root);                                        // rigid_rows.cpp
  void emit_compliant_dofs(Element& root);                                       // compliant_dofs.cpp
  void stiffen_equalities(Element& root);
  std::string rigid_solref() const;
  static std::string rigid_solimp();
  void emit_joint_couplings(Element& root);

  // ----------------------------------------------------------------------------------- assets.cpp
  void emit_visual_materials();
  void emit_texture(Element& material, const sn::VisualMaterial& m, const sn::FileTexture& t);
  std::string vertex_mesh_asset(const sn::Geometry& g);
  std::string mesh_asset(const sn::Geometry& g);
  std::string converted_mesh_asset(const sn::Geometry& g);
  void note_collada_up_axis(const sn::Geometry& g, const std::string& up);
  void mesh_left_out(const sn::Geometry& g, fe::DiagCode code, const std::string& message);

  // --------------------------------------------------------------------------------- keyframe.cpp
  void emit_initial_state(Element& root);
  std::vector<double> initial_qvel();
  static std::string joined(const std::vector<double>& values);

  // --------------------------------------------------------------------------------- contacts.cpp
  void emit_contact_pairs(Element& root);
  void emit_collision_filters(Element& root);
  void exclude_initial_overlaps(Element& root);
  std::set<std::string> group_bodies(const sn::CollisionGroup& group, std::vector<std::string>& widened);
  std::string mujoco_body(int n);

  // -------------------------------------------------------------------------------- actuators.cpp
  void emit_actuators(Element& root);
  void emit_distance_interaction(Element& root, Element& actuators, const sn::Interaction1D& i);
  void emit_steering(Element& root, const sn::Interaction1D& i);  // steering.cpp
  void emit_lidars();                                             // lidar.cpp
  void emit_terrains();                                           // terrain.cpp
  void emit_tracks(Element& root);                                // tracks.cpp
  void bind_lidar(SignalBinding& b, int lidar);
  void emit_effort_motor(Element& actuators, const sn::Interaction1D& i, const std::string& joint);
  // springs.cpp
  void emit_spring(Element& root, Element& actuators, const sn::Interaction1D& i, Element& joint,
                   std::map<Element*, double>& dampings);
  double spring_damping(const sn::Interaction1D& i, double k);
  double spring_relaxation_time(const sn::Interaction1D& i, double k);
  double effective_inertia(Element& joint);
  std::pair<double, double> effort_range(const sn::Interaction1D& i);
  void effort_limits(Element& actuator, const sn::Interaction1D& i);
  void speed_limit(Element& actuator, const sn::Interaction1D& i);

  // ------------------------------------------------------------------------- velocity_motors.cpp
  void emit_velocity_motor(Element& root, const sn::Interaction1D& i, const std::string& joint,
                           double inertia);
  bool has_range_input(int interaction) const;

  // ------------------------------------------------------------------------------- drivetrain.cpp
  void emit_drivetrain(Element& root);
  void fold_rigid_shafts();
  Element* actuator_joint(const sn::DriveCoupling& c);
  bool joins_one_joint(const sn::DriveCoupling& c) const;
  void emit_shaft_motor(Element& root, const sn::Interaction1D& i);
  void emit_friction_coupling(Element& equality, Element& tendons, const sn::DriveCoupling& c);
  double drivetrain_inertia(int start);

  // ------------------------------------------------------------------------------ drive_parts.cpp
  Element& gear_equality(Element& equality, const sn::DriveCoupling& c, double ratio);
  void emit_gear(Element& equality, Element& tendons, const sn::DriveCoupling& c);
  void emit_gearbox(Element& equality, const sn::DriveCoupling& c);
  void emit_differential(Element& equality, Element& tendons, const sn::DriveCoupling& c);
  void emit_torque_converter(Element& equality, Element& tendons, const sn::DriveCoupling& c);
  void emit_engine(const sn::DriveCoupling& c);
  void emit_drive_actuators(Element& actuators);

  // ---------------------------------------------------------------------------------- signals.cpp
  void bind_signals(Element& root, std::vector<SignalBinding>& out);
  void bind(const sn::Signal& s, SignalBinding& b);
  void bind_imu(const sn::Signal& s, SignalBinding& b);
  void add_imu_noise(const sn::Signal& s, SignalBinding& b);
  void bind_composite(const sn::Signal& s, const std::vector<SignalBinding>& parts, SignalBinding& b);
  void bind_interaction(SignalBinding& b, std::string_view stem, int k);
  void bind_enabled(SignalBinding& b, int k);
  void bind_coupling(SignalBinding& b, std::string_view stem, int k);
  bool bind_drive_part(SignalBinding& b, std::string_view stem, int k);
  bool bind_shaft(SignalBinding& b, std::string_view stem, int shaft);
  void bind_mate(SignalBinding& b, std::string_view stem, const sn::Signal& s);
  void bind_body(SignalBinding& b, std::string_view stem, int n);
  void bind_body_torque(SignalBinding& b, int n, std::string body);
  void bind_connector(SignalBinding& b, std::string_view stem, const sn::Signal& s);
  std::string site_for(int c);
  std::pair<Element*, sn::Transform> connector_mount(int c);
  void add_sensor(SignalBinding& b);

  // -------------------------------------------------------------------------------------------- state
  struct Adjacent {
    int mate;
    int a;
    int b;
    int cost;
  };

  const sn::ResolvedSystem& system_;
  const sn::SnapResult& snap_;
  const EmitOptions& options_;
  fe::DiagnosticSink& sink_;
  std::vector<Adjacent> adjacency_;
  std::vector<TreeEdge> edges_;
  std::vector<bool> in_tree_;
  std::set<int> tree_mates_;
  std::set<int> free_roots_;
  std::vector<int> initial_velocities_;  // free bodies that start moving
  std::map<int, Element*> body_element_;
  std::map<int, std::vector<Element*>> joint_of_mate_;
  std::map<int, double> mass_on_geoms_;
  // Mesh bodies whose mass properties take MuJoCo 2.2.2's default (legacy) mesh volumes: URDF links without
  // <inertial>, as MuJoCo's URDF importer computes them. The others take exact volumes.
  std::set<int> legacy_mesh_mass_;
  struct JointInfo {
    int node;
    Eigen::Vector3d pos;   // in the child body frame
    Eigen::Vector3d axis;  // unit, in the child body frame
    bool rotational;
  };
  std::map<Element*, JointInfo> joint_info_;
  std::map<int, MassProperties> body_mass_;
  std::map<int, std::vector<int>> tree_children_;
  std::map<int, std::string> velocity_motors_;  // motor interaction -> its tendon (and stand-in) name
  struct VelocityStandIn {
    Element* drive;     // the <general> stand-in
    std::string joint;  // its joint's MuJoCo name
    double inertia;     // what it drives about its axis at the initial pose
    size_t law;         // its law in laws_
  };
  std::vector<VelocityStandIn> stand_ins_;
  bool stand_in_servos_ = false;  // servos (the model has equalities), else dampers
  struct CompliantDof {
    std::string joint;
    double stiffness, relaxation_time, inertia;  // inertia: the mass or moment it moves (0: unknown)
    std::string path;                            // the mate
    fe::SourceRange where;                       // its line
  };
  std::vector<CompliantDof> compliant_dofs_;                // emit_compliant_dofs holds them
  std::set<std::string> compliant_equalities_;              // their equalities' names (not rigid rows)
  std::map<int, std::pair<double, double>> effort_ranges_;  // motor or spring -> its effort range enabled
  std::map<int, std::string> friction_couplings_;           // clutch or brake coupling -> its tendon
  std::map<int, std::string> gear_equalities_;              // gear or gearbox -> its joint equality
  std::set<int> gearboxes_;                                 // gearbox couplings
  std::map<int, std::string> tendon_gears_;                 // flexible or viscous gear -> its tendon
  std::map<int, std::string> differential_locks_;           // differential -> its lock-up equality
  std::map<int, std::string> converters_;                   // torque converter -> its base name
  std::map<int, std::string> engines_;                      // engine -> its actuator
  struct DriveActuator {
    Element element;
    double ctrl;  // initial control
  };
  std::vector<DriveActuator> drive_actuators_;      // waiting for the <actuator> section
  std::vector<std::pair<int, double>> drive_ctrl_;  // their actuator indices and initial controls
  std::vector<RuntimeLaw> laws_;
  std::map<int, const sn::JointProperties*> joint_properties_;  // mate -> its URDF joint properties
  std::set<std::string> emitted_geoms_;
  std::set<int> visual_owners_;  // bodies (and kWorld) with visual geometries; -2 once computed
  std::unordered_map<int, std::vector<const sn::Geometry*>> geometries_by_owner_;
  std::map<int, std::pair<int, double>> actuator_ctrl_;  // motor interaction -> actuator index, initial ctrl
  size_t actuator_count_ = 0;
  Element* assets_ = nullptr;
  // Mesh files read with assimp (assets.cpp), by path: the mesh, or why there is none.
  struct ReadMesh {
    std::shared_ptr<const TriangleMesh> mesh;
    std::string problem;
  };
  std::map<std::string, ReadMesh> read_meshes_;
  std::map<std::string, std::string> untouched_mesh_problems_;  // files MuJoCo reads itself -> why not, or ""
  std::map<std::string, std::string> converted_assets_;         // file and scale -> its <mesh> asset
  std::vector<ConvertedMesh> converted_meshes_;                 // handed to Emitted
  Element* size_ = nullptr;  // <size>, filled in or dropped once tracks are made (contact_buffers.cpp)
  struct DriveEdge {
    int from;        // shaft
    int to;          // shaft, -1 for an actuator
    double factor;   // speed of `to` per unit speed of `from`
    Element* joint;  // an actuator's 3-D joint
  };
  std::vector<DriveEdge> drive_edges_;
  std::vector<PendingSoftEquality> soft_equalities_;
  std::vector<std::string> shaft_joints_;  // per shaft: its MuJoCo joint (folded: the joint of its group)
  std::vector<double> shaft_offsets_;      // per shaft: that joint's qpos0 (the shaft starts at 0)
  std::vector<int> shaft_group_;           // per shaft: the first shaft of its rigid 1:1 group
  std::map<int, Element*> group_joint_;    // rigid group -> the 3-D joint it is folded into
  Element* world_ = nullptr;
  Element* sensors_ = nullptr;
  std::set<int> mocap_;
  std::set<int> sites_;                                         // connectors that have a site
  std::map<int, int> child_of_mate_;                            // tree mate -> the body whose joint it is
  std::map<int, std::vector<std::string>> equalities_of_mate_;  // loop mate -> its equality names
  std::map<int, std::string> springs_;                          // spring interaction -> its actuator
  std::map<int, std::string> range_joints_;                     // by interaction
  std::map<std::string, int> ranges_on_joint_;                  // how many of those each joint has
  std::set<std::string> imu_distortions_said_;                  // IMU distortions warned about
  std::set<std::string> imu_sensors_;                           // MuJoCo sensors made for IMU fields
  SignalClasses signal_classes_;                                // keyed by the system's type names
  std::map<int, std::string> distance_tendons_;                 // DistanceRange/Motor -> its tendon
  std::map<int, std::string> distance_mates_;                   // Distance mate -> its tendon and equality
  struct SteeringElements {
    std::string angle_equality;            // holds the left wheel's steering angle (the input)
    std::string left_joint;                // the left wheel's steering hinge (the output)
    double fit_error = 0;                  // rad: the linkage's quartic fit, over the steering range
    std::vector<double> input_polynomial;  // the left wheel's angle for the input (empty: the input itself)
    double low = 0, high = 0;              // rad: the inputs the linkage reaches (the input is clamped there)
  };
  std::map<int, SteeringElements> steering_;               // Steering interaction -> its MuJoCo elements
  std::map<int, std::vector<std::string>> lidar_sensors_;  // lidar -> its rangefinders, ray order
};

}  // namespace openplx::mjcf
