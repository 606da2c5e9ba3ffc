// An IMU's Gaussian signal noise (Sensors.<Sensor>SignalGaussianNoise: one distribution per axis, 0.20.2's
// models) applied by the runtime: every axis's readings have the model's mean and deviation, the same seed
// gives the same bytes through Simulation and SignalBridge, off reads MuJoCo's values, and spectral noise,
// which nothing applies, is a warning at its line.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "openplx/runtime/signal_bridge.h"
#include "openplx/runtime/simulation.h"
#include "tests/support/converted_model.h"
#include "tests/support/sample_statistics.h"
#include "tests/support/scratch_dir.h"
#include "tools/cli/cli.h"

namespace {

namespace fs = std::filesystem;
namespace rt = openplx::runtime;
using openplx::testing::sample_statistics;
using openplx::testing::ScratchDir;

constexpr int kReadings = 10000;

// An IMU at rest on a world connector: its accelerometer has noise on every axis, its gyroscope on x only,
// its magnetometer spectral noise (line 30), which nothing applies. Fields: accelerometer x, y, z, gyroscope
// x, magnetometer z.
const char kModel[] =
    "Scene is Physics3D.System:\n"
    "    mount is Physics3D.Interactions.MateConnector:\n"
    "        position: {0, 0, 1}\n"
    "        main_axis: Math.Vec3.Z_AXIS()\n"
    "        normal: Math.Vec3.X_AXIS()\n"
    "    imu is Sensors.IMULogic:\n"
    "        mate_connector_attachment: mount\n"
    "        accelerometer is Sensors.AccelerometerLogic:\n"
    "            mate_connector_attachment: mount\n"
    "            shake is Sensors.AccelerometerSignalGaussianNoise:\n"
    "                distribution_x.mean: 0.1\n"
    "                distribution_x.standard_deviation: 0.01\n"
    "                distribution_y.mean: -0.2\n"
    "                distribution_y.standard_deviation: 0.02\n"
    "                distribution_z.mean: 0.3\n"
    "                distribution_z.standard_deviation: 0.05\n"
    "            sensing_distortions: [imu.accelerometer.shake]\n"
    "        gyroscope is Sensors.GyroscopeLogic:\n"
    "            mate_connector_attachment: mount\n"
    "            drift is Sensors.GyroscopeSignalGaussianNoise:\n"
    "                distribution_x.mean: 0.01\n"
    "                distribution_x.standard_deviation: 0.002\n"
    "                distribution_y.mean: 0\n"
    "                distribution_y.standard_deviation: 0\n"
    "                distribution_z.mean: 0\n"
    "                distribution_z.standard_deviation: 0\n"
    "            sensing_distortions: [imu.gyroscope.drift]\n"
    "        magnetometer is Sensors.MagnetometerLogic:\n"
    "            mate_connector_attachment: mount\n"
    "            hiss is Sensors.MagnetometerSignalSpectralGaussianNoise:\n"
    "                noise_density_x: 0.001\n"
    "                noise_density_y: 0.001\n"
    "                noise_density_z: 0.001\n"
    "            sensing_distortions: [imu.magnetometer.hiss]\n"
    "    readings is Sensors.Signals.IMUOutput:\n"
    "        source: imu\n"
    "        fields: [{Sensors.Signals.TriaxialOutputField.X_F64, imu.accelerometer},\n"
    "                 {Sensors.Signals.TriaxialOutputField.Y_F64, imu.accelerometer},\n"
    "                 {Sensors.Signals.TriaxialOutputField.Z_F64, imu.accelerometer},\n"
    "                 {Sensors.Signals.TriaxialOutputField.X_F64, imu.gyroscope},\n"
    "                 {Sensors.Signals.TriaxialOutputField.Z_F64, imu.magnetometer}]\n";

constexpr int kFields = 5;
// Per field: the mean and deviation the model gives (the magnetometer's spectral noise is not applied).
constexpr std::array<double, kFields> kMean = {0.1, -0.2, 0.3, 0.01, 0};
constexpr std::array<double, kFields> kDeviation = {0.01, 0.02, 0.05, 0.002, 0};

fs::path write_model(const ScratchDir& dir) {
  std::ofstream(dir / "imu.openplx") << kModel;
  return dir / "imu.openplx";
}

// Each step's readings, noisy and (the same output read with the noise off) exact, field by field.
struct Series {
  std::vector<double> noisy, exact;
};

Series run_simulation(const fs::path& file, std::uint64_t seed, int steps = kReadings) {
  rt::LoadOptions options;
  options.sensor_noise.seed = seed;
  rt::Simulation sim = rt::Simulation::load(file.string(), options);
  rt::Output readings = sim.output("readings");
  Series s;
  for (int k = 0; k < steps; ++k) {
    sim.step();
    const Eigen::VectorXd v = readings.vector();
    sim.set_sensor_noise({false, seed});
    const Eigen::VectorXd exact = readings.vector();
    sim.set_sensor_noise({true, seed});
    for (int f = 0; f < kFields; ++f) {
      s.noisy.push_back(v[f]);
      s.exact.push_back(exact[f]);
    }
  }
  return s;
}

Series run_bridge(const ScratchDir& dir, const fs::path& file, const rt::SensorNoiseOptions& noise) {
  const openplx::testing::ConvertedModel model(dir.path(), file.string(), "imu");
  Series s;
  if (!model.m) return s;
  rt::SignalBridge bridge = rt::SignalBridge::attach(model.manifest.string(), model.m, model.d, "", noise);
  rt::Output readings = bridge.output("readings");
  for (int k = 0; k < kReadings; ++k) {
    bridge.before_step();
    mj_step(model.m, model.d);
    bridge.after_step();
    const Eigen::VectorXd v = readings.vector();
    for (int f = 0; f < kFields; ++f) s.noisy.push_back(v[f]);
  }
  return s;
}

// 10,000 readings per axis: a mean's standard error is deviation / 100, and 2 % of each mean here is 10 or
// more of them; a sample deviation's is 0.71 % of the deviation, so 2 % is 2.8 of them. The seed is fixed:
// the result does not change between runs.
TEST(ImuNoise, EveryAxisHasTheMeanAndDeviationTheModelGives) {
  const ScratchDir dir;
  const Series s = run_simulation(write_model(dir), 0);
  for (int f = 0; f < kFields; ++f) {
    SCOPED_TRACE("field " + std::to_string(f));
    std::vector<double> noise;
    for (size_t k = static_cast<size_t>(f); k < s.noisy.size(); k += kFields)
      noise.push_back(s.noisy[k] - s.exact[k]);
    const auto st = sample_statistics(noise);
    if (kDeviation[f] == 0) {
      for (double n : noise) ASSERT_EQ(n, 0.0) << "no Gaussian noise on this axis: its readings are exact";
      continue;
    }
    EXPECT_NEAR(st.mean, kMean[f], 0.02 * std::abs(kMean[f]));
    EXPECT_NEAR(st.deviation, kDeviation[f], 0.02 * kDeviation[f]);
  }
  // The accelerometer at rest reads gravity's reaction, +9.81 up, under the noise.
  EXPECT_NEAR(s.exact[2], 9.81, 0.01);
}

TEST(ImuNoise, SameSeedSameBytesThroughSimulationAndBridge) {
  const ScratchDir dir;
  const fs::path file = write_model(dir);
  const Series a = run_simulation(file, 42), b = run_simulation(file, 42), c = run_simulation(file, 43, 100);
  EXPECT_EQ(std::memcmp(a.noisy.data(), b.noisy.data(), a.noisy.size() * sizeof(double)), 0);
  EXPECT_NE(a.noisy[0], c.noisy[0]);
  EXPECT_NE(a.noisy[kFields + 2], c.noisy[kFields + 2]);
  const Series bridge = run_bridge(dir, file, {true, 42});
  ASSERT_EQ(bridge.noisy.size(), a.noisy.size());
  EXPECT_EQ(std::memcmp(bridge.noisy.data(), a.noisy.data(), a.noisy.size() * sizeof(double)), 0);
  // Off: the bridge reads what the Simulation reads with its noise off.
  const Series off = run_bridge(dir, file, {false, 42});
  EXPECT_EQ(std::memcmp(off.noisy.data(), a.exact.data(), a.exact.size() * sizeof(double)), 0);
}

// Spectral noise has no counterpart: one warning at the distortion's own line naming it and the sensor.
TEST(ImuNoise, SpectralNoiseIsAWarningAtItsLine) {
  const ScratchDir dir;
  const fs::path file = write_model(dir);
  std::ostringstream out, err;
  ASSERT_EQ(openplx::cli::run({file.string(), "-o", (dir / "imu.xml").string()}, out, err), 0) << err.str();
  const std::string expected = file.string() +
                               ":30:13: warning: `imu.magnetometer.hiss` "
                               "(Sensors.MagnetometerSignalSpectralGaussianNoise) has no counterpart";
  EXPECT_NE(err.str().find(expected), std::string::npos) << err.str();
  EXPECT_NE(err.str().find("`imu.magnetometer`'s readings carry its Gaussian noise only"), std::string::npos)
      << err.str();
}

}  // namespace
