// The openplx2mjcf command line, run in-process: exit codes, exact diagnostics, dumps and atomic output.
#include "tools/cli/cli.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/scratch_dir.h"

namespace fs = std::filesystem;
namespace cli = openplx::cli;

namespace {

class Cli : public ::testing::Test {
 protected:
  std::string write(const std::string& name, const std::string& text) {
    fs::path path = dir_ / name;
    std::ofstream(path, std::ios::binary) << text;
    return path.string();
  }
  static std::string read(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
  }
  int run(std::vector<std::string> args) {
    out_.str("");
    err_.str("");
    return cli::run(args, out_, err_);
  }

  openplx::testing::ScratchDir scratch_;
  fs::path dir_ = scratch_.path();
  std::ostringstream out_;
  std::ostringstream err_;
};

const char* kPendulum =
    "Rod:\n"
    "    length is Real: 1.0\n"
    "Scene:\n"
    "    rod is Rod\n";

TEST_F(Cli, HelpAndVersionExitZero) {
  EXPECT_EQ(run({"--help"}), 0);
  EXPECT_NE(out_.str().find("usage: openplx2mjcf FILE"), std::string::npos);
  EXPECT_EQ(run({"--version"}), 0);
  EXPECT_EQ(out_.str().rfind("openplx2mjcf ", 0), 0u);
}

TEST_F(Cli, UsageErrorsExitTwo) {
  EXPECT_EQ(run({}), 2);
  EXPECT_NE(err_.str().find("no input file"), std::string::npos);
  EXPECT_EQ(run({"a.openplx", "--frobnicate"}), 2);
  EXPECT_NE(err_.str().find("unknown option '--frobnicate'"), std::string::npos);
  EXPECT_EQ(run({"a.openplx", "b.openplx"}), 2);
  EXPECT_EQ(run({"a.openplx", "--dump=everything"}), 2);
  EXPECT_EQ(run({"a.openplx", "--model"}), 2);
  EXPECT_NE(err_.str().find("option --model needs a value"), std::string::npos);
  EXPECT_EQ(run({"a.openplx", "-B", (dir_ / "no_such_dir").string()}), 2);
}

TEST_F(Cli, ValidFileExitsZeroQuietly) {
  std::string file = write("scene.openplx", kPendulum);
  EXPECT_EQ(run({file}), 0);
  EXPECT_EQ(err_.str(), "");
  EXPECT_EQ(run({file, "--model", "Rod", "-B", dir_.string()}), 0);
  EXPECT_EQ(run({file, "--model=Scene", "--strict"}), 0);
}

TEST_F(Cli, MissingFileIsAnInputError) {
  const std::string path = (dir_ / "nope.openplx").string();
  EXPECT_EQ(run({path}), 1);
  EXPECT_EQ(err_.str(), path + ": error: cannot open file [io-error]\n");
  EXPECT_EQ(run({dir_.string()}), 1);
  EXPECT_NE(err_.str().find("is a directory"), std::string::npos);
}

TEST_F(Cli, DocumentedMessagesPrintedWithLocationAndCaret) {
  std::string file = write("broken.openplx", "Broken:\n");
  EXPECT_EQ(run({file}), 1);
  EXPECT_EQ(err_.str(), file +
                            ":1:7: error: Expected indented block [expected-block]\n"
                            "  Broken:\n"
                            "        ^\n" +
                            file +
                            ":1:1: error: No model could be found [no-model]\n"
                            "  Broken:\n"
                            "  ^\n");
  file = write("thing.openplx", "Thing:\n    speed\n");
  EXPECT_EQ(run({file}), 1);
  EXPECT_EQ(err_.str(), file +
                            ":2:10: error: Expected an is keyword [expected-is]\n"
                            "      speed\n"
                            "           ^\n");
}

TEST_F(Cli, AllSyntaxErrorsOfAFileInOneRun) {
  std::string file = write("many.openplx",
                           "A:\n"
                           "    x is Real: 1 +\n"
                           "    y is Real: 2\n"
                           "    z\n"
                           "    w is Real: \"open\n");
  EXPECT_EQ(run({file}), 1);
  const std::string err = err_.str();
  EXPECT_NE(err.find(":2:19: error:"), std::string::npos) << err;
  EXPECT_NE(err.find(":4:6: error: Expected an is keyword"), std::string::npos) << err;
  EXPECT_NE(err.find(":5:16: error: unterminated string"), std::string::npos) << err;
}

TEST_F(Cli, UnknownRootModelListsTheModels) {
  std::string file = write("scene.openplx", kPendulum);
  EXPECT_EQ(run({file, "--model", "Nope"}), 1);
  EXPECT_NE(err_.str().find("no model named `Nope` in this file; its models are Rod, Scene [unknown-model]"),
            std::string::npos)
      << err_.str();
}

TEST_F(Cli, TraitsAndGlobalsAreNotRootModels) {
  std::string file = write("only.openplx", "trait Solo:\n    a is Int: 1\nPI is Real: 3.14\n");
  EXPECT_EQ(run({file}), 1);
  EXPECT_NE(err_.str().find(":1:1: error: No model could be found [no-model]"), std::string::npos);
  // A dump does not need a root model: bundle files hold only globals and traits.
  EXPECT_EQ(run({file, "--dump=ast"}), 0);
}

TEST_F(Cli, TokenDumpIsExact) {
  std::string file = write("t.openplx", "A:\n  x is Real: -1.5e3 # c\n");
  EXPECT_EQ(run({file, "--dump=tokens"}), 0);
  EXPECT_EQ(out_.str(),
            "1:1 IDENT \"A\"\n"
            "1:2 : \":\"\n"
            "1:3 NEWLINE\n"
            "2:3 INDENT\n"
            "2:3 IDENT \"x\"\n"
            "2:5 is \"is\"\n"
            "2:8 IDENT \"Real\"\n"
            "2:12 : \":\"\n"
            "2:14 - \"-\"\n"
            "2:15 REAL \"1.5e3\"\n"
            "2:24 NEWLINE\n"
            "3:1 DEDENT\n"
            "3:1 EOF\n");
}

TEST_F(Cli, AstDumpIsExactAndDeterministic) {
  std::string file = write("scene.openplx", kPendulum);
  EXPECT_EQ(run({file, "--dump=ast"}), 0);
  const std::string first = out_.str();
  EXPECT_EQ(first,
            "model Rod @1:1-2:24\n"
            "  attr length is Real = 1.0 @2:5-2:24\n"
            "model Scene @3:1-4:15\n"
            "  attr rod is Rod @4:5-4:15\n");
  EXPECT_EQ(run({file, "--dump=ast"}), 0);
  EXPECT_EQ(out_.str(), first);
}

TEST_F(Cli, OutputFileIsWrittenWholeAndLeavesNoTemporaries) {
  std::string file = write("scene.openplx", kPendulum);
  const fs::path out = dir_ / "scene.ast";
  EXPECT_EQ(run({file, "--dump=ast", "-o", out.string()}), 0);
  EXPECT_EQ(out_.str(), "");
  EXPECT_EQ(read(out),
            "model Rod @1:1-2:24\n  attr length is Real = 1.0 @2:5-2:24\nmodel Scene @3:1-4:15\n"
            "  attr rod is Rod @4:5-4:15\n");
  size_t entries = 0;
  for (const auto& entry : fs::directory_iterator(dir_)) entries += entry.is_regular_file();
  EXPECT_EQ(entries, 2u);  // the input and the output, no temporary file left behind
}

TEST_F(Cli, BadInputWritesNoOutputFileAndKeepsAnOldOne) {
  std::string file = write("broken.openplx", "Broken:\n");
  const fs::path out = dir_ / "broken.ast";
  EXPECT_EQ(run({file, "--dump=ast", "-o", out.string()}), 1);
  EXPECT_FALSE(fs::exists(out));
  std::ofstream(out) << "previous";
  EXPECT_EQ(run({file, "--dump=ast", "-o", out.string()}), 1);
  EXPECT_EQ(read(out), "previous");
}

TEST_F(Cli, NeverOverwritesTheInput) {
  std::string file = write("scene.openplx", kPendulum);
  EXPECT_EQ(run({file, "--dump=ast", "-o", file}), 2);
  EXPECT_NE(err_.str().find("refusing to overwrite the input file"), std::string::npos);
  EXPECT_EQ(read(file), kPendulum);
}

// The manifest beside the output is written too: an input that is that manifest's path is refused as well.
TEST_F(Cli, NeverOverwritesTheInputWithTheManifest) {
  const std::string text = "{\"not\": \"a model\"}\n";
  std::string file = write("x.signals.json", text);
  EXPECT_EQ(run({file, "-o", (dir_ / "x.xml").string()}), 2);
  EXPECT_NE(err_.str().find("refusing to overwrite the input file"), std::string::npos) << err_.str();
  EXPECT_EQ(read(file), text);
  EXPECT_FALSE(fs::exists(dir_ / "x.xml"));
}
TEST_F(Cli, StrictTurnsWarningsIntoErrors) {
  std::string file = write("lenient.openplx", "trait T\n    a is Int: 1\nM:\n    with T\n");
  EXPECT_EQ(run({file}), 0);
  EXPECT_NE(err_.str().find(":1:8: warning: missing `:`"), std::string::npos) << err_.str();
  EXPECT_EQ(run({file, "--strict"}), 1);
  EXPECT_NE(err_.str().find(":1:8: error: missing `:`"), std::string::npos) << err_.str();
}

// An attribute the user sets that nothing maps is a warning at the assignment, naming it: AGX's contact
// reduction on a contact model. --strict makes it an error and writes nothing.
TEST_F(Cli, UnmappedAttributeIsWarnedAtTheUsersLine) {
  const std::string file = write("reduction.openplx",
                                 "const Steel is Physics.Geometries.Material\n"
                                 "Ball is Physics3D.Bodies.RigidBody:\n"
                                 "    inertia.mass: 1\n"
                                 "    geometry is Physics3D.Geometries.Sphere:\n"
                                 "        radius: 0.1\n"
                                 "Scene is Physics3D.System:\n"
                                 "    ball is Ball\n"
                                 "    contact is Physics.Interactions.SurfaceContact.Model:\n"
                                 "        with AGX.ContactReductionBinResolution\n"
                                 "        bin_resolution: 2\n"
                                 "        material_1: Steel\n"
                                 "        material_2: Steel\n"
                                 "        tangential_restitution: 0\n"
                                 "        normal_restitution: 0\n");
  const std::string out = (std::filesystem::path(file).parent_path() / "reduction.xml").string();
  EXPECT_EQ(run({file, "-o", out}), 0) << err_.str();
  EXPECT_NE(
      err_.str().find("reduction.openplx:10:9: warning: `contact.bin_resolution` "
                      "(AGX.ContactReductionBinResolution) has no MuJoCo counterpart here; it was ignored"),
      std::string::npos)
      << err_.str();
  EXPECT_EQ(err_.str().find("inertia.mass` ("), std::string::npos);  // what maps is not warned
  std::filesystem::remove(out);
  EXPECT_EQ(run({file, "-o", out, "--strict"}), 1);
  EXPECT_NE(err_.str().find("reduction.openplx:10:9: error: `contact.bin_resolution`"), std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(out));
}

// signal_test under --strict: its velocity motor keeps AGX's default gain, which a motor constraint needs no
// warning for, so nothing is left to turn into an error.
TEST_F(Cli, SignalTestPassesStrict) {
  const std::string file = std::string(OPENPLX_CORPUS_DIR) + "/agxunity/signal_test.openplx";
  const std::string out = (std::filesystem::path(write("x.txt", "")).parent_path() / "signal.xml").string();
  EXPECT_EQ(run({file, "-o", out, "--strict"}), 0) << err_.str();
  EXPECT_EQ(err_.str(), "");
  EXPECT_TRUE(std::filesystem::exists(out));
}

// OpenPLX has no time-step setting: --timestep sets MuJoCo's, and the emitter's stability caps follow it (a
// velocity motor's stand-in damper is I / h: the wheel's 0.01 kg m^2 over the step).
TEST_F(Cli, TimestepOptionSetsMuJoCosStep) {
  const std::string file =
      write("motor.openplx",
            "Scene is Physics3D.System:\n"
            "    anchor is Physics3D.Interactions.MateConnector:\n"
            "        main_axis: {0, 0, 1}\n"
            "    wheel is Physics3D.Bodies.RigidBody:\n"
            "        inertia.mass: 1\n"
            "        inertia.tensor: Physics3D.Bodies.Inertia.symmetric_tensor({0.01, 0.01, 0.01}, 0, 0, 0)\n"
            "        axle is Physics3D.Interactions.MateConnector:\n"
            "            main_axis: {0, 0, 1}\n"
            "    hinge is Physics3D.Interactions.Hinge:\n"
            "        connectors: [anchor, wheel.axle]\n"
            "    motor is Physics3D.Interactions.RotationalVelocityMotor:\n"
            "        connectors: [anchor, wheel.axle]\n");
  EXPECT_EQ(run({file, "-o", "-", "--timestep", "0.001"}), 0) << err_.str();
  EXPECT_NE(out_.str().find("<option timestep=\"0.001\""), std::string::npos) << out_.str();
  EXPECT_NE(out_.str().find("damping=\"10\""), std::string::npos) << out_.str();
  EXPECT_EQ(run({file, "-o", "-"}), 0) << err_.str();
  EXPECT_NE(out_.str().find("<option timestep=\"0.002\""), std::string::npos);
  EXPECT_NE(out_.str().find("damping=\"5\""), std::string::npos) << out_.str();
  for (const char* bad : {"0", "-1", "fast", "1e999", ""}) {
    EXPECT_EQ(run({file, "--timestep", bad}), 2) << bad;
    EXPECT_NE(err_.str().find("--timestep takes a positive number of seconds"), std::string::npos) << bad;
  }
}

TEST_F(Cli, OutputToStdoutWithDash) {
  std::string file = write("scene.openplx", kPendulum);
  EXPECT_EQ(run({file, "--dump=ast", "-o", "-"}), 0);
  EXPECT_EQ(out_.str().rfind("model Rod", 0), 0u);
}

}  // namespace
