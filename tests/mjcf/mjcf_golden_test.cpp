// Every sample's MJCF and signal manifest equal the reviewed golden files (regenerate: tools/update-golden),
// and the golden MJCF loads in MuJoCo.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "tests/support/scratch_dir.h"
#include "tools/cli/cli.h"

namespace fs = std::filesystem;

namespace {

std::string read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(MjcfGolden, SamplesMatchTheirGoldenFiles) {
  const fs::path root = fs::path(OPENPLX_TEST_DATA_DIR).parent_path();
  const openplx::testing::ScratchDir scratch;
  const fs::path& out = scratch.path();
  size_t samples = 0;
  for (const auto& entry : fs::directory_iterator(root / "samples")) {
    if (entry.path().extension() != ".openplx") continue;
    const std::string name = entry.path().stem().string();
    SCOPED_TRACE(name);
    std::ostringstream stdout_text, stderr_text;
    const fs::path xml = out / (name + ".xml");
    ASSERT_EQ(
        openplx::cli::run({entry.path().string(), "-o", xml.string(), "--check"}, stdout_text, stderr_text),
        0)
        << stderr_text.str();
    const fs::path golden = fs::path(OPENPLX_TEST_DATA_DIR) / "golden/mjcf";
    EXPECT_EQ(read(xml), read(golden / (name + ".xml"))) << "review, then tools/update-golden";
    EXPECT_EQ(read(out / (name + ".signals.json")), read(golden / (name + ".signals.json")));
    char error[1000] = "";
    mjModel* model = mj_loadXML((golden / (name + ".xml")).string().c_str(), nullptr, error, sizeof(error));
    EXPECT_NE(model, nullptr) << error;
    if (model) mj_deleteModel(model);
    ++samples;
  }
  EXPECT_GE(samples, 1u);
}

}  // namespace
