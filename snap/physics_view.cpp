#include "snap/physics_view.h"

#include <unordered_map>

namespace openplx::snap {
namespace {

namespace fe = openplx::frontend;

class ViewBuilder {
 public:
  ViewBuilder(fe::Evaluator& evaluator, fe::DiagnosticSink& sink) : ev_(evaluator), sink_(sink) {
    fe::Program& program = evaluator.program();
    system_ = program.builtin_model("Physics3D.System");
    body_ = program.builtin_model("Physics3D.Bodies.Body");
    connector_ = program.builtin_model("Physics3D.Interactions.MateConnector");
    adaptive_ = program.builtin_model("Physics3D.Interactions.AdaptiveMateConnector");
    mate_ = program.builtin_model("Physics3D.Interactions.Mate");
    const std::pair<const char*, MateType> kinds[] = {
        {"Lock", MateType::Lock},         {"Hinge", MateType::Hinge},
        {"Prismatic", MateType::Prismatic}, {"Cylindrical", MateType::Cylindrical},
        {"Ball", MateType::Ball},         {"Distance", MateType::Distance},
        {"ConstantVelocity", MateType::ConstantVelocity}};
    for (const auto& [name, type] : kinds) {
      if (fe::ModelInfo* m = program.builtin_model(std::string("Physics3D.Interactions.") + name)) {
        mate_kinds_.emplace_back(m, type);
      }
    }
  }

  PhysicsView build(fe::ObjectId root) {
    if (!system_ || !body_ || !connector_ || !mate_) return std::move(view_);  // no Physics3D: nothing to assemble
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
    for (Mate& mate : view_.mates) resolve_connectors(mate);
    return std::move(view_);
  }

 private:
  template <typename Stack>
  void visit(fe::ObjectId id, int enclosing, Stack& stack, bool is_root) {
    const fe::Object& obj = ev_.graph().at(id);
    int node = enclosing;
    if (obj.type->is_subtype_of(system_) || obj.type->is_subtype_of(body_)) {
      node = add_node(id, enclosing, is_root);
    } else if (obj.type->is_subtype_of(connector_)) {
      add_connector(id, enclosing);
    } else if (obj.type->is_subtype_of(mate_)) {
      add_mate(id);
    }
    // Children in reverse so the stack pops them in declaration order.
    std::vector<fe::ObjectId> children;
    for (uint32_t i = 0; i < obj.slots.size(); ++i) {
      const fe::Slot& slot = ev_.graph().at(id).slots[i];
      if (slot.owns && slot.value.kind == fe::Value::Kind::Object) children.push_back(slot.value.object);
    }
    for (auto it = children.rbegin(); it != children.rend(); ++it) stack.push_back({*it, node});
  }

  fe::SourceRange where_of(fe::ObjectId id) {
    const fe::Object& obj = ev_.graph().at(id);
    if (obj.owner == fe::kNoObject) return obj.type->decl ? obj.type->decl->range : fe::SourceRange{};
    const fe::Slot* slot = ev_.graph().at(obj.owner).find(obj.name);
    if (!slot) return {};
    return slot->declaration->member->range;
  }

  Eigen::Vector3d vec3(fe::ObjectId object, std::string_view name) {
    const fe::Value* v = ev_.value(object, name);
    if (!v || v->kind != fe::Value::Kind::Object) return Eigen::Vector3d::Zero();
    Eigen::Vector3d out;
    const char* axes[] = {"x", "y", "z"};
    for (int i = 0; i < 3; ++i) {
      const fe::Value* c = ev_.value(v->object, axes[i]);
      out[i] = c && c->is_number() ? c->as_real() : 0.0;
    }
    return out;
  }

  Transform affine(fe::ObjectId transform) {
    Transform t;
    t.position = vec3(transform, "position");
    const fe::Value* q = ev_.value(transform, "rotation");
    if (q && q->kind == fe::Value::Kind::Object) {
      double c[4] = {0, 0, 0, 1};
      const char* names[] = {"x", "y", "z", "w"};
      for (int i = 0; i < 4; ++i) {
        const fe::Value* v = ev_.value(q->object, names[i]);
        if (v && v->is_number()) c[i] = v->as_real();
      }
      t.rotation = natives::quat_normal(natives::quat_from_xyzw(c[0], c[1], c[2], c[3]));
    }
    return t;
  }

  // The local transform slot of a system (`local_transform`) or body (`kinematics.local_transform`).
  bool read_transform(fe::ObjectId id, Transform& out) {
    fe::ObjectId holder = id;
    if (ev_.graph().at(id).type->is_subtype_of(body_)) {
      const fe::Value* kinematics = ev_.value(id, "kinematics");
      if (!kinematics || kinematics->kind != fe::Value::Kind::Object) return false;
      holder = kinematics->object;
    }
    const fe::Value* value = ev_.value(holder, "local_transform");
    if (!value || value->kind != fe::Value::Kind::Object) return false;
    out = affine(value->object);
    return ev_.graph().at(holder).find("local_transform")->explicit_value;
  }

