#include "mjcf_emitter/emitter.h"

#include <algorithm>
#include <filesystem>
#include <map>
#include <queue>
#include <set>
#include <unordered_map>

#include "frontend/quoted.h"
#include "mjcf_emitter/mass_properties.h"
#include "mjcf_emitter/soft_constraints.h"

namespace openplx::mjcf {
namespace {

namespace fe = openplx::frontend;
namespace sn = openplx::snap;
using mjcf::MjObject;
using mjcf::Quantity;
using natives::affine_compose;
using natives::affine_inverse;

constexpr int kWorldVertex = -1;

struct TreeEdge {
  int mate = -1;              // -1: a free joint or a static body
  int parent = kWorldVertex;  // node index of the parent body, or the world
};

class Emitter {
 public:
  Emitter(const sn::PhysicsView& view, const sn::SnapResult& snap, fe::Evaluator& ev,
          const EmitOptions& options, fe::DiagnosticSink& sink)
      : view_(view), snap_(snap), ev_(ev), options_(options), sink_(sink) {}

  Emitted run() {
    Emitted out;
    Element& root = out.document;
    root.set("model", options_.model_name);
    root.add("compiler")
        .set("angle", "radian")
        .set("autolimits", "true")
        .set("inertiafromgeom", "auto")
        .set("inertiagrouprange", "0 2")
        .set("exactmeshinertia", "true")
        .set("balanceinertia", "false")
        .set("fusestatic", "false")
        .set("discardvisual", "false");
    root.add("option")
        .set("timestep", options_.timestep)
        .set("gravity", gravity())
        .set("integrator", "Euler");
    for (const sn::Unsupported& u : view_.unsupported) {
      warn(u.where, "`" + u.path + "` is a " + u.type +
                        ", which has no MuJoCo 2.2.2 counterpart; it and its parts "
                        "were left out");
    }
    choose_tree();
    assets_ = &root.add("asset");
    emit_visual_materials();
    Element& world = root.add("worldbody");
    world_ = &world;
    emit_world_geoms(world);
    emit_bodies(world);
    emit_loop_closures(root);
    emit_drivetrain(root);
    emit_joint_couplings(root);
    emit_contact_pairs(root);
    emit_collision_filters(root);
    emit_actuators(root);
    emit_initial_velocities(root);
    bind_signals(root, out.signals);
    if (assets_->children().empty()) drop_empty(root, "asset");
    for (const char* section : {"tendon", "equality", "contact", "actuator", "sensor"})
      drop_empty(root, section);
    out.manifest_json = manifest_json(options_.model_name, out.signals);
    soften_equalities(root);
    return out;
  }

 private:
  // ------------------------------------------------------------------------------------------- the tree

  std::string name(const std::string& path) const {
    return options_.prefix + (path.empty() ? options_.model_name : path);
  }
  bool is_body(int node) const { return node >= 0 && view_.nodes[node].kind == sn::FrameNode::Kind::Body; }
  bool is_static(int node) const { return is_body(node) && !view_.nodes[node].body.dynamic; }
  // The graph vertex a connector hangs on: its body, or the world for system connectors and World.
  int vertex_of_connector(int connector) const {
    const int owner = view_.connectors[connector].owner;
    return is_body(owner) ? owner : kWorldVertex;
  }

  static int edge_cost(const sn::Mate& mate, bool carries_interactions) {
    if (carries_interactions) return 0;
    switch (mate.type) {
      case sn::MateType::Hinge:
      case sn::MateType::Prismatic:
      case sn::MateType::Cylindrical:
        return 1;
      case sn::MateType::Lock:
        return 2;
      case sn::MateType::Ball:
        return 3;
      default:
        return 4;
    }
  }

  bool joint_mapped(const sn::Mate& mate) const {
    switch (mate.type) {
      case sn::MateType::Hinge:
      case sn::MateType::Prismatic:
      case sn::MateType::Cylindrical:
      case sn::MateType::Ball:
      case sn::MateType::Lock:
        return true;
      default:
        return false;
    }
  }

  // Prim's algorithm from the world (and static bodies) over the mates, cheapest edge first; components the
  // world does not reach get a free joint at their first declared body.
  void choose_tree() {
    edges_.assign(view_.nodes.size(), TreeEdge{});
    in_tree_.assign(view_.nodes.size(), false);
    std::vector<bool> has_interactions(view_.mates.size(), false);
    for (const sn::Interaction1D& i : view_.interactions) {
      if (i.mate >= 0) has_interactions[i.mate] = true;
    }
    for (const sn::Signal& signal : view_.signals) {  // a read mate needs a joint to read
      if (signal.input || !signal.enabled) continue;
      const int m = mate_of(signal.source);
      if (m >= 0) has_interactions[m] = true;
    }
    for (size_t m = 0; m < view_.mates.size(); ++m) {
      const sn::Mate& mate = view_.mates[m];
      if (mate.connectors[0] < 0 || mate.connectors[1] < 0) continue;
      if (!joint_mapped(mate)) {
        warn(mate.where, "`" + mate.path + "` is a " + sn::mate_type_name(mate.type) +
                             " mate, which has no MuJoCo 2.2.2 joint here; it was left out");
        continue;
      }
      const int a = vertex_of_connector(mate.connectors[0]);
      const int b = vertex_of_connector(mate.connectors[1]);
      if (a == b) {
        warn(mate.where, "`" + mate.path + "` joins two connectors of " +
                             (a >= 0 ? "the same body `" + view_.nodes[a].path + "`" : "the world") +
                             "; there is nothing for MuJoCo to constrain, so it was left out");
        continue;
      }
      adjacency_.push_back({static_cast<int>(m), a, b, edge_cost(mate, has_interactions[m])});
    }
    using Item =
        std::tuple<int, int, int>;  // cost, mate index (declaration order breaks ties), adjacency index
    std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
    std::unordered_map<int, std::vector<int>> incident;  // vertex -> adjacency indices
    for (size_t k = 0; k < adjacency_.size(); ++k) {
      incident[adjacency_[k].a].push_back(static_cast<int>(k));
      incident[adjacency_[k].b].push_back(static_cast<int>(k));
    }
    auto reach = [&](int vertex) {
      for (int k : incident[vertex]) queue.emplace(adjacency_[k].cost, adjacency_[k].mate, k);
    };
    auto grow = [&]() {
      while (!queue.empty()) {
        const auto [cost, mate, k] = queue.top();
        queue.pop();
        const auto& e = adjacency_[k];
        const bool a_in = e.a == kWorldVertex || in_tree_[e.a];
        const bool b_in = e.b == kWorldVertex || in_tree_[e.b];
        if (a_in && b_in) continue;
        const int child = a_in ? e.b : e.a;
        if (is_static(child)) continue;  // static bodies are roots of their own
        in_tree_[child] = true;
        edges_[child] = {e.mate, a_in ? e.a : e.b};
        tree_mates_.insert(e.mate);
        reach(child);
      }
    };
    reach(kWorldVertex);
    for (size_t n = 0; n < view_.nodes.size(); ++n) {
      if (is_static(static_cast<int>(n))) {
        in_tree_[n] = true;
        reach(static_cast<int>(n));
      }
    }
    grow();
    for (size_t n = 0; n < view_.nodes.size(); ++n) {
      if (!is_body(static_cast<int>(n)) || in_tree_[n]) continue;
      in_tree_[n] = true;  // a floating component: free joint at its first declared body
      free_roots_.insert(static_cast<int>(n));
      reach(static_cast<int>(n));
      grow();
    }
  }

  // ----------------------------------------------------------------------------------------- the bodies

  void emit_world_geoms(Element& world) {
    for (const sn::Geometry& g : view_.geometries) {
      if (is_body(g.owner)) continue;
      // Geometries of systems are fixed in the world at the system's pose.
      const sn::Transform frame = g.owner >= 0 ? snap_.node_world[g.owner] : sn::Transform{};
      emit_geom(world, g, affine_compose(frame, g.local), true);
    }
  }

  void emit_bodies(Element& world) {
    // Children lists in declaration order.
    std::map<int, std::vector<int>>& children = tree_children_;
    for (size_t n = 0; n < view_.nodes.size(); ++n) {
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
        sink_.report(fe::DiagCode::MjcfTooDeep, view_.nodes[item.node].where,
                     "the body chain reaches " + view_.nodes[item.node].path + " at depth " +
                         std::to_string(item.depth) + "; MuJoCo 2.2.2 reads at most " +
                         std::to_string(kMaxBodyDepth) + " nested bodies");
        continue;
      }
      Element& body = emit_body(*item.parent_element, item.node);
      const auto& kids = children[item.node];
      for (auto it = kids.rbegin(); it != kids.rend(); ++it) stack.push_back({*it, &body, item.depth + 1});
    }
  }

