// How each OpenPLX signal is reached in the emitted MuJoCo model. This is the contract between the emitter,
// which fills it (and writes it as the manifest OUT.signals.json), and the runtime, which reads and writes
// mjModel/mjData through it. Every Input/Output of the tree gets exactly one binding, mapped or not.
//
// Units are SI. Vectors are in world axes unless a quantity says otherwise. A binding names its MuJoCo
// element by name (prefix included); the runtime resolves names to ids with mj_name2id once, at load.
#pragma once

#include <functional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace openplx::mjcf {

enum class SignalValue { Real, Bool, Int, Vec2, Vec3, Vector };  // Vector: a composite's values

// The MuJoCo element type a binding's names refer to (an mjtObj).
enum class MjObject { None, Actuator, Joint, Body, Site, Equality, Tendon, Sensor };

// Manifests of format 1 gave a velocity motor a reference joint and, for an effort band not centred on
// zero, an actuator of this name with the centring force. The runtime still reads them.
inline std::string motor_bias_name(const std::string& tendon) {
  return tendon + "/bias";
}

// What the runtime does for a signal: inputs write, outputs read.
enum class Quantity {
  None,  // not mapped; `reason` says why (enabled outputs are also warned about at emission)
  // --- inputs (some are readable as outputs too, e.g. a motor's target output reads Ctrl)
  Ctrl,            // Actuator: d->ctrl[id]; `initial` is the control before the first step
  ForceRange,      // Actuator: m->actuator_forcerange[2id], [2id+1] = (min, max)   (Vec2, also readable)
  EqualityActive,  // Equality: m->eq_active[id] for every name (Bool, also readable)
  KinematicLinearVelocity,   // Body (mocap): world linear velocity; the runtime integrates d->mocap_pos.
                             // Velocity outputs of the body, of its sites and of bodies below it add this
                             // motion (MuJoCo gives mocap bodies zero velocity; its sensors read without it)
  KinematicAngularVelocity,  // Body (mocap): world angular velocity; the runtime integrates d->mocap_quat
  FreeLinearVelocity,        // Joint (free): sets the world linear velocity of a free body (qvel[0..2])
  FreeAngularVelocity,       // Joint (free): sets the world angular velocity (MuJoCo keeps it in body axes)
  MotorForceRange,  // Tendon (velocity motor): the effort band (min, max): friction loss (max - min) / 2 and
                    // the bias actuator's force (max + min) / 2 (Vec2, also readable)
  InteractionEnabled,  // an interaction's enabled state (Bool, also readable); off zeroes what it acts with:
                       // Tendon: friction loss and bias; Actuator: force range; Joint (a range): jnt_limited.
                       // `low`/`high` hold its effort range (its limits for a range) when enabled
  EngagementFraction,  // Tendon (clutch or brake): friction loss = `high` (its capacity) * fraction (Real,
                       // readable)
  Engaged,  // Tendon (automatic clutch or brake): engaging ramps the fraction to 1 over `low` seconds,
            // disengaging to 0 over `high`; `initial` is whether it starts engaged, initial_vector {capacity}
  EngageDuration,     // Tendon (automatic clutch or brake): the engagement ramp's duration, s (readable)
  DisengageDuration,  // Tendon: the disengagement ramp's duration, s (readable)
  GearRatio,  // Equality (a gear's joint equality, joint1 = output, joint2 = input): ratio = 1 / polycoef[1];
              // writing it re-anchors polycoef[0] so the shafts keep their positions (Real, readable; 0
              // while the equality is inactive, a gearbox in neutral)
  DistanceTarget,  // Equality (a Distance mate's tendon equality): the held length; writing it sets
                   // polycoef[0] = value - the tendon's initial length (Real, readable)
  GearSelect,  // Equality (a gearbox's): the gear number (Int, readable): n > 0 forward gear n, n < 0 reverse
               // gear -n, 0 neutral (inactive). `initial_vector` = forward ratios then reverse ratios, `low`
               // = how many are forward, `high` = 1 when it has a neutral gear, `initial` = the first gear.
               // Selecting re-anchors like GearRatio, with the reverse ratios negated
  EqualityTarget,  // Equality (a joint equality holding joint1 alone at a value: a kinematic steering angle):
                   // value = qpos0 of joint1 + polycoef[0]; writing sets polycoef[0] (Real, readable).
                   // With `initial_vector` = polynomial coefficients c0.. (a steering column's), joint1 is
                   // held at poly(value) and reading inverts it (steering_polynomial_inverse; within
                   // [`low`, `high`] when low < high: steering_input_for). `low` < `high` (or low = high
                   // with `initial_vector`): the linkage's reach, to which the input is clamped
  // --- outputs
  JointPosition,      // Joint: d->qpos[jnt_qposadr[id]] (hinge rad, slide m), times `sign`; with
                      // `initial_vector` = polynomial coefficients, the value x with poly(x) = qpos instead
                      // (within [`low`, `high`] when low < high: a steering column's reach)
  JointVelocity,      // Joint: d->qvel[jnt_dofadr[id]], times `sign`
  ActuatorForce,      // Actuator: d->actuator_force[id] (N or N·m on the joint)
  MotorForce,         // Tendon (velocity motor): the friction row's force (efc rows of type
                      // mjCNSTR_FRICTION_TENDON) plus the bias actuator's force, on the motor joint
  JointLimitForce,    // Joint: the joint-limit constraint force (efc rows of type mjCNSTR_LIMIT_JOINT), 0 off
  EqualityForce,      // Equality: the force of its constraint row (efc type mjCNSTR_EQUALITY) on joint1
  TendonVelocity,     // Tendon: d->ten_velocity (a clutch's or brake's slip velocity)
  TendonLength,       // Tendon: d->ten_length (a Distance mate's or DistanceRange's distance)
  TendonLimitForce,   // Tendon: its limit constraint's force (efc rows of type mjCNSTR_LIMIT_TENDON), 0 off
  TendonSpringForce,  // Tendon (a flexible or viscous gear): its passive force on joint1's side,
                      // -(stiffness (length - lengthspring) + damping velocity)
  BodyPosition,       // Body: d->xpos (the body frame's origin, world)
  BodyRPY,            // Body: d->xquat as roll, pitch, yaw: R = Rz(yaw) Ry(pitch) Rx(roll) (static xyz)
  BodyLinearVelocity,       // Body: the body frame origin's world linear velocity
  BodyAngularVelocity,      // Body: world angular velocity
  BodyLinearAcceleration,   // Body: the body frame origin's coordinate acceleration d2p/dt2, world axes (0 at
                            // rest, gravity in free fall): MuJoCo's framelinacc (proper acceleration, what an
                            // accelerometer reads; needs cacc: mj_rnePostConstraint) plus m->opt.gravity
                            // (none when gravity is disabled). Of the state the last step started from
  SitePosition,             // Site (a mate connector): d->site_xpos
  SiteRPY,                  // Site: orientation as roll, pitch, yaw
  SiteLinearVelocity,       // Site: world linear velocity of the site origin
  SiteAngularVelocity,      // Site: world angular velocity
  SiteLinearAcceleration,   // Site: the site origin's coordinate acceleration, world axes, as
                            // BodyLinearAcceleration (framelinacc + gravity)
  SiteAngularAcceleration,  // Site: world angular acceleration (frameangacc, from cacc)
  // Relative to a reference connector (`relative_to`): names {site, reference site}; with p, R, v, w, a, al
  // the site's position, rotation (world from site), velocity, angular velocity, coordinate acceleration and
  // angular acceleration (world), the reference's with subscript r, and r = p - p_r. Values are in the
  // reference's axes; velocities and accelerations are time derivatives seen from the reference frame
  // (MuJoCo's definition for frame sensors with reftype).
  SiteRelativePosition,             // R_r^T r (MuJoCo framepos with reftype="site")
  SiteRelativeRPY,                  // R_r^T R as roll, pitch, yaw (framequat with reftype: q_r^-1 q)
  SiteRelativeLinearVelocity,       // R_r^T (v - v_r - w_r x r) (framelinvel with reftype)
  SiteRelativeAngularVelocity,      // R_r^T (w - w_r) (frameangvel with reftype)
  SiteRelativeLinearAcceleration,   // R_r^T (a - a_r - al_r x r - 2 w_r x (v - v_r) + w_r x (w_r x r)): the
                                    // second derivative of R_r^T r; no MuJoCo 2.2.2 sensor (framelinacc takes
                                    // no reftype): computed from cacc like the accelerations above
  SiteRelativeAngularAcceleration,  // R_r^T (al - al_r - w_r x w): the derivative of R_r^T (w - w_r)
  MateForce,          // Site at the MuJoCo child's connector of a tree mate: the force connectors[0]'s side
                      // exerts on connectors[1]'s side, world axes. MuJoCo gives the parent's force on the
                      // child subtree (the `force` sensor, site axes); `sign` is -1 when the child holds
                      // connectors[0]
  MateTorque,         // the same, torque about the connector origin
  MateForceInFrame,   // MateForce expressed in the axes of a fixed transform (Force3DOutput `relative_to`):
                      // R^T f with R the rotation initial_vector = {w, x, y, z} (world from transform)
  MateTorqueInFrame,  // MateTorque the same way (still about the connector origin: only axes change)
  BodyTorque,  // Body (input, Torque3DInput): a pure torque, world axes, on the body: d->xfrc_applied[6 id +
               // 3..5] (MuJoCo applies xfrc_applied at the body's centre of mass; a torque alone is a couple,
               // the same about every point). Kept until written again (Vec3)
  Composite,   // Robotics RobotInput/RobotOutput: `names` are the OpenPLX paths of its parts, in order; an
               // input takes one value per part (each a scalar input), an output gives its parts' values
               // one after another (Vector)
  SensorFields,  // Sensor (an IMU output's accelerometer/gyro/magnetometer sensors, one name per field):
                 // value k = sensordata[adr(names[k]) + initial_vector[k]], the field's axis (Vector)
  Broadcast,     // Control BroadcastInput: `names` its targets' paths; one value written to each (their type)
  Affine,        // Control AffineTransform1DInput/Output: `names` {its target or source}; writes
                 // `low` * value + `high` to the target, reads `low` * (the source) + `high` (Real)
  Constant,      // no MuJoCo element: the value is `initial` (e.g. an always-enabled tree mate)
};

