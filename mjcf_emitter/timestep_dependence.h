// Which of the emitter's stability choices follow the time step it emitted for (EmitOptions::timestep), read
// off the finished document and laws: a scene stepping at another time step runs those outside the range
// they were set for, so the manifest records them and a SignalBridge warns only when there are any.
#pragma once

#include <string>
#include <vector>

#include "contract/signal_binding.h"
#include "mjcf_emitter/xml.h"

namespace openplx::mjcf {

// One short phrase per kind of element that carries a time-step choice, with how many and how it follows the
// time step h ("hard limits (2, solreflimit 2h)"), in a fixed order;
// empty when the model has none (its MJCF means the same at any time step MuJoCo integrates stably).
std::vector<std::string> timestep_choices(const Element& document, const std::vector<RuntimeLaw>& laws);

}  // namespace openplx::mjcf
