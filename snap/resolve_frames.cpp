// Systems, bodies and connectors: the frames SNAP places, with their local transforms, masses and inertias.
#include <Eigen/Eigenvalues>
#include <cmath>
#include <optional>

#include "snap/system_builder.h"

namespace openplx::snap::detail {

void SystemBuilder::read_body(fe::ObjectId id, BodyProperties& body) {
  if (const fe::Value* d = ev_.value(id, "is_dynamic"); d && d->kind == fe::Value::Kind::Bool)
    body.dynamic = d->bool_value;
  if (fe::ObjectId inertia = object(id, "inertia"); inertia != fe::kNoObject) {
    body.mass = real(inertia, "mass");
    // Above 1e307 kg MuJoCo 2.2.2 loads the body but its weight under Earth's gravity overflows (NaN from
    // the first step; measured with mj_loadXML and mj_step: 1.8e307 steps, 2e307 does not).
    constexpr double kMaxMass = 1e307;
    in_.require(std::isfinite(body.mass) && body.mass >= 0 && body.mass <= kMaxMass, inertia, "mass",
                body.mass,
                "a mass is 0 (computed from the geometries) or a positive number of kg, at most 1e307");
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

// Physics3D.System.kinematically_controlled (deprecated for RigidBody.is_dynamic, still used): the bodies
// it lists are kinematic, as `is_dynamic: false` makes them.
void SystemBuilder::apply_kinematic_control() {
  std::unordered_map<fe::ObjectId, size_t> node_of;
  for (size_t k = 0; k < system_.nodes.size(); ++k) node_of[system_.nodes[k].object] = k;
  for (size_t k = 0; k < system_.nodes.size(); ++k) {
    if (system_.nodes[k].kind != FrameNode::Kind::System) continue;
    const fe::Value* list = ev_.value(system_.nodes[k].object, "kinematically_controlled");
    if (!list || list->kind != fe::Value::Kind::Array) continue;
    for (const fe::Value& v : list->array()) {
      auto it = v.kind == fe::Value::Kind::Object ? node_of.find(v.object) : node_of.end();
      if (it != node_of.end() && system_.nodes[it->second].kind == FrameNode::Kind::Body)
        system_.nodes[it->second].body.dynamic = false;
    }
  }
}

Transform SystemBuilder::affine(fe::ObjectId transform) {
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

// A tensor MuJoCo can hold: finite, principal moments 0 or positive and each at most the sum of the other
// two (MuJoCo's own test, which it would otherwise fail at load, unlocated). A zero tensor means
// "computed".
void SystemBuilder::check_inertia_tensor(fe::ObjectId inertia, const Eigen::Matrix3d& tensor) {
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
std::optional<Eigen::Matrix3d> SystemBuilder::inertia_tensor(fe::ObjectId inertia) {
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
bool SystemBuilder::read_transform(fe::ObjectId id, Transform& out) {
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

int SystemBuilder::add_node(fe::ObjectId id, int parent, bool is_root) {
  FrameNode node;
  node.kind =
      ev_.graph().at(id).type->is_subtype_of(system_model_) ? FrameNode::Kind::System : FrameNode::Kind::Body;
  node.object = id;
  node.parent = parent;
  node.path = path_of(id);
  node.defined = read_transform(id, node.local) || is_root;  // the root frame never moves
  node.where = where_of(id);
  if (node.kind == FrameNode::Kind::Body) read_body(id, node.body);
  const int index = static_cast<int>(system_.nodes.size());
  if (is_root) system_.root = index;
  node_of_[id] = index;
  system_.nodes.push_back(std::move(node));
  system_.order.emplace_back(true, index);
  // A system's reference body is forced first when SNAP has to choose.
  if (system_.nodes[index].kind == FrameNode::Kind::System) {
    const fe::Value* ref = ev_.value(id, "reference_body");
    if (ref && ref->kind == fe::Value::Kind::Object) reference_bodies_.push_back(ref->object);
  }
  for (fe::ObjectId ref : reference_bodies_) {
    if (ref == id) system_.nodes[index].reference = true;
  }
  return index;
}

void SystemBuilder::add_connector(fe::ObjectId id, int owner, bool in_tree) {
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
      redirects_.emplace_back(static_cast<int>(system_.connectors.size()), parent);
  }
  connector_of_[id] = static_cast<int>(system_.connectors.size());
  if (in_tree) system_.order.emplace_back(false, static_cast<int>(system_.connectors.size()));
  system_.connectors.push_back(std::move(c));
}

Transform SystemBuilder::connector_frame(fe::ObjectId id, fe::SourceRange where) {
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

// A redirected connector (RedirectedMateConnector, 0.31's ConnectorProperties.Redirected) is written in its
// owner's frame and attached to `redirected_parent`. A parent below the owner through declared transforms
// takes it here (a wheel's rim at the wheel's origin); any other body of the model (a vehicle's chassis
// that SNAP places, a sibling system's body) takes it after assembly, keeping the world frame the
// connector was assembled at (W(parent)⁻¹ ∘ W(owner) ∘ M; docs/mapping.md "Redirected connectors"). Until
// then it is on its owner, as written: SNAP places the parts it joins from there.
void SystemBuilder::resolve_redirects() {
  for (const auto& [k, body] : redirects_) {
    Connector& c = system_.connectors[k];
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
    for (int n = it->second; n != kWorld; n = system_.nodes[n].parent) {
      if (n == c.owner) {
        below = true;
        break;
      }
      declared = declared && system_.nodes[n].defined;
      chain = natives::affine_compose(system_.nodes[n].local, chain);
    }
    if (!below || !declared) {
      c.redirect_to = it->second;
      continue;
    }
    c.owner = it->second;
    c.local = natives::affine_compose(natives::affine_inverse(chain), c.local);
  }
}

}  // namespace openplx::snap::detail
