// Lidars: one MuJoCo rangefinder per ray of the ray source's pattern, read as one vector, measured against a
// wall; the corpus's simple_lidar configurations (AGX's own test models) load or fail as AGX's tests expect.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "openplx/runtime/simulation.h"
#include "tests/support/scratch_dir.h"
#include "tools/cli/cli.h"

namespace {

namespace fs = std::filesystem;
namespace rt = openplx::runtime;

const fs::path kLidars = fs::path(OPENPLX_CORPUS_DIR) / "agxunity" / "simple_lidar.openplx";

// A lidar 1 m up looking along +x (its connector's normal) with five rays over ±0.4 rad of azimuth, and a
// 4 m wide wall whose near face is at x = 4.9. Ray k at azimuth a reaches the face at 4.9 / cos a, if
// 4.9 tan a is within the wall's half width (2 m): ±0.2 hit at 4.99966, ±0.4 (2.07 m aside) miss (-1).
// MuJoCo's ray casting is exact geometry: 1e-9.
TEST(Lidar, RaysMeasureTheDistanceToAWall) {
  const openplx::testing::ScratchDir dir;
  std::ofstream(dir / "wall.openplx")
      << "Scene is Physics3D.System:\n"
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
         "            horizontal_resolution: 5\n"
         "            vertical_resolution: 1\n"
         "            horizontal_fov: {-0.4, 0.4}\n"
         "            vertical_fov: {0, 0}\n"
         "    scan is Sensors.Signals.LidarOutput:\n"
         "        source: lidar\n"
         "        fields: [Sensors.Signals.LidarOutputField.Distance_F32]\n";
  rt::Simulation sim = rt::Simulation::load((dir / "wall.openplx").string());
  sim.step();
  const Eigen::VectorXd scan = sim.output("scan").vector();
  ASSERT_EQ(scan.size(), 5);
  EXPECT_EQ(scan[0], -1.0);
  EXPECT_NEAR(scan[1], 4.9 / std::cos(0.2), 1e-9);
  EXPECT_NEAR(scan[2], 4.9, 1e-9);
  EXPECT_NEAR(scan[3], 4.9 / std::cos(0.2), 1e-9);
  EXPECT_EQ(scan[4], -1.0);
}

int cli(const std::vector<std::string>& args, std::string* err) {
  std::ostringstream out, errors;
  const int status = openplx::cli::run(args, out, errors);
  *err = errors.str();
  return status;
}

// AGX rejects a lidar with two detection-distance distortions: an error at the user's
// `sensing_distortions` line (18) that names the distance distortion, and no output.
TEST(Lidar, TwoDistanceDistortionsAreAnError) {
  const openplx::testing::ScratchDir dir;
  std::string err;
  EXPECT_EQ(
      cli({kLidars.string(), "--model", "DoubleDistanceDistortionLidar", "-o", (dir / "l.xml").string()},
          &err),
      openplx::cli::kExitInputError);
  EXPECT_NE(err.find(kLidars.string() + ":18:9: error: lidar `sensor` has 2 detection-distance distortions"),
            std::string::npos)
      << err;
  EXPECT_NE(err.find("at most one distance distortion"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir / "l.xml"));
}

// ValidLidar loads with its noise parameters: its one ray's rangefinder records the 0.01 m deviation.
TEST(Lidar, ValidLidarLoadsWithItsNoise) {
  rt::LoadOptions options;
  options.model = "ValidLidar";
  rt::Simulation sim = rt::Simulation::load(kLidars.string(), options);
  const mjModel* m = sim.model();
  int rangefinders = 0;
  for (int s = 0; s < m->nsensor; ++s) {
    if (m->sensor_type[s] != mjSENS_RANGEFINDER) continue;
    ++rangefinders;
    EXPECT_EQ(m->sensor_noise[s], 0.01);
  }
  EXPECT_EQ(rangefinders, 1);
}

}  // namespace
