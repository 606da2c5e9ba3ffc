// The emitted document compiled by MuJoCo 2.2.2 for numbers only MuJoCo's compiler knows: the mass
// properties of bodies whose mass comes from meshes, and bodies' inverse inertia estimates (body_invweight0)
// for soft equalities. Mesh volumes are exact (the draft alone sets `exactmeshinertia`) or, for URDF links
// without <inertial>, MuJoCo's default legacy formula, as its URDF importer takes them: 2.2.2 sets the law
// for a whole model, so those get a draft of their own. The output carries explicit inertials instead, so
// it needs no flag that MuJoCo 3.2.5 removed, and loads with the same masses in MuJoCo 3.
#pragma once

#include <mujoco/mujoco.h>

#include <string>
#include <vector>

#include "mjcf_emitter/mujoco_library.h"
#include "mjcf_emitter/xml.h"

namespace openplx::mjcf {

class DraftModel {
 public:
  // Writes `document` into `dir` (so relative mesh paths resolve; empty: the temp folder) and loads it, with
  // exact mesh volumes or MuJoCo 2.2.2's default ones.
  DraftModel(const Element& document, const std::string& dir, bool exact_mesh_volumes = true);
  ~DraftModel();
  DraftModel(const DraftModel&) = delete;
  DraftModel& operator=(const DraftModel&) = delete;

  const mjModel* model() const { return m_; }
  int body_id(const std::string& name) const { return mj_->name2id(m_, mjOBJ_BODY, name.c_str()); }
  int joint_id(const std::string& name) const { return mj_->name2id(m_, mjOBJ_JOINT, name.c_str()); }
  const std::string& error() const { return error_; }  // why it did not load
  // What MuJoCo said while compiling it (kept, never written to MUJOCO_LOG.TXT).
  const std::vector<std::string>& warnings() const { return warnings_; }

  // Writes <inertial pos quat mass diaginertia> with the draft's mass properties into each body element
  // (found by its name attribute).
  void write_inertials(const std::vector<Element*>& bodies) const;
  // Per joint (by name): (M^-1)_jj of its first degree of freedom at the initial pose, how far a unit force
  // there accelerates it with the whole model moving along; 0 for a joint the draft lacks.
  std::vector<double> mobilities(const std::vector<std::string>& joints) const;

 private:
  const MuJoCoLibrary* mj_ = nullptr;  // loaded by the first draft
  mjModel* m_ = nullptr;
  std::string error_;
  std::vector<std::string> warnings_;
};

}  // namespace openplx::mjcf
