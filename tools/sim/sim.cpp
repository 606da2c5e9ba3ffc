#include "tools/sim/sim.h"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "contract/numbers.h"
#include "openplx/runtime/simulation.h"
#include "tools/cli/output_set.h"
#include "tools/sim/sim_options.h"

namespace openplx::sim {
namespace {

namespace rt = openplx::runtime;

std::string_view type_text(rt::ValueType type) {
  switch (type) {
    case rt::ValueType::Real:
      return "Real";
    case rt::ValueType::Bool:
      return "Bool";
    case rt::ValueType::Int:
      return "Int";
    case rt::ValueType::Vec2:
      return "Vec2";
    case rt::ValueType::Vec3:
      return "Vec3";
    case rt::ValueType::Vector:
      return "Vector";
  }
  return "?";
}

void apply(rt::Simulation& sim, const Assignment& a) {
  rt::Input input = sim.input(a.name);
  if (input.info().value == rt::ValueType::Vector) {  // a composite: {a, b, ...}, one value per target
    input.set(Eigen::VectorXd(Eigen::Map<const Eigen::VectorXd>(
        a.value.numbers.data(), static_cast<Eigen::Index>(a.value.numbers.size()))));
  } else if (a.value.is_bool) {
    input.set(a.value.numbers[0] != 0);
  } else if (a.value.numbers.size() == 2) {
    input.set(Eigen::Vector2d(a.value.numbers[0], a.value.numbers[1]));
  } else if (a.value.numbers.size() == 3) {
    input.set(Eigen::Vector3d(a.value.numbers[0], a.value.numbers[1], a.value.numbers[2]));
  } else {
    input.set(a.value.numbers[0]);
  }
}

// The output's value as text ({x, y, z} for vectors) and as CSV columns.
std::vector<double> values(const rt::Output& output) {
  switch (output.info().value) {
    case rt::ValueType::Bool:
      return {output.boolean() ? 1.0 : 0.0};
    case rt::ValueType::Vec2: {
      const Eigen::Vector2d v = output.vec2();
      return {v.x(), v.y()};
    }
    case rt::ValueType::Vec3: {
      const Eigen::Vector3d v = output.vec3();
      return {v.x(), v.y(), v.z()};
    }
    case rt::ValueType::Vector: {
      const Eigen::VectorXd v = output.vector();
      return {v.data(), v.data() + v.size()};
    }
    default:
      return {output.real()};
  }
}

std::string text(const rt::Output& output) {
  const std::vector<double> v = values(output);
  if (output.info().value == rt::ValueType::Bool) return v[0] != 0 ? "true" : "false";
  if (v.size() == 1) return mjcf::number(v[0]);
  std::string s = "{";
  for (size_t k = 0; k < v.size(); ++k) s += (k ? ", " : "") + mjcf::number(v[k]);
  return s + "}";
}

void list(const rt::Simulation& sim, std::ostream& out) {
  for (const auto& [title, signals] :
       {std::pair{"inputs", sim.inputs()}, std::pair{"outputs", sim.outputs()}}) {
    out << title << ":\n";
    for (const rt::SignalInfo& s : signals) {
      out << "  " << s.name << "  " << type_text(s.value) << (s.unit.empty() ? "" : " [" + s.unit + "]")
          << "  " << s.type << "  -> " << s.mujoco << '\n';
    }
  }
}

int simulate(const SimOptions& options, std::ostream& out, std::ostream& err) {
  rt::LoadOptions load;
  load.model = options.model;
  load.bundle_paths = options.bundle_dirs;
  load.default_bundles = options.default_bundles;
  load.timestep = options.timestep;
  load.sensor_noise = {options.noise, options.seed};
  if (!options.csv.empty()) {  // never overwrite the input
    std::error_code ec;
    if (std::filesystem::equivalent(options.csv, options.input, ec)) {
      err << options.csv << ": error: the CSV file is the model file; refusing to overwrite the input\n";
      return 1;
    }
  }
  rt::Simulation sim = rt::Simulation::load(options.input, load);
  size_t warned = 0;  // warnings printed so far: the transpilation's, then the run's as they come
  auto print_warnings = [&] {
    for (; warned < sim.warnings().size(); ++warned) err << sim.warnings()[warned];
  };
  print_warnings();
  if (options.list) {
    list(sim, out);
    return 0;
  }
  std::vector<rt::Output> printed;
  for (const std::string& name : options.prints) printed.push_back(sim.output(name));
  // The CSV goes to a temporary file, renamed over --csv's only when the run succeeded (never a partial
  // file), and never over a file the model was read from (an imported .openplx, a mesh).
  cli::OutputSet written;
  std::ofstream csv;
  if (!options.csv.empty()) {
    std::vector<std::string> read = sim.files_read();
    read.push_back(options.input);
    std::string bad, error;
    if (const std::string clash = cli::outputs_clash({{options.csv, "--csv"}}, read, bad); !clash.empty()) {
      err << bad << ": error: " << clash << '\n';
      return 1;
    }
    if (!written.stage_stream(options.csv, csv, error)) {
      err << options.csv << ": error: cannot write the CSV file: " << error << '\n';
      return 1;
    }
    csv << "time";
    for (size_t k = 0; k < printed.size(); ++k) {
      const size_t columns = values(printed[k]).size();
      for (size_t c = 0; c < columns; ++c)
        csv << ',' << options.prints[k] << (columns > 1 ? "[" + std::to_string(c) + "]" : "");
    }
    csv << '\n';
  }
  auto row = [&]() {
    if (!csv.is_open()) return;
    csv << mjcf::number(sim.time());
    for (const rt::Output& o : printed) {
      for (double v : values(o)) csv << ',' << mjcf::number(v);
    }
    csv << '\n';
  };
  size_t next = 0;
  const auto& assignments = options.assignments;
  const double h = sim.timestep();
  const double whole_steps = std::round(options.time / h);
  if (whole_steps > static_cast<double>(rt::Simulation::kMaxAdvanceSteps)) {
    err << "openplx-sim: error: --time " << options.time << " s at a time step of " << h << " s is "
        << whole_steps << " steps, more than the " << rt::Simulation::kMaxAdvanceSteps << " a run takes\n";
    return 2;
  }
  const long steps = static_cast<long>(whole_steps);
  const auto start = std::chrono::steady_clock::now();
  auto last_report = start;
  row();
  for (long k = 0; k <= steps; ++k) {
    // Inputs due at this time (half a step of slack: times are rounded to whole steps).
    while (next < assignments.size() && assignments[next].time <= sim.time() + 0.5 * h)
      apply(sim, assignments[next++]);
    if (warned != sim.warnings().size()) print_warnings();  // an input clamped
    if (k == steps) break;
    sim.step();
    if (warned != sim.warnings().size()) print_warnings();
    row();
    const auto now = std::chrono::steady_clock::now();
    if (now - last_report > std::chrono::seconds(2)) {  // long runs say how far they are
      err << "openplx-sim: t = " << sim.time() << " s of " << options.time << " s\n";
      last_report = now;
    }
  }
  if (csv.is_open()) {
    csv.close();
    std::string error;
    if (!csv || !written.commit(error)) {
      err << options.csv << ": error: cannot write the CSV file" << (error.empty() ? "" : " (" + error + ")")
          << '\n';
      return 1;
    }
  }
  for (size_t k = 0; k < printed.size(); ++k) out << options.prints[k] << " = " << text(printed[k]) << '\n';
  return 0;
}

}  // namespace

int run_sim(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  std::string error;
  std::optional<SimOptions> options = parse_sim_options(args, error);
  if (!options) {
    err << "openplx-sim: error: " << error << "\nTry 'openplx-sim --help'.\n";
    return 2;
  }
  if (options->help) {
    out << sim_usage();
    return 0;
  }
  try {
    return simulate(*options, out, err);
  } catch (const rt::LoadError& e) {
    err << e.what();
  } catch (const rt::SignalError& e) {
    err << "openplx-sim: error: " << e.what() << '\n';
  } catch (const rt::SimulationError& e) {  // what() is located: "FILE: error: at t = ..."
    err << e.what();
  }
  return 1;
}

}  // namespace openplx::sim
