#include "mjcf_emitter/emitter.h"

#include <algorithm>
#include <filesystem>
#include <map>
#include <queue>
#include <set>
#include <unordered_map>

#include "frontend/quoted.h"
#include "mjcf_emitter/mass_properties.h"

namespace openplx::mjcf {
namespace {

namespace fe = openplx::frontend;
namespace sn = openplx::snap;
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
    root.add("option").set("timestep", kTimestep).set("gravity", gravity()).set("integrator", "Euler");
    for (const sn::Unsupported& u : view_.unsupported) {
      warn(u.where, "`" + u.path + "` is a " + u.type +
                        ", which has no MuJoCo 2.2.2 counterpart; it and its parts "
                        "were left out");
    }
    choose_tree();
    assets_ = &root.add("asset");
    emit_visual_materials();
    Element& world = root.add("worldbody");
    emit_world_geoms(world);
    emit_bodies(world);
    emit_loop_closures(root);
    emit_contact_pairs(root);
    emit_actuators(root);
    emit_sensors(root);
    if (assets_->children().empty()) drop_empty(root, "asset");
    for (const char* section : {"equality", "contact", "actuator", "sensor"}) drop_empty(root, section);
    out.manifest_json = manifest();
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
    if (free_roots_.count(node)) body.add("freejoint").set("name", name(n.path));
    if (edges_[node].mate >= 0) emit_joints(body, node, edges_[node].mate);
    emit_inertial(body, node);
    for (const sn::Geometry* g : geometries_of(node)) emit_geom(body, *g, g->local, !n.body.dynamic);
    return body;
  }

