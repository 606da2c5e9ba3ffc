// The converter needs MuJoCo only to compile a draft (mesh mass properties, soft equalities) and for
// --check. Loading libmujoco then, instead of at process start, spares every other conversion the time
// MuJoCo and its dependencies take to map and relocate (about as long as a small model's whole conversion).
// Programs that link MuJoCo themselves (the runtime, openplx-sim) get the library they already have.
#pragma once

#include <mujoco/mujoco.h>

#include <string>

namespace openplx::mjcf {

struct MuJoCoLibrary {
  decltype(&mj_loadXML) loadXML = nullptr;
  decltype(&mj_deleteModel) deleteModel = nullptr;
  decltype(&mj_makeData) makeData = nullptr;
  decltype(&mj_deleteData) deleteData = nullptr;
  decltype(&mj_forward) forward = nullptr;
  decltype(&mj_name2id) name2id = nullptr;
  decltype(&mj_id2name) id2name = nullptr;
};

// Loaded on first use; nullptr when it cannot be, with `error` saying why.
const MuJoCoLibrary* mujoco_library(std::string& error);

}  // namespace openplx::mjcf
