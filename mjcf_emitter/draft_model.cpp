#include "mjcf_emitter/draft_model.h"

#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>

namespace openplx::mjcf {

namespace fs = std::filesystem;

DraftModel::DraftModel(const Element& document, const std::string& dir, bool exact_mesh_volumes) {
  const fs::path folder = dir.empty() ? fs::temp_directory_path() : fs::path(dir);
  // The pid keeps processes apart, the counter threads and calls of one process.
  static std::atomic<unsigned> counter{0};
  const fs::path file = folder / (".openplx2mjcf-draft-" + std::to_string(::getpid()) + "-" +
                                  std::to_string(counter++) + ".xml");
  std::string text = document.to_string();
  // 2.2.2 takes mesh volumes from the meshes only with this flag (otherwise from an equivalent box).
  if (const size_t at = text.find("<compiler "); exact_mesh_volumes && at != std::string::npos)
    text.insert(at + 10, "exactmeshinertia=\"true\" ");
  mj_ = mujoco_library(error_);
  if (!mj_) return;
  std::ofstream(file) << text;
  char error[1000] = "";
  {
    MuJoCoMessages messages(*mj_);
    m_ = mj_->loadXML(file.c_str(), nullptr, error, sizeof(error));
    warnings_ = std::move(messages.warnings);
  }
  if (m_ && error[0]) warnings_.emplace_back(error);  // a warning the compiler kept
  std::error_code ec;
  fs::remove(file, ec);
  if (!m_) error_ = error;
}

DraftModel::~DraftModel() {
  if (m_) mj_->deleteModel(m_);
}

void DraftModel::write_inertials(const std::vector<Element*>& bodies) const {
  if (!m_) return;
  for (Element* body : bodies) {
    const std::string* name = body->get("name");
    const int id = name ? body_id(*name) : -1;
    if (id <= 0) continue;
    const mjtNum* pos = m_->body_ipos + 3 * id;
    const mjtNum* quat = m_->body_iquat + 4 * id;
    const mjtNum* inertia = m_->body_inertia + 3 * id;
    body->add("inertial")
        .set("pos", numbers({pos[0], pos[1], pos[2]}))
        .set("quat", number(quat[0]) + " " + number(quat[1]) + " " + number(quat[2]) + " " + number(quat[3]))
        .set("mass", m_->body_mass[id])
        .set("diaginertia", numbers({inertia[0], inertia[1], inertia[2]}));
  }
}

std::vector<double> DraftModel::mobilities(const std::vector<std::string>& joints) const {
  std::vector<double> out(joints.size(), 0.0);
  if (!m_) return out;
  MuJoCoMessages messages(*mj_);
  std::string error;
  mjData* d = nullptr;
  if (!messages.call(
          nullptr, [&] { d = mj_->makeData(m_); }, error) ||
      !d)
    return out;
  if (!messages.call(
          d, [&] { mj_->forward(m_, d); }, error)) {
    mj_->deleteData(d);
    return out;
  }
  std::vector<mjtNum> unit(static_cast<size_t>(m_->nv), 0.0), column(unit.size(), 0.0);
  for (size_t k = 0; k < joints.size(); ++k) {
    const int j = mj_->name2id(m_, mjOBJ_JOINT, joints[k].c_str());
    if (j < 0) continue;
    const size_t dof = static_cast<size_t>(m_->jnt_dofadr[j]);
    std::fill(unit.begin(), unit.end(), 0.0);
    unit[dof] = 1;
    mj_->solveM(m_, d, column.data(), unit.data(), 1);
    out[k] = column[dof];
  }
  mj_->deleteData(d);
  return out;
}

}  // namespace openplx::mjcf
