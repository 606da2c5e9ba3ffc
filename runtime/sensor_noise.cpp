#include "runtime/sensor_noise.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace openplx::runtime {

std::uint64_t splitmix64(std::uint64_t x) {
  std::uint64_t z = x + 0x9e3779b97f4a7c15ULL;  // the golden gamma
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

std::uint64_t fnv1a64(std::string_view text) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (char c : text) {
    h ^= static_cast<unsigned char>(c);
    h *= 0x100000001b3ULL;
  }
  return h;
}

double standard_normal(std::uint64_t key) {
  // The top 53 bits, offset by half a unit: uniform in (0, 1), never 0, so the logarithm is finite.
  auto uniform = [](std::uint64_t bits) { return (static_cast<double>(bits >> 11) + 0.5) * 0x1.0p-53; };
  // The first two outputs of SplitMix64's stream started at `key` (its state advances by the golden gamma).
  constexpr std::uint64_t kGamma = 0x9e3779b97f4a7c15ULL;
  const double u1 = uniform(splitmix64(key)), u2 = uniform(splitmix64(key + kGamma));
  constexpr double kTwoPi = 6.283185307179586476925286766559;
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(kTwoPi * u2);
}

std::uint64_t noise_key(std::uint64_t seed, std::string_view name, int field, double time) {
  std::uint64_t time_bits;
  static_assert(sizeof time_bits == sizeof time);
  std::memcpy(&time_bits, &time, sizeof time);
  std::uint64_t k = splitmix64(seed);
  k = splitmix64(k ^ fnv1a64(name));
  k = splitmix64(k ^ static_cast<std::uint64_t>(field));
  return splitmix64(k ^ time_bits);
}

void add_sensor_noise(const SensorNoiseOptions& options, const mjcf::SignalBinding& b, const mjModel* m,
                      const std::vector<int>& ids, double time, double* values, int count) {
  const mjcf::SignalNoise& n = b.noise;
  if (!options.enabled || n.empty()) return;
  // The manifest reader checked each list holds one number for all values or one per value.
  auto at = [](const std::vector<double>& list, size_t k) {
    return list.empty() ? 0.0 : list[list.size() == 1 ? 0 : k];
  };
  const size_t values_read = std::min(
      {static_cast<size_t>(std::max(count, 0)), ids.size(), b.names.size(), b.initial_vector.size()});
  for (size_t k = 0; k < values_read; ++k) {
    const bool range = m->sensor_type[ids[k]] == mjSENS_RANGEFINDER;
    double& x = values[k];
    if (range && x < 0) continue;  // no hit: nothing to disturb
    const double deviation = at(n.deviation, k) + at(n.deviation_per_metre, k) * std::abs(x);
    const int field = static_cast<int>(b.initial_vector[k]);
    x += at(n.mean, k) + deviation * standard_normal(noise_key(options.seed, b.names[k], field, time));
    if (range) x = std::max(x, 0.0);  // a negative distance would read as a miss
  }
}

}  // namespace openplx::runtime
