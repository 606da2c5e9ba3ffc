// The bodies of the runtime's fuzz targets, shared by the libFuzzer entry points and the regression test:
// - manifest_one: the bytes as a signal manifest, attached with a SignalBridge to the cart-pole sample (its
//   MJCF compiled once per process), then every input the bridge took set and every output read around a
//   few steps;
// - runtime_input_one: the bytes as a program of input sets, steps and output reads on the drivetrain
//   sample (every kind of input: gears, clutches, brakes, kinematic and free velocities), through a bridge on
//   a fresh copy of the compiled model each run, so a run depends on its bytes alone.
// Errors the runtime reports (LoadError, SignalError, SimulationError, invalid_argument) are the expected
// outcomes; anything else, a crash or a sanitizer report, is a finding.
#pragma once

#include <unistd.h>

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "frontend/pipeline.h"
#include "mjcf_emitter/document_fingerprint.h"
#include "mjcf_emitter/emitter.h"
#include "openplx/runtime/signal_bridge.h"
#include "openplx/runtime/simulation.h"
#include "runtime/mujoco_messages.h"
#include "snap/resolve_system.h"
#include "snap/snap.h"

#ifndef OPENPLX_FUZZ_SAMPLES_DIR
#define OPENPLX_FUZZ_SAMPLES_DIR OPENPLX_SAMPLES_DIR
#endif

