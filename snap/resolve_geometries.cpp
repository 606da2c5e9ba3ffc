// Geometries (shapes, sizes, meshes, files), the materials they and contact models share, and collision
// groups.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>

#include "frontend/urdf/package_uri.h"
#include "snap/system_builder.h"

namespace openplx::snap::detail {

void SystemBuilder::add_geometry(fe::ObjectId id, int owner) {
  const fe::Object& obj = ev_.graph().at(id);
  Geometry g;
  g.object = id;
  g.visual = is(obj, visual_geometry_);
  g.owner = owner;
  g.path = path_of(id);
  g.where = where_of(id);
  for (const auto& [model, shape] : shapes_) {
    if (obj.type->is_subtype_of(model)) g.shape = shape;
  }
  if (std::optional<Transform> t = transform_of(id, std::string_view("local_transform"))) g.local = *t;
  // A size is finite and 0 or more (0: the emitter leaves the geometry out, warned).
  auto size = [&](std::string_view name) {
    const double v = real(id, name);
    in_.require(std::isfinite(v) && v >= 0, id, name, v, "a geometry's size is a finite number, 0 or more");
    return v;
  };
  switch (g.shape) {
    case Geometry::Shape::Box:
      g.size = vec3(id, "size");
      if (!(g.size.allFinite() && g.size.minCoeff() >= 0)) {
        const fe::ObjectId v = object(id, "size");
        for (const char* axis : {"x", "y", "z"}) {
          const double c = v == fe::kNoObject ? 0 : real(v, axis);
          in_.require(std::isfinite(c) && c >= 0, v, axis, c, "a box's size is finite and 0 or more");
        }
      }
      break;
    case Geometry::Shape::Sphere:
      g.size.x() = size("radius");
      break;
    case Geometry::Shape::Cylinder:
    case Geometry::Shape::Capsule:
      g.size = {size("radius"), size("height"), 0.0};
      break;
    case Geometry::Shape::ConvexMesh:
    case Geometry::Shape::TriMesh:
      read_mesh_data(id, g);
      break;
    default:
      break;
  }
  if (const fe::Value* path = ev_.value(id, "path"); path && path->kind == fe::Value::Kind::String) {
    g.file = path->string_value();
  }
  if (const fe::Value* uri = ev_.value(id, "package_uri"); uri && uri->kind == fe::Value::Kind::String) {
    g.package_uri = uri->string_value();
  }
  if (const fe::Value* scale = ev_.value(id, "scale"); scale && scale->kind == fe::Value::Kind::Object) {
    g.scale = vec3(id, "scale");
  } else if (scale && scale->is_number()) {
    g.scale = Eigen::Vector3d::Constant(scale->as_real());
  }
  geometry_materials_.push_back(object(id, "material"));
  if (const fe::Value* c = ev_.value(id, "enable_collisions"); c && c->kind == fe::Value::Kind::Bool)
    g.collides = c->bool_value;
  if (const fe::Value* m = ev_.value(id, "include_in_mass_properties");
      m && m->kind == fe::Value::Kind::Bool) {
    g.in_mass = m->bool_value;
  }
  if (g.visual) g.collides = g.in_mass = false;
  system_.geometries.push_back(std::move(g));
}

// ConvexMesh/TriMesh vertices (Math.Vec3 instances) and TriMesh triangle indices.
void SystemBuilder::read_mesh_data(fe::ObjectId id, Geometry& g) {
  if (const fe::Value* v = ev_.value(id, "vertices"); v && v->kind == fe::Value::Kind::Array) {
    for (const fe::Value& item : v->array()) {
      if (item.kind != fe::Value::Kind::Object) continue;
      Eigen::Vector3d p;
      const char* axes[] = {"x", "y", "z"};
      for (int i = 0; i < 3; ++i) {
        const fe::Value* c = ev_.value(item.object, axes[i]);
        p[i] = c && c->is_number() ? c->as_real() : 0.0;
      }
      g.vertices.push_back(p);
    }
  }
  if (const fe::Value* v = ev_.value(id, "indices"); v && v->kind == fe::Value::Kind::Array) {
    for (const fe::Value& item : v->array()) {
      if (item.kind == fe::Value::Kind::Int) g.indices.push_back(static_cast<int>(item.int_value));
    }
  }
}

// A URDF mesh named `package://P/rest` is read from `<path>/rest` when the model declares a
// Urdf.PackagePath named P (anywhere: in the scene or in the robot); otherwise from where the import found
// P.
void SystemBuilder::resolve_packages() {
  for (Geometry& g : system_.geometries) {
    const std::optional<fe::PackageUri> uri = fe::parse_package_uri(g.package_uri);
    auto it = uri ? packages_.find(uri->package) : packages_.end();
    if (it == packages_.end()) continue;
    g.file = (std::filesystem::path(it->second) / uri->inside).lexically_normal().generic_string();
  }
}

// Materials by index, shared by geometries and contact models (the same material, the same index).
int SystemBuilder::material_index(fe::ObjectId id) {
  if (id == fe::kNoObject) return -1;
  auto [it, fresh] = material_of_.try_emplace(id, static_cast<int>(system_.materials.size()));
  if (fresh) {
    const double density = in_.real(id, "density", 1000.0);
    in_.require(std::isfinite(density) && density >= 0, id, "density", density,
                "a density is a finite number of kg/m^3, 0 or more");
    system_.materials.push_back({id, density, where_of(id)});
  }
  return it->second;
}

// Geometries' materials: a contact material by index, a visual one as its visual material.
void SystemBuilder::resolve_materials() {
  std::unordered_map<fe::ObjectId, int> visual;
  for (size_t k = 0; k < system_.visual_materials.size(); ++k)
    visual[system_.visual_materials[k].object] = static_cast<int>(k);
  for (size_t k = 0; k < system_.geometries.size(); ++k) {
    Geometry& g = system_.geometries[k];
    g.material = material_index(geometry_materials_[k]);
    if (auto it = visual.find(geometry_materials_[k]); it != visual.end()) g.visual_material = it->second;
  }
}

// A Simulation.CollisionGroup's lists as nodes and geometries of this system.
CollisionGroup SystemBuilder::collision_group(fe::ObjectId group) {
  CollisionGroup out;
  if (group == fe::kNoObject) return out;
  for (fe::ObjectId body : in_.objects(group, "bodies"))
    if (auto it = node_of_.find(body); it != node_of_.end()) out.bodies.push_back(it->second);
  for (fe::ObjectId system : in_.objects(group, "systems"))
    if (auto it = node_of_.find(system); it != node_of_.end()) out.systems.push_back(it->second);
  const std::vector<fe::ObjectId> listed = in_.objects(group, "geometries");
  for (size_t k = 0; k < system_.geometries.size(); ++k) {
    if (std::find(listed.begin(), listed.end(), system_.geometries[k].object) != listed.end())
      out.geometries.push_back(static_cast<int>(k));
  }
  return out;
}

}  // namespace openplx::snap::detail
