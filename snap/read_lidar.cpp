#include "snap/read_lidar.h"

#include <algorithm>
#include <cmath>

namespace openplx::snap {
namespace fe = openplx::frontend;
namespace {

// Where the value of `object.name` was written: the assignment's own line (a user's), else `fallback`.
fe::SourceRange written_at(AttributeReader& in, fe::ObjectId object, std::string_view name,
                           fe::SourceRange fallback) {
  const fe::Slot* slot = in.graph().at(object).find(name);
  return slot && slot->binding.entry && slot->binding.entry->member ? slot->binding.entry->member->range
                                                                    : fallback;
}

// Rays of a horizontal sweep, in the connector's frame: azimuth about main_axis (z) from the normal (x),
// elevation from the x-y plane; resolutions are ray counts, spread over the fields of view inclusive.
std::vector<Eigen::Vector3d> sweep(AttributeReader& in, fe::ObjectId source) {
  auto angles = [&](const char* fov, const char* resolution) {
    const fe::ObjectId range = in.object(source, fov);
    const double lo = range == fe::kNoObject ? 0 : in.real(range, "x"),
                 hi = range == fe::kNoObject ? 0 : in.real(range, "y");
    // At most kMaxAxisRays per axis: the emitter keeps 4096 rays in all and says so; this only keeps a
    // resolution of millions from allocating them first.
    constexpr double kMaxAxisRays = 4096;
    const double given = in.real(source, resolution, 1);
    // A resolution is a ray count: none or fewer is no sweep, and quietly casting one ray would hide it.
    in.require(std::isfinite(given) && given >= 1, source, resolution, given,
               "a lidar's resolution is a ray count, 1 or more");
    const int n = std::isfinite(given) ? static_cast<int>(std::clamp(given, 1.0, kMaxAxisRays)) : 1;
    std::vector<double> out;
    for (int k = 0; k < n; ++k) out.push_back(n == 1 ? (lo + hi) / 2 : lo + (hi - lo) * k / (n - 1));
    return out;
  };
  std::vector<Eigen::Vector3d> rays;
  const std::vector<double> elevations = angles("vertical_fov", "vertical_resolution");
  const std::vector<double> azimuths = angles("horizontal_fov", "horizontal_resolution");  // read once
  for (double elevation : elevations) {
    for (double azimuth : azimuths) {
      rays.emplace_back(std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth),
                        std::sin(elevation));
    }
  }
  return rays;
}

}  // namespace

Lidar read_lidar(AttributeReader& in, fe::ObjectId id, fe::SourceRange where, fe::DiagnosticSink& sink) {
  Lidar lidar;
  lidar.object = id;
  lidar.path = in.graph().path(id);
  lidar.where = where;
  lidar.attachment = in.object(id, "mate_connector_attachment");
  const fe::ObjectId source = in.object(id, "ray_source");
  if (source != fe::kNoObject && in.graph().at(source).has("horizontal_fov")) {
    lidar.rays = sweep(in, source);
  } else {
    lidar.rays = {Eigen::Vector3d::UnitX()};  // no pattern given: one ray along the connector's normal
    lidar.default_pattern = true;
  }
  // AGX takes one detection-distance distortion; two is a configuration error.
  std::vector<std::string> distance_noises;
  for (fe::ObjectId d : in.objects(id, "sensing_distortions")) {
    if (in.type_name(d).find("LidarDetectionDistance") == std::string::npos) continue;
    distance_noises.push_back(in.graph().path(d));
    if (const fe::ObjectId g = in.object(d, "gaussian_distribution"); g != fe::kNoObject) {
      lidar.noise_mean = in.real(g, "mean");
      lidar.noise_deviation = in.real(g, "standard_deviation");
    }
    lidar.noise_slope = in.real(d, "standard_deviation_slope");
  }
  const fe::SourceRange distortions = written_at(in, id, "sensing_distortions", where);
  if (distance_noises.size() > 1) {
    std::string names;
    for (const std::string& n : distance_noises) names += (names.empty() ? "`" : ", `") + n + "`";
    sink.report(fe::DiagCode::InvalidSensor, distortions,
                "lidar `" + lidar.path + "` has " + std::to_string(distance_noises.size()) +
                    " detection-distance distortions (" + names +
                    "); a lidar takes at most one distance distortion");
  }
  for (fe::ObjectId d : in.objects(id, "ray_emission_distortions")) {
    const Eigen::Vector3d axis = in.vec3(d, "rotation_axis");
    const bool principal = (axis.array().abs() > 1e-12).count() == 1;
    sink.report(fe::DiagCode::MjcfUnmapped, written_at(in, id, "ray_emission_distortions", where),
                "`" + in.graph().path(d) + "` (ray emission noise" +
                    (principal ? "" : ", about an axis that is not a principal axis") +
                    ") has no MuJoCo counterpart: the rays are emitted undisturbed");
  }
  return lidar;
}

}  // namespace openplx::snap
