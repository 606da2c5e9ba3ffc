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

// One configuration of the bridge: its own Simulation, because reading a mate force makes every later step
// compute constraint forces (mj_rnePostConstraint) for it.
struct Bridge {
  rt::Simulation sim;
  std::vector<rt::Input> inputs;
  std::vector<rt::Output> outputs;
  std::vector<rt::ValueType> types;
};

Bridge make_bridge(const std::string& file, bool set_inputs, bool only_enabled, bool read_outputs) {
  Bridge b{rt::Simulation::load(file), {}, {}, {}};
  if (set_inputs) {
    for (const rt::SignalInfo& s : b.sim.inputs()) {
      if (s.mapped && s.value == rt::ValueType::Real) b.inputs.push_back(b.sim.input(s.name));
    }
  }
  if (!read_outputs) return b;
  for (const rt::SignalInfo& s : b.sim.outputs()) {
    if (!s.mapped || (only_enabled && !s.enabled)) continue;
    b.outputs.push_back(b.sim.output(s.name));
    b.types.push_back(s.value);
  }
  return b;
}

int main() {
  constexpr int kSteps = 100000;
  const fs::path file = fs::temp_directory_path() / "openplx_runtime_overhead_arm.openplx";
  std::ofstream(file) << chain_model(20);
  // Bridge configurations: step() only (controls written directly), the model's enabled signals (every
  // hinge's angle and speed), and every mapped output (adds body positions and velocities, mate forces and
  // torques, motor torques, which the bundles declare disabled).
  Bridge runs[] = {make_bridge(file.string(), false, false, false),
                   make_bridge(file.string(), true, true, true),
                   make_bridge(file.string(), true, false, true)};

  // The bare model: the same MJCF compiled by MuJoCo.
  const fs::path xml = fs::temp_directory_path() / "openplx_runtime_overhead_arm.xml";
  std::ofstream(xml) << runs[0].sim.mjcf();
  char error[1000] = "";
  mjModel* m = mj_loadXML(xml.c_str(), nullptr, error, sizeof(error));
  if (!m) {
    std::fprintf(stderr, "%s\n", error);
    return 1;
  }
  mjData* d = mj_makeData(m);

  double sink = 0;
  // Every run starts from the initial state and applies the same controls, so all follow one trajectory.
  auto bridge = [&](Bridge& b) {
    mj_resetData(b.sim.model(), b.sim.data());
    mj_forward(b.sim.model(), b.sim.data());
    const auto start = std::chrono::steady_clock::now();
    for (int k = 0; k < kSteps; ++k) {
      if (!b.inputs.empty()) {
        for (size_t i = 0; i < b.inputs.size(); ++i) b.inputs[i].set(0.01 * static_cast<double>(i & 3));
      } else {
        for (int i = 0; i < m->nu; ++i) b.sim.data()->ctrl[i] = 0.01 * (i & 3);
      }
      b.sim.step();
      for (size_t i = 0; i < b.outputs.size(); ++i) {
        switch (b.types[i]) {
          case rt::ValueType::Vec3:
            sink += b.outputs[i].vec3().x();
            break;
          case rt::ValueType::Vec2:
            sink += b.outputs[i].vec2().x();
            break;
          case rt::ValueType::Bool:
            sink += b.outputs[i].boolean();
            break;
          default:
            sink += b.outputs[i].real();
            break;
        }
      }
    }
    return seconds_since(start);
  };
  // Bare MuJoCo; with `forces`, also the constraint-force pass a MuJoCo force/torque sensor makes mj_step
  // run.
  auto bare = [&](bool forces) {
    mj_resetData(m, d);
    const auto start = std::chrono::steady_clock::now();
    for (int k = 0; k < kSteps; ++k) {
      for (int i = 0; i < m->nu; ++i) d->ctrl[i] = 0.01 * (i & 3);
      mj_step(m, d);
      if (forces) mj_rnePostConstraint(m, d);
    }
    return seconds_since(start);
  };
  double best[5] = {1e9, 1e9, 1e9, 1e9, 1e9};
  for (int round = 0; round < 3; ++round) {  // interleaved; the best of three of each
    best[0] = std::min(best[0], bare(false));
    for (int r = 0; r < 3; ++r) best[r + 1] = std::min(best[r + 1], bridge(runs[r]));
    best[4] = std::min(best[4], bare(true));
  }
  std::printf("model: 20 hinges with torque motors, %d bodies, %d steps, best of 3 interleaved runs\n",
              m->nbody - 1, kSteps);
  const char* rows[] = {"bare mj_step (ctrl written)", "runtime step() only",
                        "runtime, inputs + enabled outputs", "runtime, inputs + all outputs",
                        "bare mj_step + mj_rnePostConstraint"};
  for (int r = 0; r < 5; ++r) {
    const bool bridged = r >= 1 && r <= 3;
    const size_t in = bridged && r >= 2 ? runs[r - 1].inputs.size() : 0;
    const size_t out = bridged ? runs[r - 1].outputs.size() : 0;
    std::printf("%-36s %3zu in %3zu out %8.3f s %7.2f us/step  ratio %.3f\n", rows[r], in, out, best[r],
                1e6 * best[r] / kSteps, best[r] / best[0]);
  }
  std::printf("target: ratio <= 1.02 with every input set and every output read   [checksum %g]\n", sink);
  mj_deleteData(d);
  mj_deleteModel(m);
  return 0;
}