  Element& emit_body(Element& parent, int node) {
    const sn::FrameNode& n = view_.nodes[node];
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
      initial_velocities_.push_back(node);  // written as the "initial" keyframe (emit_initial_velocities)
    } else if (moving) {
      warn(n.where,
           "`" + n.path +
               ".kinematics.initial_local_*_velocity`: only a free body's initial velocity maps to MuJoCo "
               "(a keyframe); this body starts at rest");
    }
    for (const sn::Geometry* g : geometries_of(node)) emit_geom(body, *g, g->local, !n.body.dynamic);
    return body;
  }

  // A loop-closing mate's elastic flexibility (LinearElastic per direction) and its dissipation, as physical
  // stiffness and damping: the mean over the translational and over the rotational directions (one weld has
  // one value each; differing directions are warned). Damping: MechanicalDamping as given, a relaxation time
  // t as t k, else AGX's default of two time steps. nullopt when the mate is rigid.
  std::optional<MateCompliance> compliance(const sn::Mate& mate) {
    const fe::ObjectId flex = object(mate.object, "flexibility");
    if (flex == fe::kNoObject) return std::nullopt;
    const fe::ObjectId dissipation = object(mate.object, "dissipation");
    MateCompliance c;
    bool differs = false;
    auto directions = [&](std::initializer_list<const char*> axes, double& k_mean, double& b_mean) {
      int count = 0;
      double first = -1;
      for (const char* axis : axes) {
        const fe::ObjectId elastic = object(flex, axis);
        const double k = elastic == fe::kNoObject ? 0 : real(elastic, "stiffness");
        if (!(k > 0)) continue;
        double b = 2 * options_.timestep * k;
        if (const fe::ObjectId d = dissipation == fe::kNoObject ? fe::kNoObject : object(dissipation, axis);
            d != fe::kNoObject) {
          if (const fe::Value* v = ev_.value(d, "damping_constant"); v && v->is_number()) b = v->as_real();
          if (const fe::Value* t = ev_.value(d, "relaxation_time"); t && t->is_number()) b = t->as_real() * k;
        }
        differs = differs || (first >= 0 && k != first);
        first = k;
        k_mean += k;
        b_mean += b;
        ++count;
      }
      if (count > 0) {
        k_mean /= count;
        b_mean /= count;
      }
    };
    directions({"along_main", "along_normal", "along_cross"}, c.k_trans, c.b_trans);
    directions({"around_main", "around_normal", "around_cross"}, c.k_rot, c.b_rot);
    if (!(c.k_trans > 0)) return std::nullopt;
    if (differs) {
      warn(mate.where,
           "`" + mate.path +
               ".flexibility` differs between directions; a MuJoCo equality has one stiffness for "
               "its translations (and one for its rotations), so their means were used");
    }
    return c;
  }

  // Flexibility and dissipation of a mate's constrained degrees of freedom: tree joints are exactly rigid in
  // MuJoCo and equalities take MuJoCo's default softness, so a non-default model is reported, not dropped.
  void warn_mate_softness(const sn::Mate& mate, bool loop) {
    for (const char* attribute : {"flexibility", "dissipation"}) {
      const fe::ObjectId model = object(mate.object, attribute);
      if (model == fe::kNoObject) continue;
      const std::string& type = ev_.graph().at(model).type->qualified;
      if (type.find(".Default") != std::string::npos) continue;
      warn(mate.where, "`" + mate.path + "." + attribute + "` (" + type +
                           ") has no MuJoCo 2.2.2 mapping here; " +
                           (loop ? "the loop-closing equality keeps MuJoCo's default softness"
                                 : "the joint's constrained directions are rigid"));
    }
  }

  // Dry friction of a mate's free degree of freedom. MuJoCo's joint friction is a constant limit
  // (`frictionloss`), so only a friction given a constant normal force maps: limit = coefficient x normal
  // force (N for slides; read as N m for hinges, UNCONFIRMED). Friction that scales with the constraint force
  // has no 2.2.2 counterpart and is warned.
  void apply_friction(Element& joint, const sn::Mate& mate, const char* attribute) {
    const fe::ObjectId friction = object(mate.object, attribute);
    if (friction == fe::kNoObject) return;
    const std::string& type = ev_.graph().at(friction).type->qualified;
    if (type == "Physics.Interactions.Dissipation.DefaultFriction") return;
    if (type == "Physics.Interactions.Dissipation.DryConstantNormalForceFriction") {
      const double limit = real(friction, "coefficient") * real(friction, "normal_force");
      if (limit > 0) joint.set("frictionloss", limit);
      return;
    }
    warn(mate.where,
         "`" + mate.path + "." + attribute + "` (" + type +
             ") depends on the constraint force, which MuJoCo 2.2.2 joint friction cannot; the joint "
             "was emitted without friction");
  }

  void emit_joints(Element& body, int node, int m) {
    const sn::Mate& mate = view_.mates[m];
    warn_mate_softness(mate, false);
    if (mate.type == sn::MateType::Lock) return;  // a rigid child: no joint
    const int side = vertex_of_connector(mate.connectors[1]) == node ? 1 : 0;
    const sn::Connector& c = view_.connectors[mate.connectors[side]];
    // The connector in the body frame (its owner is this body).
    const Eigen::Vector3d pos = c.local.position;
    // connectors[1] relative to connectors[0] about +main_axis: on side 0 the body turns the other way.
    const Eigen::Vector3d axis = (side == 1 ? 1.0 : -1.0) * (c.local.rotation * Eigen::Vector3d::UnitZ());
    auto joint = [&](const char* type, const std::string& suffix, double ref) {
      Element& j = body.add("joint");
      j.set("name", name(mate.path) + suffix).set("type", type).set("pos", pos);
      if (std::string(type) != "ball") j.set("axis", axis);
      if (ref != 0.0) j.set("ref", ref);
      joint_of_mate_[m].push_back(&j);
      joint_info_[&j] = {node, pos, axis.normalized(), std::string(type) == "hinge"};
      return &j;
    };
    switch (mate.type) {
      case sn::MateType::Hinge:
        apply_friction(*joint("hinge", "", mate.initial_angle), mate, "friction");
        break;
      case sn::MateType::Prismatic:
        apply_friction(*joint("slide", "", mate.initial_position), mate, "friction");
        break;
      case sn::MateType::Cylindrical:
        apply_friction(*joint("slide", ".slide", mate.initial_position), mate, "friction_translational");
        apply_friction(*joint("hinge", ".hinge", mate.initial_angle), mate, "friction_rotational");
        break;
      case sn::MateType::Ball:
        joint("ball", "", 0.0);
        break;
      default:
        break;
    }
  }

  const std::vector<const sn::Geometry*>& geometries_of(int node) {
    if (geometries_by_owner_.empty()) {
      for (const sn::Geometry& g : view_.geometries) geometries_by_owner_[g.owner].push_back(&g);
    }
    return geometries_by_owner_[node];
  }

  double density_of(const sn::Geometry& g) {
    if (g.material == fe::kNoObject) return 1000.0;
    const fe::Value* d = ev_.value(g.material, "density");
    return d && d->is_number() ? d->as_real() : 1000.0;
  }

  void emit_inertial(Element& body, int node) {
    const sn::FrameNode& n = view_.nodes[node];
    if (!n.body.dynamic) return;  // a static body needs no mass
    const bool tensor_given = !n.body.inertia.isZero();
    if (n.body.mass > 0 && tensor_given) {
      const Eigen::Matrix3d r = n.body.cm.rotation.toRotationMatrix();
      // The tensor turned into the body's axes: MJCF takes fullinertia or a quat, never both.
      const Eigen::Matrix3d i = r * n.body.inertia * r.transpose();
      body_mass_[node] = {n.body.mass, n.body.cm.position, i};
      body.add("inertial")
          .set("pos", n.body.cm.position)
          .set("mass", n.body.mass)
          .set("fullinertia", number(i(0, 0)) + " " + number(i(1, 1)) + " " + number(i(2, 2)) + " " +
                                  number(i(0, 1)) + " " + number(i(0, 2)) + " " + number(i(1, 2)));
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
      // MuJoCo computes mesh volumes exactly (exactmeshinertia); the mass goes on the geoms. For motor gains
      // below, estimate the body as a sphere of radius 0.1 m.
      mass_on_geoms_[node] = n.body.mass;
      const double mass = n.body.mass > 0 ? n.body.mass : 1.0;
      body_mass_[node] = {mass, Eigen::Vector3d::Zero(), 0.4 * mass * 0.01 * Eigen::Matrix3d::Identity()};
      return;
    }
    std::optional<MassProperties> p = combine(parts);
    if (!p) {
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
    body.add("inertial")
        .set("pos", p->com)
        .set("mass", p->mass)
        .set("fullinertia", number(p->inertia(0, 0)) + " " + number(p->inertia(1, 1)) + " " +
                                number(p->inertia(2, 2)) + " " + number(p->inertia(0, 1)) + " " +
                                number(p->inertia(0, 2)) + " " + number(p->inertia(1, 2)));
  }

  void emit_geom(Element& parent, const sn::Geometry& g, const sn::Transform& pose, bool on_static) {
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
            .set("size", number(g.size.x()) + " " + number(g.size.y() / 2));
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
      if (auto it = material_names_.find(g.material); it != material_names_.end())
        geom.set("material", it->second);
    }
    if (!g.collides) geom.set("contype", 0).set("conaffinity", 0);
    if (g.visual || !g.in_mass) geom.set("group", 3);  // outside inertiagrouprange: no mass
    if (auto it = mass_on_geoms_.find(g.owner); it != mass_on_geoms_.end() && g.in_mass && it->second > 0) {
      geom.set("mass", it->second);
      it->second = 0;  // the whole given mass on the first geometry that counts
    } else if (g.in_mass && !on_static) {
      geom.set("density", density_of(g));
    }
    emitted_geoms_.insert(g.path);
    parent.add(std::move(geom));
  }

