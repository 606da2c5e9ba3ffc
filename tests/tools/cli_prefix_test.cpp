// --prefix goes into every MuJoCo name, so into XML attributes and the manifest's JSON strings: a control
// character or bytes that are not UTF-8 is a usage error naming it (exit 2, nothing written); ordinary
// prefixes, unicode letters and the characters XML and JSON escape convert, load in MuJoCo and attach.
#include <mujoco/mujoco.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "openplx/runtime/signal_bridge.h"
#include "tests/support/cli_run.h"
#include "tests/support/scratch_dir.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const std::string kCartPole = std::string(OPENPLX_SAMPLES_DIR) + "/cart_pole.openplx";

TEST(CliPrefix, ControlCharactersAndBytesThatAreNotUtf8AreUsageErrors) {
  const openplx::testing::ScratchDir dir;
  const std::vector<std::pair<std::string, std::string>> refused = {{"a\x01"
                                                                     "b/",
                                                                     "U+0001"},
                                                                    {"a\tb/", "U+0009"},
                                                                    {"left\n", "U+000A"},
                                                                    {"a\x7f/", "U+007F"},
                                                                    {"a\xc2\x85/", "U+0085"},
                                                                    {"a\xff/", "byte 0xFF"},
                                                                    {"a\xc3/", "byte 0xC3"},
                                                                    {"\xed\xa0\x80/", "byte 0xED"},
                                                                    {"a\xef\xbf\xbf/", "U+FFFF"}};
  for (const auto& [prefix, named] : refused) {
    const fs::path xml = dir / "out.xml";
    const openplx::testing::Conversion c =
        openplx::testing::cli({kCartPole, "-o", xml.string(), "--prefix", prefix});
    EXPECT_EQ(c.status, 2) << named;
    EXPECT_NE(c.errors.find("openplx2mjcf: error: --prefix"), std::string::npos) << c.errors;
    EXPECT_NE(c.errors.find(named), std::string::npos) << "expected " << named << " in: " << c.errors;
    EXPECT_FALSE(fs::exists(xml)) << named;
    EXPECT_FALSE(fs::exists(dir / "out.signals.json")) << named;
  }
  // The --prefix=P spelling too.
  EXPECT_EQ(openplx::testing::cli({kCartPole, "-o", (dir / "eq.xml").string(), "--prefix=a\x01"}).status, 2);
}

TEST(CliPrefix, OrdinaryPrefixesConvertLoadAndAttach) {
  const openplx::testing::ScratchDir dir;
  int k = 0;
  for (const std::string prefix : {"left/", "robot_1.", "bras_gauche_\xc3\xa9/", "\xe6\x9c\xba\xe5\x99\xa8/",
                                   "a b:c-d/", "q\"<&>'\\/"}) {
    const fs::path xml = dir / ("model" + std::to_string(k++) + ".xml");
    const openplx::testing::Conversion c =
        openplx::testing::cli({kCartPole, "-o", xml.string(), "--prefix", prefix});
    ASSERT_EQ(c.status, 0) << prefix << ": " << c.errors;
    const fs::path manifest = fs::path(xml).replace_extension(".signals.json");
    json j;
    ASSERT_NO_THROW(j = json::parse(std::ifstream(manifest))) << prefix;
    EXPECT_EQ(j.at("prefix"), prefix);
    char error[1000] = "";
    mjModel* m = mj_loadXML(xml.c_str(), nullptr, error, sizeof(error));
    ASSERT_NE(m, nullptr) << prefix << ": " << error;
    EXPECT_GE(mj_name2id(m, mjOBJ_JOINT, (prefix + "hinge").c_str()), 0) << prefix;
    mjData* d = mj_makeData(m);
    EXPECT_NO_THROW({
      openplx::runtime::SignalBridge bridge = openplx::runtime::SignalBridge::attach(manifest.string(), m, d);
      bridge.input("push").set(1.0);
      mj_step(m, d);
    }) << prefix;
    mj_deleteData(d);
    mj_deleteModel(m);
  }
}

}  // namespace
