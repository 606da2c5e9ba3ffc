// What a viewer (mujoco-simulate, MuJoCo's renderer) needs and the physics does not: a light when the model
// has none and `light` asks for one (a file made for a bigger scene leaves lighting to the scene, else every
// included file's light adds to the scene's and the scene is over-lit), <statistic center extent> framing the
// machine (MuJoCo's own framing takes every geom, so a 100 m ground leaves the machine a few pixels), and a
// material for each geom the model gives no colour: moving collision geometry a light neutral grey, static
// geometry (grounds, fixed bases) a darker one, visual geometry without a material a blue-grey. Geoms with a
// material or rgba keep theirs.
#pragma once

#include <string>

#include "mjcf_emitter/xml.h"

namespace openplx::mjcf {

// `prefix` names the light and the materials (scenes include several prefixed copies).
void add_viewer_defaults(Element& mujoco, const std::string& prefix, bool light);

}  // namespace openplx::mjcf
