// Terrain.Terrain as MuJoCo sees it: a static height field of its grid, surface at z = 0 of its frame; a ball
// dropped on it comes to rest on that surface. Deformation and soil are a warning at the user's line.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <fstream>

#include "openplx/runtime/simulation.h"
#include "tests/support/scratch_dir.h"

namespace {

namespace rt = openplx::runtime;

// A 0.1 m ball released 0.5 m above a 2 m x 2 m terrain lifted to z = 0.3: it settles with its centre at
// 0.3 + 0.1 = 0.4, less MuJoCo's soft-contact penetration (m g / k of its default contact, under 1 mm).
TEST(Terrain, IsAStaticHeightFieldABallRestsOn) {
  const openplx::testing::ScratchDir dir;
  std::ofstream(dir / "terrain.openplx")
      << "Scene is Physics3D.System:\n"
         "    ground is Terrain.Terrain:\n"
         "        kinematics.local_transform.position: {0, 0, 0.3}\n"
         "        num_elements_x: 21\n"
         "        num_elements_y: 21\n"
         "        element_size: 0.1\n"
         "        max_depth: 0.5\n"
         "    ball is Physics3D.Bodies.RigidBody:\n"
         "        inertia.mass: 1\n"
         "        kinematics.local_transform.position: {0.05, -0.05, 0.8}\n"
         "        shape is Physics3D.Geometries.Sphere:\n"
         "            radius: 0.1\n"
         "    height is Physics3D.Signals.Position3DOutput:\n"
         "        source: ball\n";
  rt::Simulation sim = rt::Simulation::load((dir / "terrain.openplx").string());
  const mjModel* m = sim.model();
  ASSERT_EQ(m->nhfield, 1);
  EXPECT_EQ(m->hfield_nrow[0], 21);
  EXPECT_EQ(m->hfield_ncol[0], 21);
  EXPECT_DOUBLE_EQ(m->hfield_size[0], 1.0);  // half extents: (21 - 1) x 0.1 / 2
  EXPECT_DOUBLE_EQ(m->hfield_size[1], 1.0);
  ASSERT_EQ(sim.warnings().size(), 1u);
  EXPECT_NE(sim.warnings()[0].find("terrain.openplx:2:5: warning: terrain `ground` is a static height field"),
            std::string::npos)
      << sim.warnings()[0];
  sim.advance(2.0);
  EXPECT_NEAR(sim.output("height").vec3().z(), 0.4, 1e-3);
  EXPECT_LT(sim.output("height").vec3().z(), 0.4 + 1e-9);  // on it, not above it
}

// A grid of 1e9 x 1e9 elements (a typo, not a terrain) is left out with a warning instead of allocating.
TEST(Terrain, AnAbsurdGridIsLeftOutWithAWarning) {
  const openplx::testing::ScratchDir dir;
  std::ofstream(dir / "terrain.openplx") << "Scene is Physics3D.System:\n"
                                            "    ground is Terrain.Terrain:\n"
                                            "        num_elements_x: 1000000000\n"
                                            "        num_elements_y: 1000000000\n"
                                            "        element_size: 0.1\n"
                                            "        max_depth: 0.5\n";
  rt::Simulation sim = rt::Simulation::load((dir / "terrain.openplx").string());
  EXPECT_EQ(sim.model()->nhfield, 0);
  ASSERT_EQ(sim.warnings().size(), 1u);
  EXPECT_NE(sim.warnings()[0].find("needs from 2 x 2 to 10 million elements"), std::string::npos);
}

}  // namespace
