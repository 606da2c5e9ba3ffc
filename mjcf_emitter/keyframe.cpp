// Lowering pass, the initial state: <keyframe><key name="initial"> with free bodies' initial velocities and
// every actuator's initial control (motor targets, spring rests, force motors' default efforts).
#include "mjcf_emitter/lowering.h"

namespace openplx::mjcf {

using natives::affine_compose;
using natives::affine_inverse;

// Free bodies' initial velocities as keyframe "initial" (MJCF has no initial velocity; MuJoCo fills the
// key's qpos with qpos0). The runtime starts from it; MuJoCo users call mj_resetDataKeyframe. OpenPLX gives
// both velocities in the owning system's frame; a free joint's qvel is the world linear velocity, then the
// angular velocity in the body's frame.
void Lowering::emit_initial_state(Element& root) {
  std::vector<double> ctrl(actuator_count_, 0.0);
  for (const auto& [interaction, control] : actuator_ctrl_)
    ctrl[static_cast<size_t>(control.first)] = control.second;
  for (const auto& [index, control] : drive_ctrl_) ctrl[static_cast<size_t>(index)] = control;
  const bool moving = !initial_velocities_.empty();
  if ((!moving && ctrl.empty()) || !options_.keyframe) return;
  Element& key = root.add("keyframe").add("key").set("name", name("initial"));  // prefixed: scenes merge
  if (moving) key.set("qvel", joined(initial_qvel()));
  if (!ctrl.empty()) key.set("ctrl", joined(ctrl));
}

// Free bodies' initial velocities, as the key's qvel.
std::vector<double> Lowering::initial_qvel() {
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
    const sn::FrameNode& n = system_.nodes[node];
    const Eigen::Matrix3d system =
        n.parent >= 0 ? snap_.node_world[n.parent].rotation.toRotationMatrix() : Eigen::Matrix3d::Identity();
    const Eigen::Matrix3d body = snap_.node_world[node].rotation.toRotationMatrix();
    const Eigen::Vector3d linear = system * n.body.initial_linear_velocity;
    const Eigen::Vector3d angular = body.transpose() * (system * n.body.initial_angular_velocity);
    const size_t at = static_cast<size_t>(dof_address.at(body_element_.at(node)));
    for (int k = 0; k < 3; ++k) {
      qvel[at + k] = linear[k];
      qvel[at + 3 + k] = angular[k];
    }
  }
  return qvel;
}

std::string Lowering::joined(const std::vector<double>& values) {
  std::string text;
  for (double v : values) {
    if (!text.empty()) text += ' ';
    append_number(text, v);
  }
  return text;
}

}  // namespace openplx::mjcf
