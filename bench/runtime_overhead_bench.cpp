// The runtime's signal bridge against bare MuJoCo: a 20-joint arm (a chain of 20 hinged links, each with a
// torque motor and angle and speed outputs) stepped 100,000 times with every mapped input set and every
// mapped output read each step, next to mj_step on the same compiled model in the same run. Target: <= 1.02x.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "openplx/runtime/simulation.h"

namespace rt = openplx::runtime;
namespace fs = std::filesystem;

namespace {

std::string chain_model(int links) {
  std::string text =
      "Link is Physics3D.Bodies.RigidBody:\n"
      "    inertia.mass: 0.5\n"
      "    geometry is Physics3D.Geometries.Box:\n"
      "        size: {0.04, 0.04, 0.2}\n"
      "    top is Physics3D.Interactions.MateConnector:\n"
      "        position.z: 0.1\n"
      "        main_axis: Math.Vec3.Y_AXIS()\n"
      "        normal: Math.Vec3.Z_AXIS()\n"
      "    bottom is Physics3D.Interactions.MateConnector:\n"
      "        position.z: -0.1\n"
      "        main_axis: Math.Vec3.Y_AXIS()\n"
      "        normal: Math.Vec3.Z_AXIS()\n"
      "Arm is Physics3D.System:\n"
      "    base is Physics3D.Interactions.MateConnector:\n"
      "        main_axis: Math.Vec3.Y_AXIS()\n"
      "        normal: Math.Vec3.Z_AXIS()\n";
  for (int k = 0; k < links; ++k) {
    const std::string l = "l" + std::to_string(k), j = "j" + std::to_string(k);
    const std::string parent = k == 0 ? "base" : "l" + std::to_string(k - 1) + ".bottom";
    text += "    " + l + " is Link\n";
    text += "    " + j + " is Physics3D.Interactions.Hinge:\n        connectors: [" + parent + ", " + l +
            ".top]\n        initial_angle: 0.05\n        angle_output.enabled: true\n"
            "        angular_velocity_output.enabled: true\n";
    text += "    m" + std::to_string(k) +
            " is Physics3D.Interactions.TorqueMotor:\n        connectors: " + j + ".connectors\n";
  }
  return text;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

int main() {
  constexpr int kSteps = 100000;
  const fs::path file = fs::temp_directory_path() / "openplx_runtime_overhead_arm.openplx";
  std::ofstream(file) << chain_model(20);
  rt::Simulation sim = rt::Simulation::load(file.string());

  // Every mapped input and output, each written or read once per step.
  std::vector<rt::Input> inputs;
  std::vector<rt::Output> outputs;
  for (const rt::SignalInfo& s : sim.inputs()) {
    if (s.mapped && s.value == rt::ValueType::Real) inputs.push_back(sim.input(s.name));
  }
  for (const rt::SignalInfo& s : sim.outputs()) {
    if (!s.mapped) continue;
    rt::Output o = sim.output(s.name);
    try {
      s.value == rt::ValueType::Vec3   ? (void)o.vec3()
      : s.value == rt::ValueType::Vec2 ? (void)o.vec2()
                                       : (void)o.real();
      outputs.push_back(o);
    } catch (const rt::SignalError&) {  // sensor-only outputs that are not enabled
    }
  }
  // The bare model: the same MJCF compiled by MuJoCo.
  const fs::path xml = fs::temp_directory_path() / "openplx_runtime_overhead_arm.xml";
  std::ofstream(xml) << sim.mjcf();
  char error[1000] = "";
  mjModel* m = mj_loadXML(xml.c_str(), nullptr, error, sizeof(error));
  if (!m) {
    std::fprintf(stderr, "%s\n", error);
    return 1;
  }
  mjData* d = mj_makeData(m);

  // Enabled outputs are the ones the model declares for its controller (here: every hinge's angle and speed);
  // "all" adds every other mapped output (body positions and velocities the bundles declare disabled).
  std::vector<rt::Output> enabled;
  for (const rt::Output& o : outputs) {
    if (o.info().enabled) enabled.push_back(o);
  }
  std::vector<bool> vector_output;
  for (const rt::Output& o : outputs) vector_output.push_back(o.info().value == rt::ValueType::Vec3);

  double sink = 0;
  // Every run starts from the initial state and applies the same controls, so all follow one trajectory.
  auto bridge = [&](bool set_inputs, const std::vector<rt::Output>& read) {
    mj_resetData(sim.model(), sim.data());
    mj_forward(sim.model(), sim.data());
    const auto start = std::chrono::steady_clock::now();
    for (int k = 0; k < kSteps; ++k) {
      if (set_inputs) {
        for (size_t i = 0; i < inputs.size(); ++i) inputs[i].set(0.01 * static_cast<double>(i & 3));
      } else {
        for (int i = 0; i < m->nu; ++i) sim.data()->ctrl[i] = 0.01 * (i & 3);
      }
      sim.step();
      for (size_t i = 0; i < read.size(); ++i) {
        sink += &read == &outputs && vector_output[i] ? read[i].vec3().x() : read[i].real();
      }
    }
    return seconds_since(start);
  };
  auto bare = [&]() {
    mj_resetData(m, d);
    const auto start = std::chrono::steady_clock::now();
    for (int k = 0; k < kSteps; ++k) {
      for (int i = 0; i < m->nu; ++i) d->ctrl[i] = 0.01 * (i & 3);
      mj_step(m, d);
    }
    return seconds_since(start);
  };
  const std::vector<rt::Output> none;
  double best[4] = {1e9, 1e9, 1e9, 1e9};
  for (int round = 0; round < 3; ++round) {  // interleaved; the best of three of each
    best[0] = std::min(best[0], bare());
    best[1] = std::min(best[1], bridge(false, none));
    best[2] = std::min(best[2], bridge(true, enabled));
    best[3] = std::min(best[3], bridge(true, outputs));
  }
  std::printf("model: 20 hinges with torque motors, %d bodies, %d steps, best of 3 interleaved runs\n",
              m->nbody - 1, kSteps);
  const char* rows[] = {"bare mj_step (ctrl written)", "runtime step() only",
                        "runtime, inputs + enabled outputs", "runtime, inputs + all outputs"};
  const size_t reads[] = {0, 0, enabled.size(), outputs.size()};
  for (int r = 0; r < 4; ++r) {
    std::printf("%-36s %3zu in %3zu out %8.3f s %7.2f us/step  ratio %.3f\n", rows[r],
                r >= 2 ? inputs.size() : 0, reads[r], best[r], 1e6 * best[r] / kSteps, best[r] / best[0]);
  }
  std::printf("target: ratio <= 1.02 with every input set and every output read   [checksum %g]\n", sink);
  mj_deleteData(d);
  mj_deleteModel(m);
  return 0;
}
