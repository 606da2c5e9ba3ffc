// From an .openplx file to a loaded MuJoCo model: the whole transpiler in-process (front end, resolved
// system, SNAP, MJCF emitter), then mj_loadXML. Mesh paths in the MJCF are absolute, so the XML may live
// anywhere.
#pragma once

#include <mujoco/mujoco.h>

#include <string>
#include <vector>

#include "contract/signal_binding.h"

namespace openplx::runtime {

struct LoadedModel {
  mjModel* model = nullptr;  // owned by the caller (mj_deleteModel)
  std::string root_name;
  std::string xml;
  std::vector<mjcf::SignalBinding> signals;
  std::vector<mjcf::RuntimeLaw> laws;
  std::vector<std::string> warnings;    // printed diagnostics, one each
  std::vector<std::string> files_read;  // every file read from disk: the model, imports, bundles, meshes
};

// Throws LoadError with the printed diagnostics when the model has errors or MuJoCo rejects the MJCF.
LoadedModel load_model(const std::string& path, const std::string& model,
                       const std::vector<std::string>& bundle_paths, double timestep,
                       bool default_bundles = true);

// The folders add_default_bundle_dir registered.
std::vector<std::string>& default_bundle_dirs();

}  // namespace openplx::runtime
