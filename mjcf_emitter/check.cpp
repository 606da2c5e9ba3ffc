#include "mjcf_emitter/check.h"

#include <mujoco/mujoco.h>

#include <cmath>

#include "mjcf_emitter/mujoco_library.h"
#include "mjcf_emitter/xml.h"

namespace openplx::mjcf {

CheckResult check_mjcf(const std::string& xml_path, const snap::ResolvedSystem& view,
                       const snap::SnapResult& snap, const std::string& prefix, const std::string& root_name,
                       double tolerance) {
  CheckResult result;
  const MuJoCoLibrary* mj = mujoco_library(result.load_error);
  if (!mj) return result;
  char error[1000] = "";
  mjModel* model = mj->loadXML(xml_path.c_str(), nullptr, error, sizeof(error));
  if (!model) {
    result.load_error = error;
    return result;
  }
  result.loaded = true;
  mjData* data = mj->makeData(model);
  mj->forward(model, data);
  for (size_t n = 0; n < view.nodes.size(); ++n) {
    const snap::FrameNode& node = view.nodes[n];
    if (node.kind != snap::FrameNode::Kind::Body) continue;
    const std::string name = prefix + (node.path.empty() ? root_name : node.path);
    const int id = mj->name2id(model, mjOBJ_BODY, name.c_str());
    if (id < 0) {
      result.problems.push_back("body " + name + " is missing from the MJCF");
      continue;
    }
    const Eigen::Vector3d pos(data->xpos[3 * id], data->xpos[3 * id + 1], data->xpos[3 * id + 2]);
    const Eigen::Quaterniond quat(data->xquat[4 * id], data->xquat[4 * id + 1], data->xquat[4 * id + 2],
                                  data->xquat[4 * id + 3]);
    const double dp = (pos - snap.node_world[n].position).norm();
    const double dq = quat.angularDistance(snap.node_world[n].rotation);
    result.max_position_error = std::max(result.max_position_error, dp);
    result.max_rotation_error = std::max(result.max_rotation_error, dq);
    if (dp > tolerance || dq > tolerance) {
      result.problems.push_back("body " + name + " is " + number(dp) + " m and " + number(dq) +
                                " rad away from its SNAP pose");
    }
  }
  // Equality residuals: the constraint rows' violations after mj_forward.
  for (int i = 0; i < data->nefc; ++i) {
    if (data->efc_type[i] != mjCNSTR_EQUALITY) continue;
    const double r = std::abs(data->efc_pos[i]);
    result.max_equality_residual = std::max(result.max_equality_residual, r);
    if (r > std::max(tolerance, 1e-7)) {
      const int eq = data->efc_id[i];
      const char* eq_name = mj->id2name(model, mjOBJ_EQUALITY, eq);
      result.problems.push_back(std::string("equality ") + (eq_name ? eq_name : std::to_string(eq)) +
                                " starts violated by " + number(r));
    }
  }
  mj->deleteData(data);
  mj->deleteModel(model);
  return result;
}

}  // namespace openplx::mjcf
