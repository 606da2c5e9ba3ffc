// A model's fingerprint, written into its signal manifest so that a SignalBridge can tell whether the
// mjModel it is attached to is the model the manifest was emitted with. It covers the model's own bodies
// (with their parents) and joints (with their type and body), by name without the prefix, so that it holds
// when the file is <include>d into a bigger scene with other (differently prefixed) models and when the
// names carry another prefix than the one emitted. The emitter computes it from the MJCF document, the
// runtime from the compiled mjModel (struct fields only, no MuJoCo call); the document's version is
// mjcf_emitter/document_fingerprint.h.
//
// Text: "v1 bodies=B joints=J hash=H" (H: 16 hex digits, FNV-1a over the sorted lines "body NAME PARENT"
// and "joint NAME TYPE BODY", where PARENT is "-" for a body outside the model, e.g. the world).
#pragma once

#include <mujoco/mujoco.h>

#include <string>
#include <string_view>
#include <vector>

namespace openplx::mjcf {

struct Fingerprint {
  int bodies = 0, joints = 0;
  std::string hash;
  std::string text() const;
  // "v1 bodies=B joints=J hash=H" back; false when it is not one (another version, or damaged).
  static bool parse(std::string_view text, Fingerprint& out);
};

// The sorted lines a fingerprint hashes, collected by the emitter (from its document) and the runtime (from
// an mjModel) alike, so both hash the same way.
struct FingerprintLines {
  std::vector<std::string> lines;
  int bodies = 0, joints = 0;
  void body(std::string_view name, std::string_view parent);
  void joint(std::string_view name, std::string_view type, std::string_view body);
  Fingerprint finish();
};
// The part of `name` after `prefix`; false when `name` is empty or does not start with it.
bool strip_prefix(std::string_view name, std::string_view prefix, std::string_view& out);

// The elements of `m` whose names start with `prefix` (all named ones when it is empty). `bodies`, when
// given (m->nbody flags), keeps only the bodies it flags and their joints: without a prefix, a scene's
// other models can be left out by keeping only the body trees the manifest's own elements are in.
Fingerprint model_fingerprint(const mjModel* m, std::string_view prefix,
                              const std::vector<bool>* bodies = nullptr);

}  // namespace openplx::mjcf