  // Visuals materials as MJCF materials: base colour tint -> rgba, 1 - roughness -> shininess (MuJoCo's is
  // a glossiness), metallic -> reflectance. Textures have no mapping yet.
  void emit_visual_materials() {
    for (fe::ObjectId m : view_.visual_materials) {
      const std::string path = ev_.graph().path(m);
      Element& material = assets_->add("material");
      material.set("name", name(path));
      if (fe::ObjectId tint = object(m, "base_color_tint"); tint != fe::kNoObject) {
        material.set("rgba", number(real(tint, "r", 1)) + " " + number(real(tint, "g", 1)) + " " +
                                 number(real(tint, "b", 1)) + " " + number(real(tint, "a", 1)));
      }
      if (const fe::Value* r = ev_.value(m, "roughness"); r && r->is_number()) {
        material.set("shininess", std::clamp(1.0 - r->as_real(), 0.0, 1.0));
      }
      if (const fe::Value* metal = ev_.value(m, "metallic"); metal && metal->is_number()) {
        material.set("reflectance", std::clamp(metal->as_real(), 0.0, 1.0));
      }
      material_names_[m] = name(path);
      // Texture maps carry pixels inline (base64); MuJoCo 2.2.2 reads textures only from image files.
      for (const char* map : {"base_color_map", "roughness_map", "metallic_map", "alpha_map",
                              "ambient_occlusion_map", "normal_map"}) {
        const fe::ObjectId texture = object(m, map);
        const fe::ObjectId data = texture == fe::kNoObject ? fe::kNoObject : object(texture, "data");
        if (data != fe::kNoObject && real(data, "width") > 0 && real(data, "height") > 0) {
          warn(sn::source_of(ev_.graph(), texture),
               "`" + path + "." + map +
                   "` is an inline texture, which MuJoCo 2.2.2 cannot read (it takes image "
                   "files); the material keeps its colour only");
        }
      }
    }
  }

  // A mesh given by its vertices (and, for a TriMesh, its triangles) as an inline MJCF mesh asset.
  std::string vertex_mesh_asset(const sn::Geometry& g) {
    const size_t n = g.vertices.size();
    bool valid_faces = g.indices.size() % 3 == 0;
    for (int k : g.indices) valid_faces = valid_faces && k >= 0 && static_cast<size_t>(k) < n;
    if (n < 4 || !valid_faces) {
      warn(g.where, "`" + g.path +
                        (n < 4 ? ".vertices` has fewer than 4 points"
                               : ".indices` are not triangles of its vertices") +
                        "; MuJoCo needs a solid mesh, so it was left out");
      return {};
    }
    if (g.shape == sn::Geometry::Shape::TriMesh && g.collides) {
      warn(g.where, "`" + g.path +
                        "` is a triangle mesh; MuJoCo 2.2.2 collides with its convex hull, so contacts "
                        "use the hull");
    }
    std::string vertex, face;
    for (const Eigen::Vector3d& p : g.vertices) {
      vertex += (vertex.empty() ? "" : " ") + number(p.x()) + " " + number(p.y()) + " " + number(p.z());
    }
    for (int k : g.indices) face += (face.empty() ? "" : " ") + std::to_string(k);
    const std::string mesh_name = name(g.path);
    Element& mesh = assets_->add("mesh");
    mesh.set("name", mesh_name).set("vertex", vertex);
    if (!face.empty()) mesh.set("face", face);
    return mesh_name;
  }

