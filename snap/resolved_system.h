// The resolved system: everything later passes need to know about an evaluated OpenPLX model, as typed data
// built once from the ObjectGraph (resolve_system.h) and completed by SNAP (snap.h). The frame tree of
// systems and bodies with their mass properties and initial velocities, geometries with their materials,
// mate connectors, mates with per-DOF flexibility, dissipation and friction as numbers, 1-DOF interactions
// with every parameter, drivetrain parts, signals with their resolved sources, contact models, collision
// groups, gravity, and the assembled world frames. Every item keeps the source range it came from.
//
// The MJCF emitter and the runtime read only this: nothing here refers back to the evaluator. `object` fields
// are the ObjectGraph ids the items came from, kept as plain numbers (identity for the builder and tools).
// Attribute values are stored as the model gives them; policies (defaults that depend on the time step, what
// MuJoCo can express) belong to the emitter.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "frontend/diagnostics/source.h"
#include "frontend/natives/math_rotation.h"

namespace openplx::snap {

using Transform = natives::Affine;  // rotate, then translate; compose(lhs, rhs) applies rhs first
using ObjectRef = std::uint32_t;    // an ObjectGraph id (frontend::ObjectId)
inline constexpr ObjectRef kNoObjectRef = UINT32_MAX;

inline constexpr int kWorld = -1;  // the world frame: parent of the root node, owner of World connectors
inline constexpr double kInf = std::numeric_limits<double>::infinity();

// Mass properties of a body, as the model gives them (mass 0 / zero tensor: compute from the geometry).
struct BodyProperties {
  double mass = 0.0;
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();  // about the CM frame's origin, in its axes
  Transform cm;                                       // relative to the body frame
  bool dynamic = true;
  // A URDF link's mass law, from the URDF importer's `urdf_mass` marker (docs/urdf.md): Collisions for a
  // link without <inertial> (MuJoCo's importer: its collision geometry at 1000 kg/m^3, MuJoCo's default mesh
  // volumes), AsWritten for an <inertial> of mass 0 (massless, where OpenPLX's 0 means "computed").
  enum class UrdfMass { None, Collisions, AsWritten };
  UrdfMass urdf_mass = UrdfMass::None;
  frontend::SourceRange tensor_where;  // where the inertia tensor was written (a repair is warned there)
  Eigen::Vector3d initial_linear_velocity = Eigen::Vector3d::Zero();  // in the owning system's frame
  Eigen::Vector3d initial_angular_velocity = Eigen::Vector3d::Zero();
};

struct FrameNode {
  enum class Kind { System, Body };
  Kind kind;
  ObjectRef object;
  int parent = kWorld;     // index into nodes, or kWorld
  std::string path;        // instance path relative to the root ("" for the root)
  Transform local;         // relative to the parent node (SNAP fills the undefined ones)
  bool defined = false;    // the model assigned the transform (or a part of it); SNAP never moves it
  bool reference = false;  // a system's reference_body: forced first when SNAP is stuck
  BodyProperties body;     // Body nodes
  frontend::SourceRange where;
};

// A collision or visual shape attached to a body (or a system).
struct Geometry {
  enum class Shape { Box, Sphere, Cylinder, Capsule, Plane, ConvexMesh, TriMesh, ExternalMesh, Other };
  ObjectRef object;
  Shape shape = Shape::Other;
  bool visual = false;  // a Visuals geometry: drawn, never collides, no mass
  int owner = kWorld;
  std::string path;
  Transform local;  // relative to the owner
  Eigen::Vector3d size =
      Eigen::Vector3d::Zero();  // box: full extents; sphere: (r); cylinder, capsule: (r, h)
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();
  std::string file;                       // external mesh
  std::string package_uri;                // a URDF mesh's `package://` name, resolved into `file`
  std::vector<Eigen::Vector3d> vertices;  // ConvexMesh, TriMesh (in the geometry frame)
  std::vector<int> indices;               // TriMesh: three vertex indices per triangle
  int material = -1;         // index into ResolvedSystem::materials (the `material` attribute), -1: none
  int visual_material = -1;  // its material as an index into ResolvedSystem::visual_materials, -1: none
  bool collides = true;
  bool in_mass = true;
  frontend::SourceRange where;
};

// A material some geometry or contact model names (Physics.Charges/Physics3D material, or a visual one).
struct Material {
  ObjectRef object;
  double density = 1000.0;  // kg/m^3; 1000 when the material gives none
  frontend::SourceRange where;
};

// Where the user wrote a value, and its name there: a value assigned in a declaration that several instances
// share is named by that declaration (`Paint.metallic_map`), the same for all of them (read_parameters.h).
struct WrittenValue {
  std::string name;
  frontend::SourceRange where;
};

// An inline texture map of a visual material (pixels in the model, not an image file).
struct InlineTexture {
  std::string attribute;  // base_color_map, roughness_map, ...
  WrittenValue map;       // the material's assignment of it
};

// A texture map read from an image file (`import @"x.png"`), with its sampling as the model gives it.
struct FileTexture {
  std::string attribute;  // base_color_map, roughness_map, ...
  std::string file;       // absolute path
  double scale_u = 1, scale_v = 1, offset_u = 0, offset_v = 0;
  int wrap_mode = 0, filter_mode = 1;  // Visuals.Textures.WrapMode / FilterMode (Repeat, Linear)
  std::string swizzle;                 // "" when none
  WrittenValue map;                    // the material's assignment of it
  WrittenValue swizzle_at, wrap_at, filter_at, offset_at;  // the texture's own settings
};

// Visuals.Materials.Material.
struct VisualMaterial {
  ObjectRef object;
  std::string path;
  std::optional<Eigen::Vector4d> tint;  // base_color_tint r, g, b, a (a component that is not a number: 1)
  std::optional<double> roughness, metallic;
  bool roughness_written = false, metallic_written = false;  // assigned, not the traits' defaults
  std::optional<double> alpha;                               // Transparency's opacity
  std::vector<InlineTexture> inline_textures;  // maps that carry pixels with a positive width and height
  std::vector<FileTexture> file_textures;      // maps read from image files
  frontend::SourceRange where;
};

// Viscous damping as the model gives it: MechanicalDamping's damping constant, or a relaxation time.
struct Damping {
  bool given = false;  // a dissipation model is present
  std::optional<double> damping_constant;
  std::optional<double> relaxation_time;
};

// Springs, ranges and motors acting on the degree of freedom of a mate's connectors.
struct Interaction1D {
  enum class Kind {
    LinearSpring,
    TorsionSpring,
    LinearRange,
    RotationalRange,
    LinearVelocityMotor,
    RotationalVelocityMotor,
    ForceMotor,
    TorqueMotor,
    DistanceRange,
    DistanceMotor,
    Steering,  // Vehicles kinematic steering: holds two steerable suspensions' angles by its mechanism
    Other
  };
  ObjectRef object;
  Kind kind = Kind::Other;
  std::string path;
  int mate = -1;  // the mate with the same two connectors, -1 when none
  int connectors[2] = {
      -1, -1};     // DistanceRange, DistanceMotor: its connectors (indices into ResolvedSystem::connectors)
  int shaft = -1;  // a drivetrain motor: the shaft it drives
  bool enabled = true;
  double start = 0, end = 0;                     // ranges
  double stiffness = 0;                          // springs: flexibility.stiffness (0: none given)
  double rest = 0;                               // springs: position (linear) or angle (torsion)
  Damping damping;                               // springs: dissipation
  double min_effort = -kInf, max_effort = kInf;  // springs and motors
  std::optional<double> gain;                    // velocity motors
  std::optional<double> target_speed;            // velocity motors
  double default_effort = 0;                     // force/torque motors: default_force / default_torque
  int steered[2] = {-1, -1};                     // Steering: the left and right suspension mates
  std::string mechanism;                         // Steering: "Ackermann", "BellCrank", "RackAndPinion"
  // Steering (AGX's parameters: lengths are fractions of the track): the knuckle arm's angle from the axle
  // (rad) and length (over the track); BellCrank and RackAndPinion: the tie rods' angle to the axle line at
  // rest (rad), the steering arm's length (over the knuckle arm's), the rack's length (over the track,
  // RackAndPinion) and the steering column's rotation per input rotation.
  double knuckle_angle = 0, knuckle_length = 0;
  double tie_rod_angle = 0, column_distance = 0, rack_length = 0, gear = 1;
  // Steering: where the user wrote each geometry attribute it has (a bundle default has no entry).
  std::vector<std::pair<std::string, frontend::SourceRange>> written;
  frontend::SourceRange where;
};

// What an OpenPLX signal's `source` is in this system.
enum class SignalSource { None, Interaction, Mate, Body, Shaft, Connector, Coupling, Lidar, Other };

// An OpenPLX input or output signal of the tree.
struct Signal {
  ObjectRef object;
  bool input = false;
  std::string path;
  std::string_view type;  // its model's name, e.g. "Physics.Signals.AngleOutput", held by the program
  SignalSource source_kind = SignalSource::None;
  int source = -1;  // index into the list of its kind (interactions, mates, nodes, shafts, connectors)
  std::string source_path;  // the source's instance path (Other sources)
  bool enabled = true;
  // Declared in a user's file, not by a bundle model on every instance (RigidBody's velocity inputs): an
  // unmapped input is warned about only then.
  bool user_declared = false;
  // A composite (Robotics.Signals.RobotInput's targets, RobotOutput's joint and object sources, Control's
  // virtual signals): its parts in order, as indices into ResolvedSystem::signals (-1: a part that is no
  // signal of the tree). Vector: one value per part; Broadcast: one value to every part; Affine: one part,
  // scale * value + offset.
  enum class Composition { Vector, Broadcast, Affine };
  bool composite = false;
  Composition composition = Composition::Vector;
  double scale = 1, offset = 0;
  std::vector<int> parts;
  size_t sensors = 0;  // RobotOutput sensors (not mapped)
  // A connector output's `relative_to`: the reference connector (index into connectors), -1 for the world
  // (the default, Physics3D.Interactions.World); `relative_to_path` names what it is when that is neither.
  int relative_to = -1;
  std::string relative_to_path;
  // Force3DOutput / Torque3DOutput `relative_to` (a Math.AffineTransform), when given.
  std::optional<Transform> relative_transform;
  // Sensors.Signals.IMUOutput: per field, an axis (0 x, 1 y, 2 z) of one of the IMU's three-axis sensors.
  struct SensorField {
    enum class Kind { Unknown, Accelerometer, Gyroscope, Magnetometer };
    Kind kind = Kind::Unknown;
    int axis = 0;
    int connector = -1;  // the sensor's mate_connector_attachment, -1 when none
    std::string sensor_path;
    // The sensor's Gaussian signal noise on this axis (its *SignalGaussianNoise distortions added up), and
    // the distortions nothing applies (spectral noise, a gyroscope's linear-acceleration effect).
    double noise_mean = 0, noise_deviation = 0;
    struct Distortion {
      std::string path, type;
      frontend::SourceRange where;
    };
    std::vector<Distortion> unapplied;
  };
  bool imu = false;
  std::vector<SensorField> sensor_fields;
  frontend::SourceRange where;
};

// A Sensors lidar: rangefinder rays from its connector (directions in the connector's frame: z = main_axis,
// x = normal), and the Gaussian distance noise MuJoCo can record.
struct Lidar {
  ObjectRef object;
  std::string path;
  ObjectRef attachment;  // its mate_connector_attachment
  int connector = -1;    // index into ResolvedSystem::connectors, -1 when none
  std::vector<Eigen::Vector3d> rays;
  bool default_pattern = false;  // no ray pattern given: one ray along the normal
  double noise_mean = 0, noise_deviation = 0, noise_slope = 0;
  frontend::SourceRange where;
};

// A Terrain.Terrain: a grid of num_x x num_y heights spaced element_size around its frame's origin, its
// surface at z = 0 of that frame, max_depth deep.
struct Terrain {
  ObjectRef object;
  std::string path;
  int parent = kWorld;  // the enclosing node
  Transform local;      // relative to the parent
  int num_x = 0, num_y = 0;
  double element_size = 0, max_depth = 0;
  frontend::SourceRange where;
};

// A Vehicles.TrackSystem.Base: link_count links of the link description's box, routed around its wheels
// (bodies turning about their center connectors' main axes).
struct TrackSystem {
  ObjectRef object;
  std::string path;
  int link_count = 0;
  double link_width = 0, link_height = 0;
  double link_mass = 0;        // the description's inertia.mass; 0: from density
  double link_density = 1000;  // its contact geometry's (or the tracks') material
  struct Wheel {
    int body = -1;       // node index
    int connector = -1;  // its center connector (connector index)
    double radius = 0;
  };
  std::vector<Wheel> wheels;  // in track_wheels order
  int chassis = -1;           // chassis_body's node: the links do not touch it
  frontend::SourceRange where;
};

struct Connector {
  ObjectRef object;
  int owner = kWorld;  // node index or kWorld
  std::string path;
  Transform local;  // frame relative to the owner: z = main_axis, x = normal (orthogonalised), y = z × x
  bool adaptive = false;
  // A redirected connector's parent whose frame SNAP has to place first: after assembly the connector moves
  // there, keeping its world frame (run_snap). -1: none.
  int redirect_to = -1;
  frontend::SourceRange where;
};

enum class MateType {
  Lock,
  Hinge,
  Prismatic,
  Cylindrical,
  Ball,
  Distance,
  ConstantVelocity,
  Planar,
  Suspension,   // Vehicles SingleMate: travel (with spring and damper), steering when steerable, spin
  ElasticTire,  // Vehicles ElasticWheel's tire_mate: all six directions free, each with its spring and damper
  Other
};

// A mate's stiffness and damping in one of its six directions.
struct DofCompliance {
  double stiffness = 0;  // LinearElastic stiffness (0: none)
  std::optional<double> damping_constant;
  std::optional<double> relaxation_time;
};

// Dry friction of a mate's free degree of freedom.
struct MateFriction {
  std::string type;  // its model's qualified name, "" when none
  double coefficient = 0, normal_force = 0;
};

struct Mate {
  // Directions of flexibility and dissipation, in this order.
  static constexpr const char* kDirections[6] = {"along_main",  "along_normal",  "along_cross",
                                                 "around_main", "around_normal", "around_cross"};
  ObjectRef object;
  MateType type = MateType::Other;
  std::string path;
  int connectors[2] = {-1, -1};  // indices into ResolvedSystem::connectors; -1 when missing
  double initial_angle = 0.0;
  double initial_position = 0.0;  // Distance: initial_distance
  double target_distance = 0.0;   // Distance
  double initial_normal_angle = 0.0;
  double initial_cross_angle = 0.0;
  bool enable_snap = true;
  bool enabled = true;
  bool flexible = false;         // a flexibility model is given
  std::string flexibility_type;  // qualified model names, "" when none
  std::string dissipation_type;
  std::array<DofCompliance, 6> dofs;  // per kDirections
  MateFriction friction, friction_translational, friction_rotational;
  // Suspension: travel along `travel` (connectors[0]'s owner frame; zero: that connector's normal) with a
  // spring and damper, rotation about it when steerable, spin about main_axis.
  bool steerable = false;
  Eigen::Vector3d travel = Eigen::Vector3d::Zero();
  double travel_stiffness = 0, travel_damping = 0;
  frontend::SourceRange where;
};

// Contact properties for a pair of materials (Physics.Interactions.SurfaceContact.Model).
struct ContactModel {
  ObjectRef object;
  std::string path;
  int material1 = -1, material2 = -1;  // indices into ResolvedSystem::materials, -1: none
  bool enabled = true;
  double friction = 1.0;  // its friction model's coefficient (1 when none)
  double normal_restitution = 0, tangential_restitution = 0;
  WrittenValue normal_restitution_at, tangential_restitution_at;
  frontend::SourceRange where;
};

// A model with no MuJoCo counterpart (terrain, shovels, tracked belts, lidars): kept out of the system,
// its mappable neighbours go on without it.
struct Unsupported {
  ObjectRef object;
  std::string path;
  std::string type;
  frontend::SourceRange where;
};

// A rotating 1-D body of a drivetrain (DriveTrain.Shaft, Physics1D rotational bodies).
struct Shaft {
  ObjectRef object;
  std::string path;
  double inertia = 1.0;  // kg m^2
  frontend::SourceRange where;
};

// A table of (x, y) points, x increasing; read by linear interpolation, flat beyond its ends.
using Curve = std::vector<std::pair<double, double>>;

// How drivetrain shafts are tied to each other and to 3-D mates, and what drives them.
struct DriveCoupling {
  enum class Kind { Actuator, Gear, Differential, Clutch, Brake, GearBox, TorqueConverter, Engine };
  Kind kind = Kind::Gear;
  ObjectRef object;
  std::string path;
  // Actuator: {shaft}; Gear, GearBox, Clutch, TorqueConverter: {input, output}; Brake: one or two;
  // Differential: {drive, left, right}; Engine: {shaft}
  std::vector<int> shafts;
  int mate = -1;           // Actuator: the 3-D mate it drives
  double ratio = 1.0;      // Gear: ratio; Differential: gear_ratio
  bool locked_up = false;  // Differential
  frontend::SourceRange where;
  // Clutch, Brake: dry friction of capacity torque_capacity * engagement. Manual ones engage by their
  // fraction; automatic ones ramp between 0 and 1 over their durations when engaged or disengaged.
  double torque_capacity = 0;
  double engagement_fraction = 1;  // initial_engagement_fraction
  bool automatic = false;
  bool initially_engaged = false;  // automatic
  double engagement_duration = 0.1, disengagement_duration = 0.1;
  // Gear (FlexibleGear), GearBox: flexibility.stiffness (inf: rigid) and dissipation.damping_constant;
  // ViscousGear: dissipation.viscosity (inf: rigid).
  double stiffness = kInf, damping = 0, viscosity = kInf;
  double breakaway_torque = -1;  // TorqueLimitedSlipDifferential (-1: an open differential)
  // GearBox: ratios by gear number (forward 1.., reverse -1..); 0 is neutral when it has one.
  std::vector<double> forward_gears, reverse_gears;
  int initial_gear = 0;
  bool has_neutral_gear = true;
  // Engine: full-throttle torque (N m) over speed (rev/min); idle speed its governor holds; throttle
  // before any input; crank inertia added to its shaft.
  Curve torque_curve;
  double idle_rpm = 0, initial_throttle = 0, crank_inertia = 0;
  double min_effort = -kInf, max_effort = kInf;
  // TorqueConverter: over nu = turbine speed / pump speed, the pump's capacity factor and the turbine's
  // torque multiplication; pump torque = factor * oil_density * diameter^5 * pump speed^2.
  Curve geometry_factors, torque_multipliers;
  double oil_density = 0, diameter = 0, lock_up_time = 0;
};

// A joint that follows another (Urdf.Mimic): follower = multiplier * leader + offset.
struct JointCoupling {
  ObjectRef object;
  std::string path;
  int follower = -1, leader = -1;  // mate indices
  double multiplier = 1.0, offset = 0.0;
  frontend::SourceRange where;
};

// What a URDF joint adds to its mate (Urdf.JointProperties): <dynamics> damping and Coulomb friction, and
// the <limit> effort and velocity that bound the motors a user adds (0: none).
struct JointProperties {
  ObjectRef object;
  std::string path;
  int mate = -1;
  double damping = 0, friction = 0, effort = 0, velocity = 0;
  frontend::SourceRange where;
};

// A Simulation.CollisionGroup as indices into the system.
struct CollisionGroup {
  std::vector<int> bodies;      // nodes its `bodies` list names
  std::vector<int> systems;     // nodes its `systems` list names
  std::vector<int> geometries;  // geometries its `geometries` list names
};

// A Simulation.DisableCollisionPair: no contacts between what its two CollisionGroups hold.
struct CollisionFilter {
  ObjectRef object;
  std::string path;
  CollisionGroup group1, group2;
  frontend::SourceRange where;
};

// Simulation.Environment's gravity field of the root.
struct Gravity {
  enum class Kind { Standard, Uniform, NonUniform };
  Kind kind = Kind::Standard;
  Eigen::Vector3d vector{0, 0, -9.81};  // Uniform: the field's vector
};

// SNAP's output: world frames of the assembled system.
struct SnapResult {
  std::vector<Transform> node_world;       // per node
  std::vector<Transform> connector_world;  // per connector
  std::vector<int> placed_by;              // per node: the mate that placed it, -1 if none
  std::vector<bool> forced;                // per node: forced to the identity
};

struct ResolvedSystem {
  std::vector<FrameNode> nodes;  // parents before children, in declaration order
  std::vector<Connector> connectors;
  std::vector<Mate> mates;
  std::vector<Geometry> geometries;
  std::vector<Material> materials;
  std::vector<Interaction1D> interactions;
  std::vector<Signal> signals;
  std::vector<Unsupported> unsupported;
  std::vector<ContactModel> contact_models;
  std::vector<VisualMaterial> visual_materials;  // Visuals.Materials.Material instances, the root included
  std::vector<Shaft> shafts;
  std::vector<DriveCoupling> couplings;
  std::vector<JointCoupling> joint_couplings;
  std::vector<Lidar> lidars;
  std::vector<Terrain> terrains;
  std::vector<TrackSystem> tracks;
  std::vector<JointProperties> joint_properties;
  std::vector<CollisionFilter> collision_filters;
  Gravity gravity;
  int root = kWorld;  // node of the root object, when it is a system or a body
  // Nodes and the tree's own connectors in declaration order (depth first): {is_node, index}.
  std::vector<std::pair<bool, int>> order;
  SnapResult assembly;  // filled by run_snap
};

// The offset a mate's free degrees of freedom take at rest: connectors[1]'s frame relative to
// connectors[0]'s. Hinge: rotation by initial_angle about main_axis (right-handed); Prismatic: translation by
// initial_position along it; Cylindrical: both; Distance: translation by initial_distance; others: none.
Transform joint_offset(const Mate& mate);

std::string mate_type_name(MateType type);

}  // namespace openplx::snap