  void emit_joints(Element& body, int node, int m) {
    const sn::Mate& mate = view_.mates[m];
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
        joint("hinge", "", mate.initial_angle);
        break;
      case sn::MateType::Prismatic:
        joint("slide", "", mate.initial_position);
        break;
      case sn::MateType::Cylindrical:
        joint("slide", ".slide", mate.initial_position);
        joint("hinge", ".hinge", mate.initial_angle);
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
      body_mass_[node] = {n.body.mass, n.body.cm.position, r * n.body.inertia * r.transpose()};
      body.add("inertial")
          .set("pos", n.body.cm.position)
          .set_quat("quat", n.body.cm.rotation)
          .set("mass", n.body.mass)
          .set("fullinertia", number(n.body.inertia(0, 0)) + " " + number(n.body.inertia(1, 1)) + " " +
                                  number(n.body.inertia(2, 2)) + " " + number(n.body.inertia(0, 1)) + " " +
                                  number(n.body.inertia(0, 2)) + " " + number(n.body.inertia(1, 2)));
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
      default:
        warn(g.where, "`" + g.path +
                          "` is a geometry MuJoCo 2.2.2 cannot take here (convex or triangle mesh given "
                          "by vertices); it was left out");
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
    }
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
      switch (mate.type) {
        case sn::MateType::Lock: {
          Element& weld = equality.add("weld").set("name", name(mate.path)).set("body1", a);
          if (e.b >= 0) weld.set("body2", b);
          weld.set("anchor",
                   frame1.position);  // where the error is measured: the weld point, in body2's frame
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

  // One <pair> per pair of colliding geometries whose materials a SurfaceContact model names.
  void emit_contact_pairs(Element& root) {
    Element* contact = nullptr;
    for (const std::unique_ptr<Element>& e : root.children()) {
      if (e->name() == "contact") contact = e.get();
    }
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
    for (const sn::Interaction1D& i : view_.interactions) {
      const bool velocity = i.kind == K::LinearVelocityMotor || i.kind == K::RotationalVelocityMotor;
      if (!velocity || i.mate < 0 || !tree_mates_.count(i.mate)) continue;
      if (Element* joint = joint_for(i.mate, i.kind == K::RotationalVelocityMotor)) ++velocity_motors_[joint];
    }
    for (const sn::Interaction1D& i : view_.interactions) {
      if (i.mate < 0 || !tree_mates_.count(i.mate)) continue;  // loop mates warned above
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
      if (spring.first > 0 && spring.second != 0) joint->set("springref", spring.second / spring.first);
      if (dampings[joint] > 0) joint->set("damping", dampings[joint]);
    }
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
    return 2 * kTimestep * k;
  }

  // MuJoCo's velocity actuator pushes explicitly: stable under Euler only while kv h / I_eff < 2. Half of the
  // limit keeps tracking fast (the velocity error halves every step) with margin.
  double velocity_gain(double gain, Element& joint, const sn::Interaction1D& motor) {
    const double inertia = effective_inertia(joint);
    if (!(inertia > 0)) return gain;
    // The limit holds for the sum of the gains on one joint: share it among its velocity motors.
    const double stable = 0.5 * inertia / kTimestep / std::max(1, velocity_motors_[&joint]);
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
    const double lo = real(i.object, "min_effort", -INFINITY), hi = real(i.object, "max_effort", INFINITY);
    if (std::isfinite(lo) || std::isfinite(hi)) {
      actuator.set("forcelimited", "true")
          .set("forcerange",
               number(std::isfinite(lo) ? lo : -1e10) + " " + number(std::isfinite(hi) ? hi : 1e10));
    }
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

  // ----------------------------------------------------------------------------------------- sensors

  void emit_sensors(Element& root) {
    Element& sensors = root.add("sensor");
    for (const sn::Signal& s : view_.signals) {
      if (s.input || !s.enabled || s.source == fe::kNoObject) continue;
      const std::string& type = s.type;
      auto ends_with = [&](std::string_view suffix) {
        return type.size() >= suffix.size() &&
               type.compare(type.size() - suffix.size(), suffix.size(), suffix) == 0;
      };
      const int mate = mate_of(s.source);
      const int body = node_of(s.source);
      Element* joint = nullptr;
      if (mate >= 0)
        joint = joint_for(mate, !ends_with("Position1DOutput") && !ends_with("LinearVelocity1DOutput"));
      std::string element;
      if (joint && (ends_with(".AngleOutput") || ends_with("Position1DOutput"))) {
        element = "jointpos";
      } else if (joint && (ends_with("AngularVelocity1DOutput") || ends_with("LinearVelocity1DOutput"))) {
        element = "jointvel";
      } else if (body >= 0 && ends_with("Position3DOutput")) {
        element = "framepos";
      } else if (body >= 0 && ends_with("RPYOutput")) {
        element = "framequat";  // the runtime turns it into roll-pitch-yaw
      } else if (body >= 0 && ends_with("LinearVelocity3DOutput")) {
        element = "framelinvel";
      } else if (body >= 0 && ends_with("AngularVelocity3DOutput")) {
        element = "frameangvel";
      } else if (actuator_ctrl_.count(s.source) &&
                 (ends_with("Torque1DOutput") || ends_with("Force1DOutput"))) {
        element = "actuatorfrc";
      } else {
        warn(s.where, "output `" + s.path + "` (" + type + ") has no MuJoCo sensor yet; it was left out");
        continue;
      }
      Element& sensor = sensors.add(element);
      sensor.set("name", name(s.path));
      if (element == "jointpos" || element == "jointvel") {
        sensor.set("joint", *joint->get("name"));
      } else if (element == "actuatorfrc") {
        sensor.set("actuator", name(view_path(s.source)));
      } else {
        sensor.set("objtype", "xbody").set("objname", name(view_.nodes[body].path));
      }
      signals_[s.object] = {element, name(s.path)};
    }
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

  // --------------------------------------------------------------------------------------- manifest

  std::string manifest() {
    std::string out = "{\n  \"model\": " + fe::quoted(options_.model_name) + ",\n  \"signals\": [";
    bool first = true;
    for (const sn::Signal& s : view_.signals) {
      std::string element = "none", target, extra;
      if (s.input) {
        auto ends_with = [&](std::string_view suffix) {
          return s.type.size() >= suffix.size() &&
                 s.type.compare(s.type.size() - suffix.size(), suffix.size(), suffix) == 0;
        };
        if (auto it = actuator_ctrl_.find(s.source); it != actuator_ctrl_.end()) {
          const std::string index = ", \"index\": " + std::to_string(it->second.first);
          if (ends_with("Velocity1DInput") || ends_with("Torque1DInput") || ends_with("Force1DInput")) {
            // MJCF has no initial control: the runtime sets ctrl[index] = initial before the first step.
            element = "ctrl";
            target = name(view_path(s.source));
            extra = index + ", \"initial\": " + number(it->second.second);
          } else if (ends_with("TorqueRangeInput") || ends_with("ForceRangeInput")) {
            element = "forcerange";  // the runtime writes m->actuator_forcerange[2 index ..]
            target = name(view_path(s.source));
            extra = index;
          }
        }
      } else if (auto it = signals_.find(s.object); it != signals_.end()) {
        element = it->second.first;
        target = it->second.second;
      }
      out += first ? "\n" : ",\n";
      first = false;
      out += "    {\"path\": " + fe::quoted(s.path) + ", \"direction\": \"" + (s.input ? "input" : "output") +
             "\", \"type\": " + fe::quoted(s.type) + ", \"enabled\": " + (s.enabled ? "true" : "false") +
             ", \"mujoco\": " + fe::quoted(element) + ", \"name\": " + fe::quoted(target) + extra + "}";
    }
    return out + "\n  ]\n}\n";
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

  static constexpr double kTimestep = 0.002;

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
  std::set<std::string> emitted_geoms_;
  std::map<fe::ObjectId, std::string> material_names_;
  std::unordered_map<fe::ObjectId, int> mate_index_;
  std::unordered_map<fe::ObjectId, int> body_index_;
  std::unordered_map<int, std::vector<const sn::Geometry*>> geometries_by_owner_;
  std::map<fe::ObjectId, std::pair<int, double>> actuator_ctrl_;  // motor -> actuator index, initial ctrl
  std::map<fe::ObjectId, std::pair<std::string, std::string>> signals_;
  size_t actuator_count_ = 0;
  Element* assets_ = nullptr;
};

}  // namespace

Emitted emit_mjcf(const snap::PhysicsView& view, const snap::SnapResult& snap, frontend::Evaluator& evaluator,
                  const EmitOptions& options, frontend::DiagnosticSink& sink) {
  return Emitter(view, snap, evaluator, options, sink).run();
}

}  // namespace openplx::mjcf