// Gaussian noise the runtime adds to an output's values when it reads them (sensor distortions: a lidar's
// distance noise, an IMU axis's signal noise). Each list holds one number for every value, or one per value.
// A value x read becomes x + N(mean, deviation + deviation_per_metre * |x|); a rangefinder's miss (-1) stays
// -1 and a noisy distance stays >= 0. Empty lists: no noise.
struct SignalNoise {
  std::vector<double> mean, deviation, deviation_per_metre;
  bool empty() const { return mean.empty() && deviation.empty() && deviation_per_metre.empty(); }
};

struct SignalBinding {
  std::string path;  // OpenPLX path relative to the root model, e.g. "pendulum.motor.torque_output"
  bool input = false;
  std::string type;  // the signal's OpenPLX model, e.g. "Physics.Signals.AngleOutput"
  SignalValue value = SignalValue::Real;
  std::string unit;  // "rad", "rad/s", "m", "m/s", "m/s^2", "N", "N*m", "" (dimensionless or Bool)
  bool enabled = true;
  Quantity quantity = Quantity::None;
  MjObject object = MjObject::None;
  std::vector<std::string> names;  // MuJoCo names of `object` (usually one; a hinge loop closure has two)
  std::string sensor;              // a MuJoCo sensor carrying the same value, "" when none
  double sign = 1.0;     // JointPosition/JointVelocity/MateForce/MateTorque: value = sign * MuJoCo's (an rpm
                         // output is a JointVelocity with sign 60 / 2 pi)
  double initial = 0.0;  // Ctrl: initial control; Constant: the value (Bool: 0 or 1)
  std::vector<double> initial_vector;  // Kinematic*Velocity: the velocity before any input (world axes)
  double low = 0.0;                    // InteractionEnabled
  double high = 0.0;                   // InteractionEnabled
  std::string reason;                  // None: why nothing maps
  bool runtime = false;  // its behaviour needs the runtime: a law it computes each step (RuntimeLaw) or an
                         // engagement ramp; the MJCF alone carries the closest static behaviour
  SignalNoise noise;     // SensorFields outputs: sensor noise the runtime applies (written only when given)
};

