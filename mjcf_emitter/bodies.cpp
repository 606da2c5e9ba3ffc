// Lowering pass, bodies: <body> with its pose, <inertial> and <geom>s, world geoms, mocap and free bodies.
#include "mjcf_emitter/lowering.h"

#include <cmath>

#include "frontend/urdf/mujoco_principal_inertia.h"

namespace openplx::mjcf {

using natives::affine_compose;
using natives::affine_inverse;

namespace {
// MJCF's fullinertia: the moments, then the products (xy, xz, yz).
std::string full_inertia(const Eigen::Matrix3d& i) {
  return numbers({i(0, 0), i(1, 1), i(2, 2), i(0, 1), i(0, 2), i(1, 2)});
}
}  // namespace

std::string Lowering::geom_class(const char* kind) const {
  return options_.prefix + kind;
}

// Whether the body (or, for geometries of the world and of systems, the world) holds a visual geometry.
bool Lowering::has_visuals(int owner) {
  if (visual_owners_.empty()) {
    visual_owners_.insert(-2);  // computed
    for (const sn::Geometry& g : system_.geometries)
      if (g.visual) visual_owners_.insert(is_body(g.owner) ? g.owner : sn::kWorld);
  }
  return visual_owners_.count(is_body(owner) ? owner : sn::kWorld) > 0;
}

// The geom classes: visual geoms shown and without contacts, collision geoms hidden (group 3).
void Lowering::emit_geom_classes(Element& root) {
  Element& defaults = root.add("default");
  defaults.add("default")
      .set("class", geom_class("visual"))
      .add("geom")
      .set("group", 2)
      .set("contype", 0)
      .set("conaffinity", 0)
      .set("density", 0);  // never mass, also where MuJoCo's compiler sums the geoms (static bodies)
  defaults.add("default").set("class", geom_class("collision")).add("geom").set("group", 3);
}

void Lowering::emit_world_geoms(Element& world) {
  for (const sn::Geometry& g : system_.geometries) {
    if (is_body(g.owner)) continue;
    // Geometries of systems are fixed in the world at the system's pose.
    const sn::Transform frame = g.owner >= 0 ? snap_.node_world[g.owner] : sn::Transform{};
    emit_geom(world, g, affine_compose(frame, g.local), true);
  }
}

void Lowering::emit_bodies(Element& world) {
  // Children lists in declaration order.
  std::map<int, std::vector<int>>& children = tree_children_;
  for (size_t n = 0; n < system_.nodes.size(); ++n) {
    if (is_body(static_cast<int>(n))) children[edges_[n].parent].push_back(static_cast<int>(n));
  }
  struct Item {
    int node;
    Element* parent_element;
    int depth;
  };
  std::vector<Item> stack;
  const auto& roots = children[kWorldVertex];
  for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.push_back({*it, &world, 1});
  while (!stack.empty()) {
    const Item item = stack.back();
    stack.pop_back();
    if (item.depth > kMaxBodyDepth) {
      sink_.report(fe::DiagCode::MjcfTooDeep, system_.nodes[item.node].where,
                   "the body chain reaches " + system_.nodes[item.node].path + " at depth " +
                       std::to_string(item.depth) + "; MuJoCo 2.2.2 reads at most " +
                       std::to_string(kMaxBodyDepth) + " nested bodies");
      continue;
    }
    Element& body = emit_body(*item.parent_element, item.node);
    const auto& kids = children[item.node];
    for (auto it = kids.rbegin(); it != kids.rend(); ++it) stack.push_back({*it, &body, item.depth + 1});
  }
}

Element& Lowering::emit_body(Element& parent, int node) {
  const sn::FrameNode& n = system_.nodes[node];
  const int parent_node = edges_[node].parent;
  const sn::Transform parent_world = parent_node >= 0 ? snap_.node_world[parent_node] : sn::Transform{};
  const sn::Transform local = affine_compose(affine_inverse(parent_world), snap_.node_world[node]);
  Element& body = parent.add("body");
  body.set("name", name(n.path)).set("pos", local.position).set_quat("quat", local.rotation);
  body_element_[node] = &body;
  if (is_static(node)) {  // kinematic: the runtime moves it by its velocity inputs
    body.set("mocap", "true");
    mocap_.insert(node);
  }
  if (edges_[node].mate >= 0) child_of_mate_[edges_[node].mate] = node;
  if (free_roots_.count(node)) body.add("freejoint").set("name", name(n.path));
  if (edges_[node].mate >= 0) emit_joints(body, node, edges_[node].mate);
  emit_inertial(body, node);
  const bool moving = !n.body.initial_linear_velocity.isZero() || !n.body.initial_angular_velocity.isZero();
  if (moving && free_roots_.count(node)) {
    initial_velocities_.push_back(node);       // written as the "initial" keyframe (emit_initial_state)
  } else if (moving && !mocap_.count(node)) {  // a kinematic body's drives its velocity inputs (signals.cpp)
    warn(
        n.where,
        "`" + n.path +
            ".kinematics.initial_local_*_velocity`: a body moving through its joints has no initial velocity "
            "of its own in MuJoCo; this body starts at rest");
  }
  for (const sn::Geometry* g : geometries_of(node)) emit_geom(body, *g, g->local, !n.body.dynamic);
  return body;
}

const std::vector<const sn::Geometry*>& Lowering::geometries_of(int node) {
  if (geometries_by_owner_.empty()) {
    for (const sn::Geometry& g : system_.geometries) geometries_by_owner_[g.owner].push_back(&g);
  }
  return geometries_by_owner_[node];
}

double Lowering::density_of(const sn::Geometry& g) {
  return g.material >= 0 ? system_.materials[g.material].density : 1000.0;
}

// Mass properties (docs/mapping.md "Physics3D: bodies and geometries" and docs/urdf.md): the model's tensor
// when given; else from the geometry that counts for mass at its material's density (visual geometry never
// counts), scaled to the given mass. Meshes: MuJoCo computes their volumes in a draft (finish_with_draft),
// exactly, or for a URDF link without <inertial> (the URDF importer's `urdf_mass` marker,
// BodyProperties::urdf_mass) with MuJoCo 2.2.2's default formula, as MuJoCo's own URDF importer does
// (--urdf-exact-mesh-mass: exactly).
void Lowering::emit_inertial(Element& body, int node) {
  const sn::FrameNode& n = system_.nodes[node];
  using UrdfMass = sn::BodyProperties::UrdfMass;
  // A URDF <inertial> of mass 0: massless, as MuJoCo's importer takes it (OpenPLX's 0 would mean "computed").
  const bool massless = n.body.urdf_mass == UrdfMass::AsWritten && !(n.body.mass > 0);
  const int edge = edges_[node].mate;
  const bool welded = edge >= 0 && system_.mates[edge].type == sn::MateType::Lock;
  if (!n.body.dynamic || (massless && welded)) {
    // A static body needs no mass: MuJoCo sums its collision geoms (visual ones have density 0), as its
    // URDF importer does for a root link. A massless link stays massless and keeps the tensor it was given,
    // as MuJoCo's importer keeps it (a mass-0 foot welded to a moving leg still adds its inertia there).
    if (massless)
      write_inertial(body, 0.0, n.body.cm.position, n.body.cm.rotation, n.body.inertia,
                     n.body.tensor_where.file != fe::kNoFile ? n.body.tensor_where : n.where,
                     "`" + (n.path.empty() ? "" : n.path + ".") + "inertia.tensor`");
    return;
  }
  const bool tensor_given = !n.body.inertia.isZero();
  if (n.body.mass > 0 && tensor_given) {
    const Eigen::Matrix3d r = n.body.cm.rotation.toRotationMatrix();
    body_mass_[node] = {n.body.mass, n.body.cm.position, r * n.body.inertia * r.transpose()};
    write_inertial(body, n.body.mass, n.body.cm.position, n.body.cm.rotation, n.body.inertia,
                   n.body.tensor_where.file != fe::kNoFile ? n.body.tensor_where : n.where,
                   "`" + (n.path.empty() ? "" : n.path + ".") + "inertia.tensor`");
    return;
  }
  std::vector<std::pair<const sn::Geometry*, double>> parts;
  bool meshes = false;
  for (const sn::Geometry* g : geometries_of(node)) {
    if (!g->in_mass) continue;
    parts.emplace_back(g, density_of(*g));
    meshes = meshes || !unit_density_properties(*g);
  }
  if (meshes) {
    // The mass goes on the geoms; the draft compile (finish_with_draft) turns it into an explicit inertial.
    // For motor gains below, estimate the body as a sphere of radius 0.1 m.
    mass_on_geoms_[node] = n.body.mass;
    if (n.body.urdf_mass == UrdfMass::Collisions && !options_.urdf_exact_mesh_mass)
      legacy_mesh_mass_.insert(node);
    const double mass = n.body.mass > 0 ? n.body.mass : 1.0;
    body_mass_[node] = {mass, Eigen::Vector3d::Zero(), 0.4 * mass * 0.01 * Eigen::Matrix3d::Identity()};
    return;
  }
  std::optional<MassProperties> p = combine(parts);
  if (!p && n.body.mass <= 0 && welded) {
    return;  // a massless frame welded to its parent (a URDF tool frame): MuJoCo keeps it massless too
  }
  if (!p) {
    // Also a URDF link without <inertial> or collision geometry on a moving joint, which MuJoCo's importer
    // leaves massless and then refuses (widowx): the stand-in lets the robot load.
    const double mass = n.body.mass > 0 ? n.body.mass : 1.0;
    warn(n.where, "`" + n.path +
                      ".inertia` gives no tensor and the body has no geometry to compute one from; " +
                      "used a " + number(mass) + " kg sphere of radius 0.1 m");
    body.add("inertial")
        .set("pos", "0 0 0")
        .set("mass", mass)
        .set("diaginertia", Eigen::Vector3d::Constant(0.4 * mass * 0.01));
    body_mass_[node] = {mass, Eigen::Vector3d::Zero(), 0.4 * mass * 0.01 * Eigen::Matrix3d::Identity()};
    return;
  }
  if (n.body.mass > 0) {  // the model's mass, distributed like the geometry
    p->inertia *= n.body.mass / p->mass;
    p->mass = n.body.mass;
  }
  body_mass_[node] = *p;
  write_inertial(body, p->mass, p->com, Eigen::Quaterniond::Identity(), p->inertia, n.where,
                 "the inertia of `" + n.path + "` computed from its geometry");
}

// MuJoCo 2.2.2 diagonalises a fullinertia itself (mju_eig3), takes it only when the smallest of its moments
// is at least 1e-14, and refuses moments that break A + B >= C exactly. The check runs on the numbers
// MuJoCo will see: fullinertia for a tensor in the body's axes; principal moments and axes from the tensor in
// its own frame where that frame is turned (as MuJoCo's URDF importer diagonalises the <inertia> it reads),
// or where fullinertia would be refused (an ideal rod). Moments MuJoCo would refuse become their mean (its
// balanceinertia), with a warning at the tensor, so the output always loads.
void Lowering::write_inertial(Element& body, double mass, const Eigen::Vector3d& com,
                              const Eigen::Quaterniond& axes, const Eigen::Matrix3d& tensor,
                              fe::SourceRange where, const std::string& what) {
  namespace mi = mujoco_inertia;
  Element& inertial = body.add("inertial").set("pos", com).set("mass", mass);
  const mi::Principal p = mi::principal_moments(tensor);
  const bool turned = !(axes.w() == 1 && axes.x() == 0 && axes.y() == 0 && axes.z() == 0);
  const bool accepted = !mi::negative(p.moments) && mi::triangle(p.moments);
  // Measured on 2.2.2: a fullinertia whose smallest eigenvalue is below 1e-14 (not mjMINVAL) is refused
  // ("inertia must have positive eigenvalues"); principal moments down to mjMINVAL are taken.
  constexpr double kFullInertiaFloor = 1e-14;
  if (!turned && accepted && p.moments[2] >= kFullInertiaFloor) {
    inertial.set("fullinertia", full_inertia(tensor));
    return;
  }
  Eigen::Vector3d moments(p.moments[0], p.moments[1], p.moments[2]);
  if (!accepted) {
    double mean = moments.sum() / 3;
    std::string done = "they were set to their mean " + number(mean) + " (MuJoCo's balanceinertia)";
    if (!(mean > 0)) {
      const double radius = std::cbrt(3 * mass / (4 * M_PI * 1000.0));
      mean = 0.4 * mass * radius * radius;
      done = "they were set to " + number(mean) + ", a solid sphere's of the same mass at water density";
    }
    warn(where,
         what + ": its principal moments " + number(moments[0]) + ", " + number(moments[1]) + ", " +
             number(moments[2]) + ", as MuJoCo 2.2.2 computes them, " +
             (mi::negative(p.moments) ? "are not all positive"
                                      : "break the triangle inequality A + B >= C, which MuJoCo checks "
                                        "exactly and refuses") +
             "; " + done);
    moments.setConstant(mean);
  }
  const Eigen::Quaterniond q =
      (axes * Eigen::Quaterniond(p.axes[0], p.axes[1], p.axes[2], p.axes[3])).normalized();
  if (!(q.w() == 1 && q.x() == 0 && q.y() == 0 && q.z() == 0))
    inertial.set("quat", numbers({q.w(), q.x(), q.y(), q.z()}));
  inertial.set("diaginertia", moments);
}

void Lowering::emit_geom(Element& parent, const sn::Geometry& g, const sn::Transform& pose, bool on_static) {
  using Shape = sn::Geometry::Shape;
  Element geom("geom");
  geom.set("name", name(g.path));
  sn::Transform frame = pose;
  // OpenPLX cylinders and capsules lie along local Y; MuJoCo's along local Z.
  const Eigen::Quaterniond y_to_z(Eigen::AngleAxisd(-M_PI / 2, Eigen::Vector3d::UnitX()));
  const bool primitive = g.shape == Shape::Box || g.shape == Shape::Sphere || g.shape == Shape::Cylinder ||
                         g.shape == Shape::Capsule;
  const double smallest = g.shape == Shape::Box      ? g.size.minCoeff()
                          : g.shape == Shape::Sphere ? g.size.x()
                                                     : std::min(g.size.x(), g.size.y());
  if (primitive && !(smallest > 0)) {
    warn(g.where, "`" + g.path + "` has a zero size; MuJoCo needs positive sizes, so it was left out");
    return;
  }
  switch (g.shape) {
    case Shape::Box:
      geom.set("type", "box").set("size", Eigen::Vector3d(g.size / 2));
      break;
    case Shape::Sphere:
      geom.set("type", "sphere").set("size", g.size.x());
      break;
    case Shape::Cylinder:
    case Shape::Capsule:
      geom.set("type", g.shape == Shape::Cylinder ? "cylinder" : "capsule")
          .set("size", numbers({g.size.x(), g.size.y() / 2}));
      frame.rotation = frame.rotation * y_to_z;
      break;
    case Shape::Plane:
      if (!on_static) {
        warn(g.where, "`" + g.path +
                          "` is a plane on a moving body; MuJoCo 2.2.2 allows planes only on static "
                          "bodies, so it was left out");
        return;
      }
      geom.set("type", "plane").set("size", "0 0 1");
      break;
    case Shape::ExternalMesh: {
      const std::string mesh = mesh_asset(g);
      if (mesh.empty()) return;
      geom.set("type", "mesh").set("mesh", mesh);
      break;
    }
    case Shape::ConvexMesh:
    case Shape::TriMesh: {
      const std::string mesh = vertex_mesh_asset(g);
      if (mesh.empty()) return;
      geom.set("type", "mesh").set("mesh", mesh);
      break;
    }
    default:
      warn(g.where, "`" + g.path + "` is a geometry MuJoCo 2.2.2 has no counterpart for; it was left out");
      return;
  }
  geom.set("pos", frame.position).set_quat("quat", frame.rotation);
  if (g.visual) {
    if (g.visual_material >= 0) geom.set("material", name(system_.visual_materials[g.visual_material].path));
  }
  // MuJoCo's viewers show groups 0-2: visual geoms in 2, collision geoms in 3 where their body has visual
  // ones to show instead (mujoco_menagerie's convention), else in 0.
  if (g.visual) {
    geom.set("class", geom_class("visual"));
  } else {
    geom.set("class", geom_class("collision"));
    if (!has_visuals(g.owner)) geom.set("group", 0);
    if (!g.collides) geom.set("contype", 0).set("conaffinity", 0);
  }
  if (!g.in_mass && mass_on_geoms_.count(g.owner)) geom.set("mass", 0.0);  // the draft sums every geom
  if (auto it = mass_on_geoms_.find(g.owner); it != mass_on_geoms_.end() && g.in_mass && it->second > 0) {
    geom.set("mass", it->second);
    it->second = 0;  // the whole given mass on the first geometry that counts
  } else if (g.in_mass && !on_static) {
    geom.set("density", density_of(g));
  } else if (!g.in_mass && !g.visual && on_static) {
    geom.set("density", 0.0);  // left out of mass (include_in_mass_properties: false)
  }
  emitted_geoms_.insert(g.path);
  parent.add(std::move(geom));
}

}  // namespace openplx::mjcf
