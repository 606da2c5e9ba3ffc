// Load an OpenPLX model straight into MuJoCo and drive it by OpenPLX signal names.
//
//   auto sim = openplx::runtime::Simulation::load("pendulum.openplx");
//   auto torque = sim.input("motor.torque_input");
//   auto angle = sim.output("hinge.angle_output");
//   for (int k = 0; k < 1000; ++k) { torque.set(-5.0 * angle.real()); sim.step(); }
//
// Names are OpenPLX paths relative to the root model ("pendulum.motor.torque_input"); a name that starts with
// the root model's name ("PendulumScene.pendulum.motor.torque_input") is accepted too. Unknown names, wrong
// value types, NaN/Inf and inputs MuJoCo cannot carry throw SignalError naming the signal; the state is then
// untouched. Real inputs with a range the model gives (an actuator's control range, a clutch's engagement
// fraction in [0, 1], a kinematic steering joint's limits) are clamped to it, and the first clamp of each
// input is said once in warnings(). Outputs read after step() describe the state after that step; forces and
// accelerations describe the step just taken. Input and Output handles stay valid while their Simulation
// lives (moves included).
#pragma once

#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace openplx::runtime {

// The model did not load: what() holds every diagnostic, printed as `file:line:col: error: message`.
class LoadError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A signal was misused: an unknown name (what() lists close names), a wrong value type, NaN/Inf, or a
// signal that has no MuJoCo counterpart.
class SignalError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// The simulation left the model's motion: MuJoCo found a NaN, infinite or huge position, velocity or
// acceleration (and reset its mjData to the initial state, time 0), a NaN or huge control (it zeroed the
// controls), dropped contacts or constraints because its buffers were full, or stopped on an error of its
// own. what() says when (the simulated time before MuJoCo's reset), what, which DOF and which OpenPLX joint
// and body it belongs to, the values that blew up (when MuJoCo's warning reached the runtime's handler), and
// a hint (the time step against the one the model was emitted for, a stiff spring, an unbounded input).
class SimulationError : public std::runtime_error {
 public:
  SimulationError(const std::string& message, double time, int warning)
      : std::runtime_error(message), time_(time), warning_(warning) {}
  double time() const { return time_; }     // the simulated time it happened at, s
  int warning() const { return warning_; }  // the mjtWarning, or -1 for an error MuJoCo stopped on
 private:
  double time_;
  int warning_;
};

// What step() (and the bridge's after_step()) do when MuJoCo's warnings say the step was not the model's
// motion (see SimulationError). Errors MuJoCo stops on (mju_error) always throw.
enum class OnInstability {
  Throw,     // throw SimulationError; mjData stays as MuJoCo left it (reset to the initial state for bad
             // values), so a caller that catches it may go on from there knowingly
  Continue,  // MuJoCo's own behaviour: its reset stands and stepping goes on; the description is added to
             // warnings() instead (at most 1000 run warnings are kept)
};

struct LoadOptions {
  std::string model;                      // the root model; empty: the file's last model
  std::vector<std::string> bundle_paths;  // extra bundle folders (like openplx2mjcf -B)
  double timestep = 0.002;                // MuJoCo's time step, s (like openplx2mjcf --timestep)
  bool default_bundles = true;  // false: only bundle_paths and OPENPLX_BUNDLE_PATH (--no-default-bundles)
  OnInstability on_instability = OnInstability::Throw;
};

enum class ValueType { Real, Bool, Int, Vec2, Vec3, Vector };  // Vector: a composite robot signal

struct SignalInfo {
  std::string name;  // path relative to the root model
  std::string type;  // the OpenPLX signal model, e.g. "Physics.Signals.AngleOutput"
  ValueType value = ValueType::Real;
  std::string unit;     // SI: "rad", "m/s", "N*m", ... ("" for Bool and dimensionless)
  bool enabled = true;  // the model's `enabled` flag (every output can be read regardless)
  bool mapped = false;  // false: MuJoCo has no counterpart, `mujoco` says why
  size_t size = 1;      // how many numbers it carries (Vec2 2, Vec3 3, a composite its parts' total)
  std::string mujoco;   // what it reads or writes, e.g. "actuator motor: ctrl", or why it is not mapped
};

struct SimulationState;
class SignalBridge;

// Handles to one signal. Scalar joint and actuator signals take an inlined fast path (a pointer into
// mjData resolved at load), so a controller pays a few nanoseconds per signal per step.
class Input {
 public:
  void set(double value) {
    if (direct_ && value >= low_ && value <= high_) {  // in range, so finite; else checked (clamped, NaN)
      *direct_ = value;
    } else {
      set_checked(value);
    }
  }
  void set(bool value);
  void set(const Eigen::Vector2d& value);
  void set(const Eigen::Vector3d& value);
  void set(const Eigen::VectorXd& value);  // a composite (Robotics RobotInput): one value per target
  const SignalInfo& info() const;