// A gearbox's ratio in gear `gear` (Quantity::GearSelect): forward gears n > 0, reverse gears -n (negated),
// 0 for neutral (gear 0 with a neutral gear, or a zero ratio, which the lists may hold as extra neutrals).
// Without a neutral gear, 0 selects the first forward gear (UNCONFIRMED). `valid` is false out of range.
struct GearSelection {
  double ratio = 0;
  bool valid = true;
};
GearSelection gearbox_ratio(const std::vector<double>& forward, const std::vector<double>& reverse,
                            bool has_neutral, int gear);

// c[0] + c[1] x + c[2] x^2 + ... (a steering column's left wheel angle for its input).
double steering_polynomial(const std::vector<double>& c, double x);
// The x nearest zero's branch with steering_polynomial(c, x) = y, by Newton's method from y / c[1] (the
// polynomial is monotonic over the steering range it was fitted on); y itself when c is empty.
double steering_polynomial_inverse(const std::vector<double>& c, double y);

// A law MJCF cannot state, computed by the runtime before each step and written into actuators.
struct RuntimeLaw {
  enum class Kind {
    // actuators {engine} on the engine's shaft; curve = full-throttle torque (N m) over speed (rev/min);
    // parameter = idle rev/min. Writes gain = curve(speed), and a bias holding at least the throttle the
    // idle governor asks for: min(1, (idle - speed) / (0.1 idle)) below idle.
    Engine,
    // actuators {pump, turbine} (<motor>s on the two shafts); curve = capacity factor over nu = turbine /
    // pump speed, curve2 = torque multiplication over nu; parameter = oil_density * diameter^5. Writes
    // pump = -factor * parameter * w_pump |w_pump|, turbine = -multiplier * pump.
    TorqueConverter,
    // actuators {spring} (its <general> stand-in; the fixed tendon of the same name holds the joint alone);
    // parameter = SPOOK relaxation time (s); joint_damping = the damping the stand-in put on the joint. The
    // runtime makes the tendon's friction row AGX's spring row (docs/mapping.md "Springs") and adds its force
    // to the actuator's.
    Spring,
    // actuators {motor}: a velocity motor's stand-in, a <general> on its joint (ctrl = the target; its
    // forcerange = the effort band; off = gear 0): b * ctrl with a damper b on the joint (joint_damping), or
    // a servo within the band (joint_damping 0). The fixed tendon of the same name (the joint alone) carries
    // the runtime's row, AGX's bounded velocity constraint; the runtime removes the stand-in's gain, bias and
    // damper (the actuator then pushes the band's centre).
    VelocityMotor,
    // equalities {one joint equality holding an elastic degree of freedom at 0}: AGX's compliance row with
    // `stiffness` and SPOOK relaxation time `parameter`; the MJCF alone holds it with MuJoCo's softness.
    Compliance,
    // The rows AGX solves as hard constraints, exact only with the runtime: joints' limit rows (ranges),
    // tendons' friction rows (brakes, clutches, slip limits), equalities' rows (gears, couplings).
    RigidRows,
  };
  Kind kind = Kind::Engine;
  std::string path;                    // the OpenPLX part
  std::vector<std::string> actuators;  // MuJoCo actuator names
  std::vector<double> curve_x, curve_y, curve2_x, curve2_y;
  double parameter = 0;
  double joint_damping = 0;  // Spring, VelocityMotor: the damping the stand-in put on the joint
  double stiffness = 0;      // Compliance, Spring (0 in manifests before it: the actuator's gain)
  std::vector<std::string> joints, tendons, equalities;  // Compliance, RigidRows: MuJoCo names
};
// The manifest's name of a law kind ("engine", "spring", ...).
std::string_view to_string(RuntimeLaw::Kind kind);

