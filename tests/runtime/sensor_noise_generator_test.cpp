// The sensor-noise generator: SplitMix64 and FNV-1a give their published values (so the bytes are the same
// with any standard library), and the normal deviates have a standard normal's moments and tail.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "runtime/sensor_noise.h"

namespace {

namespace rt = openplx::runtime;

// SplitMix64 started at 0 (its reference implementation by Vigna): e220a8397b1dcdaf, then 6e789e6aa1b965f4.
// FNV-1a 64: the offset basis for "", and the published value for "a".
TEST(SensorNoiseGenerator, PublishedValues) {
  EXPECT_EQ(rt::splitmix64(0), 0xe220a8397b1dcdafULL);
  EXPECT_EQ(rt::splitmix64(0x9e3779b97f4a7c15ULL), 0x6e789e6aa1b965f4ULL);
  EXPECT_EQ(rt::fnv1a64(""), 0xcbf29ce484222325ULL);
  EXPECT_EQ(rt::fnv1a64("a"), 0xaf63dc4c8601ec8cULL);
}

// 200,000 deviates from consecutive keys. Standard errors: mean 1 / sqrt(n) = 0.0022, variance sqrt(2 / n) =
// 0.0032, fourth moment sqrt(96 / n) = 0.022 (E z^8 - (E z^4)^2 = 105 - 9); the share beyond 2 (0.0455)
// sqrt(p (1 - p) / n) = 0.00047. Each is held to 5 standard errors.
TEST(SensorNoiseGenerator, StandardNormalMoments) {
  constexpr int n = 200000;
  double m1 = 0, m2 = 0, m4 = 0, beyond2 = 0;
  for (int k = 0; k < n; ++k) {
    const double z = rt::standard_normal(rt::noise_key(0, "lidar.ray0", 0, k * 0.002));
    ASSERT_TRUE(std::isfinite(z));
    m1 += z;
    m2 += z * z;
    m4 += z * z * z * z;
    beyond2 += std::abs(z) > 2;
  }
  EXPECT_NEAR(m1 / n, 0, 5 * 0.0022);
  EXPECT_NEAR(m2 / n, 1, 5 * 0.0032);
  EXPECT_NEAR(m4 / n, 3, 5 * 0.022);
  EXPECT_NEAR(beyond2 / n, 0.0455, 5 * 0.00047);
}

// Keys differ with each of their parts.
TEST(SensorNoiseGenerator, EveryPartOfTheKeyCounts) {
  const std::uint64_t key = rt::noise_key(1, "imu.gyroscope", 0, 0.004);
  EXPECT_NE(key, rt::noise_key(2, "imu.gyroscope", 0, 0.004));
  EXPECT_NE(key, rt::noise_key(1, "imu.accelerometer", 0, 0.004));
  EXPECT_NE(key, rt::noise_key(1, "imu.gyroscope", 1, 0.004));
  EXPECT_NE(key, rt::noise_key(1, "imu.gyroscope", 0, 0.006));
  EXPECT_EQ(key, rt::noise_key(1, "imu.gyroscope", 0, 0.004));
}

}  // namespace
