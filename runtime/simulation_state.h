// What a Simulation owns: the MuJoCo model and data, and every OpenPLX signal resolved to MuJoCo ids and
// addresses once, at load, so reading and writing a signal is an array access.
#pragma once

#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <string>
#include <unordered_map>
#include <vector>

#include "mjcf_emitter/signal_binding.h"
#include "openplx/runtime/simulation.h"

namespace openplx::runtime {

struct ResolvedSignal {
  mjcf::SignalBinding binding;
  SignalInfo info;
  std::vector<int> ids;  // MuJoCo ids of binding.names
  int sensor = -1;       // sensor id, -1 when none
  int address = -1;      // qpos address (joints), mocap index (kinematic bodies), dof address (free joints)
  int dof = -1;          // dof address (joints)
  double* direct = nullptr;  // Real signals that are one mjData number: its address (value = scale * *direct)
  double scale = 1.0;
  const double* direct3 = nullptr;  // Vec3 outputs that are three consecutive mjData numbers
};

struct SimulationState {
  mjModel* m = nullptr;
  mjData* d = nullptr;
  std::string root;
  std::string xml;
  std::vector<std::string> warnings;
  std::vector<ResolvedSignal> signals;
  std::unordered_map<std::string, int> by_name;   // path -> index into signals
  std::vector<Eigen::Vector3d> kinematic_linear;  // per mocap body: world velocities the inputs set
  std::vector<Eigen::Vector3d> kinematic_angular;
  bool kinematic = false;            // some kinematic velocity was set
  bool stale = false;                // an input changed what mj_step1 computes: redo it before the next step
  std::vector<int> limit_signals;    // signals reading joint-limit forces
  std::vector<double> limit_forces;  // per signal: the limit force of the step just taken
  std::vector<int> post_step_signals;      // requested outputs computed after each step (no sensor)
  std::vector<Eigen::Vector3d> post_step;  // per signal: their values

  SimulationState() = default;
  SimulationState(const SimulationState&) = delete;
  SimulationState& operator=(const SimulationState&) = delete;
  ~SimulationState();

  void resolve(std::vector<mjcf::SignalBinding> bindings);
  int find(std::string_view name, bool input) const;  // throws SignalError
  void step();
  void cache_limit_forces();
  void request_output(int index);  // Simulation::output() asked for it: start computing it if it needs to be
  void compute_post_step();

  // Checked access: throws SignalError when the value kind does not fit the signal.
  void write(int index, const double* values, int count, ValueType given);
  void read(int index, double* values, int count, ValueType wanted) const;
};

}  // namespace openplx::runtime
