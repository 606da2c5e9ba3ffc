// The `openplx-sim` command line:
//   openplx-sim FILE [--model NAME] [-B DIR]... [--time T] [--set NAME=VALUE]... [--at T NAME=VALUE]...
//               [--print NAME]... [--csv FILE] [--list] [--seed N] [--no-noise]
// VALUE is a number, true/false, {a, b} or {x, y, z}.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace openplx::sim {

// The time steps openplx::runtime::Simulation::load takes, s.
inline constexpr double kMinTimestep = 1e-6, kMaxTimestep = 1.0;

struct SignalValue {
  std::vector<double> numbers;  // 1, 2 or 3 numbers
  bool is_bool = false;
};

struct Assignment {
  double time = 0.0;  // --set: 0
  std::string name;
  SignalValue value;
};

struct SimOptions {
  std::string input;
  std::string model;
  std::vector<std::string> bundle_dirs;
  bool default_bundles = true;  // --no-default-bundles
  double time = 1.0;
  double timestep = 0.002;
  std::vector<Assignment> assignments;  // --set then --at, in the order given
  std::vector<std::string> prints;
  std::string csv;
  bool list = false;
  bool help = false;
  bool noise = true;       // --no-noise: outputs without the model's sensor noise
  std::uint64_t seed = 0;  // --seed: the sensor noise's seed (runtime::SensorNoiseOptions)
};

// Parses argv[1..]; nullopt and `error` on a usage error.
std::optional<SimOptions> parse_sim_options(const std::vector<std::string>& args, std::string& error);
// "1.5", "true", "{1, 2}", "{1, 2, 3}"; nullopt when it is none of them.
std::optional<SignalValue> parse_signal_value(const std::string& text);
std::string sim_usage();

}  // namespace openplx::sim