// The value kind and SI unit of a signal model, from its name ("Physics.Signals.AngleOutput" -> Real, "rad").
struct SignalKind {
  SignalValue value = SignalValue::Real;
  std::string_view unit;  // a literal
};
SignalKind signal_kind(std::string_view type);
// A signal model's name without namespace and Input/Output ending: "Physics.Signals.AngleOutput" -> "Angle".
std::string_view signal_stem(std::string_view type);

// signal_kind and signal_stem worked out once per model name: a large model has thousands of signals of a
// few models. A name is known by where it is held, not by its text: the view's are its models' names, each
// held once by the program, so a model is classified once and no name is hashed; an equal name held
// elsewhere is classified again, alike. Names must outlive this.
class SignalClasses {
 public:
  struct Class {
    SignalKind kind;
    std::string_view stem;  // in the name
  };
  const Class& of(std::string_view type) {
    auto [it, fresh] = classes_.try_emplace(type);
    if (fresh) it->second = {signal_kind(type), signal_stem(type)};
    return it->second;
  }
  size_t size() const { return classes_.size(); }

 private:
  struct Where {
    size_t operator()(std::string_view s) const { return std::hash<const char*>{}(s.data()) ^ s.size(); }
  };
  struct Same {
    bool operator()(std::string_view a, std::string_view b) const {
      return a.data() == b.data() && a.size() == b.size();
    }
  };
  std::unordered_map<std::string_view, Class, Where, Same> classes_;
};

