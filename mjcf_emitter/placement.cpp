#include "mjcf_emitter/placement.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <vector>

#include "mjcf_emitter/attribute_numbers.h"

namespace openplx::mjcf {
namespace {

Eigen::Vector3d moved_point(const Placement& p, const Eigen::Vector3d& x) {
  return p.position + p.rotation * x;
}

void move_point_attribute(Element& e, std::string_view key, const Placement& p, bool default_origin) {
  std::optional<Eigen::Vector3d> x = attribute_vector(e, key);
  if (!x && !default_origin) return;
  e.set(key, moved_point(p, x.value_or(Eigen::Vector3d::Zero())));
}

void rotate_direction_attribute(Element& e, std::string_view key, const Placement& p,
                                const Eigen::Vector3d& fallback) {
  e.set(key, Eigen::Vector3d(p.rotation * attribute_vector(e, key).value_or(fallback)));
}

// An element hanging from the world: its frame (pos, quat) or, for a capsule-like geom, its ends (fromto).
void move_world_child(Element& e, const Placement& p) {
  if (const std::vector<double> ends = attribute_numbers(e, "fromto"); ends.size() == 6) {
    const Eigen::Vector3d a = moved_point(p, {ends[0], ends[1], ends[2]});
    const Eigen::Vector3d b = moved_point(p, {ends[3], ends[4], ends[5]});
    e.set("fromto", numbers({a.x(), a.y(), a.z(), b.x(), b.y(), b.z()}));
    return;
  }
  move_point_attribute(e, "pos", p, true);
  if (e.name() == "light") {
    rotate_direction_attribute(e, "dir", p, Eigen::Vector3d(0, 0, -1));  // MuJoCo's default direction
    return;
  }
  e.set_quat("quat", p.rotation * attribute_quat(e));
}

// qpos and qvel addresses of the world's top-level free joints, numbered as MuJoCo numbers joints: body by
// body, depth first, in document order.
struct FreeJointAddress {
  int qpos, qvel;
};
std::vector<FreeJointAddress> top_level_free_joints(const Element& world) {
  std::vector<FreeJointAddress> free;
  int nq = 0, nv = 0;
  std::vector<std::pair<const Element*, bool>> stack{{&world, false}};
  while (!stack.empty()) {
    const auto [body, top_level] = stack.back();
    stack.pop_back();
    for (const std::unique_ptr<Element>& e : body->children()) {
      std::string type = e->name() == "freejoint" ? "free" : "";
      if (e->name() == "joint") type = e->get("type") ? *e->get("type") : "hinge";
      if (type.empty()) continue;
      if (type == "free") {
        if (top_level) free.push_back({nq, nv});
        nq += 7, nv += 6;
      } else if (type == "ball") {
        nq += 4, nv += 3;
      } else {
        nq += 1, nv += 1;
      }
    }
    const auto& children = body->children();
    for (auto it = children.rbegin(); it != children.rend(); ++it)
      if ((*it)->name() == "body") stack.push_back({it->get(), body == &world});
  }
  return free;
}

// A key's free-joint coordinates: qpos holds the world position and orientation, qvel the world linear
// velocity (its angular velocity is in the body's frame and stays).
void move_keyframes(Element& mujoco, const std::vector<FreeJointAddress>& free, const Placement& p) {
  Element* keyframe = mujoco.child("keyframe");
  if (!keyframe || free.empty()) return;
  for (const std::unique_ptr<Element>& key : keyframe->children()) {
    if (std::vector<double> qpos = attribute_numbers(*key, "qpos"); !qpos.empty()) {
      for (const FreeJointAddress& a : free) {
        const size_t i = static_cast<size_t>(a.qpos);
        if (i + 7 > qpos.size()) continue;
        const Eigen::Vector3d x = moved_point(p, {qpos[i], qpos[i + 1], qpos[i + 2]});
        Eigen::Quaterniond q =
            p.rotation * Eigen::Quaterniond(qpos[i + 3], qpos[i + 4], qpos[i + 5], qpos[i + 6]).normalized();
        if (q.w() < 0) q.coeffs() = -q.coeffs();
        const double moved[7] = {x.x(), x.y(), x.z(), q.w(), q.x(), q.y(), q.z()};
        std::copy(moved, moved + 7, qpos.begin() + static_cast<std::ptrdiff_t>(i));
      }
      std::string text;
      for (double v : qpos) (text.empty() ? text : text += ' ') += number(v);
      key->set("qpos", text);
    }
    if (std::vector<double> qvel = attribute_numbers(*key, "qvel"); !qvel.empty()) {
      for (const FreeJointAddress& a : free) {
        const size_t i = static_cast<size_t>(a.qvel);
        if (i + 6 > qvel.size()) continue;
        const Eigen::Vector3d v = p.rotation * Eigen::Vector3d(qvel[i], qvel[i + 1], qvel[i + 2]);
        for (int k = 0; k < 3; ++k) qvel[i + static_cast<size_t>(k)] = v[k];
      }
      std::string text;
      for (double v : qvel) (text.empty() ? text : text += ' ') += number(v);
      key->set("qvel", text);
    }
  }
}

bool is_world(const std::string* body) {
  return !body || *body == "world";
}

// Equality anchors in the world's frame: a connect's anchor is in body1's frame, a weld's in body2's (the
// world when body2 is left out).
void move_world_anchors(Element& mujoco, const Placement& p) {
  Element* equality = mujoco.child("equality");
  if (!equality) return;
  for (const std::unique_ptr<Element>& e : equality->children()) {
    const bool in_world = (e->name() == "connect" && is_world(e->get("body1"))) ||
                          (e->name() == "weld" && is_world(e->get("body2")));
    if (in_world) move_point_attribute(*e, "anchor", p, true);
  }
}

}  // namespace

std::optional<Placement> parse_placement(std::string_view text, std::string& error) {
  std::vector<double> values;
  const char* at = text.data();
  const char* end = at + text.size();
  while (at < end) {
    while (at < end && (*at == ' ' || *at == ',' || *at == '\t')) ++at;
    if (at == end) break;
    if (*at == '+') ++at;  // from_chars takes no leading '+'
    double v = 0;
    auto [next, ec] = std::from_chars(at, end, v);
    if (ec != std::errc() || !std::isfinite(v)) {
      error = "a pose is 'x y z' or 'x y z qw qx qy qz' (numbers), not '" + std::string(text) + "'";
      return std::nullopt;
    }
    values.push_back(v);
    at = next;
  }
  if (values.size() != 3 && values.size() != 7) {
    error = "a pose is 'x y z' or 'x y z qw qx qy qz' (3 or 7 numbers), not '" + std::string(text) + "'";
    return std::nullopt;
  }
  Placement p;
  p.position = Eigen::Vector3d(values[0], values[1], values[2]);
  if (values.size() == 7) {
    const Eigen::Quaterniond q(values[3], values[4], values[5], values[6]);
    if (!(q.norm() > 1e-9)) {
      error = "the pose's quaternion '" + std::string(text) + "' has no direction (all zero)";
      return std::nullopt;
    }
    p.rotation = q.normalized();
  }
  return p;
}

void place_model(Element& mujoco, const Placement& p) {
  Element* world = mujoco.child("worldbody");
  if (!world) return;
  move_keyframes(mujoco, top_level_free_joints(*world), p);
  for (const std::unique_ptr<Element>& e : world->children()) {
    const std::string& kind = e->name();
    if (kind == "body" || kind == "geom" || kind == "site" || kind == "camera" || kind == "light")
      move_world_child(*e, p);
  }
  move_world_anchors(mujoco, p);
  if (Element* statistic = mujoco.child("statistic")) move_point_attribute(*statistic, "center", p, false);
}

}  // namespace openplx::mjcf
