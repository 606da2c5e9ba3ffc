// Reads a signal manifest (manifest_json's format) back into bindings and laws, for bridges on models
// the runtime did not load itself.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "contract/signal_binding.h"

namespace openplx::mjcf {

struct Manifest {
  std::string model;        // the root model's name
  std::string prefix;       // the prefix its MuJoCo names were emitted with
  std::string fingerprint;  // Fingerprint text; "" in manifests written before it existed
  int format_version = 0;   // kManifestFormatVersion it was written in; 0: written before it existed
  double timestep = 0;      // the time step the model was emitted for; 0: not recorded
  std::string mujoco;       // the MuJoCo its numbers are for ("2.2.2", "3"); "": not recorded
  // Whether the emitter's stability choices follow `timestep` (true when not recorded), and which.
  bool timestep_dependent = true;
  std::vector<std::string> timestep_choices;
  std::vector<SignalBinding> signals;
  std::vector<RuntimeLaw> laws;
};

// A manifest that cannot be used; what() is "PATH: error: ...\n" (the runtime passes it on as a LoadError).
class ManifestError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Throws ManifestError("PATH: error: ...") when the file cannot be read or is not a manifest (a field
// missing or of the wrong JSON type, named with its signal's or law's path), when its format_version is no
// whole number from 1 to what this runtime reads (kManifestFormatVersion), when one signal path is listed
// twice, when a signal's value kind is not one its quantity gives or takes, and when a
// binding or law is inconsistent in itself (a quantity on the wrong kind of element or value, no names
// where the runtime needs one, a non-finite number where it computes with it, a torque converter without
// its two actuators...), naming the signal or law.
Manifest read_manifest(const std::string& path);
// The same from text (`path` only names it in messages).
Manifest parse_manifest(const std::string& text, const std::string& path);

}  // namespace openplx::mjcf
