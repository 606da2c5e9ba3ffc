#include "mjcf_emitter/viewer_defaults.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "mjcf_emitter/attribute_numbers.h"

namespace openplx::mjcf {
namespace {

// A geom as a bounding sphere in world coordinates, and whether it moves (its body or an ancestor has a
// joint). Planes and height fields (grounds) have none.
struct GeomBound {
  Eigen::Vector3d center;
  double radius;
  bool moving;
};

// What a body's mass properties say of its size, for mesh geoms (their vertices are in files): the
// circumradius of the box with the body's principal moments. 0 without an <inertial>.
double size_from_inertia(const Element& body) {
  for (const std::unique_ptr<Element>& e : body.children()) {
    if (e->name() != "inertial") continue;
    const std::vector<double> mass = attribute_numbers(*e, "mass");
    std::vector<double> moments = attribute_numbers(*e, "fullinertia");
    if (moments.empty()) moments = attribute_numbers(*e, "diaginertia");
    if (mass.size() != 1 || !(mass[0] > 0) || moments.size() < 3) return 0;
    return std::sqrt(std::max(0.0, 1.5 * (moments[0] + moments[1] + moments[2]) / mass[0]));
  }
  return 0;
}

// The radius of the sphere around a geom's frame that holds it; negative for unbounded shapes.
double geom_radius(const Element& geom, const Element& body) {
  const std::string type = geom.get("type") ? *geom.get("type") : "sphere";
  std::vector<double> s = attribute_numbers(geom, "size");
  s.resize(3, 0.0);
  if (type == "plane" || type == "hfield") return -1;
  if (type == "sphere") return s[0];
  if (type == "capsule") return s[0] + s[1];
  if (type == "cylinder") return std::hypot(s[0], s[1]);
  if (type == "box") return Eigen::Vector3d(s[0], s[1], s[2]).norm();
  if (type == "ellipsoid") return std::max({s[0], s[1], s[2]});
  return size_from_inertia(body);  // mesh
}

bool has_joint(const Element& body) {
  return std::any_of(body.children().begin(), body.children().end(),
                     [](const auto& e) { return e->name() == "joint" || e->name() == "freejoint"; });
}

// Every geom of the world and its bodies, in world coordinates.
std::vector<GeomBound> geom_bounds(const Element& world) {
  struct Frame {
    const Element* body;
    Eigen::Vector3d position;
    Eigen::Quaterniond rotation;
    bool moving;
  };
  std::vector<GeomBound> bounds;
  std::vector<Frame> stack{{&world, Eigen::Vector3d::Zero(), Eigen::Quaterniond::Identity(), false}};
  while (!stack.empty()) {
    const Frame f = stack.back();
    stack.pop_back();
    for (const std::unique_ptr<Element>& e : f.body->children()) {
      if (e->name() == "geom") {
        const double radius = geom_radius(*e, *f.body);
        if (radius < 0) continue;
        const Eigen::Vector3d local = attribute_vector(*e, "pos").value_or(Eigen::Vector3d::Zero());
        bounds.push_back({f.position + f.rotation * local, radius, f.moving});
      } else if (e->name() == "body") {
        const Eigen::Vector3d local = attribute_vector(*e, "pos").value_or(Eigen::Vector3d::Zero());
        const bool mocap = e->get("mocap") && *e->get("mocap") == "true";
        stack.push_back({e.get(), f.position + f.rotation * local, f.rotation * attribute_quat(*e),
                         !mocap && (f.moving || has_joint(*e))});
      }
    }
  }
  return bounds;
}

// <statistic center extent> as MuJoCo computes them (the centre of the bounding box, twice the farthest
// reach from it), over the moving geoms only when there are any.
void frame_the_machine(Element& mujoco, const Element& world) {
  std::vector<GeomBound> bounds = geom_bounds(world);
  if (std::any_of(bounds.begin(), bounds.end(), [](const GeomBound& b) { return b.moving; }))
    std::erase_if(bounds, [](const GeomBound& b) { return !b.moving; });
  if (bounds.empty()) return;
  Eigen::Vector3d low = Eigen::Vector3d::Constant(INFINITY), high = -low;
  for (const GeomBound& b : bounds) {
    low = low.cwiseMin(b.center - Eigen::Vector3d::Constant(b.radius));
    high = high.cwiseMax(b.center + Eigen::Vector3d::Constant(b.radius));
  }
  const Eigen::Vector3d center = (low + high) / 2;
  double reach = 0;
  for (const GeomBound& b : bounds) reach = std::max(reach, (b.center - center).norm() + b.radius);
  Element* statistic = mujoco.child("statistic");
  if (!statistic) statistic = &mujoco.add("statistic");
  if (!statistic->get("center")) statistic->set("center", center);
  // MuJoCo's own floor for a model of points (its default extent is 2).
  if (!statistic->get("extent")) statistic->set("extent", std::max(2 * reach, 0.01));
}

bool has_light(const Element& e) {
  if (e.name() == "light") return true;
  return std::any_of(e.children().begin(), e.children().end(), [](const auto& c) { return has_light(*c); });
}

// A directional light shining along gravity (straight down when there is none), above the machine.
void add_light(Element& mujoco, Element& world, const std::string& prefix) {
  Eigen::Vector3d down(0, 0, -1);
  if (const Element* option = mujoco.child("option")) {
    const std::optional<Eigen::Vector3d> g = attribute_vector(*option, "gravity");
    if (g && g->norm() > 0) down = g->normalized();
  }
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double extent = 1;
  if (const Element* statistic = mujoco.child("statistic")) {
    center = attribute_vector(*statistic, "center").value_or(center);
    const std::vector<double> e = attribute_numbers(*statistic, "extent");
    if (e.size() == 1) extent = e[0];
  }
  world.add("light")
      .set("name", prefix + "light")
      .set("directional", "true")
      .set("pos", Eigen::Vector3d(center - 2 * extent * down))
      .set("dir", down)
      .set("diffuse", "0.6 0.6 0.6")
      .set("specular", "0.2 0.2 0.2");
}

// Materials for geoms the model gives no colour, by what they are.
void colour_plain_geoms(Element& mujoco, const Element& world, const std::string& prefix) {
  const std::string visual_class = prefix + "visual";
  const std::string moving_name = prefix + "default.moving", static_name = prefix + "default.static",
                    visual_name = prefix + "default.visual";
  bool moving_used = false, static_used = false, visual_used = false;
  std::vector<std::pair<const Element*, bool>> stack{{&world, false}};
  while (!stack.empty()) {
    const auto [body, moving] = stack.back();
    stack.pop_back();
    for (const std::unique_ptr<Element>& e : body->children()) {
      if (e->name() == "body") {
        const bool mocap = e->get("mocap") && *e->get("mocap") == "true";
        stack.push_back({e.get(), !mocap && (moving || has_joint(*e))});
        continue;
      }
      if (e->name() != "geom" || e->get("material") || e->get("rgba")) continue;
      const bool visual = e->get("class") && *e->get("class") == visual_class;
      bool& used = visual ? visual_used : moving ? moving_used : static_used;
      e->set("material", visual ? visual_name : moving ? moving_name : static_name);
      used = true;
    }
  }
  if (!moving_used && !static_used && !visual_used) return;
  Element* assets = mujoco.child("asset");
  if (!assets) assets = &mujoco.add("asset");
  auto material = [&](const std::string& name, const char* rgba) {
    assets->add("material").set("name", name).set("rgba", rgba).set("specular", 0.3).set("shininess", 0.3);
  };
  if (moving_used) material(moving_name, "0.75 0.75 0.72 1");
  if (static_used) material(static_name, "0.38 0.4 0.43 1");
  if (visual_used) material(visual_name, "0.55 0.65 0.8 1");
}

}  // namespace

void add_viewer_defaults(Element& mujoco, const std::string& prefix, bool light) {
  Element* world = mujoco.child("worldbody");
  if (!world) return;
  frame_the_machine(mujoco, *world);
  if (light && !has_light(*world)) add_light(mujoco, *world, prefix);
  colour_plain_geoms(mujoco, *world, prefix);
}

}  // namespace openplx::mjcf