 private:
  friend class SignalBridge;
  Input(SimulationState* state, int index, double* direct, double low, double high)
      : state_(state), index_(index), direct_(direct), low_(low), high_(high) {}
  void set_checked(double value);
  SimulationState* state_;
  int index_;
  double* direct_;     // a Real input that is one mjData number, else null
  double low_, high_;  // the values the fast path writes as they are: its range, else all finite numbers
};

class Output {
 public:
  double real() const { return direct_ ? scale_ * *direct_ : real_checked(); }
  bool boolean() const;
  Eigen::Vector2d vec2() const;
  Eigen::VectorXd vector() const;  // a composite (Robotics RobotOutput): its sources' values in order
  Eigen::Vector3d vec3() const {
    return direct3_ ? Eigen::Vector3d(direct3_[0], direct3_[1], direct3_[2]) : vec3_checked();
  }
  const SignalInfo& info() const;

 private:
  friend class SignalBridge;
  Output(SimulationState* state, int index, const double* direct, double scale, const double* direct3)
      : state_(state), index_(index), direct_(direct), scale_(scale), direct3_(direct3) {}
  double real_checked() const;
  Eigen::Vector3d vec3_checked() const;
  SimulationState* state_;
  int index_;
  const double* direct_;  // a Real output that is one mjData number (times scale_), else null
  double scale_;
  const double* direct3_;  // a Vec3 output that is three consecutive mjData numbers, else null
};

// A model loaded from OpenPLX, with its own mjModel and mjData and one SignalBridge on them.
class Simulation {
 public:
  // Throws LoadError for every reason it cannot load: an empty or missing path, a bundle folder of
  // options.bundle_paths that does not exist, a time step outside [kMinTimestep, kMaxTimestep], the
  // model's own errors, MuJoCo's. Installs MuJoCo's message handlers when none are set (runtime/README.md).
  static Simulation load(const std::string& path, const LoadOptions& options = {});
  static constexpr double kMinTimestep = 1e-6, kMaxTimestep = 1.0;  // s, as openplx2mjcf --timestep

  Simulation(Simulation&&) noexcept;
  Simulation& operator=(Simulation&&) noexcept;
  ~Simulation();

  Input input(std::string_view name);  // throws SignalError
  Output output(std::string_view name);

  // One MuJoCo step. Throws SimulationError when MuJoCo's warnings say it was not the model's motion (unless
  // set_on_instability(OnInstability::Continue)), and for an error MuJoCo stopped on.
  void step();
  // Steps until time() has advanced by `seconds` (rounded to whole steps). Throws std::invalid_argument for
  // a negative or non-finite span or one of more than kMaxAdvanceSteps steps; SimulationError as step().
  void advance(double seconds);
  static constexpr long kMaxAdvanceSteps = 1'000'000'000;
  void set_on_instability(OnInstability what);
  double time() const;
  double timestep() const;

  // Raw access for existing MuJoCo pipelines. After writing qpos/qvel or model fields yourself, call
  // mj_forward(model(), data()) so outputs and the next step see the change.
  const mjModel* model() const;
  mjData* data();

  std::vector<SignalInfo> inputs() const;
  std::vector<SignalInfo> outputs() const;
  const std::string& root_model() const;
  const std::string& mjcf() const;  // the MJCF the model was loaded from
  // Printed warnings of the transpilation, then those of the run as they come (each a line ending in '\n'):
  // an input clamped to its range (once per input), MuJoCo's own warnings, and instabilities under
  // OnInstability::Continue.
  const std::vector<std::string>& warnings() const;

 private:
  explicit Simulation(std::unique_ptr<SimulationState> state);
  std::unique_ptr<SignalBridge> bridge_;
  SimulationState* state_;  // the bridge's
};

// Adds a folder searched for the standard bundles when the library is not run from its build or install
// tree. The installed CMake package calls it (through OPENPLX2MJCF_INSTALLED_BUNDLES) with its own folder.
void add_default_bundle_dir(const std::string& dir);

#ifdef OPENPLX2MJCF_INSTALLED_BUNDLES
inline const bool installed_bundles_registered =
    (add_default_bundle_dir(OPENPLX2MJCF_INSTALLED_BUNDLES), true);
#endif

// Adds a file tried for the URDF importer module (libopenplx_urdf.so, loaded on the first URDF import) when
// the library is not run from its build or install tree. The installed CMake package registers its own.
void add_urdf_module(const std::string& path);

#ifdef OPENPLX2MJCF_INSTALLED_URDF_MODULE
inline const bool installed_urdf_module_registered =
    (add_urdf_module(OPENPLX2MJCF_INSTALLED_URDF_MODULE), true);
#endif

}  // namespace openplx::runtime
