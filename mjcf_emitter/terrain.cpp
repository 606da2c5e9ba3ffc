// Lowering pass, terrains: a Terrain.Terrain becomes a static MuJoCo height field of its grid (flat, its
// surface at z = 0 of its frame, max_depth deep). Deformation, soil and shovels have no MuJoCo counterpart.
#include "mjcf_emitter/lowering.h"

namespace openplx::mjcf {

void Lowering::emit_terrains() {
  for (const sn::Terrain& t : system_.terrains) {
    constexpr double kMaxPoints = 1e7;  // 80 MB of heights in MuJoCo: beyond that, a typo, not a terrain
    if (t.num_x < 2 || t.num_y < 2 || !(t.element_size > 0) ||
        static_cast<double>(t.num_x) * t.num_y > kMaxPoints) {
      warn(t.where, "terrain `" + t.path +
                        "` needs from 2 x 2 to 10 million elements of positive size; it was "
                        "left out");
      continue;
    }
    warn(t.where, "terrain `" + t.path +
                      "` is a static height field here: its deformation, soil and material " +
                      "are not simulated");
    const std::string field = name(t.path);
    const double depth = t.max_depth > 0 ? t.max_depth : t.element_size;
    assets_->add("hfield")
        .set("name", field)
        .set("nrow", t.num_y)
        .set("ncol", t.num_x)
        .set("size", number((t.num_x - 1) * t.element_size / 2) + " " +
                         number((t.num_y - 1) * t.element_size / 2) + " " + number(depth) + " " +
                         number(depth));
    const sn::Transform parent = t.parent >= 0 ? snap_.node_world[t.parent] : sn::Transform{};
    const sn::Transform pose = natives::affine_compose(parent, t.local);
    world_->add("geom")
        .set("name", field)
        .set("type", "hfield")
        .set("hfield", field)
        .set("pos", pose.position)
        .set_quat("quat", pose.rotation);
  }
}

}  // namespace openplx::mjcf
