// What a Simulation owns: the MuJoCo model and data, and every OpenPLX signal resolved to MuJoCo ids and
// addresses once, at load, so reading and writing a signal is an array access.
#pragma once

#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <map>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "contract/signal_binding.h"
#include "mujoco_support/instability.h"
#include "openplx/runtime/signals.h"
#include "runtime/constraint_rows.h"
#include "runtime/drive_laws.h"
#include "runtime/frame_motion.h"
#include "runtime/mujoco_messages.h"

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
  const double* direct3 = nullptr;          // Vec3 outputs that are three consecutive mjData numbers
  int bias = -1;                            // MotorForce: the motor's bias actuator, -1 when it has none
  std::vector<int> parts;                   // Composite: its parts' indices
  double low = -mjMAXVAL, high = mjMAXVAL;  // a Real input's range (clamped, said once); finite
  bool clamp_said = false;
};

// What an interaction acts with when enabled, and whether it is (see Quantity::InteractionEnabled). Range
// inputs change the effort range even while the interaction is off; switching it on restores it.
struct EffortSwitch {
  bool enabled = true;
  double low = 0, high = 0;
  int bias = -1;  // a velocity motor's bias actuator
};

struct SimulationState final : MessageSink {
  mjModel* m = nullptr;
  mjData* d = nullptr;
  bool owns = true;         // deletes m and d (a Simulation's); a bridge on someone's model does not
  bool registered = false;  // in the bridges' registry (one bridge per mjData and prefix)
  std::string root;
  std::string xml;
  std::vector<std::string> warnings;    // the transpilation's, then the run's (warn)
  std::vector<std::string> files_read;  // by the transpilation (Simulation::files_read)
  std::string source;                   // the model file or manifest, first in messages
  std::string prefix;                   // the prefix of its MuJoCo names, stripped in messages
  double emitted_timestep = 0;          // the time step the model was emitted for, 0: unknown
  OnInstability on_instability = OnInstability::Throw;
  SensorNoiseOptions noise;             // sensor noise added to outputs when read (sensor_noise.h)
  std::vector<std::string> mismatches;  // bindings resolve refused: "`path`: why" (a bridge refuses them)
  size_t run_warnings = 0;              // how many run warnings were given (at most kMaxRunWarnings are kept)
  static constexpr size_t kMaxRunWarnings = 1000;
  // A step being watched (begin_watch .. end_watch): MuJoCo's counters and time before it, and what its
  // warning callback saw (the state before MuJoCo's reset).
  mjcf::WarningCounts counts_before;
  double time_before = 0;
  mjcf::WarnedState seen;
  std::vector<std::string> seen_texts;  // MuJoCo's own texts of the step's warnings (the first 8)
  std::vector<ResolvedSignal> signals;
  std::unordered_map<std::string, int> by_name;   // path -> index into signals
  std::vector<Eigen::Vector3d> kinematic_linear;  // per mocap body: world velocities the inputs set
  std::vector<Eigen::Vector3d> kinematic_angular;
  bool kinematic = false;  // some kinematic velocity was set
  bool stale = false;      // an input changed what mj_step1 computes: redo it before the next step
  // A bridge after the user's mj_step: xpos, cvel, tendon lengths and sensors are of the state before the
  // step (bring_current.cpp). Outputs share it by pointer so their inlined fast path can check it.
  mutable bool derived_state_behind = false;
  mutable std::vector<mjtNum> qpos_kept;  // bring_current's copy of qpos
  std::vector<int> constraint_signals;    // signals reading constraint forces (joint limits, motors)
  std::vector<double> constraint_forces;  // per signal: the constraint force of the step just taken
  std::map<std::pair<int, int>, EffortSwitch> switches;  // by (mjtObj, id)
  struct Engagement {                                    // an automatic clutch or brake (Quantity::Engaged)
    bool engaged = false;
    double fraction = 0, capacity = 0, engage_time = 0, disengage_time = 0;
  };
  std::map<int, Engagement> engagements;   // by tendon id
  struct GearBox {                         // Quantity::GearSelect
    std::vector<double> forward, reverse;  // ratios by gear number
    bool neutral = true;                   // 0 is neutral
    int gear = 0;
  };
  std::map<int, GearBox> gearboxes;  // by equality id
  DriveLaws laws;
  ConstraintRows rows;       // AGX's constraint law for the model's motors, springs, ranges and couplings
  bool rows_hooked = false;  // a bridge's rows, written by the process-wide mjcb_control (row_hook.h)
  bool hook_replaced_said = false;
  std::vector<std::string> row_problems;   // laws of rows that do not fit the model (rows.resolve)
  std::vector<int> post_step_signals;      // requested outputs computed after each step (no sensor)
  std::vector<Eigen::Vector3d> post_step;  // per signal: their values

  SimulationState() = default;
  SimulationState(const SimulationState&) = delete;
  SimulationState& operator=(const SimulationState&) = delete;
  ~SimulationState();

  void begin_watch();  // before a step: MuJoCo's counters and time; this state receives MuJoCo's warnings
  void end_watch();    // after it: throws SimulationError (or warns) when a warning says it went wrong
  void check_warnings(bool time_went_back);
  void mujoco_warning(const char* text) override;
  [[noreturn]] void mujoco_failed(const std::string& error);  // an mju_error inside a step
  void warn(std::string text);                                // a run warning, kept while there is room

  void resolve(std::vector<mjcf::SignalBinding> bindings, const std::vector<mjcf::RuntimeLaw>& drive_laws);
  void select_gear(const ResolvedSignal& s, int gear);
  void reanchor_gear(int equality, double ratio);
  int find(std::string_view name, bool input) const;  // throws SignalError
  void step();                                        // mj_step2 and the next mj_step1, with the hooks below
  void before_step();                                 // laws into actuators
  void after_step();  // cached constraint forces, post-step outputs, engagement ramps, kinematic bodies
  void cache_constraint_forces();
  void ramp_engagements();
  void init_switches();
  void resolve_composites();
  EffortSwitch& effort_switch(const ResolvedSignal& s);
  void apply(const ResolvedSignal& s);
  void request_output(int index);  // Simulation::output() asked for it: start computing it if it needs to be
  void compute_post_step();

  // Checked access: throws SignalError when the value kind does not fit the signal.
  void write(int index, const double* values, int count, ValueType given);
  void read(int index, double* values, int count, ValueType wanted) const;
  Eigen::Vector3d carried_linear(int body, const mjtNum* point) const;
  Eigen::Vector3d carried_angular(int body) const;
  // A site's (or, body = true, a body frame's) motion now, velocities with the carried motion; accelerations
  // (coordinate, from cacc: mj_rnePostConstraint must have run) only when asked.
  FrameMotion motion(int id, bool body, bool acceleration) const;
  void bring_current() const;  // derived fields to the state at d->time, without contacts or constraint rows
};

// Whether an output reads fields mj_step computes before integrating (so a bridge must bring them current).
bool reads_derived_state(mjcf::Quantity q);

}  // namespace openplx::runtime
