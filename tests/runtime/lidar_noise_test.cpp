// A lidar's detection-distance noise (Sensors.LidarDetectionDistanceGaussianNoise, AGX's lidar test sets
// deviations 0 / 0.01 / 0.02) applied by the runtime: the readings' mean and deviation match the model's, the
// same seed gives the same bytes through Simulation and SignalBridge alike, and with the noise off the
// readings are MuJoCo's own.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <cstring>
#include <fstream>
#include <iterator>
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
constexpr double kWall = 4.9;  // the wall's near face, m from the lidar along its first ray

struct Noise {
  double mean, deviation, slope;
};

// A lidar 1 m up with two rays: one along +x onto a wall whose face is at x = 4.9, one at 1.2 rad of azimuth
// that passes the wall's 2 m half width (4.9 tan 1.2 = 12.6 m aside) and hits nothing.
std::string lidar_scene(const Noise& n) {
  std::ostringstream text;
  text << "Scene is Physics3D.System:\n"
          "    wall is Physics3D.Bodies.RigidBody:\n"
          "        is_dynamic: false\n"
          "        kinematics.local_transform.position: {5, 0, 0}\n"
          "        slab is Physics3D.Geometries.Box:\n"
          "            size: {0.2, 4, 4}\n"
          "    mount is Physics3D.Interactions.MateConnector:\n"
          "        position: {0, 0, 1}\n"
          "        main_axis: {0, 0, 1}\n"
          "        normal: {1, 0, 0}\n"
          "    lidar is Sensors.PulsedLidarLogic:\n"
          "        mate_connector_attachment: mount\n"
          "        wavelength: 865\n"
          "        ray_source becomes Sensors.Optics.HorizontalSweepRaySource:\n"
          "            frequency: 10\n"
          "            horizontal_resolution: 2\n"
          "            vertical_resolution: 1\n"
          "            horizontal_fov: {0, 1.2}\n"
          "            vertical_fov: {0, 0}\n"
          "        distance_noise is Sensors.LidarDetectionDistanceGaussianNoise:\n"
          "            gaussian_distribution.mean: "
       << n.mean
       << "\n"
          "            gaussian_distribution.standard_deviation: "
       << n.deviation
       << "\n"
          "            standard_deviation_slope: "
       << n.slope
       << "\n"
          "        sensing_distortions: [lidar.distance_noise]\n"
          "    scan is Sensors.Signals.LidarOutput:\n"
          "        source: lidar\n"
          "        fields: [Sensors.Signals.LidarOutputField.Distance_F32]\n";
  return text.str();
}

fs::path write_scene(const ScratchDir& dir, const Noise& n) {
  const fs::path file = dir / "lidar.openplx";
  std::ofstream(file) << lidar_scene(n);
  return file;
}

// The first ray's readings, one per step over kReadings steps, and whether the missing ray stayed -1.
struct Readings {
  std::vector<double> hit;
  bool miss_exact = true;
};

Readings run_simulation(const fs::path& file, const rt::SensorNoiseOptions& noise, int steps = kReadings) {
  rt::LoadOptions options;
  options.sensor_noise = noise;
  rt::Simulation sim = rt::Simulation::load(file.string(), options);
  rt::Output scan = sim.output("scan");
  Readings r;
  for (int k = 0; k < steps; ++k) {
    sim.step();
    const Eigen::VectorXd v = scan.vector();
    r.hit.push_back(v[0]);
    r.miss_exact = r.miss_exact && v[1] == -1.0;
  }
  return r;
}

// The model converted to MJCF and its manifest, loaded with MuJoCo's own mj_loadXML and driven by a bridge
// around plain mj_step.
Readings run_bridge(const ScratchDir& dir, const fs::path& file, const rt::SensorNoiseOptions& noise) {
  const openplx::testing::ConvertedModel model(dir.path(), file.string(), "lidar");
  Readings r;
  if (!model.m) return r;
  rt::SignalBridge bridge = rt::SignalBridge::attach(model.manifest.string(), model.m, model.d, "", noise);
  rt::Output scan = bridge.output("scan");
  for (int k = 0; k < kReadings; ++k) {
    bridge.before_step();
    mj_step(model.m, model.d);
    bridge.after_step();
    const Eigen::VectorXd v = scan.vector();
    r.hit.push_back(v[0]);
    r.miss_exact = r.miss_exact && v[1] == -1.0;
  }
  return r;
}