  int add_node(fe::ObjectId id, int parent, bool is_root) {
    FrameNode node;
    node.kind = ev_.graph().at(id).type->is_subtype_of(system_) ? FrameNode::Kind::System : FrameNode::Kind::Body;
    node.object = id;
    node.parent = parent;
    node.path = ev_.graph().path(id);
    node.defined = read_transform(id, node.local) || is_root;  // the root frame never moves
    node.where = where_of(id);
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
    c.path = ev_.graph().path(id);
    c.adaptive = adaptive_ && ev_.graph().at(id).type->is_subtype_of(adaptive_);
    c.where = where_of(id);
    c.local = connector_frame(id, c.where);
    connector_of_[id] = static_cast<int>(view_.connectors.size());
    if (in_tree) view_.order.emplace_back(false, static_cast<int>(view_.connectors.size()));
    view_.connectors.push_back(std::move(c));
  }

  Transform connector_frame(fe::ObjectId id, fe::SourceRange where) {
    const Eigen::Vector3d position = vec3(id, "position");
    const Eigen::Vector3d main_axis = vec3(id, "main_axis");
    const Eigen::Vector3d normal = vec3(id, "normal");
    std::optional<Transform> frame = natives::affine_from_axes(main_axis, normal, position);
    if (!frame) {
      sink_.report(fe::DiagCode::InvalidConnector, where,
                   "mate connector " + ev_.graph().path(id) +
                       " has no frame: main_axis must be non-zero and normal must not be parallel to it");
      return Transform{position, Eigen::Quaterniond::Identity()};
    }
    return *frame;
  }

  void add_mate(fe::ObjectId id) {
    Mate mate;
    mate.object = id;
    mate.path = ev_.graph().path(id);
    mate.where = where_of(id);
    const fe::ModelInfo* type = ev_.graph().at(id).type;
    for (const auto& [model, kind] : mate_kinds_) {
      if (type->is_subtype_of(model)) mate.type = kind;
    }
    auto real = [&](std::string_view name, double& out) {
      const fe::Value* v = ev_.value(id, name);
      if (v && v->is_number()) out = v->as_real();
    };
    real("initial_angle", mate.initial_angle);
    real("initial_position", mate.initial_position);
    real("initial_normal_angle", mate.initial_normal_angle);
    real("initial_cross_angle", mate.initial_cross_angle);
    if (const fe::Value* snap = ev_.value(id, "enable_snap"); snap && snap->kind == fe::Value::Kind::Bool) {
      mate.enable_snap = snap->bool_value;
    }
    view_.mates.push_back(std::move(mate));
  }

  // Connectors are references to objects anywhere in the tree (or to the World singleton).
  void resolve_connectors(Mate& mate) {
    const fe::Value* list = ev_.value(mate.object, "connectors");
    const size_t count = list && list->kind == fe::Value::Kind::Array ? list->array.size() : 0;
    if (count != 2) {
      sink_.report(fe::DiagCode::InvalidMate, mate.where,
                   "mate " + mate.path + " needs exactly two connectors, has " + std::to_string(count));
      return;
    }
    for (int side = 0; side < 2; ++side) {
      const fe::Value& item = list->array[side];
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
                   "connector " + ev_.graph().path(item.object) + " of mate " + mate.path +
                       " belongs to no system or body of this model");
    }
  }

  fe::Evaluator& ev_;
  fe::DiagnosticSink& sink_;
  PhysicsView view_;
  fe::ModelInfo* system_ = nullptr;
  fe::ModelInfo* body_ = nullptr;
  fe::ModelInfo* connector_ = nullptr;
  fe::ModelInfo* adaptive_ = nullptr;
  fe::ModelInfo* mate_ = nullptr;
  std::vector<std::pair<fe::ModelInfo*, MateType>> mate_kinds_;
  std::unordered_map<fe::ObjectId, int> node_of_;
  std::unordered_map<fe::ObjectId, int> connector_of_;
  std::vector<fe::ObjectId> reference_bodies_;
};

}  // namespace

PhysicsView build_physics_view(frontend::Evaluator& evaluator, frontend::ObjectId root, frontend::DiagnosticSink& sink) {
  return ViewBuilder(evaluator, sink).build(root);
}

Transform joint_offset(const Mate& mate) {
  Transform j;
  const Eigen::Vector3d z = Eigen::Vector3d::UnitZ();
  switch (mate.type) {
    case MateType::Hinge: j.rotation = natives::quat_angle_axis(mate.initial_angle, z); break;
    case MateType::Prismatic: j.position = mate.initial_position * z; break;
    case MateType::Cylindrical:
      j.rotation = natives::quat_angle_axis(mate.initial_angle, z);
      j.position = mate.initial_position * z;
      break;
    default: break;
  }
  return j;
}

std::string mate_type_name(MateType type) {
  switch (type) {
    case MateType::Lock: return "Lock";
    case MateType::Hinge: return "Hinge";
    case MateType::Prismatic: return "Prismatic";
    case MateType::Cylindrical: return "Cylindrical";
    case MateType::Ball: return "Ball";
    case MateType::Distance: return "Distance";
    case MateType::ConstantVelocity: return "ConstantVelocity";
    case MateType::Other: return "Mate";
  }
  return "Mate";
}

}  // namespace openplx::snap
