// openplx-sim in-process: options, value syntax, printed values, CSV time series, listing and errors.
#include "tools/sim/sim.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "tests/support/light_rod.h"
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

// A run MuJoCo had to reset is exit 1 with the message, never a printed value.
TEST(Sim, DivergingModelExitsOneWithTheMessage) {
  const openplx::testing::ScratchDir scratch;
  const fs::path model = scratch / "light_rod.openplx";
  std::ofstream(model) << openplx::testing::kLightRodPendulum << openplx::testing::kLightRodMotor;
  const SimRun run = sim({model.string(), "--time", "1", "--at", "0.5", "motor.torque_input=1e8", "--print",
                          "hinge.angle_output"});
  EXPECT_EQ(run.status, 1);
  EXPECT_EQ(run.out, "");  // no value printed for a run that went wrong
  EXPECT_NE(run.err.find("light_rod.openplx: error: at t = 0.5 s"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("joint `hinge` in body `rod`"), std::string::npos) << run.err;
}

TEST(Sim, HostileOptionsAreErrors) {
  const std::string drivetrain = std::string(OPENPLX_SAMPLES_DIR) + "/drivetrain_machine.openplx";
  for (const char* gear : {"gear=2147483648", "gear=-2147483648", "gear=1e300", "gear=-1e300"}) {
    const SimRun run = sim({drivetrain, "--time", "0.01", "--set", gear});
    EXPECT_EQ(run.status, 1) << gear;
    EXPECT_NE(run.err.find("is not one of its"), std::string::npos) << run.err;
  }
  const std::string pendulum = std::string(OPENPLX_SAMPLES_DIR) + "/pendulum.openplx";
  for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{{"--time", "nan"},
                                                                                    {"--time", "inf"},
                                                                                    {"--time", "1e300"},
                                                                                    {"--timestep", "1e308"},
                                                                                    {"--timestep", "1e-320"},
                                                                                    {"--timestep", "nan"}}) {
    std::vector<std::string> line = {pendulum};
    line.insert(line.end(), args.begin(), args.end());
    const SimRun run = sim(line);
    EXPECT_EQ(run.status, 2) << args[0] << ' ' << args[1] << ": " << run.err;
    EXPECT_NE(run.err.find("error:"), std::string::npos) << run.err;
  }
}

TEST(Sim, NeverOverwritesTheModelWithTheCsv) {
  const openplx::testing::ScratchDir scratch;
  const fs::path model = scratch / "pendulum.openplx";
  fs::copy_file(fs::path(OPENPLX_SAMPLES_DIR) / "pendulum.openplx", model);
  const uintmax_t size = fs::file_size(model);
  for (const fs::path& csv : {model, scratch / "." / "pendulum.openplx"}) {
    const SimRun run = sim({model.string(), "--time", "0.01", "--csv", csv.string()});
    EXPECT_EQ(run.status, 1);
    EXPECT_NE(run.err.find("refusing to overwrite the input"), std::string::npos) << run.err;
    EXPECT_EQ(fs::file_size(model), size);
  }
}

TEST(Sim, ClampedInputIsSaid) {
  const std::string drivetrain = std::string(OPENPLX_SAMPLES_DIR) + "/drivetrain_machine.openplx";
  const SimRun run =
      sim({drivetrain, "--time", "0.01", "--set", "throttle=5", "--at", "0.004", "throttle=7"});
  ASSERT_EQ(run.status, 0) << run.err;
  const size_t at = run.err.find("input `throttle` got 5, outside its range [0, 1]: clamped to 1");
  EXPECT_NE(at, std::string::npos) << run.err;
  EXPECT_EQ(run.err.find("input `throttle` got", at + 1), std::string::npos) << run.err;  // once
}

}  // namespace
