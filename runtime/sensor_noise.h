// Sensor noise as AGX defines it (a lidar's detection-distance noise, an IMU axis's Gaussian signal noise),
// added by the runtime when an output is read; MuJoCo 2.2.2 applies no sensor noise itself.
//
// Every draw is a pure function of (seed, MuJoCo sensor name, field, mjData time): no generator state is
// kept, so reading an output twice in a step gives the same value, the values do not depend on which other
// outputs were read or in which order, and two outputs reading the same sensor axis agree. The generator is
// SplitMix64 (Steele, Lea and Flood, "Fast splittable pseudorandom number generators", 2014), specified here
// bit for bit, and the normal deviate is Box-Muller's cos branch: the bytes depend on no standard library's
// distributions, only on std::log and std::cos (the same C library gives the same bytes; another one may
// round their last bit differently).
#pragma once

#include <mujoco/mujoco.h>

#include <cstdint>
#include <string_view>
#include <vector>

#include "contract/signal_binding.h"
#include "openplx/runtime/signals.h"

namespace openplx::runtime {

// One step of SplitMix64 from state `x` (the state advanced by the golden gamma, then mixed).
std::uint64_t splitmix64(std::uint64_t x);
// FNV-1a (64 bit) of a name: a sensor's stream, the same in every process.
std::uint64_t fnv1a64(std::string_view text);
// A standard normal deviate drawn from `key`: the first two outputs of SplitMix64 started at `key`, as
// uniforms in (0, 1), then Box-Muller.
double standard_normal(std::uint64_t key);
// The key of sensor `name`'s field `field` read at time `time` under `seed`.
std::uint64_t noise_key(std::uint64_t seed, std::string_view name, int field, double time);

// Adds binding `b`'s noise to `values` (`count` of them, value k read from sensor ids[k], field
// b.initial_vector[k]) as read at time `time`. Nothing when the noise is off or the binding has none. A
// rangefinder's miss (negative) stays as it is and a noisy distance is at least 0.
void add_sensor_noise(const SensorNoiseOptions& options, const mjcf::SignalBinding& b, const mjModel* m,
                      const std::vector<int>& ids, double time, double* values, int count);

}  // namespace openplx::runtime