  std::string mesh_asset(const sn::Geometry& g) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (!fs::is_regular_file(g.file, ec)) {
      sink_.report(fe::DiagCode::MjcfMissingAsset, g.where,
                   "mesh file " + g.file + " of `" + g.path + "` not found");
      return {};
    }
    std::string ext = fs::path(g.file).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (ext != ".obj" && ext != ".stl" && ext != ".msh") {
      sink_.report(fe::DiagCode::MjcfMissingAsset, g.where,
                   "mesh file " + g.file + " of `" + g.path + "` is " + ext +
                       "; MuJoCo 2.2.2 reads OBJ, binary STL and MSH");
      return {};
    }
    std::string file = g.file;
    if (!options_.output_dir.empty())
      file = fs::path(g.file).lexically_relative(options_.output_dir).generic_string();
    const std::string mesh_name = name(g.path);
    assets_->add("mesh").set("name", mesh_name).set("file", file).set("scale", g.scale);
    return mesh_name;
  }

  // ------------------------------------------------------------------------------- loops and actuators

  void emit_loop_closures(Element& root) {
    Element& equality = root.add("equality");
    Element& contact = root.add("contact");
    std::set<std::pair<std::string, std::string>> excluded;
    for (const auto& e : adjacency_) {
      if (tree_mates_.count(e.mate)) continue;
      const sn::Mate& mate = view_.mates[e.mate];
      const std::string a = e.a >= 0 ? name(view_.nodes[e.a].path) : "world";
      const std::string b = e.b >= 0 ? name(view_.nodes[e.b].path) : "world";
      // The anchor: connector 0 in its body's frame (MuJoCo derives body2's point from the assembled pose).
      // A connector on the world side (World, or one owned by a system) is given in world coordinates.
      const sn::Transform frame0 =
          e.a >= 0 ? view_.connectors[mate.connectors[0]].local : snap_.connector_world[mate.connectors[0]];
      const sn::Transform frame1 =
          e.b >= 0 ? view_.connectors[mate.connectors[1]].local : snap_.connector_world[mate.connectors[1]];
      const Eigen::Vector3d anchor = frame0.position;
      const std::optional<MateCompliance> soft = compliance(mate);
      if (!soft) warn_mate_softness(mate, true);
      switch (mate.type) {
        case sn::MateType::Lock: {
          Element& weld = equality.add("weld").set("name", name(mate.path)).set("body1", a);
          if (e.b >= 0) weld.set("body2", b);
          weld.set("anchor",
                   frame1.position);  // where the error is measured: the weld point, in body2's frame
          equalities_of_mate_[e.mate].push_back(*weld.get("name"));
          if (soft) soft_equalities_.push_back({&weld, a, b, *soft, true});
          break;
        }
        case sn::MateType::Ball:
        case sn::MateType::Hinge: {
          // A hinge closing a loop: two points on its axis (one would leave the axis free to tilt).
          const Eigen::Vector3d axis = frame0.rotation * Eigen::Vector3d::UnitZ();
          const int count = mate.type == sn::MateType::Hinge ? 2 : 1;
          for (int k = 0; k < count; ++k) {
            const Eigen::Vector3d point =
                count == 1 ? anchor : Eigen::Vector3d(anchor + (k == 0 ? 0.05 : -0.05) * axis);
            Element& connect = equality.add("connect");
            connect.set("name", name(mate.path) + (count == 1 ? "" : (k == 0 ? ".a" : ".b"))).set("body1", a);
            if (e.b >= 0) connect.set("body2", b);
            connect.set("anchor", point);
            equalities_of_mate_[e.mate].push_back(*connect.get("name"));
            if (soft) soft_equalities_.push_back({&connect, a, b, *soft, false});
          }
          if (soft && soft->k_rot > 0) {
            warn(mate.where,
                 "`" + mate.path + ".flexibility`: the rotational stiffness of a " +
                     sn::mate_type_name(mate.type) +
                     " closing a loop is not mapped (MuJoCo's connect constrains points only); its "
                     "translational stiffness is");
          }
          break;
        }
        default:
          warn(mate.where, "`" + mate.path + "` closes a kinematic loop as a " +
                               sn::mate_type_name(mate.type) +
                               "; MuJoCo 2.2.2 has no exact equality for it, so it was left out");
          continue;
      }
      if (e.a >= 0 && e.b >= 0 && excluded.insert({std::min(a, b), std::max(a, b)}).second) {
        contact.add("exclude").set("body1", a).set("body2", b);
      }
      for (const sn::Interaction1D& i : view_.interactions) {
        if (i.mate == e.mate) {
          warn(i.where, "`" + i.path + "` acts on `" + mate.path +
                            "`, which closes a loop and has no MuJoCo joint; " + "it was left out");
        }
      }
    }
  }

  // Free bodies' initial velocities as keyframe "initial" (MJCF has no initial velocity; MuJoCo fills the
  // key's qpos with qpos0). The runtime starts from it; MuJoCo users call mj_resetDataKeyframe. OpenPLX gives
  // both velocities in the owning system's frame; a free joint's qvel is the world linear velocity, then the
  // angular velocity in the body's frame.
  void emit_initial_velocities(Element& root) {
    if (initial_velocities_.empty()) return;
    std::map<const Element*, int> dof_address;
    int nv = 0;
    std::vector<const Element*> stack{world_};  // MuJoCo numbers dofs body by body, depth first
    while (!stack.empty()) {
      const Element* body = stack.back();
      stack.pop_back();
      dof_address[body] = nv;
      for (const std::unique_ptr<Element>& e : body->children()) {
        if (e->name() == "freejoint") nv += 6;
        if (e->name() == "joint") {
          const std::string* type = e->get("type");
          nv += !type || *type == "hinge" || *type == "slide" ? 1 : *type == "ball" ? 3 : 6;
        }
      }
      const auto& children = body->children();
      for (auto it = children.rbegin(); it != children.rend(); ++it) {
        if ((*it)->name() == "body") stack.push_back(it->get());
      }
    }
    std::vector<double> qvel(static_cast<size_t>(nv), 0.0);
    for (int node : initial_velocities_) {
      const sn::FrameNode& n = view_.nodes[node];
      const Eigen::Matrix3d system = n.parent >= 0 ? snap_.node_world[n.parent].rotation.toRotationMatrix()
                                                   : Eigen::Matrix3d::Identity();
      const Eigen::Matrix3d body = snap_.node_world[node].rotation.toRotationMatrix();
      const Eigen::Vector3d linear = system * n.body.initial_linear_velocity;
      const Eigen::Vector3d angular = body.transpose() * (system * n.body.initial_angular_velocity);
      const size_t at = static_cast<size_t>(dof_address.at(body_element_.at(node)));
      for (int k = 0; k < 3; ++k) {
        qvel[at + k] = linear[k];
        qvel[at + 3 + k] = angular[k];
      }
    }
    std::string text;
    for (double v : qvel) text += (text.empty() ? "" : " ") + number(v);
    root.add("keyframe").add("key").set("name", name("initial")).set("qvel", text);  // prefixed: scenes merge
  }

  // Simulation.DisableCollisionPair. MuJoCo excludes contacts per pair of bodies, so each group becomes the
  // bodies that hold its systems', bodies' and geometries' shapes; a group naming only some of a body's
  // colliding geometries is widened to the whole body, with a warning.
  void emit_collision_filters(Element& root) {
    if (view_.collision_filters.empty()) return;
    Element* contact = root.child("contact");
    std::set<std::pair<std::string, std::string>> excluded;
    for (const std::unique_ptr<Element>& e : contact->children()) {
      if (e->name() == "exclude") excluded.insert({*e->get("body1"), *e->get("body2")});
    }
    std::unordered_map<fe::ObjectId, int> node;  // systems and bodies alike
    for (size_t n = 0; n < view_.nodes.size(); ++n) node[view_.nodes[n].object] = static_cast<int>(n);
    for (const sn::CollisionFilter& f : view_.collision_filters) {
      std::vector<std::string> widened;
      const std::set<std::string> first = group_bodies(f.group1, node, widened);
      const std::set<std::string> second = group_bodies(f.group2, node, widened);
      for (const std::string& body : widened) {
        warn(f.where, "`" + f.path + "`: MuJoCo excludes contacts between whole bodies, so all of `" + body +
                          "`'s geometries were excluded, not only those its group names");
      }
      for (const std::string& a : first) {
        for (const std::string& b : second) {
          if (a == b) continue;  // a body's own geometries never collide in MuJoCo
          const auto pair = std::minmax(a, b);
          if (excluded.insert({pair.first, pair.second}).second)
            contact->add("exclude").set("body1", pair.first).set("body2", pair.second);
        }
      }
    }
  }

  // The MuJoCo bodies holding the shapes of a Simulation.CollisionGroup.
  std::set<std::string> group_bodies(fe::ObjectId group, const std::unordered_map<fe::ObjectId, int>& node,
                                     std::vector<std::string>& widened) {
    std::set<std::string> bodies;
    if (group == fe::kNoObject) return bodies;
    auto listed = [&](const char* attribute) {
      std::vector<fe::ObjectId> out;
      const fe::Value* v = ev_.value(group, attribute);
      if (v && v->kind == fe::Value::Kind::Array) {
        for (const fe::Value& item : v->array)
          if (item.kind == fe::Value::Kind::Object) out.push_back(item.object);
      }
      return out;
    };
    auto within = [&](int n, int ancestor) {
      for (; n >= 0; n = view_.nodes[n].parent) {
        if (n == ancestor) return true;
      }
      return false;
    };
    for (fe::ObjectId body : listed("bodies")) {
      if (auto it = node.find(body); it != node.end()) bodies.insert(mujoco_body(it->second));
    }
    for (fe::ObjectId system : listed("systems")) {
      auto it = node.find(system);
      if (it == node.end()) continue;
      for (const sn::Geometry& g : view_.geometries) {
        if (g.collides && within(g.owner, it->second)) bodies.insert(mujoco_body(g.owner));
      }
    }
    std::set<fe::ObjectId> geometries;
    for (fe::ObjectId g : listed("geometries")) geometries.insert(g);
    std::set<int> owners;
    for (const sn::Geometry& g : view_.geometries) {
      if (geometries.count(g.object)) owners.insert(g.owner);
    }
    for (int owner : owners) {
      const std::string body = mujoco_body(owner);
      bodies.insert(body);
      for (const sn::Geometry& g : view_.geometries) {
        if (g.owner == owner && g.collides && !geometries.count(g.object)) {
          if (std::find(widened.begin(), widened.end(), body) == widened.end()) widened.push_back(body);
          break;
        }
      }
    }
    return bodies;
  }

  // The MuJoCo body a node's shapes end up in: its own, or the world for a system's (emit_world_geoms).
  std::string mujoco_body(int n) { return n >= 0 && is_body(n) ? name(view_.nodes[n].path) : "world"; }

  // One <pair> per pair of colliding geometries whose materials a SurfaceContact model names.
  void emit_contact_pairs(Element& root) {
    Element* contact = root.child("contact");
    for (const sn::ContactModel& cm : view_.contact_models) {
      const fe::Value* enabled = ev_.value(cm.object, "enabled");
      if (enabled && enabled->kind == fe::Value::Kind::Bool && !enabled->bool_value) continue;
      double mu = 1.0;
      if (fe::ObjectId friction = object(cm.object, "friction"); friction != fe::kNoObject) {
        mu = real(friction, "coefficient", 1.0);
      }
      for (const char* restitution : {"normal_restitution", "tangential_restitution"}) {
        const fe::Value* v = ev_.value(cm.object, restitution);
        if (v && v->is_number() && v->as_real() != 0.0) {
          warn(cm.where, "`" + cm.path + "." + restitution +
                             "` has no MuJoCo 2.2.2 parameter; its contacts are "
                             "emitted without restitution");
        }
      }
      size_t pairs = 0;
      for (const sn::Geometry& a : view_.geometries) {
        for (const sn::Geometry& b : view_.geometries) {
          if (&a >= &b || a.visual || b.visual || !a.collides || !b.collides || a.owner == b.owner) continue;
          const bool match = (a.material == cm.material1 && b.material == cm.material2) ||
                             (a.material == cm.material2 && b.material == cm.material1);
          if (!match || !emitted_geoms_.count(a.path) || !emitted_geoms_.count(b.path)) continue;
          contact->add("pair")
              .set("name", name(cm.path) + "/" + std::to_string(pairs++))
              .set("geom1", name(a.path))
              .set("geom2", name(b.path))
              .set("condim", 3)
              .set("friction", number(mu) + " " + number(mu) + " 0.005 0.0001 0.0001");
        }
      }
    }
  }

  double real(fe::ObjectId object, std::string_view attribute, double fallback = 0.0) {
    const fe::Value* v = ev_.value(object, attribute);
    return v && v->is_number() ? v->as_real() : fallback;
  }

  void emit_actuators(Element& root) {
    Element& actuators = root.add("actuator");
    using K = sn::Interaction1D::Kind;
    // Ranges and springs are joint attributes; several on one joint intersect (ranges) or add up (springs).
    std::map<Element*, std::pair<double, double>> ranges;
    std::map<Element*, std::pair<double, double>> springs;  // sum k, sum k * rest
    std::map<Element*, double> dampings;
    for (const sn::JointProperties& p : view_.joint_properties) {
      if (p.mate >= 0) joint_properties_[p.mate] = &p;
    }
    for (const sn::Interaction1D& i : view_.interactions) {
      const bool velocity = i.kind == K::LinearVelocityMotor || i.kind == K::RotationalVelocityMotor;
      if (!velocity || i.mate < 0 || !tree_mates_.count(i.mate)) continue;
      if (Element* joint = joint_for(i.mate, i.kind == K::RotationalVelocityMotor)) ++velocity_motors_[joint];
    }
    for (const sn::Interaction1D& i : view_.interactions) {
      if (i.shaft >= 0) {
        emit_shaft_motor(actuators, i);
        continue;
      }
      if (i.mate < 0) {
        warn(i.where, "`" + i.path +
                          "` acts on connectors that no mate joins (or on a drivetrain it cannot "
                          "drive); it was left out");
        continue;
      }
      if (!tree_mates_.count(i.mate)) continue;  // loop mates warned above
      const bool rotational = i.kind == K::TorsionSpring || i.kind == K::RotationalRange ||
                              i.kind == K::RotationalVelocityMotor || i.kind == K::TorqueMotor;
      Element* joint = joint_for(i.mate, rotational);
      if (!joint) {
        warn(i.where, "`" + i.path + "` acts on `" + view_.mates[i.mate].path + "`, whose joint has no " +
                          (rotational ? "rotational" : "linear") + " degree of freedom; it was left out");
        continue;
      }
      const std::string joint_name = *joint->get("name");
      switch (i.kind) {
        case K::LinearRange:
        case K::RotationalRange: {
          const double lo = real(i.object, "start"), hi = real(i.object, "end");
          range_joints_[i.object] = joint_name;
          auto [it, fresh] = ranges.try_emplace(joint, lo, hi);
          if (!fresh) it->second = {std::max(it->second.first, lo), std::min(it->second.second, hi)};
          break;
        }
        case K::LinearSpring:
        case K::TorsionSpring: {
          double k = 0;
          if (fe::ObjectId flex = object(i.object, "flexibility"); flex != fe::kNoObject)
            k = real(flex, "stiffness");
          const double rest = real(i.object, i.kind == K::LinearSpring ? "position" : "angle");
          auto& [sum_k, sum_kr] = springs[joint];
          sum_k += k;
          sum_kr += k * rest;
          springs_[i.object] = {joint_name, k, rest, 0.0};
          dampings[joint] += spring_damping(i, k);
          if (std::isfinite(real(i.object, "min_effort", -INFINITY)) ||
              std::isfinite(real(i.object, "max_effort", INFINITY))) {
            warn(i.where, "`" + i.path +
                              ".min_effort`/`max_effort`: a MuJoCo joint spring has no force limit; the "
                              "spring was emitted without one");
          }
          break;
        }
        case K::LinearVelocityMotor:
        case K::RotationalVelocityMotor: {
          // f = kv (ctrl - qdot); kv is bounded by the motor's gain and by what explicit Euler keeps stable.
          const double gain = real(i.object, "gain", 1e8);
          Element& a = actuators.add("velocity");
          a.set("name", name(i.path)).set("joint", joint_name).set("kv", velocity_gain(gain, *joint, i));
          effort_limits(a, i);
          speed_limit(a, i);
          actuator_ctrl_[i.object] = {static_cast<int>(actuator_count_++), real(i.object, "target_speed")};
          break;
        }
        case K::ForceMotor:
        case K::TorqueMotor: {
          Element& a = actuators.add("motor");
          a.set("name", name(i.path)).set("joint", joint_name).set("gear", "1");
          effort_limits(a, i);
          actuator_ctrl_[i.object] = {
              static_cast<int>(actuator_count_++),
              real(i.object, i.kind == K::ForceMotor ? "default_force" : "default_torque")};
          break;
        }
        default:
          warn(i.where, "`" + i.path + "` has no MuJoCo mapping yet; it was left out");
          break;
      }
    }
    apply_joint_properties(dampings);
    for (auto& [joint, range] : ranges) {
      if (range.first > range.second) {
        warn({}, "the ranges on joint " + *joint->get("name") + " do not overlap; the joint is locked at " +
                     number(range.first));
        range.second = range.first;
      }
      joint->set("limited", "true").set("range", number(range.first) + " " + number(range.second));
    }
    for (auto& [joint, spring] : springs) {
      joint->set("stiffness", spring.first);
      const double rest = spring.first > 0 ? spring.second / spring.first : 0.0;
      if (rest != 0) joint->set("springref", rest);
      for (auto& [object, info] : springs_) {
        if (info.joint == *joint->get("name")) info.joint_rest = rest;
      }
    }
    for (auto& [joint, damping] : dampings) {
      if (damping > 0) joint->set("damping", damping);
    }
  }

  // URDF <dynamics>: damping adds to the springs' own; friction becomes frictionloss (a constant Coulomb
  // friction is exactly what MuJoCo's joint friction is), added to a mate friction already there.
  void apply_joint_properties(std::map<Element*, double>& dampings) {
    for (const sn::JointProperties& p : view_.joint_properties) {
      if (p.mate < 0 || !tree_mates_.count(p.mate)) {
        if (p.damping > 0 || p.friction > 0)
          warn(p.where, "`" + p.path +
                            "` (URDF dynamics) is on a mate that closes a loop or joins nothing; " +
                            "MuJoCo's equality constraints have no damping or friction, so it was left out");
        continue;
      }
      Element* joint = joint_for(p.mate, view_.mates[p.mate].type != sn::MateType::Prismatic);
      if (!joint) continue;  // a Lock: nothing moves
      if (p.damping > 0) dampings[joint] += p.damping;
      if (p.friction > 0) {
        const std::string* had = joint->get("frictionloss");
        joint->set("frictionloss", p.friction + (had ? std::stod(*had) : 0.0));
      }
    }
  }

  // Flexible loop closures need MuJoCo's own inverse-inertia estimate (dA): loaded once, then written.
  void soften_equalities(Element& root) {
    if (soft_equalities_.empty() || sink_.has_errors()) return;
    const SoftEqualityResult r =
        apply_soft_equalities(root, soft_equalities_, options_.output_dir, options_.timestep);
    if (!r.error.empty()) {
      warn({}, "flexible loop closures kept MuJoCo's default softness: the draft model did not load (" +
                   r.error + ")");
    }
    for (const std::string& e : r.unstable) {
      warn({}, "equality " + e + " is stiffer than explicit integration at " + number(options_.timestep) +
                   " s resolves (h sqrt(k/m) > 1); it may oscillate");
    }
  }

  // ------------------------------------------------------------------------------------------ drivetrains

  // A drivetrain as MuJoCo joints and constraints: every shaft is a rotor body spinning about z at the world
  // origin (no geometry, its inertia about the axis), hinge/prismatic actuators tie a shaft's angle to the
  // mate's joint and gears tie two shafts with joint equalities (MuJoCo measures both from their initial
  // values), a differential ties its three shafts with a fixed tendon held at its initial length:
  // w_drive = gear_ratio (w_left + w_right) / 2. Gears: ratio = input speed / output speed (UNCONFIRMED for
  // AGX; the corpus only uses -1, where both readings agree).
  // Joints that follow another (URDF mimic): a joint equality, follower = offset + multiplier * leader
  // (MuJoCo measures both from the initial configuration).
  void emit_joint_couplings(Element& root) {
    Element* equality = root.child("equality");
    for (const sn::JointCoupling& c : view_.joint_couplings) {
      auto joint = [&](int mate) -> Element* {
        if (mate < 0 || !tree_mates_.count(mate)) return nullptr;
        return joint_for(mate, view_.mates[mate].type != sn::MateType::Prismatic);
      };
      Element* follower = joint(c.follower);
      Element* leader = joint(c.leader);
      if (!follower || !leader || follower == leader) {
        warn(c.where, "`" + c.path +
                          "` does not couple two hinge or prismatic joints of MuJoCo's tree; it was "
                          "left out");
        continue;
      }
      equality->add("joint")
          .set("name", name(c.path))
          .set("joint1", *follower->get("name"))
          .set("joint2", *leader->get("name"))
          .set("polycoef", number(c.offset) + " " + number(c.multiplier) + " 0 0 0");
    }
  }

  void emit_drivetrain(Element& root) {
    if (view_.shafts.empty()) return;
    for (const sn::Shaft& shaft : view_.shafts) {
      Element& body = world_->add("body");
      body.set("name", name(shaft.path)).set("pos", "0 0 0");
      Element& joint = body.add("joint");
      joint.set("name", name(shaft.path)).set("type", "hinge").set("axis", "0 0 1");
      const double inertia = std::max(shaft.inertia, 1e-9);
      body.add("inertial")
          .set("pos", "0 0 0")
          .set("mass", 1.0)
          .set("diaginertia", Eigen::Vector3d::Constant(inertia));
      shaft_joints_.push_back(name(shaft.path));
    }
    Element* equality = root.child("equality");
    Element& tendons = root.add("tendon");
    for (const sn::DriveCoupling& c : view_.couplings) {
      const bool complete = std::none_of(c.shafts.begin(), c.shafts.end(), [](int k) { return k < 0; });
      const size_t needed = c.kind == sn::DriveCoupling::Kind::Actuator ? 1
                            : c.kind == sn::DriveCoupling::Kind::Gear   ? 2
                                                                        : 3;
      if (!complete || c.shafts.size() != needed) {
        warn(c.where, "`" + c.path + "` does not connect drivetrain shafts; it was left out");
        continue;
      }
      switch (c.kind) {
        case sn::DriveCoupling::Kind::Actuator: {
          Element* joint = c.mate >= 0 && tree_mates_.count(c.mate)
                               ? joint_for(c.mate, view_.mates[c.mate].type != sn::MateType::Prismatic)
                               : nullptr;
          if (!joint) {
            warn(c.where, "`" + c.path +
                              ".mate_3d` is not a hinge or prismatic joint of MuJoCo's tree; the "
                              "actuator was left out");
            continue;
          }
          equality->add("joint")
              .set("name", name(c.path))
              .set("joint1", *joint->get("name"))
              .set("joint2", shaft_joints_[c.shafts[0]])
              .set("polycoef", "0 1 0 0 0");
          drive_edges_.push_back({c.shafts[0], -1, 1.0, joint});
          break;
        }
        case sn::DriveCoupling::Kind::Gear:
          if (c.ratio == 0) {
            warn(c.where, "`" + c.path + ".ratio` is 0; the gear was left out");
            continue;
          }
          equality->add("joint")
              .set("name", name(c.path))
              .set("joint1", shaft_joints_[c.shafts[1]])
              .set("joint2", shaft_joints_[c.shafts[0]])
              .set("polycoef", "0 " + number(1 / c.ratio) + " 0 0 0");
          drive_edges_.push_back({c.shafts[0], c.shafts[1], 1 / c.ratio, nullptr});
          break;
        case sn::DriveCoupling::Kind::Differential: {
          if (const fe::Value* locked = ev_.value(c.object, "locked_up");
              locked && locked->kind == fe::Value::Kind::Bool && locked->bool_value) {
            warn(c.where, "`" + c.path + ".locked_up` has no mapping; the differential is emitted open");
          }
          Element& tendon = tendons.add("fixed");
          tendon.set("name", name(c.path));
          const double half = c.ratio / 2;
          tendon.add("joint").set("joint", shaft_joints_[c.shafts[0]]).set("coef", 1.0);
          tendon.add("joint").set("joint", shaft_joints_[c.shafts[1]]).set("coef", -half);
          tendon.add("joint").set("joint", shaft_joints_[c.shafts[2]]).set("coef", -half);
          equality->add("tendon").set("name", name(c.path)).set("tendon1", name(c.path));
          // For gain estimates: an axle turns about 1/gear_ratio as fast as the drive.
          drive_edges_.push_back({c.shafts[0], c.shafts[1], 1 / c.ratio, nullptr});
          drive_edges_.push_back({c.shafts[0], c.shafts[2], 1 / c.ratio, nullptr});
          break;
        }
      }
    }
  }

  // A rotational velocity motor on a shaft: a <velocity> actuator on the shaft's joint, its gain capped like
  // the 3-D motors' by the inertia the whole drivetrain presents at that shaft.
  void emit_shaft_motor(Element& actuators, const sn::Interaction1D& i) {
    const double gain = real(i.object, "gain", 1e8);
    const double stable = 0.5 * drivetrain_inertia(i.shaft) / options_.timestep;
    if (gain > stable) note_capped_gain(i, gain, stable);
    Element& a = actuators.add("velocity");
    a.set("name", name(i.path)).set("joint", shaft_joints_[i.shaft]).set("kv", std::min(gain, stable));
    effort_limits(a, i);
    actuator_ctrl_[i.object] = {static_cast<int>(actuator_count_++), real(i.object, "target_speed", 1.0)};
  }

  // Inertia reflected to shaft `start`: every shaft's inertia and every driven joint's subtree inertia, times
  // the square of its speed relative to the start (gears scale speeds by their ratio; an even differential
  // split is assumed).
  double drivetrain_inertia(int start) {
    std::map<int, double> speed{{start, 1.0}};
    std::vector<int> todo{start};
    double total = 0;
    while (!todo.empty()) {
      const int s = todo.back();
      todo.pop_back();
      total += std::max(view_.shafts[s].inertia, 1e-9) * speed[s] * speed[s];
      for (const DriveEdge& e : drive_edges_) {
        if (e.joint && e.from == s) total += effective_inertia(*e.joint) * speed[s] * speed[s];
        if (e.to < 0 || (e.from != s && e.to != s)) continue;
        const int next = e.from == s ? e.to : e.from;
        if (speed.count(next)) continue;
        speed[next] = e.from == s ? speed[s] * e.factor : speed[s] / e.factor;
        todo.push_back(next);
      }
    }
    return total;
  }

  // Simulation.Environment's uniform gravity field, else standard gravity.
  Eigen::Vector3d gravity() {
    Eigen::Vector3d g(0, 0, -9.81);
    const fe::ObjectId root = view_.root >= 0 ? view_.nodes[view_.root].object : fe::kNoObject;
    if (root == fe::kNoObject) return g;
    const fe::ObjectId field = object(root, "gravity");
    if (field == fe::kNoObject) return g;
    const fe::ObjectId vector = object(field, "vector");
    if (vector == fe::kNoObject) {
      warn(view_.nodes[view_.root].where,
           "`gravity` is not a uniform field; MuJoCo has only uniform gravity, so "
           "standard gravity was used");
      return g;
    }
    return {real(vector, "x"), real(vector, "y"), real(vector, "z")};
  }

  // Viscous damping of a spring: MechanicalDamping gives it, ConstraintRelaxationTimeDamping gives the time
  // (b = t k); the default is AGX's: a relaxation time of two time steps.
  double spring_damping(const sn::Interaction1D& i, double k) {
    const fe::ObjectId d = object(i.object, "dissipation");
    if (d == fe::kNoObject) return 0.0;
    if (const fe::Value* b = ev_.value(d, "damping_constant"); b && b->is_number()) return b->as_real();
    if (const fe::Value* t = ev_.value(d, "relaxation_time"); t && t->is_number()) return t->as_real() * k;
    return 2 * options_.timestep * k;
  }

  // MuJoCo's velocity actuator pushes explicitly: stable under Euler only while kv h / I_eff < 2. Half of the
  // limit keeps tracking fast (the velocity error halves every step) with margin.
  double velocity_gain(double gain, Element& joint, const sn::Interaction1D& motor) {
    const double inertia = effective_inertia(joint);
    if (!(inertia > 0)) return gain;
    // The limit holds for the sum of the gains on one joint: share it among its velocity motors.
    const double stable = 0.5 * inertia / options_.timestep / std::max(1, velocity_motors_[&joint]);
    if (gain > stable) {
      note_capped_gain(motor, gain, stable);
      return stable;
    }
    return gain;
  }
  void note_capped_gain(const sn::Interaction1D& motor, double gain, double stable) {
    warn(motor.where, "`" + motor.path + ".gain` " + number(gain) +
                          " would make MuJoCo's explicit velocity motor " +
                          "unstable; emitted kv = " + number(stable) +
                          " (half the stability limit I/h, shared by the joint's velocity motors)");
  }

  // The inertia the joint drives at the initial pose: the subtree below it, about the joint axis (rotation)
  // or its mass (translation).
  double effective_inertia(Element& joint) {
    const JointInfo& info = joint_info_.at(&joint);
    const sn::Transform& child = snap_.node_world[info.node];
    const Eigen::Vector3d axis = child.rotation * info.axis;
    const Eigen::Vector3d point = child.rotation * info.pos + child.position;
    double total = 0.0;
    std::vector<int> todo{info.node};
    while (!todo.empty()) {
      const int b = todo.back();
      todo.pop_back();
      for (int c : tree_children_[b]) todo.push_back(c);
      auto it = body_mass_.find(b);
      if (it == body_mass_.end()) continue;
      const MassProperties& p = it->second;
      if (!info.rotational) {
        total += p.mass;
        continue;
      }
      const Eigen::Matrix3d r = snap_.node_world[b].rotation.toRotationMatrix();
      const Eigen::Vector3d com = r * p.com + snap_.node_world[b].position;
      total +=
          axis.dot(r * p.inertia * r.transpose() * axis) + p.mass * (com - point).cross(axis).squaredNorm();
    }
    return total;
  }

  fe::ObjectId object(fe::ObjectId id, std::string_view attribute) {
    const fe::Value* v = ev_.value(id, attribute);
    return v && v->kind == fe::Value::Kind::Object ? v->object : fe::kNoObject;
  }

  void effort_limits(Element& actuator, const sn::Interaction1D& i) {
    double lo = real(i.object, "min_effort", -INFINITY), hi = real(i.object, "max_effort", INFINITY);
    // A URDF effort limit bounds every motor on its joint, as the robot's actuator would.
    if (auto it = joint_properties_.find(i.mate); it != joint_properties_.end() && it->second->effort > 0) {
      lo = std::max(lo, -it->second->effort);
      hi = std::min(hi, it->second->effort);
    }
    // Always limited (±1e10 when the model gives no limit): every motor model has a range input, and the
    // runtime can tighten only a limited actuator.
    actuator.set("forcelimited", "true")
        .set("forcerange",
             number(std::isfinite(lo) ? lo : -1e10) + " " + number(std::isfinite(hi) ? hi : 1e10));
  }

  // A URDF velocity limit bounds the speed a velocity motor may be asked for (its control range).
  void speed_limit(Element& actuator, const sn::Interaction1D& i) {
    auto it = joint_properties_.find(i.mate);
    if (it == joint_properties_.end() || it->second->velocity <= 0) return;
    const double v = it->second->velocity;
    actuator.set("ctrllimited", "true").set("ctrlrange", number(-v) + " " + number(v));
  }

  Element* joint_for(int mate, bool rotational) {
    auto it = joint_of_mate_.find(mate);
    if (it == joint_of_mate_.end()) return nullptr;
    for (Element* j : it->second) {
      const bool hinge = *j->get("type") == "hinge";
      if (hinge == rotational && *j->get("type") != "ball") return j;
    }
    return nullptr;
  }

  // ------------------------------------------------------------------------------ signals and sensors

  // One binding per OpenPLX signal (signal_binding.h), and a MuJoCo sensor for every enabled output that
  // has one. Outputs without a sensor (controls, ranges, constants) are computed by the runtime.
  void bind_signals(Element& root, std::vector<SignalBinding>& out) {
    sensors_ = &root.add("sensor");
    for (const sn::Signal& s : view_.signals) {
      SignalBinding b = bind(s);
      if (!b.input && b.enabled && b.quantity == Quantity::None) {
        warn(s.where, "output `" + s.path + "` (" + s.type + ") has no MuJoCo counterpart: " + b.reason +
                          "; it was left out");
      }
      if (!b.input && b.enabled) add_sensor(b);
      out.push_back(std::move(b));
    }
  }

  SignalBinding bind(const sn::Signal& s) {
    SignalBinding b;
    b.path = s.path;
    b.input = s.input;
    b.type = s.type;
    b.enabled = s.enabled;
    const SignalKind kind = signal_kind(s.type);
    b.value = kind.value;
    b.unit = kind.unit;
    const std::string_view stem = signal_stem(s.type);
    if (s.source == fe::kNoObject) return unmapped(std::move(b), "it has no source");
    if (const int i = index_of(interaction_index_, s.source, view_.interactions); i >= 0)
      return bind_interaction(std::move(b), stem, view_.interactions[i]);
    if (const int m = mate_of(s.source); m >= 0) return bind_mate(std::move(b), stem, m);
    if (const int n = node_of(s.source); n >= 0) return bind_body(std::move(b), stem, n);
    if (const int k = index_of(shaft_index_, s.source, view_.shafts);
        k >= 0 && !b.input && any_of(stem, {"Angle", "AngularVelocity1D"})) {
      return mapped(std::move(b), stem == "Angle" ? Quantity::JointPosition : Quantity::JointVelocity,
                    MjObject::Joint, shaft_joints_[k]);
    }
    if (const int c = index_of(connector_index_, s.source, view_.connectors); c >= 0)
      return bind_connector(std::move(b), stem, c);
    return unmapped(std::move(b), "its source `" + view_path(s.source) + "` has no MuJoCo element");
  }

  static SignalBinding unmapped(SignalBinding b, std::string reason) {
    b.quantity = Quantity::None;
    b.reason = std::move(reason);
    return b;
  }
  static SignalBinding mapped(SignalBinding b, Quantity quantity, MjObject object, std::string element) {
    b.quantity = quantity;
    b.object = object;
    b.names = {std::move(element)};
    return b;
  }
  static bool any_of(std::string_view stem, std::initializer_list<std::string_view> stems) {
    return std::find(stems.begin(), stems.end(), stem) != stems.end();
  }

  SignalBinding bind_interaction(SignalBinding b, std::string_view stem, const sn::Interaction1D& i) {
    if (auto a = actuator_ctrl_.find(i.object); a != actuator_ctrl_.end()) {  // a motor
      const std::string actuator = name(i.path);
      if (any_of(stem, {"TorqueRange", "ForceRange"}))
        return mapped(std::move(b), Quantity::ForceRange, MjObject::Actuator, actuator);
      const bool effort = any_of(stem, {"Torque1D", "Force1D"});
      const bool target = b.input || !effort;  // an effort motor's input, a velocity motor's target
      if (effort && !b.input)
        return mapped(std::move(b), Quantity::ActuatorForce, MjObject::Actuator, actuator);
      if (target && any_of(stem, {"Torque1D", "Force1D", "AngularVelocity1D", "LinearVelocity1D"})) {
        b.initial = a->second.second;
        return mapped(std::move(b), Quantity::Ctrl, MjObject::Actuator, actuator);
      }
    }
    if (auto sp = springs_.find(i.object); sp != springs_.end()) {
      const SpringInfo& spring = sp->second;
      if (any_of(stem, {"Angle", "Position1D"})) {
        b.initial = spring.joint_rest;
        return mapped(std::move(b), Quantity::SpringRest, MjObject::Joint, spring.joint);
      }
      if (!b.input && any_of(stem, {"Torque1D", "Force1D"})) {
        b.gain = -spring.stiffness;
        b.offset = spring.rest;
        return mapped(std::move(b), Quantity::SpringForce, MjObject::Joint, spring.joint);
      }
    }
    if (auto r = range_joints_.find(i.object); r != range_joints_.end() && !b.input) {
      if (any_of(stem, {"Angle", "Position1D"}))
        return mapped(std::move(b), Quantity::JointPosition, MjObject::Joint, r->second);
      if (any_of(stem, {"Torque1D", "Force1D"}))
        return mapped(std::move(b), Quantity::JointLimitForce, MjObject::Joint, r->second);
    }
    return unmapped(std::move(b), "`" + i.path + "` has no MuJoCo element that carries it");
  }

  SignalBinding bind_mate(SignalBinding b, std::string_view stem, int m) {
    const sn::Mate& mate = view_.mates[m];
    const bool tree = tree_mates_.count(m) > 0;
    if (any_of(stem, {"EnableInteraction", "InteractionEnabled"})) {
      if (auto e = equalities_of_mate_.find(m); e != equalities_of_mate_.end()) {
        b = mapped(std::move(b), Quantity::EqualityActive, MjObject::Equality, "");
        b.names = e->second;
        return b;
      }
      if (!tree) return unmapped(std::move(b), "`" + mate.path + "` was left out of the MJCF");
      if (b.input) {
        return unmapped(std::move(b),
                        "`" + mate.path + "` is a joint of MuJoCo's body tree, which cannot be switched off");
      }
      b.quantity = Quantity::Constant;
      b.initial = 1.0;
      return b;
    }
    if (!tree) {
      return unmapped(std::move(b), "`" + mate.path +
                                        "` closes a kinematic loop as an equality constraint, which has no "
                                        "joint coordinate or force sensor");
    }
    if (!b.input && any_of(stem, {"Angle", "AngularVelocity1D", "Position1D", "LinearVelocity1D"})) {
      const bool rotational = any_of(stem, {"Angle", "AngularVelocity1D"});
      Element* joint = joint_for(m, rotational);
      if (!joint) {
        return unmapped(std::move(b), "`" + mate.path + "` has no " + (rotational ? "rotational" : "linear") +
                                          " joint coordinate");
      }
      const bool position = any_of(stem, {"Angle", "Position1D"});
      return mapped(std::move(b), position ? Quantity::JointPosition : Quantity::JointVelocity,
                    MjObject::Joint, *joint->get("name"));
    }
    if (!b.input && any_of(stem, {"Force3D", "Torque3D"})) {
      auto found = child_of_mate_.find(m);
      if (found == child_of_mate_.end()) return unmapped(std::move(b), "`" + mate.path + "` was not emitted");
      const int child = found->second;
      const int side = vertex_of_connector(mate.connectors[1]) == child ? 1 : 0;
      b = mapped(std::move(b), stem == "Force3D" ? Quantity::MateForce : Quantity::MateTorque, MjObject::Site,
                 site_for(mate.connectors[side]));
      b.sign = side == 1 ? 1.0 : -1.0;
      return b;
    }
    return unmapped(std::move(b), "`" + mate.path + "` has no MuJoCo element that carries it");
  }

  SignalBinding bind_body(SignalBinding b, std::string_view stem, int n) {
    const std::string body = name(view_.nodes[n].path);
    if (!body_element_.count(n))
      return unmapped(std::move(b), "`" + view_.nodes[n].path + "` was not emitted");
    if (b.input) {
      const bool linear = stem == "LinearVelocity3D";
      if (!linear && stem != "AngularVelocity3D") return unmapped(std::move(b), "no MuJoCo input of a body");
      if (mocap_.count(n)) {
        return mapped(std::move(b),
                      linear ? Quantity::KinematicLinearVelocity : Quantity::KinematicAngularVelocity,
                      MjObject::Body, body);
      }
      if (free_roots_.count(n)) {
        return mapped(std::move(b), linear ? Quantity::FreeLinearVelocity : Quantity::FreeAngularVelocity,
                      MjObject::Joint, body);
      }
      return unmapped(std::move(b), "`" + view_.nodes[n].path +
                                        "` moves through its joints in MuJoCo; its velocity cannot be set");
    }
    const Quantity q = stem == "Position3D" || stem == "Position" ? Quantity::BodyPosition
                       : stem == "RPY"                            ? Quantity::BodyRPY
                       : stem == "LinearVelocity3D"               ? Quantity::BodyLinearVelocity
                       : stem == "AngularVelocity3D"              ? Quantity::BodyAngularVelocity
                       : stem == "Acceleration3D"                 ? Quantity::BodyLinearAcceleration
                                                                  : Quantity::None;
    if (q == Quantity::None) return unmapped(std::move(b), "no MuJoCo quantity of a body matches it");
    return mapped(std::move(b), q, MjObject::Body, body);
  }

  SignalBinding bind_connector(SignalBinding b, std::string_view stem, int c) {
    const Quantity q = b.input                       ? Quantity::None
                       : stem == "Position3D"        ? Quantity::SitePosition
                       : stem == "RPY"               ? Quantity::SiteRPY
                       : stem == "LinearVelocity3D"  ? Quantity::SiteLinearVelocity
                       : stem == "AngularVelocity3D" ? Quantity::SiteAngularVelocity
                                                     : Quantity::None;
    if (q == Quantity::None)
      return unmapped(std::move(b), "no MuJoCo quantity of a mate connector matches it");
    return mapped(std::move(b), q, MjObject::Site, site_for(c));
  }

  // A site at a mate connector, in the MuJoCo body that carries it (the world for system connectors).
  std::string site_for(int c) {
    const sn::Connector& connector = view_.connectors[c];
    const std::string site = name(connector.path);
    if (!sites_.insert(c).second) return site;
    const int owner = vertex_of_connector(c);
    auto body = body_element_.find(owner);
    Element& parent = owner >= 0 && body != body_element_.end() ? *body->second : *world_;
    const sn::Transform frame = owner >= 0 ? connector.local : snap_.connector_world[c];
    parent.add("site").set("name", site).set("pos", frame.position).set_quat("quat", frame.rotation);
    return site;
  }

  void add_sensor(SignalBinding& b) {
    struct Sensor {
      const char* element;
      const char* objtype;  // frame sensors; nullptr: the element names its object by attribute
      const char* attribute;
    };
    Sensor sensor{};
    switch (b.quantity) {
      case Quantity::JointPosition:
        sensor = {"jointpos", nullptr, "joint"};
        break;
      case Quantity::JointVelocity:
        sensor = {"jointvel", nullptr, "joint"};
        break;
      case Quantity::JointLimitForce:
        sensor = {"jointlimitfrc", nullptr, "joint"};
        break;
      case Quantity::ActuatorForce:
        sensor = {"actuatorfrc", nullptr, "actuator"};
        break;
      case Quantity::MateForce:
        sensor = {"force", nullptr, "site"};
        break;
      case Quantity::MateTorque:
        sensor = {"torque", nullptr, "site"};
        break;
      case Quantity::BodyPosition:
        sensor = {"framepos", "xbody", nullptr};
        break;
      case Quantity::BodyRPY:
        sensor = {"framequat", "xbody", nullptr};
        break;  // the runtime gives RPY
      case Quantity::BodyLinearVelocity:
        sensor = {"framelinvel", "xbody", nullptr};
        break;
      case Quantity::BodyAngularVelocity:
        sensor = {"frameangvel", "xbody", nullptr};
        break;
      case Quantity::BodyLinearAcceleration:
        sensor = {"framelinacc", "xbody", nullptr};
        break;
      case Quantity::SitePosition:
        sensor = {"framepos", "site", nullptr};
        break;
      case Quantity::SiteRPY:
        sensor = {"framequat", "site", nullptr};
        break;
      case Quantity::SiteLinearVelocity:
        sensor = {"framelinvel", "site", nullptr};
        break;
      case Quantity::SiteAngularVelocity:
        sensor = {"frameangvel", "site", nullptr};
        break;
      default:
        return;  // computed by the runtime
    }
    Element& e = sensors_->add(sensor.element);
    e.set("name", name(b.path));
    if (sensor.objtype) {
      e.set("objtype", sensor.objtype).set("objname", b.names.front());
    } else {
      e.set(sensor.attribute, b.names.front());
    }
    b.sensor = name(b.path);
  }

  template <typename T>
  int index_of(std::unordered_map<fe::ObjectId, int>& index, fe::ObjectId id, const std::vector<T>& items) {
    if (index.empty()) {
      for (size_t k = 0; k < items.size(); ++k) index[items[k].object] = static_cast<int>(k);
    }
    auto it = index.find(id);
    return it == index.end() ? -1 : it->second;
  }

  std::string view_path(fe::ObjectId id) const { return ev_.graph().path(id); }
  int mate_of(fe::ObjectId id) {
    if (mate_index_.empty()) {
      for (size_t m = 0; m < view_.mates.size(); ++m)
        mate_index_[view_.mates[m].object] = static_cast<int>(m);
    }
    auto it = mate_index_.find(id);
    return it == mate_index_.end() ? -1 : it->second;
  }
  int node_of(fe::ObjectId id) {
    if (body_index_.empty()) {
      for (size_t n = 0; n < view_.nodes.size(); ++n) {
        if (is_body(static_cast<int>(n))) body_index_[view_.nodes[n].object] = static_cast<int>(n);
      }
    }
    auto it = body_index_.find(id);
    return it == body_index_.end() ? -1 : it->second;
  }

  void warn(fe::SourceRange where, const std::string& message) {
    sink_.report(fe::DiagCode::MjcfUnmapped, where, message);
  }
  static void drop_empty(Element& root, std::string_view section) {
    auto& kids = root.children();
    kids.erase(std::remove_if(kids.begin(), kids.end(),
                              [&](const std::unique_ptr<Element>& e) {
                                return e->name() == section && e->children().empty();
                              }),
               kids.end());
  }

  struct Adjacent {
    int mate;
    int a;
    int b;
    int cost;
  };

  const sn::PhysicsView& view_;
  const sn::SnapResult& snap_;
  fe::Evaluator& ev_;
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
  struct JointInfo {
    int node;
    Eigen::Vector3d pos;   // in the child body frame
    Eigen::Vector3d axis;  // unit, in the child body frame
    bool rotational;
  };
  std::map<Element*, JointInfo> joint_info_;
  std::map<int, MassProperties> body_mass_;
  std::map<int, std::vector<int>> tree_children_;
  std::map<Element*, int> velocity_motors_;
  std::map<int, const sn::JointProperties*> joint_properties_;  // mate -> its URDF joint properties
  std::set<std::string> emitted_geoms_;
  std::map<fe::ObjectId, std::string> material_names_;
  std::unordered_map<fe::ObjectId, int> mate_index_;
  std::unordered_map<fe::ObjectId, int> body_index_;
  std::unordered_map<int, std::vector<const sn::Geometry*>> geometries_by_owner_;
  std::map<fe::ObjectId, std::pair<int, double>> actuator_ctrl_;  // motor -> actuator index, initial ctrl
  size_t actuator_count_ = 0;
  Element* assets_ = nullptr;
  struct DriveEdge {
    int from;        // shaft
    int to;          // shaft, -1 for an actuator
    double factor;   // speed of `to` per unit speed of `from`
    Element* joint;  // an actuator's 3-D joint
  };
  std::vector<DriveEdge> drive_edges_;
  std::vector<PendingSoftEquality> soft_equalities_;
  std::vector<std::string> shaft_joints_;  // per shaft: its MuJoCo joint
  Element* world_ = nullptr;
  Element* sensors_ = nullptr;
  std::set<int> mocap_;
  std::set<int> sites_;                                         // connectors that have a site
  std::map<int, int> child_of_mate_;                            // tree mate -> the body whose joint it is
  std::map<int, std::vector<std::string>> equalities_of_mate_;  // loop mate -> its equality names
  struct SpringInfo {
    std::string joint;
    double stiffness;
    double rest;
    double joint_rest;  // the rest of all springs on the joint (stiffness-weighted)
  };
  std::map<fe::ObjectId, SpringInfo> springs_;
  std::map<fe::ObjectId, std::string> range_joints_;
  std::unordered_map<fe::ObjectId, int> interaction_index_;
  std::unordered_map<fe::ObjectId, int> connector_index_;
  std::unordered_map<fe::ObjectId, int> shaft_index_;
};

}  // namespace

Emitted emit_mjcf(const snap::PhysicsView& view, const snap::SnapResult& snap, frontend::Evaluator& evaluator,
                  const EmitOptions& options, frontend::DiagnosticSink& sink) {
  return Emitter(view, snap, evaluator, options, sink).run();
}

}  // namespace openplx::mjcf
