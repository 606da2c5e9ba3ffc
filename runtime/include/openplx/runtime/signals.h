// The signals of a model in MuJoCo, by OpenPLX name: the errors, the handles (Input, Output) and what they
// describe (SignalInfo). Shared by Simulation (simulation.h: OpenPLX loaded in-process) and SignalBridge
// (signal_bridge.h: a manifest attached to your own mjModel and mjData). Names are OpenPLX paths relative to
// the root model ("pendulum.motor.torque_input"); a name that starts with the root model's name
// ("PendulumScene.pendulum.motor.torque_input") is accepted too. Unknown names, wrong value types, NaN/Inf
// and inputs MuJoCo cannot carry throw SignalError naming the signal; the state is then untouched. Real
// inputs with a range the model gives (an actuator's control range, a clutch's engagement fraction in
// [0, 1], a kinematic steering joint's limits) are clamped to it, and the first clamp of each input is said
// once in warnings(). Input and Output handles stay valid while their Simulation or bridge lives (moves
// included).
#pragma once

#include <mujoco/mujoco.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#if !defined(OPENPLX_RUNTIME_NO_EIGEN) && __has_include(<Eigen/Core>)
#include <Eigen/Core>
#define OPENPLX_RUNTIME_HAS_EIGEN 1
#else
#define OPENPLX_RUNTIME_HAS_EIGEN 0
#endif

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

// Sensor noise (a lidar's distance noise, an IMU's Gaussian signal noise, as the model gives them) is added
// when an output is read. Each draw depends on the seed, the sensor, its axis and the simulated time only:
// the same seed gives the same values, and reading an output again within a step gives the same value.
struct SensorNoiseOptions {
  bool enabled = true;     // false: outputs read exactly what MuJoCo computed
  std::uint64_t seed = 0;  // the default seed is 0
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
//
// Vector values come as std::array/std::vector (set_vec3, vec3_values, ...), so a program needs no Eigen;
// where <Eigen/Core> is on the include path (find_package(openplx2mjcf) adds it when Eigen3 is installed),
// the same values are also Eigen vectors (set(Eigen::Vector3d), vec3(), ...). Define
// OPENPLX_RUNTIME_NO_EIGEN to leave the Eigen forms out.
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
  void set_vec2(const std::array<double, 2>& value) { set_values(value.data(), 2, ValueType::Vec2); }
  void set_vec3(const std::array<double, 3>& value) { set_values(value.data(), 3, ValueType::Vec3); }
  // A composite (Robotics RobotInput): one value per target.
  void set_vector(const std::vector<double>& values) {
    set_values(values.data(), static_cast<int>(values.size()), ValueType::Vector);
  }
#if OPENPLX_RUNTIME_HAS_EIGEN
  void set(const Eigen::Vector2d& value) {
    set_values(value.data(), 2, ValueType::Vec2);
  }
  void set(const Eigen::Vector3d& value) {
    set_values(value.data(), 3, ValueType::Vec3);
  }
  void set(const Eigen::VectorXd& value) {
    set_values(value.data(), static_cast<int>(value.size()), ValueType::Vector);
  }
#endif
  const SignalInfo& info() const;

 private:
  friend class SignalBridge;
  Input(SimulationState* state, int index, double* direct, double low, double high)
      : state_(state), index_(index), direct_(direct), low_(low), high_(high) {}
  void set_checked(double value);
  void set_values(const double* values, int count, ValueType given);
  SimulationState* state_;
  int index_;
  double* direct_;     // a Real input that is one mjData number, else null
  double low_, high_;  // the values the fast path writes as they are: its range, else all finite numbers
};

// Outputs read after a bridge's after_step() are the state at the new time, as a Simulation's are: the
// first read of a body, site, tendon or sensor output brings MuJoCo's derived fields (xpos, cvel,
// site_xpos, ten_length, sensordata of the position and velocity stages) up to date in your mjData, as
// mj_forward's first stages would; contacts and constraint rows (efc_*) are left as mj_step left them.
class Output {
 public:
  double real() const { return direct_ ? scale_ * *direct_ : real_checked(); }
  bool boolean() const;
  std::array<double, 2> vec2_values() const;
  std::array<double, 3> vec3_values() const {
    if (direct3_ && !*behind_) return {direct3_[0], direct3_[1], direct3_[2]};
    return vec3_checked();
  }
  std::vector<double> vector_values() const;  // a composite (Robotics RobotOutput): its sources' values
#if OPENPLX_RUNTIME_HAS_EIGEN
  Eigen::Vector2d vec2() const {
    const std::array<double, 2> v = vec2_values();
    return {v[0], v[1]};
  }
  Eigen::Vector3d vec3() const {
    const std::array<double, 3> v = vec3_values();
    return {v[0], v[1], v[2]};
  }
  Eigen::VectorXd vector() const {
    const std::vector<double> v = vector_values();
    return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
  }
#endif
  const SignalInfo& info() const;

 private:
  friend class SignalBridge;
  Output(SimulationState* state, int index, const double* direct, double scale, const double* direct3,
         const bool* behind)
      : state_(state), index_(index), direct_(direct), scale_(scale), direct3_(direct3), behind_(behind) {}
  double real_checked() const;
  std::array<double, 3> vec3_checked() const;
  SimulationState* state_;
  int index_;
  const double* direct_;  // a Real output that is one mjData number (times scale_), else null
  double scale_;
  const double* direct3_;  // a Vec3 output that is three consecutive mjData numbers, else null
  const bool* behind_;     // direct3_'s numbers are a step old (a bridge after mj_step): read them checked
};

}  // namespace openplx::runtime
