// Reads a signal manifest (mjcf::manifest_json's format) back into bindings and laws, for bridges on models
// the runtime did not load itself.
#pragma once

#include <string>
#include <vector>

#include "mjcf_emitter/signal_binding.h"

namespace openplx::runtime {

struct Manifest {
  std::string model;   // the root model's name
  std::string prefix;  // the prefix its MuJoCo names were emitted with
  std::vector<mjcf::SignalBinding> signals;
  std::vector<mjcf::RuntimeLaw> laws;
};

// Throws LoadError("PATH: error: ...") when the file cannot be read or is not a manifest.
Manifest read_manifest(const std::string& path);

}  // namespace openplx::runtime