namespace openplx::fuzz {

namespace rt = openplx::runtime;

// A sample emitted and compiled once: the pristine model each run copies, and its manifest's text.
struct CompiledSample {
  mjModel* model = nullptr;
  std::string manifest;
};

inline CompiledSample compile_sample(const std::string& file) {
  namespace fe = openplx::frontend;
  CompiledSample out;
  fe::SourceManager sources;
  fe::DiagnosticSink sink;
  fe::LoadRequest request;
  request.path = std::string(OPENPLX_FUZZ_SAMPLES_DIR) + "/" + file;
  fe::Evaluation evaluation = fe::evaluate_file(request, sources, sink);
  if (evaluation.root == fe::kNoObject || sink.has_errors()) return out;
  openplx::snap::ResolvedSystem system =
      openplx::snap::resolve_system(*evaluation.evaluator, evaluation.root, sink);
  openplx::snap::run_snap(system, sink);
  openplx::mjcf::EmitOptions options;
  options.model_name = evaluation.evaluator->root_name();
  const openplx::mjcf::Emitted emitted = openplx::mjcf::emit_mjcf(system, options, sink);
  openplx::mjcf::ManifestModel facts;
  facts.fingerprint = openplx::mjcf::model_fingerprint(emitted.document, "").text();
  facts.timestep = 0.002;
  out.manifest = openplx::mjcf::manifest_json(options.model_name, "", emitted.signals, emitted.laws, facts);
  const std::string xml = (std::filesystem::temp_directory_path() /
                           ("openplx_fuzz_" + std::to_string(getpid()) + "_" + file + ".xml"))
                              .string();
  std::ofstream(xml) << emitted.document.to_string();
  char error[1000] = "";
  out.model = mj_loadXML(xml.c_str(), nullptr, error, sizeof(error));
  std::error_code ignored;
  std::filesystem::remove(xml, ignored);
  return out;
}

// A file that exists while it lives (the bridge reads manifests from files), in `dir`.
class TemporaryFile {
 public:
  TemporaryFile(const std::filesystem::path& dir, const std::string& name, const void* data, size_t size)
      : path_((dir / ("openplx_fuzz_" + std::to_string(getpid()) + "_" + name)).string()) {
    std::ofstream(path_, std::ios::binary)
        .write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  ~TemporaryFile() {
    std::error_code ignored;
    std::filesystem::remove(path_, ignored);
  }
  TemporaryFile(const TemporaryFile&) = delete;
  TemporaryFile& operator=(const TemporaryFile&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

// A fresh copy of a compiled sample and its data, freed after the run.
struct Run {
  mjModel* m = nullptr;
  mjData* d = nullptr;
  explicit Run(const mjModel* pristine)
      : m(mj_copyModel(nullptr, pristine)), d(m ? mj_makeData(m) : nullptr) {}
  ~Run() {
    if (d) mj_deleteData(d);
    if (m) mj_deleteModel(m);
  }
  Run(const Run&) = delete;
  Run& operator=(const Run&) = delete;
};

// One step as a bridge user takes it; MuJoCo's errors land in the runtime's handler, as in the runtime.
inline void bridge_step(rt::SignalBridge& bridge, Run& run) {
  bridge.before_step();
  std::string error;
  if (!rt::call_mujoco(
          run.d, [&run] { mj_step(run.m, run.d); }, error))
    throw std::runtime_error(error);
  bridge.after_step();
}

inline void set_input(rt::Input& input, const double* values, size_t count) {
  switch (input.info().value) {
    case rt::ValueType::Bool:
      input.set(values[0] != 0);
      return;
    case rt::ValueType::Vec2:
      input.set(Eigen::Vector2d(values[0], values[1 % count]));
      return;
    case rt::ValueType::Vec3:
      input.set(Eigen::Vector3d(values[0], values[1 % count], values[2 % count]));
      return;
    case rt::ValueType::Vector: {
      Eigen::VectorXd v(static_cast<Eigen::Index>(input.info().size));
      for (Eigen::Index k = 0; k < v.size(); ++k) v[k] = values[static_cast<size_t>(k) % count];
      input.set(v);
      return;
    }
    default:
      input.set(values[0]);
  }
}

inline void read_output(const rt::Output& output) {
  switch (output.info().value) {
    case rt::ValueType::Bool:
      (void)output.boolean();
      return;
    case rt::ValueType::Vec2:
      (void)output.vec2();
      return;
    case rt::ValueType::Vec3:
      (void)output.vec3();
      return;
    case rt::ValueType::Vector:
      (void)output.vector();
      return;
    default:
      (void)output.real();
  }
}

template <typename Body>
void expected_errors(Body&& body) {
  try {
    body();
  } catch (const rt::LoadError&) {
  } catch (const rt::SignalError&) {
  } catch (const rt::SimulationError&) {
  } catch (const std::invalid_argument&) {
  } catch (const std::runtime_error&) {  // bridge_step: an error MuJoCo stopped on
  }
}

inline void manifest_one(const uint8_t* data, size_t size,
                         const std::filesystem::path& dir = std::filesystem::temp_directory_path()) {
  static const CompiledSample sample = compile_sample("cart_pole.openplx");
  if (!sample.model) return;
  const TemporaryFile manifest(dir, "manifest.signals.json", data, size);
  Run run(sample.model);
  expected_errors([&] {
    rt::SignalBridge bridge = rt::SignalBridge::attach(manifest.path(), run.m, run.d);
    const double values[3] = {0.5, -0.25, 1.0};
    for (const rt::SignalInfo& info : bridge.inputs()) {
      expected_errors([&] {
        rt::Input input = bridge.input(info.name);
        set_input(input, values, 3);
      });
    }
    for (int k = 0; k < 3; ++k) {
      bridge_step(bridge, run);
      for (const rt::SignalInfo& info : bridge.outputs())
        expected_errors([&] { read_output(bridge.output(info.name)); });
    }
  });
}

// Ops, one byte each, then their operands: 0 set input (index byte, then 8-byte doubles as its kind takes,
// any bit pattern: NaN, Inf, 2^31, 1e300, denormals), 1 steps (count byte, 1-8), 2 read output (index
// byte), 3 switch OnInstability. At most 64 ops.
inline void runtime_input_one(const uint8_t* data, size_t size,
                              const std::filesystem::path& dir = std::filesystem::temp_directory_path()) {
  static const CompiledSample sample = compile_sample("drivetrain_machine.openplx");
  if (!sample.model) return;
  const TemporaryFile manifest(dir, "drivetrain.signals.json", sample.manifest.data(),
                               sample.manifest.size());
  Run run(sample.model);
  size_t at = 0;
  auto byte = [&]() -> uint8_t { return at < size ? data[at++] : 0; };
  auto number = [&]() {
    double v = 0;
    uint8_t bytes[8] = {};
    for (uint8_t& b : bytes) b = byte();
    std::memcpy(&v, bytes, sizeof(v));
    return v;
  };
  expected_errors([&] {
    rt::SignalBridge bridge = rt::SignalBridge::attach(manifest.path(), run.m, run.d);
    const std::vector<rt::SignalInfo> inputs = bridge.inputs(), outputs = bridge.outputs();
    if (inputs.empty() || outputs.empty()) return;
    bool keep_going = false;
    for (int op = 0; op < 64 && at < size; ++op) {
      switch (byte() % 4) {
        case 0: {
          const rt::SignalInfo& info = inputs[byte() % inputs.size()];
          const size_t count = info.value == rt::ValueType::Vec2     ? 2
                               : info.value == rt::ValueType::Vec3   ? 3
                               : info.value == rt::ValueType::Vector ? 4
                                                                     : 1;
          double values[4];
          for (size_t k = 0; k < count; ++k) values[k] = number();
          expected_errors([&] {
            rt::Input input = bridge.input(info.name);
            set_input(input, values, count);
          });
          break;
        }
        case 1: {
          const int steps = 1 + byte() % 8;
          for (int k = 0; k < steps; ++k) expected_errors([&] { bridge_step(bridge, run); });
          break;
        }
        case 2:
          expected_errors([&] { read_output(bridge.output(outputs[byte() % outputs.size()].name)); });
          break;
        default:
          keep_going = !keep_going;
          bridge.set_on_instability(keep_going ? rt::OnInstability::Continue : rt::OnInstability::Throw);
      }
    }
  });
}

}  // namespace openplx::fuzz
