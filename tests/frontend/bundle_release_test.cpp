// A user's bundle release instead of ours (--no-default-bundles -B RELEASE). We have no official release
// here, so each test writes a small one: a copy of our bundles whose configs pin their dependencies the
// way releases do ("Physics3D==0.20.2"), plus a bundle of its own written with the constructs releases use
// (indexing, `reference` attributes, dotted re-typing, `{}`). Corpus models then convert against it alone and
// pass --check, giving the same MJCF as with our bundles.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "tests/support/scratch_dir.h"
#include "tools/cli/cli.h"

namespace {

namespace fs = std::filesystem;

const fs::path kBundles = fs::path(OPENPLX_TEST_DATA_DIR) / ".." / "bundles";

std::string read(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// Our bundles as release VERSION: every config's version and pinned dependencies rewritten.
fs::path write_release(const fs::path& root, const std::string& version, const std::string& math_pin) {
  const fs::path release = root / "release";
  fs::copy(kBundles, release, fs::copy_options::recursive);
  for (const auto& entry : fs::directory_iterator(release)) {
    const fs::path config = entry.path() / "config.openplx";
    if (!fs::exists(config)) continue;
    std::istringstream lines(read(config));
    std::string text, line;
    while (std::getline(lines, line)) {
      if (line.find("version:") != std::string::npos) {
        line = "    version: \"" + version + "\"";
      } else if (line.find("dependencies:") != std::string::npos) {
        line = std::regex_replace(line, std::regex("\"Math\""), "\"Math==" + math_pin + "\"");
        line = std::regex_replace(line, std::regex("\"(Physics|Physics1D|Physics3D)\""),
                                  "\"$1==" + version + "\"");
      }
      text += line + "\n";
    }
    std::ofstream(config) << text;
  }
  fs::create_directories(release / "Rigs");
  std::ofstream(release / "Rigs" / "config.openplx") << "config is BundleConfig:\n"
                                                        "    name: \"Rigs\"\n"
                                                        "    version: \"" +
                                                            version +
                                                            "\"\n"
                                                            "    dependencies: [\"Physics3D==" +
                                                            version + "\"]\n";
  // Written as 0.20 releases write models.
  std::ofstream(release / "Rigs" / "Rigs.openplx")
      << "Link is Physics3D.Bodies.RigidBody:\n"
         "    inertia.mass: 1\n"
         "    shape is Physics3D.Geometries.Box:\n"
         "        size: {0.1, 0.1, 1}\n"
         "    start is Physics3D.Interactions.MateConnector:\n"
         "        position.z: 0.5\n"
         "        main_axis: Math.Vec3.Y_AXIS()\n"
         "    end is Physics3D.Interactions.MateConnector:\n"
         "        position.z: -0.5\n"
         "        main_axis: Math.Vec3.Y_AXIS()\n"
         "Chain is Physics3D.System:\n"
         "    anchor is Physics3D.Interactions.MateConnector reference\n"
         "    first is Link\n"
         "    second is Link\n"
         "    links is Link[]: [first, second]\n"
         "    joint is Physics3D.Interactions.Hinge:\n"
         "        connectors: [links[0].end, links[1].start]\n"
         "    top is Physics3D.Interactions.Hinge:\n"
         "        connectors: [links[0].start, anchor]\n"
         "    extras is Real[]: {}\n"
         "    joint.angle_output.enabled: true\n";
  return release;
}

int convert(const std::vector<std::string>& args, std::string* out = nullptr, std::string* err = nullptr) {
  std::ostringstream text, errors;
  const int status = openplx::cli::run(args, text, errors);
  if (out) *out = text.str();
  if (err) *err = errors.str();
  return status;
}

TEST(BundleRelease, CorpusModelsConvertAgainstAPinnedReleaseAlone) {
  const openplx::testing::ScratchDir dir;
  const fs::path release = write_release(dir.path(), "0.20.2", "0.20.2");
  for (const char* name :
       {"LinearRangeTest", "simpler_inverted_pendulum", "signal_test", "differential_test"}) {
    SCOPED_TRACE(name);
    const std::string model =
        (fs::path(OPENPLX_CORPUS_DIR) / "agxunity" / (std::string(name) + ".openplx")).string();
    const std::string theirs = (dir / (std::string(name) + "_release.xml")).string();
    const std::string ours = (dir / (std::string(name) + "_ours.xml")).string();
    std::string err;
    ASSERT_EQ(convert({model, "--no-default-bundles", "-B", release.string(), "--check", "-o", theirs},
                      nullptr, &err),
              0)
        << err;
    ASSERT_EQ(convert({model, "-o", ours}, nullptr, &err), 0) << err;
    EXPECT_EQ(read(theirs), read(ours));  // the same bundles, so the same MJCF
  }
}

TEST(BundleRelease, ReleaseConstructsEvaluateAndConvert) {
  const openplx::testing::ScratchDir dir;
  const fs::path release = write_release(dir.path(), "0.20.2", "0.20.2");
  const fs::path model = dir / "rig.openplx";
  std::ofstream(model) << "Rig is Rigs.Chain:\n"
                          "    world is Physics3D.Interactions.MateConnector:\n"
                          "        main_axis: Math.Vec3.Y_AXIS()\n"
                          "    anchor: world\n";
  std::string values, err;
  ASSERT_EQ(convert({model.string(), "--no-default-bundles", "-B", release.string(), "--dump=values"},
                    &values, &err),
            0)
      << err;
  EXPECT_NE(values.find("joint.connectors = [-> first.end, -> second.start]"), std::string::npos) << values;
  EXPECT_NE(values.find("anchor = -> world"), std::string::npos) << values;
  EXPECT_NE(values.find("extras = []"), std::string::npos) << values;
  ASSERT_EQ(convert({model.string(), "--no-default-bundles", "-B", release.string(), "--check", "-o",
                     (dir / "rig.xml").string()},
                    nullptr, &err),
            0)
      << err;
}

TEST(BundleRelease, WithoutDefaultBundlesOnlyTheReleaseIsSeen) {
  const openplx::testing::ScratchDir dir;
  const std::string model = (fs::path(OPENPLX_CORPUS_DIR) / "agxunity" / "LinearRangeTest.openplx").string();
  std::string err;
  EXPECT_NE(convert({model, "--no-default-bundles", "-o", (dir / "x.xml").string()}, nullptr, &err), 0);
  EXPECT_NE(err.find("Unknown name Physics3D"), std::string::npos) << err;
  // A pin the release does not meet is reported where the config is used.
  const fs::path release = write_release(dir.path(), "0.20.2", "0.19.0");
  EXPECT_NE(convert({model, "--no-default-bundles", "-B", release.string(), "-o", (dir / "y.xml").string()},
                    nullptr, &err),
            0);
  EXPECT_NE(err.find("requires Math@0.19.0 but found Math@0.20.2"), std::string::npos) << err;
}

}  // namespace

namespace {

// 0.31 spells connector kinds as traits on a plain MateConnector, and interactions' connector arrays as a
// trait: the same model in both spellings assembles the same.
TEST(BundleRelease, Spellings031AssembleAsTheOlderOnes) {
  const openplx::testing::ScratchDir dir;
  const std::string body =
      "Box is Physics3D.Bodies.RigidBody:\n"
      "    inertia.mass: 1\n"
      "    shape is Physics3D.Geometries.Box:\n"
      "        size: {0.2, 0.2, 0.2}\n"
      "    fixed is Physics3D.Interactions.MateConnector:\n"
      "        position: {0, 0, 0.1}\n"
      "Scene is Physics3D.System:\n"
      "    a is Box:\n"
      "        kinematics.local_transform.position: {0, 0, 1}\n"
      "    b is Box:\n"
      "        kinematics.local_transform.position: {1, 0, 0}\n";
  const std::string old_form = body +
                               "        moving is Physics3D.Interactions.AdaptiveMateConnector\n"
                               "    lock is Physics3D.Interactions.Lock:\n"
                               "        connectors: [a.fixed, b.moving]\n";
  const std::string new_form =
      body +
      "        moving is Physics3D.Interactions.MateConnector with "
      "Physics3D.Interactions.ConnectorProperties.Adaptive\n"
      "    lock is Physics3D.Interactions.Lock with Physics.Interactions.Configurations.ConnectorArray:\n"
      "        connectors: [a.fixed, b.moving]\n";
  std::ofstream(dir / "old.openplx") << old_form;
  std::ofstream(dir / "new.openplx") << new_form;
  std::string old_snap, new_snap, err;
  ASSERT_EQ(convert({(dir / "old.openplx").string(), "--dump=snap"}, &old_snap, &err), 0) << err;
  ASSERT_EQ(convert({(dir / "new.openplx").string(), "--dump=snap"}, &new_snap, &err), 0) << err;
  EXPECT_EQ(new_snap, old_snap);
  // The adaptive connector moved onto its partner, 1.1 m up at a.fixed, instead of b moving.
  EXPECT_NE(new_snap.find("b.moving position {0.0, 0.0, 1.1}"), std::string::npos) << new_snap;
}

}  // namespace
