#include "snap/read_parameters.h"

#include <cmath>

#include "snap/resolve_system.h"

namespace openplx::snap {

namespace fe = openplx::frontend;

namespace {

constexpr std::string_view kStiffnessRule = "a stiffness is 0 or positive (Math.INF: rigid)";
constexpr std::string_view kDampingRule =
    "a damping constant or relaxation time is a finite number, 0 or positive";

// A stiffness (infinite: rigid) or a damping constant / relaxation time (finite), refused when negative.
double stiffness(AttributeReader& in, fe::ObjectId elastic) {
  const double k = in.real(elastic, "stiffness");
  in.require(k >= 0, elastic, "stiffness", k, kStiffnessRule);
  return k;
}
std::optional<double> damping(AttributeReader& in, fe::ObjectId dissipation, std::string_view name) {
  const std::optional<double> d = in.number(dissipation, name);
  if (d) in.require(std::isfinite(*d) && *d >= 0, dissipation, name, *d, kDampingRule);
  return d;
}

Damping read_damping(AttributeReader& in, fe::ObjectId dissipation) {
  Damping d;
  if (dissipation == fe::kNoObject) return d;
  d.given = true;
  d.damping_constant = damping(in, dissipation, "damping_constant");
  d.relaxation_time = damping(in, dissipation, "relaxation_time");
  return d;
}

MateFriction read_friction(AttributeReader& in, fe::ObjectId mate, const char* attribute) {
  MateFriction f;
  const fe::ObjectId friction = in.values_of(mate, attribute);
  if (friction == fe::kNoObject) return f;
  f.type = in.type_name(friction);
  f.coefficient = in.real(friction, "coefficient");
  f.normal_force = in.real(friction, "normal_force");
  in.require(std::isfinite(f.coefficient) && f.coefficient >= 0, friction, "coefficient", f.coefficient,
             "a friction coefficient is a finite number, 0 or positive");
  in.require(std::isfinite(f.normal_force) && f.normal_force >= 0, friction, "normal_force", f.normal_force,
             "a normal force is a finite number, 0 or positive");
  return f;
}

bool in_bundle(const fe::ModelInfo* m) {
  return m && m->doc && m->doc->bundle;
}

// Whether `object.name` holds a value assigned to it, not a declaration's default.
bool assigned(AttributeReader& in, fe::ObjectId object, std::string_view name) {
  const fe::Slot* slot = in.graph().at(object).find(name);
  return slot && slot->explicit_value;
}

}  // namespace

std::optional<std::string> written_name(const fe::ObjectGraph& graph, const fe::Slot& slot) {
  const fe::Entry* entry = slot.binding.entry;
  const fe::ModelInfo* model = slot.binding.model;
  if (!entry || !entry->member || !model || in_bundle(model)) return std::nullopt;
  const bool root = graph.root != fe::kNoObject && model == graph.at(graph.root).type;
  std::string written = root ? "" : model->qualified;
  for (std::string_view part : entry->path) (written += written.empty() ? "" : ".") += part;
  return written;
}

WrittenValue written_value(const AttributeReader& in, fe::ObjectId object, std::string_view name) {
  const fe::ObjectGraph& g = in.graph();
  fe::ObjectId at = object;
  std::string_view attribute = name;
  std::string below;  // the path from the assigned attribute down to `name` (`.y` of a vector written whole)
  for (int depth = 0; depth < 8; ++depth) {
    const fe::Slot* slot = g.at(at).find(attribute);
    if (std::optional<std::string> written = slot ? written_name(g, *slot) : std::nullopt)
      return {*written + below, slot->binding.entry->member->range};
    const fe::Object& o = g.at(at);
    if (o.owner == fe::kNoObject) break;
    below = "." + std::string(attribute) + below;
    attribute = o.name;
    at = o.owner;
  }
  return {g.path(object) + "." + std::string(name), source_of(g, object)};
}

void read_mate_parameters(AttributeReader& in, fe::ObjectId id, Mate& mate) {
  mate.enabled = in.boolean(id, "enabled").value_or(true);
  // Read for their values only: a default no entry touches is read from its type's checked one.
  const fe::ObjectId flexibility = in.values_of(id, "flexibility");
  const fe::ObjectId dissipation = in.values_of(id, "dissipation");
  if (flexibility != fe::kNoObject) {
    mate.flexible = true;
    mate.flexibility_type = in.type_name(flexibility);
  }
  if (dissipation != fe::kNoObject) mate.dissipation_type = in.type_name(dissipation);
  for (size_t k = 0; k < mate.dofs.size(); ++k) {
    DofCompliance& dof = mate.dofs[k];
    const char* direction = Mate::kDirections[k];
    if (flexibility != fe::kNoObject) {
      if (const fe::ObjectId elastic = in.object(flexibility, direction); elastic != fe::kNoObject)
        dof.stiffness = stiffness(in, elastic);
    }
    if (dissipation != fe::kNoObject) {
      if (const fe::ObjectId d = in.object(dissipation, direction); d != fe::kNoObject) {
        dof.damping_constant = damping(in, d, "damping_constant");
        dof.relaxation_time = damping(in, d, "relaxation_time");
      }
    }
  }
  mate.friction = read_friction(in, id, "friction");
  mate.friction_translational = read_friction(in, id, "friction_translational");
  mate.friction_rotational = read_friction(in, id, "friction_rotational");
}

void read_interaction_parameters(AttributeReader& in, fe::ObjectId id, Interaction1D& i) {
  using K = Interaction1D::Kind;
  i.enabled = in.boolean(id, "enabled").value_or(true);
  switch (i.kind) {
    case K::LinearRange:
    case K::RotationalRange:
    case K::DistanceRange:
      i.start = in.real(id, "start");
      i.end = in.real(id, "end");
      break;
    case K::LinearSpring:
    case K::TorsionSpring:
      if (const fe::ObjectId flexibility = in.object(id, "flexibility"); flexibility != fe::kNoObject)
        i.stiffness = stiffness(in, flexibility);
      i.rest = in.real(id, i.kind == K::LinearSpring ? "position" : "angle");
      in.require(std::isfinite(i.rest), id, i.kind == K::LinearSpring ? "position" : "angle", i.rest,
                 "a spring's rest position or angle is finite");
      i.damping = read_damping(in, in.object(id, "dissipation"));
      break;
    case K::LinearVelocityMotor:
    case K::RotationalVelocityMotor:
    case K::DistanceMotor:
      i.gain = in.number(id, "gain");
      i.target_speed = in.number(id, "target_speed");
      if (i.gain)
        in.require(std::isfinite(*i.gain) && *i.gain >= 0, id, "gain", *i.gain,
                   "a gain is finite, 0 or more");
      if (i.target_speed)
        in.require(std::isfinite(*i.target_speed), id, "target_speed", *i.target_speed,
                   "a target speed is finite");
      break;
    case K::ForceMotor:
    case K::TorqueMotor:
      i.default_effort = in.real(id, i.kind == K::ForceMotor ? "default_force" : "default_torque");
      in.require(std::isfinite(i.default_effort), id,
                 i.kind == K::ForceMotor ? "default_force" : "default_torque", i.default_effort,
                 "a motor's default effort is finite");
      break;
    case K::Steering:  // its geometry is read with the suspensions it steers (read_steering)
      break;
    case K::Other:
      return;
  }
  i.min_effort = in.real(id, "min_effort", -kInf);
  i.max_effort = in.real(id, "max_effort", kInf);
}

VisualMaterial read_visual_material(AttributeReader& in, fe::ObjectId id) {
  VisualMaterial m;
  m.object = id;
  m.path = in.graph().path(id);
  m.where = source_of(in.graph(), id);
  if (const fe::ObjectId tint = in.object(id, "base_color_tint"); tint != fe::kNoObject)
    m.tint = Eigen::Vector4d(in.real(tint, "r", 1), in.real(tint, "g", 1), in.real(tint, "b", 1),
                             in.real(tint, "a", 1));
  m.roughness = in.number(id, "roughness");
  m.metallic = in.number(id, "metallic");
  m.alpha = in.number(id, "alpha");
  m.roughness_written = m.roughness && assigned(in, id, "roughness");
  m.metallic_written = m.metallic && assigned(in, id, "metallic");
  for (const char* map : {"base_color_map", "roughness_map", "metallic_map", "alpha_map",
                          "ambient_occlusion_map", "normal_map"}) {
    const fe::ObjectId texture = in.object(id, map);
    if (texture == fe::kNoObject) continue;
    if (const std::string file = in.string(texture, "path").value_or(""); !file.empty()) {
      FileTexture t;
      t.attribute = map;
      t.file = file;
      t.scale_u = in.real(texture, "scale_u", 1.0);
      t.scale_v = in.real(texture, "scale_v", 1.0);
      t.offset_u = in.real(texture, "offset_u", 0.0);
      t.offset_v = in.real(texture, "offset_v", 0.0);
      t.wrap_mode = static_cast<int>(in.real(texture, "wrap_mode", 0.0));
      t.filter_mode = static_cast<int>(in.real(texture, "filter_mode", 1.0));
      t.swizzle = in.string(texture, "swizzle").value_or("");
      t.map = written_value(in, id, map);
      // Each setting where it was written (the texture may be a declaration of its own, shared).
      if (!t.swizzle.empty()) t.swizzle_at = written_value(in, texture, "swizzle");
      if (t.wrap_mode != 0) t.wrap_at = written_value(in, texture, "wrap_mode");
      if (t.filter_mode != 1) t.filter_at = written_value(in, texture, "filter_mode");
      if (t.offset_u != 0 || t.offset_v != 0)
        t.offset_at = written_value(in, texture, t.offset_u != 0 ? "offset_u" : "offset_v");
      m.file_textures.push_back(std::move(t));
      continue;
    }
    const fe::ObjectId data = in.object(texture, "data");
    if (data != fe::kNoObject && in.real(data, "width") > 0 && in.real(data, "height") > 0)
      m.inline_textures.push_back({map, written_value(in, id, map)});
  }
  return m;
}

void read_contact_parameters(AttributeReader& in, fe::ObjectId id, ContactModel& model) {
  model.enabled = in.boolean(id, "enabled").value_or(true);
  if (const fe::ObjectId friction = in.object(id, "friction"); friction != fe::kNoObject) {
    model.friction = in.real(friction, "coefficient", 1.0);
    in.require(std::isfinite(model.friction) && model.friction >= 0, friction, "coefficient", model.friction,
               "a friction coefficient is a finite number, 0 or positive");
  }
  model.normal_restitution = in.real(id, "normal_restitution");
  model.tangential_restitution = in.real(id, "tangential_restitution");
  if (model.normal_restitution != 0)
    model.normal_restitution_at = written_value(in, id, "normal_restitution");
  if (model.tangential_restitution != 0)
    model.tangential_restitution_at = written_value(in, id, "tangential_restitution");
}

Gravity read_gravity(AttributeReader& in, fe::ObjectId root) {
  Gravity g;
  if (root == fe::kNoObject) return g;
  const fe::ObjectId field = in.object(root, "gravity");
  if (field == fe::kNoObject) return g;
  const fe::ObjectId vector = in.object(field, "vector");
  if (vector == fe::kNoObject) {
    g.kind = Gravity::Kind::NonUniform;
    return g;
  }
  g.kind = Gravity::Kind::Uniform;
  g.vector = {in.real(vector, "x"), in.real(vector, "y"), in.real(vector, "z")};
  in.require_finite_components(vector, "gravity is finite");
  return g;
}

}  // namespace openplx::snap
