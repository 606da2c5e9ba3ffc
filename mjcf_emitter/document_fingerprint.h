// The fingerprint of an emitted MJCF document (contract/model_fingerprint.h says what it covers), written
// into the signal manifest; the runtime computes the same from the compiled mjModel.
#pragma once

#include <string_view>

#include "contract/model_fingerprint.h"
#include "mjcf_emitter/xml.h"

namespace openplx::mjcf {

// `document`: the emitted <mujoco> element; `prefix`: the one its names carry.
Fingerprint model_fingerprint(const Element& document, std::string_view prefix);

}  // namespace openplx::mjcf
