// openplx-sim in-process: options, value syntax, printed values, CSV time series, listing and errors.
#include "tools/sim/sim.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "tests/support/scratch_dir.h"
#include "tools/sim/sim_options.h"

namespace {

namespace fs = std::filesystem;
using openplx::sim::parse_signal_value;
using openplx::sim::run_sim;

const std::string kSignalTest = (fs::path(OPENPLX_CORPUS_DIR) / "agxunity" / "signal_test.openplx").string();

struct SimRun {
  int status;
  std::string out, err;
};
SimRun sim(const std::vector<std::string>& args) {
  std::ostringstream out, err;
  const int status = run_sim(args, out, err);
  return {status, out.str(), err.str()};
}

double printed(const std::string& out, const std::string& name) {
  const size_t at = out.find(name + " = ");
  EXPECT_NE(at, std::string::npos) << out;
  return at == std::string::npos ? NAN : std::stod(out.substr(at + name.size() + 3));
}

TEST(Sim, SetAtAndPrint) {
  const SimRun run = sim({kSignalTest, "--time", "0.4", "--set", "motorSpeedInput=1", "--at", "0.2",
                          "motorSpeedInput=-1", "--print", "angularVelocity", "--print", "boxRPY"});
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_NEAR(printed(run.out, "angularVelocity"), -1.0, 1e-6);
  // 0.2 s at +1 rad/s then 0.2 s at -1: back near zero yaw, printed as a vector.
  EXPECT_NE(run.out.find("boxRPY = {0, 0, "), std::string::npos) << run.out;
}

TEST(Sim, CsvHasOneRowPerStep) {
  const openplx::testing::ScratchDir scratch;
  const fs::path csv = scratch / "sim.csv";
  const SimRun run = sim({kSignalTest, "--time", "0.01", "--set", "motorSpeedInput=1", "--print",
                          "angularVelocity", "--print", "boxRPY", "--csv", csv.string()});
  ASSERT_EQ(run.status, 0) << run.err;
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "time,angularVelocity,boxRPY[0],boxRPY[1],boxRPY[2]");
  size_t rows = 0;
  while (std::getline(in, line)) ++rows;
  EXPECT_EQ(rows, 6u);  // t = 0 and 5 steps of 2 ms
}

// --timestep is MuJoCo's step: 0.01 s at 1 ms is ten steps, eleven rows with t = 0.
TEST(Sim, TimestepSetsTheStep) {
  const openplx::testing::ScratchDir scratch;
  const fs::path csv = scratch / "sim_timestep.csv";
  const SimRun run = sim({kSignalTest, "--time", "0.01", "--timestep", "0.001", "--print", "angularVelocity",
                          "--csv", csv.string()});
  ASSERT_EQ(run.status, 0) << run.err;
  std::ifstream in(csv);
  std::string line;
  size_t rows = 0;
  while (std::getline(in, line)) ++rows;
  EXPECT_EQ(rows, 12u);  // the header, t = 0 and 10 steps
  EXPECT_EQ(sim({kSignalTest, "--timestep", "0"}).status, 2);
}

TEST(Sim, ListShowsTypesUnitsAndMuJoCoElements) {
  const SimRun run = sim({kSignalTest, "--list"});
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_NE(
      run.out.find("  motorSpeedInput  Real [rad/s]  Physics.Signals.AngularVelocity1DInput  -> actuator "
                   "motor: ctrl\n"),
      std::string::npos)
      << run.out;
  EXPECT_NE(run.out.find("outputs:\n"), std::string::npos);
}

TEST(Sim, ErrorsAreReportedWithStatus) {
  EXPECT_EQ(sim({}).status, 2);
  EXPECT_EQ(sim({kSignalTest, "--set", "motorSpeedInput"}).status, 2);
  EXPECT_EQ(sim({kSignalTest, "--set", "motorSpeedInput=fast"}).status, 2);
  EXPECT_EQ(sim({kSignalTest, "--time", "-1"}).status, 2);
  const SimRun unknown = sim({kSignalTest, "--print", "angularVelocty"});
  EXPECT_EQ(unknown.status, 1);
  EXPECT_NE(unknown.err.find("no output named `angularVelocty`; did you mean `angularVelocity`?"),
            std::string::npos)
      << unknown.err;
  const SimRun wrong_type = sim({kSignalTest, "--set", "motorSpeedInput={1, 2}"});
  EXPECT_EQ(wrong_type.status, 1);
  EXPECT_NE(wrong_type.err.find("takes a Real, not a Vec2"), std::string::npos) << wrong_type.err;
  EXPECT_EQ(sim({"/nonexistent.openplx"}).status, 1);
}

TEST(Sim, ValueSyntax) {
  EXPECT_EQ(parse_signal_value("1.5")->numbers, std::vector<double>{1.5});
  EXPECT_TRUE(parse_signal_value("true")->is_bool);
  EXPECT_EQ(parse_signal_value("{1, -2}")->numbers, (std::vector<double>{1, -2}));
  EXPECT_EQ(parse_signal_value("{1,2,3}")->numbers, (std::vector<double>{1, 2, 3}));
  EXPECT_EQ(parse_signal_value("{1}")->numbers, std::vector<double>{1});  // a one-target composite
  EXPECT_EQ(parse_signal_value("{1, 2, 3, 4}")->numbers.size(), 4u);      // a composite robot input
  EXPECT_FALSE(parse_signal_value("{}"));
  EXPECT_FALSE(parse_signal_value("1.5x"));
  EXPECT_FALSE(parse_signal_value("nan"));
  EXPECT_FALSE(parse_signal_value(""));
}

}  // namespace
