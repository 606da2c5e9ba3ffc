// Lowering pass, lidars: one MuJoCo rangefinder per ray, on a site at the lidar's connector turned so that
// its z axis is the ray (a rangefinder measures along its site's +z to the nearest geom of another body, -1
// when nothing is hit). A LidarOutput reads them all as one vector; its distance noise is the runtime's.
#include <algorithm>

#include "mjcf_emitter/lowering.h"

namespace openplx::mjcf {

namespace {
constexpr size_t kMaxRays = 4096;  // each ray is a site and a sensor: a dense scan would swamp the model

bool noisy(const sn::Lidar& lidar) {
  return lidar.noise_deviation != 0 || lidar.noise_mean != 0 || lidar.noise_slope != 0;
}
}  // namespace

void Lowering::emit_lidars() {
  for (size_t k = 0; k < system_.lidars.size(); ++k) {
    const sn::Lidar& lidar = system_.lidars[k];
    if (lidar.connector < 0) {
      warn(lidar.where,
           "lidar `" + lidar.path + "` has no mate_connector_attachment in the model; it was left out");
      continue;
    }
    if (lidar.default_pattern) {
      warn(lidar.where, "lidar `" + lidar.path +
                            "`'s ray source gives no ray pattern MuJoCo can read; it has one "
                            "ray, along its connector's normal");
    }
    if (noisy(lidar)) {
      warn(lidar.where, "lidar `" + lidar.path + "`'s distance noise (mean " + number(lidar.noise_mean) +
                            " m, deviation " + number(lidar.noise_deviation) + " m + " +
                            number(lidar.noise_slope) +
                            " per m of distance) is applied by the runtime (Simulation, SignalBridge, "
                            "openplx-sim) when its "
                            "output is read; MuJoCo does not apply it, so the bare MJCF's ranges are exact "
                            "(its rangefinders "
                            "record the deviation as `noise`)");
    }
    if (lidar.noise_deviation < 0 || lidar.noise_slope < 0) {
      warn(lidar.where,
           "lidar `" + lidar.path +
               "`'s distance noise has a negative standard_deviation or standard_deviation_slope; "
               "the runtime takes it as 0");
    }
    size_t rays = lidar.rays.size();
    if (rays > kMaxRays) {
      warn(lidar.where, "lidar `" + lidar.path + "` has " + std::to_string(rays) + " rays; the first " +
                            std::to_string(kMaxRays) + " were made rangefinders");
      rays = kMaxRays;
    }
    const auto [parent, frame] = connector_mount(lidar.connector);
    std::vector<std::string>& names = lidar_sensors_[static_cast<int>(k)];
    for (size_t r = 0; r < rays; ++r) {
      const std::string ray = name(lidar.path) + ".ray" + std::to_string(r);
      const Eigen::Vector3d direction = frame.rotation * lidar.rays[r].normalized();
      parent->add("site")
          .set("name", ray)
          .set("pos", frame.position)
          .set_quat("quat", Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), direction));
      Element& sensor = sensors_->add("rangefinder").set("name", ray).set("site", ray);
      if (lidar.noise_deviation > 0) sensor.set("noise", lidar.noise_deviation);
      names.push_back(ray);
    }
  }
}

// A LidarOutput: every ray's distance, in ray order (-1 where nothing is hit).
void Lowering::bind_lidar(SignalBinding& b, int k) {
  auto it = lidar_sensors_.find(k);
  if (b.input || it == lidar_sensors_.end())
    return unmapped(b, "lidar `" + system_.lidars[k].path + "` has no rangefinders");
  b.value = SignalValue::Vector;
  b.unit = "m";
  b.quantity = Quantity::SensorFields;
  b.object = MjObject::Sensor;
  b.names = it->second;
  b.initial_vector.assign(b.names.size(), 0.0);  // each rangefinder's single value
  const sn::Lidar& lidar = system_.lidars[k];
  if (noisy(lidar)) {  // one distance noise for every ray; the runtime applies it
    b.noise = {
        {lidar.noise_mean}, {std::max(0.0, lidar.noise_deviation)}, {std::max(0.0, lidar.noise_slope)}};
    b.runtime = true;
  }
}

}  // namespace openplx::mjcf
