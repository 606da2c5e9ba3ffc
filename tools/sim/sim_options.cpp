#include "tools/sim/sim_options.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace openplx::sim {
namespace {

std::optional<double> parse_number(const std::string& text) {
  const char* begin = text.c_str();
  while (*begin == ' ') ++begin;
  char* end = nullptr;
  const double value = std::strtod(begin, &end);
  if (end == begin) return std::nullopt;
  while (*end == ' ') ++end;
  if (*end != '\0' || !std::isfinite(value)) return std::nullopt;
  return value;
}

// A decimal number that fits 64 unsigned bits, digits only (strtoull alone takes "-1" as 2^64 - 1).
std::optional<std::uint64_t> parse_seed(const std::string& text) {
  if (text.empty() || text.size() > 20 ||
      !std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; }))
    return std::nullopt;
  errno = 0;
  const unsigned long long value = std::strtoull(text.c_str(), nullptr, 10);
  if (errno == ERANGE) return std::nullopt;
  return static_cast<std::uint64_t>(value);
}

// "NAME=VALUE"
std::optional<Assignment> parse_assignment(const std::string& text, std::string& error) {
  const size_t eq = text.find('=');
  if (eq == std::string::npos || eq == 0) {
    error = "expected NAME=VALUE, got '" + text + "'";
    return std::nullopt;
  }
  std::optional<SignalValue> value = parse_signal_value(text.substr(eq + 1));
  if (!value) {
    error = "'" + text.substr(eq + 1) + "' is not a number, true/false or {a, b, ...}";
    return std::nullopt;
  }
  return Assignment{0.0, text.substr(0, eq), *value};
}

}  // namespace

std::optional<SignalValue> parse_signal_value(const std::string& text) {
  if (text == "true" || text == "false") return SignalValue{{text == "true" ? 1.0 : 0.0}, true};
  if (!text.empty() && text.front() == '{' && text.back() == '}') {
    SignalValue value;
    std::stringstream parts(text.substr(1, text.size() - 2));
    std::string part;
    while (std::getline(parts, part, ',')) {
      std::optional<double> number = parse_number(part);
      if (!number) return std::nullopt;
      value.numbers.push_back(*number);
    }
    if (value.numbers.empty()) return std::nullopt;  // {a, b}, {x, y, z}, or a composite's {a, b, c, ...}
    return value;
  }
  if (std::optional<double> number = parse_number(text)) return SignalValue{{*number}, false};
  return std::nullopt;
}

std::string sim_usage() {
  return "usage: openplx-sim FILE [--model NAME] [-B DIR]... [--no-default-bundles] [--time T] [--timestep "
         "S] [--set "
         "NAME=VALUE]...\n"
         "                   [--at T NAME=VALUE]... [--print NAME]... [--csv FILE] [--list] [--seed N] "
         "[--no-noise]\n"
         "Runs an OpenPLX model headless in MuJoCo. VALUE is a number, true/false, {a, b}, {x, y, z} or, for "
         "a\n"
         "composite robot input, one value per target: {a, b, c, ...}.\n"
         "  --time T         simulated seconds (default 1)\n"
         "  --timestep S     MuJoCo's time step in seconds, 1e-6 to 1 (default 0.002)\n"
         "  --set NAME=V     set an input before the first step\n"
         "  --at T NAME=V    set an input once the simulated time reaches T\n"
         "  --print NAME     print an output's final value as `NAME = value`\n"
         "  --csv FILE       write the time series of the printed outputs\n"
         "  --list           list inputs and outputs with their types and MuJoCo elements\n"
         "  --seed N         seed of the sensor noise, 0 to 2^64-1 (default 0): the same seed, the same "
         "values\n"
         "  --no-noise       outputs without the model's sensor noise (lidar distance, IMU signal noise)\n";
}

std::optional<SimOptions> parse_sim_options(const std::vector<std::string>& args, std::string& error) {
  SimOptions options;
  std::vector<Assignment> timed;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    auto value = [&](size_t count = 1) -> bool {
      if (i + count >= args.size()) {
        error = "option " + arg + " needs " + (count == 1 ? "a value" : "two values");
        return false;
      }
      return true;
    };
    if (arg == "--help" || arg == "-h") {
      options.help = true;
    } else if (arg == "--list") {
      options.list = true;
    } else if (arg == "--no-noise") {
      options.noise = false;
    } else if (arg == "--seed") {
      if (!value()) return std::nullopt;
      std::optional<std::uint64_t> seed = parse_seed(args[++i]);
      if (!seed) {
        error = "--seed needs a whole number from 0 to 18446744073709551615, got '" + args[i] + "'";
        return std::nullopt;
      }
      options.seed = *seed;
    } else if (arg == "--no-default-bundles") {
      options.default_bundles = false;
    } else if (arg == "--model") {
      if (!value()) return std::nullopt;
      options.model = args[++i];
    } else if (arg == "-B" || arg == "--bundle-path") {
      if (!value()) return std::nullopt;
      options.bundle_dirs.push_back(args[++i]);
    } else if (arg == "--time") {
      if (!value()) return std::nullopt;
      std::optional<double> t = parse_number(args[++i]);
      if (!t || *t < 0) {
        error = "--time needs a non-negative number, got '" + args[i] + "'";
        return std::nullopt;
      }
      options.time = *t;
    } else if (arg == "--timestep") {
      if (!value()) return std::nullopt;
      std::optional<double> h = parse_number(args[++i]);
      if (!h || !(*h > 0)) {
        error = "--timestep needs a positive number of seconds, got '" + args[i] + "'";
        return std::nullopt;
      }
      if (*h < kMinTimestep || *h > kMaxTimestep) {
        error = "--timestep " + args[i] + " is outside what a simulation can use (1e-06 to 1 s)";
        return std::nullopt;
      }
      options.timestep = *h;
    } else if (arg == "--set") {
      if (!value()) return std::nullopt;
      std::optional<Assignment> a = parse_assignment(args[++i], error);
      if (!a) return std::nullopt;
      options.assignments.push_back(*a);
    } else if (arg == "--at") {
      if (!value(2)) return std::nullopt;
      std::optional<double> t = parse_number(args[++i]);
      if (!t || *t < 0) {
        error = "--at needs a non-negative time, got '" + args[i] + "'";
        return std::nullopt;
      }
      std::optional<Assignment> a = parse_assignment(args[++i], error);
      if (!a) return std::nullopt;
      a->time = *t;
      timed.push_back(*a);
    } else if (arg == "--print") {
      if (!value()) return std::nullopt;
      options.prints.push_back(args[++i]);
    } else if (arg == "--csv") {
      if (!value()) return std::nullopt;
      options.csv = args[++i];
    } else if (!arg.empty() && arg[0] == '-') {
      error = "unknown option '" + arg + "'";
      return std::nullopt;
    } else if (options.input.empty()) {
      options.input = arg;
    } else {
      error = "more than one input file ('" + options.input + "' and '" + arg + "')";
      return std::nullopt;
    }
  }
  if (!options.help && options.input.empty()) {
    error = "no input file";
    return std::nullopt;
  }
  std::stable_sort(timed.begin(), timed.end(),
                   [](const Assignment& a, const Assignment& b) { return a.time < b.time; });
  options.assignments.insert(options.assignments.end(), timed.begin(), timed.end());
  return options;
}

}  // namespace openplx::sim
