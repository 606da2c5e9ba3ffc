// The declarations a bundle release leaves to its host (natives/host_declarations.h): chosen by the
// release's generation, used only where the release itself declares nothing of that name.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "frontend/natives/host_declarations.h"
#include "tests/support/scratch_dir.h"
#include "tools/cli/cli.h"

namespace {

namespace fs = std::filesystem;
namespace nat = openplx::natives;

TEST(HostDeclarations, VersionsCompareByTheirNumbers) {
  EXPECT_LT(nat::compare_versions("0.9", "0.20"), 0);
  EXPECT_EQ(nat::compare_versions("0.20", "0.20.0"), 0);
  EXPECT_GT(nat::compare_versions("0.20.2", "0.20"), 0);
  EXPECT_GT(nat::compare_versions("1.0.0", "0.26.3"), 0);
}

TEST(HostDeclarations, TheGenerationOfARelease) {
  EXPECT_EQ(nat::host_generation("0.20.2").first_version, "0.20");
  EXPECT_EQ(nat::host_generation("0.17.8").first_version, "0.20");  // older than all known: the oldest
  ASSERT_NE(nat::find_host_declaration("0.20.2", "Physics.Interactions", "Connector"), nullptr);
  EXPECT_EQ(nat::find_host_declaration("0.20.2", "Physics", "Connector"), nullptr);
  ASSERT_NE(nat::find_host_declaration("0.20.2", "", "Blob"), nullptr);
}

int convert(const std::vector<std::string>& args, std::string* out, std::string* err) {
  std::ostringstream o, e;
  const int status = openplx::cli::run(args, o, e);
  *out = o.str();
  *err = e.str();
  return status;
}

// A one-bundle release `Physics` 0.20.1 whose Interaction holds connectors; `own` adds its own Connector.
fs::path write_release(const fs::path& root, bool own) {
  const fs::path physics = root / "release" / "Physics";
  fs::create_directories(physics / "Interactions");
  std::ofstream(physics / "config.openplx") << "config is BundleConfig:\n    name: \"Physics\"\n"
                                               "    version: \"0.20.1\"\n";
  std::ofstream(physics / "Interactions" / "Interaction.openplx")
      << "Interaction:\n    connectors is Physics.Interactions.Connector[]: []\n"
         "Pin is Physics.Interactions.Connector\n";
  if (own)
    std::ofstream(physics / "Interactions" / "Connector.openplx") << "Connector:\n    mark is Int: 7\n";
  return root / "release";
}

TEST(HostDeclarations, DeclaredWhereTheReleaseLeavesThem) {
  const openplx::testing::ScratchDir dir;
  const fs::path release = write_release(dir.path(), false);
  std::ofstream(dir / "m.openplx") << "M is Physics.Interactions.Interaction:\n"
                                      "    pin is Physics.Interactions.Pin\n"
                                      "    connectors: [pin]\n";
  std::string out, err;
  ASSERT_EQ(
      convert({(dir / "m.openplx").string(), "--no-default-bundles", "-B", release.string(), "--dump=values"},
              &out, &err),
      0)
      << err;
  EXPECT_NE(out.find("connectors = [-> pin]"), std::string::npos) << out;
  // Our own bundles declare Connector themselves: nothing is added to them.
  EXPECT_EQ(err, "");
}

TEST(HostDeclarations, AReleaseKeepsItsOwnDeclaration) {
  const openplx::testing::ScratchDir dir;
  const fs::path release = write_release(dir.path(), true);
  std::ofstream(dir / "m.openplx") << "M is Physics.Interactions.Pin\n";
  std::string out, err;
  ASSERT_EQ(
      convert({(dir / "m.openplx").string(), "--no-default-bundles", "-B", release.string(), "--dump=values"},
              &out, &err),
      0)
      << err;
  EXPECT_NE(out.find("mark = 7"), std::string::npos) << out;
}

TEST(HostDeclarations, OffWithoutARelease) {
  // A file outside any bundle that names Blob gets no host declaration: Blob is the release's host's.
  const openplx::testing::ScratchDir dir;
  std::ofstream(dir / "m.openplx") << "M:\n    b is Blob\n";
  std::string out, err;
  EXPECT_EQ(convert({(dir / "m.openplx").string(), "--dump=values"}, &out, &err), 1);
  EXPECT_NE(err.find("Unknown name Blob"), std::string::npos) << err;
}

}  // namespace
