// Who lights a converted file (--lights, docs/decisions.md "Scenes light themselves"): a model converted on
// its own brings a light; a file made for a scene (--no-keyframe) leaves it to the scene; on and off decide.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "tests/support/cli_run.h"
#include "tests/support/scratch_dir.h"

namespace {

using openplx::testing::ScratchDir;

// The <light> elements of the cart-pole converted with `options`, as their names.
std::vector<std::string> lights(const std::vector<std::string>& options) {
  const ScratchDir dir;
  const std::string xml = (dir / "cart_pole.xml").string();
  std::vector<std::string> args{std::string(OPENPLX_SAMPLES_DIR) + "/cart_pole.openplx", "-o", xml};
  args.insert(args.end(), options.begin(), options.end());
  const openplx::testing::Conversion c = openplx::testing::cli(args);
  EXPECT_EQ(c.status, 0) << c.errors;
  std::ifstream in(xml);
  std::vector<std::string> names;
  for (std::string line; std::getline(in, line);) {
    const size_t at = line.find("<light name=\"");
    if (at != std::string::npos) names.push_back(line.substr(at + 13, line.find('"', at + 13) - at - 13));
  }
  return names;
}

using Names = std::vector<std::string>;

TEST(SceneLights, AStandaloneFileIsLitAnIncludedOneIsNot) {
  EXPECT_EQ(lights({}), Names{"light"});
  EXPECT_EQ(lights({"--prefix", "left/"}), Names{"left/light"});
  EXPECT_EQ(lights({"--no-keyframe"}), Names{});
  EXPECT_EQ(lights({"--lights", "auto", "--no-keyframe"}), Names{});
  EXPECT_EQ(lights({"--lights=auto"}), Names{"light"});
}

TEST(SceneLights, OnAndOffDecide) {
  EXPECT_EQ(lights({"--no-keyframe", "--lights", "on", "--prefix", "p/"}), Names{"p/light"});
  EXPECT_EQ(lights({"--lights", "off"}), Names{});
  // The last one given holds.
  EXPECT_EQ(lights({"--lights", "off", "--lights=on"}), Names{"light"});
}

TEST(SceneLights, AnotherValueIsAUsageError) {
  const openplx::testing::Conversion c =
      openplx::testing::cli({std::string(OPENPLX_SAMPLES_DIR) + "/cart_pole.openplx", "--lights", "dim"});
  EXPECT_EQ(c.status, 2);
  EXPECT_NE(c.errors.find("--lights takes auto, on or off, not 'dim'"), std::string::npos) << c.errors;
}

}  // namespace