// 10,000 readings: the sample mean's standard error is deviation / 100 and the sample deviation's is
// deviation / sqrt(2 * 9,999) = 0.71 % of it, so 2 % is 2.8 standard errors for the deviation and 5 or more
// for the means below (each mean is chosen so). The seed is fixed: the result does not change between runs.
void expect_agx_statistics(const std::vector<double>& readings, const Noise& n) {
  std::vector<double> noise;
  for (double r : readings) noise.push_back(r - kWall);
  const auto s = sample_statistics(noise);
  const double deviation = n.deviation + n.slope * kWall;  // AGX's: the base plus the slope per metre
  EXPECT_NEAR(s.mean, n.mean, 0.02 * n.mean) << "deviation " << deviation;
  EXPECT_NEAR(s.deviation, deviation, 0.02 * deviation);
}

TEST(LidarNoise, ReadingsHaveTheMeanAndDeviationAgxSets) {
  for (const Noise& n : {Noise{0.05, 0.01, 0}, Noise{0.05, 0.02, 0}, Noise{0.3, 0.01, 0.02}}) {
    SCOPED_TRACE("mean " + std::to_string(n.mean) + " deviation " + std::to_string(n.deviation) + " slope " +
                 std::to_string(n.slope));
    const ScratchDir dir;
    const fs::path file = write_scene(dir, n);
    const Readings sim = run_simulation(file, {});
    expect_agx_statistics(sim.hit, n);
    EXPECT_TRUE(sim.miss_exact) << "a ray that hits nothing reads -1, noise or not";
    // The bridge draws exactly what the Simulation draws: same seed, sensor names and times.
    const Readings bridge = run_bridge(dir, file, {});
    ASSERT_EQ(bridge.hit.size(), sim.hit.size());
    EXPECT_EQ(std::memcmp(bridge.hit.data(), sim.hit.data(), sim.hit.size() * sizeof(double)), 0);
    EXPECT_TRUE(bridge.miss_exact);
  }
}

TEST(LidarNoise, TheSeedDecidesTheBytes) {
  const ScratchDir dir;
  const fs::path file = write_scene(dir, {0.05, 0.02, 0});
  const Readings a = run_simulation(file, {true, 7}, 200), b = run_simulation(file, {true, 7}, 200),
                 c = run_simulation(file, {true, 8}, 200);
  ASSERT_EQ(a.hit.size(), 200u);
  EXPECT_EQ(std::memcmp(a.hit.data(), b.hit.data(), a.hit.size() * sizeof(double)), 0);
  int same = 0;
  for (size_t k = 0; k < a.hit.size(); ++k) same += a.hit[k] == c.hit[k];
  EXPECT_EQ(same, 0) << "another seed draws other values";
  const Readings bridge_a = run_bridge(dir, file, {true, 7}), bridge_c = run_bridge(dir, file, {true, 8});
  EXPECT_EQ(std::memcmp(bridge_a.hit.data(), a.hit.data(), a.hit.size() * sizeof(double)), 0);
  EXPECT_NE(bridge_c.hit[0], bridge_a.hit[0]);
}

