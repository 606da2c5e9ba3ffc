// openplx-sim's sensor-noise options: --seed N (the same seed prints the same values, another seed others)
// and --no-noise (MuJoCo's own distance), on a lidar with distance noise facing a wall 4.9 m away.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "tests/support/scratch_dir.h"
#include "tools/sim/sim.h"

namespace {

namespace fs = std::filesystem;

struct SimRun {
  int status;
  std::string out, err;
};
SimRun sim(const std::vector<std::string>& args) {
  std::ostringstream out, err;
  const int status = openplx::sim::run_sim(args, out, err);
  return {status, out.str(), err.str()};
}

fs::path write_lidar(const openplx::testing::ScratchDir& dir) {
  std::ofstream(dir / "lidar.openplx")
      << "Scene is Physics3D.System:\n"
         "    wall is Physics3D.Bodies.RigidBody:\n"
         "        is_dynamic: false\n"
         "        kinematics.local_transform.position: {5, 0, 0}\n"
         "        slab is Physics3D.Geometries.Box:\n"
         "            size: {0.2, 4, 4}\n"
         "    mount is Physics3D.Interactions.MateConnector:\n"
         "        main_axis: {0, 0, 1}\n"
         "        normal: {1, 0, 0}\n"
         "    lidar is Sensors.PulsedLidarLogic:\n"
         "        mate_connector_attachment: mount\n"
         "        wavelength: 865\n"
         "        distance_noise is Sensors.LidarDetectionDistanceGaussianNoise:\n"
         "            gaussian_distribution.mean: 0\n"
         "            gaussian_distribution.standard_deviation: 0.02\n"
         "            standard_deviation_slope: 0\n"
         "        sensing_distortions: [lidar.distance_noise]\n"
         "    scan is Sensors.Signals.LidarOutput:\n"
         "        source: lidar\n"
         "        fields: [Sensors.Signals.LidarOutputField.Distance_F32]\n";
  return dir / "lidar.openplx";
}

// The printed `scan = d` (one ray: one number) as a number.
double scan(const SimRun& run) {
  const size_t at = run.out.find("scan = ");
  EXPECT_NE(at, std::string::npos) << run.out << run.err;
  return at == std::string::npos ? NAN : std::stod(run.out.substr(at + 7));
}

TEST(SimNoise, SeedAndNoNoise) {
  const openplx::testing::ScratchDir dir;
  const std::string file = write_lidar(dir).string();
  const SimRun a = sim({file, "--time", "0.01", "--seed", "3", "--print", "scan"});
  const SimRun b = sim({file, "--time", "0.01", "--seed", "3", "--print", "scan"});
  const SimRun c = sim({file, "--time", "0.01", "--seed", "18446744073709551615", "--print", "scan"});
  const SimRun off = sim({file, "--time", "0.01", "--seed", "3", "--no-noise", "--print", "scan"});
  ASSERT_EQ(a.status, 0) << a.err;
  EXPECT_EQ(a.out, b.out);
  EXPECT_NE(a.out, c.out);
  EXPECT_NEAR(scan(off), 4.9, 1e-9);  // the wall's face, exact ray casting
  EXPECT_NE(scan(a), scan(off));
  EXPECT_NEAR(scan(a), 4.9, 5 * 0.02);  // one draw of deviation 0.02: within 5 of them
}

TEST(SimNoise, SeedMustBeAWholeNumberIn64Bits) {
  const openplx::testing::ScratchDir dir;
  const std::string file = write_lidar(dir).string();
  for (const char* bad : {"-1", "18446744073709551616", "1.5", "", "seven"}) {
    const SimRun run = sim({file, "--seed", bad});
    EXPECT_EQ(run.status, 2) << bad;
    EXPECT_NE(run.err.find("--seed needs a whole number from 0 to 18446744073709551615"), std::string::npos)
        << run.err;
  }
}

}  // namespace
