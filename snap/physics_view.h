// The physics view of an evaluated model: the frame tree of systems and bodies, mate connectors with their
// frames, and mates with their connectors and initial values. Read from the ObjectGraph by model type
// (Physics3D.System, Physics3D.Bodies.Body, Physics3D.Interactions.MateConnector, ...Mate), so user models
// deriving from the bundle models are recognised. Problems (a normal parallel to its main axis, a mate
// without two connectors) are reported at the user's line.
#pragma once

#include <string>
#include <vector>

#include "frontend/diagnostics.h"
#include "frontend/evaluator.h"
#include "frontend/natives/math_rotation.h"

namespace openplx::snap {

using Transform = natives::Affine;  // rotate, then translate; compose(lhs, rhs) applies rhs first

inline constexpr int kWorld = -1;  // the world frame: parent of the root node, owner of World connectors

// Mass properties of a body, as the model gives them (mass 0 / zero tensor: compute from the geometry).
struct BodyProperties {
  double mass = 0.0;
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();  // about the CM frame's origin, in its axes
  Transform cm;                                       // relative to the body frame
  bool dynamic = true;
  Eigen::Vector3d initial_linear_velocity = Eigen::Vector3d::Zero();  // in the owning system's frame
  Eigen::Vector3d initial_angular_velocity = Eigen::Vector3d::Zero();
};

struct FrameNode {
  enum class Kind { System, Body };
  Kind kind;
  frontend::ObjectId object;
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
  frontend::ObjectId object;
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
  frontend::ObjectId material = frontend::kNoObject;
  bool collides = true;
  bool in_mass = true;
  frontend::SourceRange where;
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
    Other
  };
  frontend::ObjectId object;
  Kind kind = Kind::Other;
  std::string path;
  int mate = -1;   // the mate with the same two connectors, -1 when none
  int shaft = -1;  // a drivetrain motor: the shaft it drives
  frontend::SourceRange where;
};

// An OpenPLX input or output signal of the tree.
struct Signal {
  frontend::ObjectId object;
  bool input = false;
  std::string path;
  std::string type;  // its model, e.g. "Physics.Signals.AngleOutput"
  frontend::ObjectId source = frontend::kNoObject;
  bool enabled = true;
  frontend::SourceRange where;
};

struct Connector {
  frontend::ObjectId object;
  int owner = kWorld;  // node index or kWorld
  std::string path;
  Transform local;  // frame relative to the owner: z = main_axis, x = normal (orthogonalised), y = z × x
  bool adaptive = false;
  frontend::SourceRange where;
};

enum class MateType { Lock, Hinge, Prismatic, Cylindrical, Ball, Distance, ConstantVelocity, Other };

struct Mate {
  frontend::ObjectId object;
  MateType type = MateType::Other;
  std::string path;
  int connectors[2] = {-1, -1};  // indices into PhysicsView::connectors; -1 when missing
  double initial_angle = 0.0;
  double initial_position = 0.0;
  double initial_normal_angle = 0.0;
  double initial_cross_angle = 0.0;
  bool enable_snap = true;
  frontend::SourceRange where;
};

// Contact properties for a pair of materials (Physics.Interactions.SurfaceContact.Model).
struct ContactModel {
  frontend::ObjectId object;
  std::string path;
  frontend::ObjectId material1 = frontend::kNoObject;
  frontend::ObjectId material2 = frontend::kNoObject;
  frontend::SourceRange where;
};

// A model with no MuJoCo counterpart (terrain, shovels, tracked belts, lidars): kept out of the view,
// its mappable neighbours go on without it.
struct Unsupported {
  frontend::ObjectId object;
  std::string path;
  std::string type;
  frontend::SourceRange where;
};

// A rotating 1-D body of a drivetrain (DriveTrain.Shaft, Physics1D rotational bodies).
struct Shaft {
  frontend::ObjectId object;
  std::string path;
  double inertia = 1.0;  // kg m^2
  frontend::SourceRange where;
};

// How drivetrain shafts are tied to each other and to 3-D mates.
struct DriveCoupling {
  enum class Kind { Actuator, Gear, Differential };
  Kind kind = Kind::Gear;
  frontend::ObjectId object;
  std::string path;
  std::vector<int> shafts;  // Actuator: {shaft}; Gear: {input, output}; Differential: {drive, left, right}
  int mate = -1;            // Actuator: the 3-D mate it drives
  double ratio = 1.0;       // Gear: ratio; Differential: gear_ratio
  frontend::SourceRange where;
};

// A joint that follows another (Urdf.Mimic): follower = multiplier * leader + offset.
struct JointCoupling {
  frontend::ObjectId object;
  std::string path;
  int follower = -1, leader = -1;  // mate indices
  double multiplier = 1.0, offset = 0.0;
  frontend::SourceRange where;
};

// What a URDF joint adds to its mate (Urdf.JointProperties): <dynamics> damping and Coulomb friction, and
// the <limit> effort and velocity that bound the motors a user adds (0: none).
struct JointProperties {
  frontend::ObjectId object;
  std::string path;
  int mate = -1;
  double damping = 0, friction = 0, effort = 0, velocity = 0;
  frontend::SourceRange where;
};

// A Simulation.DisableCollisionPair: no contacts between what its two CollisionGroups hold.
struct CollisionFilter {
  frontend::ObjectId object;
  std::string path;
  frontend::ObjectId group1 = frontend::kNoObject, group2 = frontend::kNoObject;
  frontend::SourceRange where;
};

struct PhysicsView {
  std::vector<FrameNode> nodes;  // parents before children, in declaration order
  std::vector<Connector> connectors;
  std::vector<Mate> mates;
  std::vector<Geometry> geometries;
  std::vector<Interaction1D> interactions;
  std::vector<Signal> signals;
  std::vector<Unsupported> unsupported;
  std::vector<ContactModel> contact_models;
  std::vector<frontend::ObjectId>
      visual_materials;  // Visuals.Materials.Material instances, the root included
  std::vector<Shaft> shafts;
  std::vector<DriveCoupling> couplings;
  std::vector<JointCoupling> joint_couplings;
  std::vector<JointProperties> joint_properties;
  std::vector<CollisionFilter> collision_filters;
  int root = kWorld;  // node of the root object, when it is a system or a body
  // Nodes and the tree's own connectors in declaration order (depth first): {is_node, index}.
  std::vector<std::pair<bool, int>> order;
};

// Where an instance was declared: its attribute's line in the owner, or its model's declaration for roots.
frontend::SourceRange source_of(const frontend::ObjectGraph& graph, frontend::ObjectId id);

// Builds the view of the tree under `root`. Requires the graph to be fully evaluated.
PhysicsView build_physics_view(frontend::Evaluator& evaluator, frontend::ObjectId root,
                               frontend::DiagnosticSink& sink);

// The offset a mate's free degrees of freedom take at rest: connectors[1]'s frame relative to
// connectors[0]'s. Hinge: rotation by initial_angle about main_axis (right-handed); Prismatic: translation by
// initial_position along it; Cylindrical: both; others: none.
Transform joint_offset(const Mate& mate);

std::string mate_type_name(MateType type);

}  // namespace openplx::snap
