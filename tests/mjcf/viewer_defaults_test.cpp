// Viewer-ready output: every sample, loaded by MuJoCo, has a light, a <statistic> framing its machine rather
// than its ground, and a colour for every geom a viewer shows (groups 0-2).
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>

#include "tests/support/scratch_dir.h"
#include "tools/cli/cli.h"

namespace fs = std::filesystem;

namespace {

mjModel* convert_and_load(const std::string& sample, const fs::path& dir) {
  const std::string out = (dir / (sample + ".xml")).string();
  std::ostringstream o, e;
  EXPECT_EQ(
      openplx::cli::run({std::string(OPENPLX_SAMPLES_DIR) + "/" + sample + ".openplx", "-o", out}, o, e), 0)
      << e.str();
  char error[1000] = "";
  mjModel* m = mj_loadXML(out.c_str(), nullptr, error, sizeof(error));
  EXPECT_NE(m, nullptr) << error;
  return m;
}

TEST(ViewerDefaults, EverySampleIsLitFramedAndColoured) {
  const openplx::testing::ScratchDir dir;
  for (const char* sample :
       {"pendulum", "four_bar", "two_joint_arm", "cart_pole", "vehicle_circle", "drivetrain_machine"}) {
    SCOPED_TRACE(sample);
    mjModel* m = convert_and_load(sample, dir.path());
    ASSERT_NE(m, nullptr);
    EXPECT_GE(m->nlight, 1);
    // Every body that moves lies within the framed sphere (its centre, extent / 2 around it).
    mjData* d = mj_makeData(m);
    mj_forward(m, d);
    const double* c = m->stat.center;
    for (int b = 1; b < m->nbody; ++b) {
      if (m->body_dofnum[b] == 0 && m->body_parentid[b] == 0) continue;  // static: grounds, fixed bases
      const double* x = d->xpos + 3 * b;
      EXPECT_LE(std::hypot(x[0] - c[0], x[1] - c[1], x[2] - c[2]), m->stat.extent / 2 + 1e-9)
          << mj_id2name(m, mjOBJ_BODY, b);
    }
    // The machine, not a 100 m ground: every sample is smaller than 10 m.
    EXPECT_LT(m->stat.extent, 10.0);
    for (int g = 0; g < m->ngeom; ++g) {
      if (m->geom_group[g] > 2) continue;
      const float* rgba = m->geom_rgba + 4 * g;
      const bool grey_default = rgba[0] == 0.5f && rgba[1] == 0.5f && rgba[2] == 0.5f;
      EXPECT_TRUE(m->geom_matid[g] >= 0 || !grey_default) << "geom " << g << " has MuJoCo's default grey";
    }
    mj_deleteData(d);
    mj_deleteModel(m);
  }
}

}  // namespace