std::string_view to_string(SignalValue value);
std::string_view to_string(MjObject object);
std::string_view to_string(Quantity quantity);

// The manifest (documented field by field, with every quantity, in docs/signals.schema.json): {
// "format_version", "model", "prefix", [the ManifestModel facts], "signals": [{"path", "direction", "type",
// "value", "unit", "enabled", "quantity", "object", "names", "sensor", "sign", "initial", "initial_vector",
// "low", "high", "reason", "runtime", and "noise" {"mean", "deviation", "deviation_per_metre" (when any)}
// when the output has sensor noise}], "laws": [{"kind", "path", "actuators", "curve_x", "curve_y",
// "curve2_x", "curve2_y", "parameter"}]} with keys in that order, one signal or law per line, deterministic.
// Numbers JSON cannot hold are the strings "inf", "-inf", "nan". `prefix` is the one every MuJoCo name
// carries.
//
// The format's version: raised on any change a reader of the previous version would misread (a field
// removed, renamed or given another meaning or unit, a quantity applied differently); a field or quantity
// added that old readers may ignore keeps it. A reader refuses versions above the one it knows.
inline constexpr int kManifestFormatVersion = 1;

// What the manifest says about the model itself, written after "prefix" when given: "fingerprint" (a
// SignalBridge refuses a model whose own fingerprint differs: model_fingerprint.h), "timestep" (the time
// step it was emitted for), "mujoco" (the MuJoCo version its numbers are for, --mujoco), and
// "timestep_dependent" with "timestep_choices": whether, and through which elements, the emitter's stability
// choices follow that time step (timestep_dependence.h), so that a scene stepping at another one is
// warned about only when it matters.
struct ManifestModel {
  std::string fingerprint;                    // model_fingerprint(document, prefix).text(); "" leaves it out
  double timestep = 0;                        // s; 0 leaves it out (and the two fields after it)
  std::string mujoco;                         // "2.2.2" or "3"; "" leaves it out
  std::vector<std::string> timestep_choices;  // timestep_choices(document, laws); empty: not dependent
};
std::string manifest_json(std::string_view model_name, std::string_view prefix,
                          const std::vector<SignalBinding>& bindings, const std::vector<RuntimeLaw>& laws,
                          const ManifestModel& model = {});
// The same text handed to `write` in pieces of about 64 KiB (a 10,000-body model's manifest is 40 MB).
void write_manifest_json(std::string_view model_name, std::string_view prefix,
                         const std::vector<SignalBinding>& bindings, const std::vector<RuntimeLaw>& laws,
                         const std::function<void(std::string_view)>& write);
void write_manifest_json(std::string_view model_name, std::string_view prefix,
                         const std::vector<SignalBinding>& bindings, const std::vector<RuntimeLaw>& laws,
                         const ManifestModel& model, const std::function<void(std::string_view)>& write);

}  // namespace openplx::mjcf