// Off: what MuJoCo's rangefinder computed, to the bit, through both entry points.
TEST(LidarNoise, OffReadsMuJoCosOwnDistance) {
  const ScratchDir dir;
  const fs::path file = write_scene(dir, {0.05, 0.02, 0.02});
  rt::LoadOptions options;
  options.sensor_noise.enabled = false;
  rt::Simulation sim = rt::Simulation::load(file.string(), options);
  sim.step();
  const int ray = mj_name2id(sim.model(), mjOBJ_SENSOR, "lidar.ray0");
  ASSERT_GE(ray, 0);
  const double exact = sim.data()->sensordata[sim.model()->sensor_adr[ray]];
  EXPECT_NEAR(exact, kWall, 1e-9);
  EXPECT_EQ(sim.output("scan").vector()[0], exact);
  sim.set_sensor_noise({});  // on again, default seed: now it differs
  EXPECT_NE(sim.output("scan").vector()[0], exact);
  const Readings bridge = run_bridge(dir, file, {false, 0});
  for (double r : bridge.hit) ASSERT_EQ(r, bridge.hit.front());
  EXPECT_EQ(bridge.hit.front(), exact);
}

// One draw per step: reading again within the step gives the same value; the next step draws anew.
TEST(LidarNoise, OneDrawPerStep) {
  const ScratchDir dir;
  rt::Simulation sim = rt::Simulation::load(write_scene(dir, {0.05, 0.02, 0}).string());
  rt::Output scan = sim.output("scan");
  sim.step();
  const double first = scan.vector()[0];
  EXPECT_EQ(scan.vector()[0], first);
  EXPECT_EQ(sim.output("scan").vector()[0], first);
  sim.step();
  EXPECT_NE(scan.vector()[0], first);
}

// The conversion says where the noise is applied (the runtime) and what the bare MJCF does (nothing), and
// the manifest carries it on the output.
TEST(LidarNoise, ConversionWarnsAndTheManifestCarriesIt) {
  const ScratchDir dir;
  const fs::path file = write_scene(dir, {0.05, 0.01, 0.02});
  std::ostringstream out, err;
  ASSERT_EQ(openplx::cli::run({file.string(), "-o", (dir / "l.xml").string()}, out, err), 0) << err.str();
  EXPECT_NE(err.str().find("is applied by the runtime"), std::string::npos) << err.str();
  EXPECT_NE(err.str().find("MuJoCo does not apply it"), std::string::npos) << err.str();
  std::ifstream manifest(dir / "l.signals.json");
  const std::string text((std::istreambuf_iterator<char>(manifest)), std::istreambuf_iterator<char>());
  EXPECT_NE(
      text.find("\"noise\": {\"mean\": [0.05], \"deviation\": [0.01], \"deviation_per_metre\": [0.02]}"),
      std::string::npos)
      << text;
}

// A manifest whose noise the runtime could not apply is refused at attach, naming the signal.
TEST(LidarNoise, ABrokenNoiseIsRefused) {
  const ScratchDir dir;
  const fs::path file = write_scene(dir, {0.05, 0.01, 0});
  std::ostringstream out, err;
  ASSERT_EQ(openplx::cli::run({file.string(), "-o", (dir / "l.xml").string()}, out, err), 0) << err.str();
  std::ifstream in(dir / "l.signals.json");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string given = "\"deviation\": [0.01]";
  ASSERT_NE(text.find(given), std::string::npos);
  char error[1000] = "";
  mjModel* m = mj_loadXML((dir / "l.xml").string().c_str(), nullptr, error, sizeof error);
  ASSERT_NE(m, nullptr) << error;
  mjData* d = mj_makeData(m);
  for (const auto& [broken, why] :
       {std::pair{"\"deviation\": [-0.01]", "holds a negative number"},
        {"\"deviation\": [0.01, 0.01, 0.01]", "one for every value, or one per value"}}) {
    std::string edited = text;
    edited.replace(edited.find(given), given.size(), broken);
    std::ofstream(dir / "broken.signals.json") << edited;
    try {
      rt::SignalBridge::attach((dir / "broken.signals.json").string(), m, d);
      ADD_FAILURE() << "attached with " << broken;
    } catch (const rt::LoadError& e) {
      EXPECT_NE(std::string(e.what()).find("signal `scan`: its noise's deviation"), std::string::npos)
          << e.what();
      EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
    }
  }
  mj_deleteData(d);
  mj_deleteModel(m);
}

}  // namespace
