// Lowering pass, signals: one binding per OpenPLX signal, <sensor>s for enabled outputs, <site>s at mate
// connectors.
#include "mjcf_emitter/lowering.h"

namespace openplx::mjcf {

namespace {
// What a binding knows of its signal alone: path, direction, type and enabled flag.
void identify(SignalBinding& b, const sn::Signal& s) {
  b.path = s.path;
  b.input = s.input;
  b.type = s.type;
  b.enabled = s.enabled;
}

// The true reason a switch-like signal (Bool, Activate, Engage) found nothing to bind to, in place of the
// binders' general one: its source has MuJoCo elements, but the signal means nothing they can carry.
void explain_switch(SignalBinding& b, std::string_view stem) {
  if (b.quantity != Quantity::None) return;
  if (!b.reason.ends_with("that carries it")) return;  // a more particular reason stands
  if (stem == "Bool") {
    b.reason =
        "a plain Bool signal says nothing of what it switches (EnableInteraction and Engage signals do), so "
        "no "
        "MuJoCo quantity can take it";
  } else if (stem == "Activate" || stem == "Activated") {
    b.reason =
        "activation is an end effector's state (a gripper's, Robotics); MuJoCo has none for this source, "
        "whose on/off state, where MuJoCo can switch it, is EnableInteraction's";
  } else if (stem == "Engage" || stem == "Engaged") {
    b.reason = "only automatic clutches and brakes engage and release; this source has no engaged state";
  }
}
}  // namespace

// One binding per OpenPLX signal (signal_binding.h), and a MuJoCo sensor for every enabled output that
// has one. Outputs without a sensor (controls, ranges, constants) are computed by the runtime.
void Lowering::bind_signals(Element& root, std::vector<SignalBinding>& out) {
  sensors_ = &root.add("sensor");
  emit_lidars();
  // Counted once: a count per enabled signal was quadratic in a robot's joints.
  for (const auto& [interaction, joint] : range_joints_) ++ranges_on_joint_[joint];
  out.reserve(out.size() + system_.signals.size());
  for (const sn::Signal& s : system_.signals) {  // each binding made in place, never moved
    SignalBinding& b = out.emplace_back();
    if (s.composite) continue;
    identify(b, s);
    if (s.imu) {
      bind_imu(s, b);
    } else {
      bind(s, b);
      explain_switch(b, signal_classes_.of(s.type).stem);
    }
  }
  // Composites after their parts.
  for (size_t k = 0; k < system_.signals.size(); ++k) {
    if (!system_.signals[k].composite) continue;
    SignalBinding b;  // apart from `out` until done: it reads its parts there
    identify(b, system_.signals[k]);
    bind_composite(system_.signals[k], out, b);
    out[k] = std::move(b);
  }
  for (size_t k = 0; k < system_.signals.size(); ++k) {
    const sn::Signal& s = system_.signals[k];
    SignalBinding& b = out[k];
    // Inputs a bundle model declares on every instance (a body's velocity inputs) are not warned about;
    // an input the user declared is theirs, and dropping it silently would hide it.
    if ((!b.input || s.composite || s.user_declared) && b.enabled && b.quantity == Quantity::None) {
      warn(s.where, std::string(b.input ? "input" : "output") + " `" + s.path + "` (" + b.type +
                        ") has no MuJoCo counterpart: " + b.reason + "; it was left out");
    }
    if (!b.input && b.enabled && !s.composite && !s.imu) add_sensor(b);
  }
}

// An IMU output: each field an axis of an accelerometer, gyroscope or magnetometer, which become MuJoCo's
// sensors of those kinds at a site on the sensor's connector (its axes: x normal, y cross, z main axis). An
// accelerometer reads proper acceleration (gravity included), as a real one does.
void Lowering::bind_imu(const sn::Signal& s, SignalBinding& b) {
  b.value = SignalValue::Vector;
  using Kind = sn::Signal::SensorField::Kind;
  for (const sn::Signal::SensorField& f : s.sensor_fields) {
    if (f.kind == Kind::Unknown || f.connector < 0 || f.axis < 0 || f.axis > 2) {
      return unmapped(b, f.kind == Kind::Unknown ? "a field's sensor is not an accelerometer, "
                                                   "gyroscope or magnetometer"
                         : f.connector < 0       ? "a field's sensor has no mate_connector_attachment"
                                                 : "a field is not X, Y or Z");
    }
    const std::string sensor = name(f.sensor_path);
    if (imu_sensors_.insert(sensor).second) {
      sensors_
          ->add(f.kind == Kind::Accelerometer ? "accelerometer"
                : f.kind == Kind::Gyroscope   ? "gyro"
                                              : "magnetometer")
          .set("name", sensor)
          .set("site", site_for(f.connector));
    }
    b.names.push_back(sensor);
    b.initial_vector.push_back(f.axis);
  }
  b.quantity = Quantity::SensorFields;
  b.object = MjObject::Sensor;
  add_imu_noise(s, b);
}

// The fields' Gaussian signal noise, one mean and deviation per field, for the runtime to apply (MuJoCo 2.2.2
// applies no sensor noise); distortions without a counterpart are warned about once per sensor.
void Lowering::add_imu_noise(const sn::Signal& s, SignalBinding& b) {
  bool noisy = false;
  for (const sn::Signal::SensorField& f : s.sensor_fields) {
    noisy = noisy || f.noise_mean != 0 || f.noise_deviation != 0;
    for (const sn::Signal::SensorField::Distortion& d : f.unapplied) {
      if (!imu_distortions_said_.insert(d.path).second) continue;
      warn(d.where, "`" + d.path + "` (" + d.type + ") has no counterpart in the runtime or MuJoCo: `" +
                        f.sensor_path + "`'s readings carry its Gaussian noise only");
    }
  }
  if (!noisy) return;
  for (const sn::Signal::SensorField& f : s.sensor_fields) {
    b.noise.mean.push_back(f.noise_mean);
    b.noise.deviation.push_back(f.noise_deviation);
  }
  b.runtime = true;  // the MJCF alone reads the sensors without noise
}

// A RobotInput or RobotOutput: its parts' paths in order. An input's parts must be scalar inputs (one value
// each); an output's parts any outputs. Sensors (members unpublished) are not composed.
void Lowering::bind_composite(const sn::Signal& s, const std::vector<SignalBinding>& parts,
                              SignalBinding& b) {
  b.value = SignalValue::Vector;
  if (s.sensors > 0) {
    warn(s.where, "`" + s.path +
                      ".sensors` has no mapping (Robotics sensors' members are unpublished); the " +
                      "output composes its joint and object sources only");
  }
  for (int p : s.parts) {
    if (p < 0) return unmapped(b, "one of its parts is not a signal of this model");
    const SignalBinding& part = parts[static_cast<size_t>(p)];
    if (part.quantity == Quantity::None || part.quantity == Quantity::Composite)
      return unmapped(b, "its part `" + part.path + "` is not mapped: " + part.reason);
    if (part.input != s.input)
      return unmapped(b, "its part `" + part.path + "` is an " + (part.input ? "input" : "output"));
    const bool scalar =
        part.value == SignalValue::Real || part.value == SignalValue::Bool || part.value == SignalValue::Int;
    const bool vector_input = s.input && s.composition == sn::Signal::Composition::Vector;
    if ((vector_input || s.composition == sn::Signal::Composition::Affine) && !scalar)
      return unmapped(b, "its part `" + part.path + "` is not one number");
    if (s.composition == sn::Signal::Composition::Broadcast && !b.names.empty() &&
        part.value != parts[static_cast<size_t>(s.parts.front())].value)
      return unmapped(b, "its targets take different kinds of values");
    b.names.push_back(part.path);
  }
  switch (s.composition) {
    case sn::Signal::Composition::Vector:
      b.quantity = Quantity::Composite;
      break;
    case sn::Signal::Composition::Broadcast:
      if (s.parts.empty()) return unmapped(b, "it has no targets");
      b.quantity = Quantity::Broadcast;
      b.value = parts[static_cast<size_t>(s.parts.front())].value;
      break;
    case sn::Signal::Composition::Affine:
      if (s.parts.size() != 1) return unmapped(b, "it has no target or source signal");
      b.quantity = Quantity::Affine;
      b.value = SignalValue::Real;
      b.low = s.scale;
      b.high = s.offset;
      break;
  }
  return;
}

void Lowering::bind(const sn::Signal& s, SignalBinding& b) {
  const SignalClasses::Class& type = signal_classes_.of(s.type);
  b.value = type.kind.value;
  b.unit = type.kind.unit;
  const std::string_view stem = type.stem;
  using Source = sn::SignalSource;
  switch (s.source_kind) {
    case Source::None:
      return unmapped(b, "it has no source");
    case Source::Interaction:
      return bind_interaction(b, stem, s.source);
    case Source::Mate:
      return bind_mate(b, stem, s);
    case Source::Body:
      return bind_body(b, stem, s.source);
    case Source::Shaft:
      if (bind_shaft(b, stem, s.source)) return;
      break;
    case Source::Connector:
      return bind_connector(b, stem, s);
    case Source::Coupling:
      if (stem == "RelativeVelocity1D") b.unit = "rad/s";  // drivetrain parts join rotating shafts
      return bind_coupling(b, stem, s.source);
    case Source::Lidar:
      return bind_lidar(b, s.source);
    case Source::Other:
      // A steering system itself (RackAndPinion's, BellCrank's): its angle is its interaction's.
      for (const auto& [k, elements] : steering_) {
        const std::string& path = system_.interactions[k].path;
        if (path.size() == s.source_path.size() + 12 && path.starts_with(s.source_path) &&
            path.ends_with(".interaction"))
          return bind_interaction(b, stem, k);
      }
      break;
  }
  return unmapped(b, "its source `" +
                         (s.source_kind == Source::Shaft ? system_.shafts[s.source].path : s.source_path) +
                         "` has no MuJoCo element");
}

void Lowering::bind_interaction(SignalBinding& b, std::string_view stem, int k) {
  const sn::Interaction1D& i = system_.interactions[k];
  if (auto range = distance_tendons_.find(k); range != distance_tendons_.end()) {
    const bool motor = i.kind == sn::Interaction1D::Kind::DistanceMotor;
    if (stem == "Position1D" && !b.input)
      return mapped(b, Quantity::TendonLength, MjObject::Tendon, range->second);
    if (stem == "Force1D" && !b.input && !motor)
      return mapped(b, Quantity::TendonLimitForce, MjObject::Tendon, range->second);
    if (stem == "LinearVelocity1D" && motor) {  // the servo's target, also readable
      b.initial = actuator_ctrl_.at(k).second;
      return mapped(b, Quantity::Ctrl, MjObject::Actuator, name(i.path));
    }
  }
  if (auto steering = steering_.find(k); steering != steering_.end() && stem == "Angle") {
    // The left wheel's steering angle, held by the angle equality, or the input through its polynomial.
    b.initial_vector = steering->second.input_polynomial;
    b.low = steering->second.low;  // the linkage's reach, to which the runtime clamps the input
    b.high = steering->second.high;
    if (b.input) {
      return mapped(b, Quantity::EqualityTarget, MjObject::Equality, steering->second.angle_equality);
    }
    return mapped(b, Quantity::JointPosition, MjObject::Joint, steering->second.left_joint);
  }
  if (any_of(stem, {"EnableInteraction", "InteractionEnabled"})) return bind_enabled(b, k);
  const bool effort = any_of(stem, {"Torque1D", "Force1D"});
  const bool range = any_of(stem, {"TorqueRange", "ForceRange"});
  const std::string element = name(i.path);
  if (auto v = velocity_motors_.find(k); v != velocity_motors_.end()) {
    // The stand-in servo carries the band and the target; the runtime's row makes them exact.
    b.runtime = true;
    if (range) return mapped(b, Quantity::ForceRange, MjObject::Actuator, v->second);
    if (effort && !b.input) return mapped(b, Quantity::MotorForce, MjObject::Tendon, v->second);
    if (any_of(stem, {"AngularVelocity1D", "LinearVelocity1D"})) {  // the target, also readable
      b.initial = actuator_ctrl_.at(k).second;
      return mapped(b, Quantity::Ctrl, MjObject::Actuator, element);
    }
    b.runtime = false;
  } else if (auto sp = springs_.find(k); sp != springs_.end()) {
    // The runtime's spring row (springs.cpp) reads the rest and writes the force.
    if (any_of(stem, {"Angle", "Position1D"})) {  // the rest, also readable
      b.initial = actuator_ctrl_.at(k).second;
      b.runtime = true;
      return mapped(b, Quantity::Ctrl, MjObject::Actuator, sp->second);
    }
    if (effort && !b.input) {
      b.runtime = true;
      return mapped(b, Quantity::ActuatorForce, MjObject::Actuator, sp->second);
    }
  } else if (auto a = actuator_ctrl_.find(k); a != actuator_ctrl_.end()) {  // a force or torque motor
    if (range) return mapped(b, Quantity::ForceRange, MjObject::Actuator, element);
    if (effort && !b.input) return mapped(b, Quantity::ActuatorForce, MjObject::Actuator, element);
    if (effort) {
      b.initial = a->second.second;
      return mapped(b, Quantity::Ctrl, MjObject::Actuator, element);
    }
  }
  if (auto r = range_joints_.find(k); r != range_joints_.end() && !b.input) {
    if (any_of(stem, {"Angle", "Position1D"}))
      return mapped(b, Quantity::JointPosition, MjObject::Joint, r->second);
    if (effort) return mapped(b, Quantity::JointLimitForce, MjObject::Joint, r->second);
  }
  return unmapped(b, concat({"`", i.path, "` has no MuJoCo element that carries it"}));
}

// The enabled state of a motor, spring or range: what the runtime zeroes to switch it off, and the effort
// range (a range's limits) it restores.
void Lowering::bind_enabled(SignalBinding& b, int k) {
  const sn::Interaction1D& i = system_.interactions[k];
  b.initial = i.enabled ? 1.0 : 0.0;
  if (auto e = effort_ranges_.find(k); e != effort_ranges_.end()) {
    mapped(b, Quantity::InteractionEnabled, MjObject::Actuator, name(i.path));
    std::tie(b.low, b.high) = e->second;
    return;
  }
  if (auto r = range_joints_.find(k); r != range_joints_.end()) {
    if (ranges_on_joint_[r->second] > 1) {
      return unmapped(b, concat({"`", i.path, "` shares joint ", r->second,
                                 " with other ranges; MuJoCo has one limit per joint, so one range "
                                 "cannot be switched alone"}));
    }
    mapped(b, Quantity::InteractionEnabled, MjObject::Joint, r->second);
    b.low = i.start;
    b.high = i.end;
    return;
  }
  if (auto t = distance_tendons_.find(k); t != distance_tendons_.end()) {
    return unmapped(b, concat({"`", i.path, "` is the length limit of MuJoCo tendon ", t->second,
                               ", which the runtime does not switch on and off"}));
  }
  return unmapped(b, concat({"`", i.path, "` was not emitted"}));
}

// A drivetrain part's signals: gears' torques and ratios, clutches' and brakes' torque (the friction row's
// force), slip velocity and engagement; the rest in bind_drive_part.
void Lowering::bind_coupling(SignalBinding& b, std::string_view stem, int k) {
  const sn::DriveCoupling& c = system_.couplings[k];
  if (bind_drive_part(b, stem, k)) return;
  if (auto gear = gear_equalities_.find(k); gear != gear_equalities_.end()) {
    if (stem == "Torque1D" && !b.input)  // the torque the equality puts on the output shaft
      return mapped(b, Quantity::EqualityForce, MjObject::Equality, gear->second);
    if (stem == "Fraction") {
      b.initial = c.ratio;
      return mapped(b, Quantity::GearRatio, MjObject::Equality, gear->second);
    }
  }
  auto tendon = friction_couplings_.find(k);
  if (tendon == friction_couplings_.end())
    return unmapped(b, concat({"`", c.path, "` has no MuJoCo element that carries it"}));
  if (stem == "Torque1D" && !b.input)
    return mapped(b, Quantity::MotorForce, MjObject::Tendon, tendon->second);
  if (any_of(stem, {"EnableInteraction", "InteractionEnabled"})) {  // off: no friction at all
    mapped(b, Quantity::InteractionEnabled, MjObject::Tendon, tendon->second);
    b.initial = 1.0;
    const double band =
        c.torque_capacity *
        std::clamp(c.automatic ? (c.initially_engaged ? 1.0 : 0.0) : c.engagement_fraction, 0.0, 1.0);
    std::tie(b.low, b.high) = std::pair(-band, band);
    return;
  }
  if (stem == "RelativeVelocity1D" && !b.input)
    return mapped(b, Quantity::TendonVelocity, MjObject::Tendon, tendon->second);
  if (stem == "Fraction" && (!c.automatic || !b.input)) {  // an automatic one ramps its own
    mapped(b, Quantity::EngagementFraction, MjObject::Tendon, tendon->second);
    b.initial = c.engagement_fraction;
    b.high = c.torque_capacity;
    return;
  }
  if (any_of(stem, {"Engage", "Engaged"}) && c.automatic) {
    mapped(b, Quantity::Engaged, MjObject::Tendon, tendon->second);
    b.runtime = true;  // the ramp
    b.initial = c.initially_engaged ? 1.0 : 0.0;
    b.low = c.engagement_duration;
    b.high = c.disengagement_duration;
    b.initial_vector = {c.torque_capacity};
    return;
  }
  if (stem == "Fraction" && c.automatic) {
    return unmapped(b, concat({"`", c.path,
                               "` is automatic: it ramps its own engagement fraction when its engage input "
                               "switches, so the fraction can be read (FractionOutput) but not set"}));
  }
  if (any_of(stem, {"Engage", "Engaged"}) && !c.automatic) {
    return unmapped(b, concat({"`", c.path,
                               "` is manual: it has no engaged state of its own, only its engagement "
                               "fraction (FractionInput and FractionOutput set and read it)"}));
  }
  if (c.automatic && stem.ends_with("Duration")) {
    // Which one: the signal's type says (DriveTrain's AutomaticClutch...DurationInput); a plain
    // Physics.Signals.DurationInput (a brake's) says neither, and then the attribute's name does.
    const bool disengage =
        stem.ends_with("DisengagementDuration") ||
        (stem == "Duration" && b.path.find(".disengagement_duration_") != std::string::npos);
    mapped(b, disengage ? Quantity::DisengageDuration : Quantity::EngageDuration, MjObject::Tendon,
           tendon->second);
    b.runtime = true;
    b.initial = disengage ? c.disengagement_duration : c.engagement_duration;
    return;
  }
  return unmapped(b, concat({"`", c.path, "` has no MuJoCo element that carries it"}));
}

void Lowering::bind_mate(SignalBinding& b, std::string_view stem, const sn::Signal& s) {
  const int m = s.source;
  const sn::Mate& mate = system_.mates[m];
  if (auto distance = distance_mates_.find(m);
      distance != distance_mates_.end() && stem != "EnableInteraction" && stem != "InteractionEnabled") {
    // Any position input sets the target distance; the mate's own target output reads it back.
    if (stem == "Position1D" && (b.input || b.path.find(".target_distance_output") != std::string::npos)) {
      mapped(b, Quantity::DistanceTarget, MjObject::Equality, distance->second);
      b.initial = mate.target_distance;
      return;
    }
    if (stem == "Position1D" && !b.input)
      return mapped(b, Quantity::TendonLength, MjObject::Tendon, distance->second);
    if (stem == "Force1D" && !b.input)  // the equality row's force along the tendon
      return mapped(b, Quantity::EqualityForce, MjObject::Equality, distance->second);
    return unmapped(b, concat({"`", mate.path, "` is a distance constraint without this signal"}));
  }
  const bool tree = tree_mates_.count(m) > 0;
  if (any_of(stem, {"EnableInteraction", "InteractionEnabled"})) {
    if (auto e = equalities_of_mate_.find(m); e != equalities_of_mate_.end()) {
      mapped(b, Quantity::EqualityActive, MjObject::Equality, "");
      b.names = e->second;
      return;
    }
    if (!tree) return unmapped(b, concat({"`", mate.path, "` was left out of the MJCF"}));
    if (b.input) {
      return unmapped(
          b, concat({"`", mate.path, "` is a joint of MuJoCo's body tree, which cannot be switched off"}));
    }
    b.quantity = Quantity::Constant;
    b.initial = 1.0;
    return;
  }
  if (!tree && !equalities_of_mate_.count(m)) {  // its own warning says why (e.g. no joint type here)
    return unmapped(b, concat({"`", mate.path, "` was left out of the MJCF"}));
  }
  if (!tree) {
    return unmapped(
        b, concat({"`", mate.path,
                   mate.enabled ? "` closes a kinematic loop as an equality constraint"
                                : "` is disabled (`enabled: false`): an inactive equality constraint",
                   ", which has no joint coordinate or force sensor"}));
  }
  if (!b.input && any_of(stem, {"Angle", "AngularVelocity1D", "Position1D", "LinearVelocity1D"})) {
    const bool rotational = any_of(stem, {"Angle", "AngularVelocity1D"});
    Element* joint = joint_for(m, rotational);
    if (!joint) {
      return unmapped(b, concat({"`", mate.path, "` has no ", rotational ? "rotational" : "linear",
                                 " joint coordinate"}));
    }
    const bool position = any_of(stem, {"Angle", "Position1D"});
    return mapped(b, position ? Quantity::JointPosition : Quantity::JointVelocity, MjObject::Joint,
                  *joint->get("name"));
  }
  if (!b.input && any_of(stem, {"Force3D", "Torque3D"})) {
    auto found = child_of_mate_.find(m);
    if (found == child_of_mate_.end()) return unmapped(b, concat({"`", mate.path, "` was not emitted"}));
    const int child = found->second;
    const int side = vertex_of_connector(mate.connectors[1]) == child ? 1 : 0;
    const bool force = stem == "Force3D";
    if (s.relative_transform) {  // its axes: a transform is a value, fixed in the world
      const Eigen::Quaterniond q = s.relative_transform->rotation.normalized();
      mapped(b, force ? Quantity::MateForceInFrame : Quantity::MateTorqueInFrame, MjObject::Site,
             site_for(mate.connectors[side]));
      b.initial_vector = {q.w(), q.x(), q.y(), q.z()};
    } else {
      mapped(b, force ? Quantity::MateForce : Quantity::MateTorque, MjObject::Site,
             site_for(mate.connectors[side]));
    }
    b.sign = side == 1 ? 1.0 : -1.0;
    return;
  }
  return unmapped(b, concat({"`", mate.path, "` has no MuJoCo element that carries it"}));
}

void Lowering::bind_body(SignalBinding& b, std::string_view stem, int n) {
  std::string body = name(system_.nodes[n].path);  // moved into the binding that names it
  if (!body_element_.count(n)) return unmapped(b, concat({"`", system_.nodes[n].path, "` was not emitted"}));
  if (b.input) {
    if (stem == "Torque3D") return bind_body_torque(b, n, std::move(body));
    const bool linear = stem == "LinearVelocity3D";
    if (!linear && stem != "AngularVelocity3D") {
      return unmapped(b, concat({"a body takes velocity and torque inputs; ", stem, " is neither"}));
    }
    if (mocap_.count(n)) {  // starting at the body's initial velocity, in world axes
      const sn::FrameNode& node = system_.nodes[n];
      const Eigen::Matrix3d system = node.parent >= 0
                                         ? snap_.node_world[node.parent].rotation.toRotationMatrix()
                                         : Eigen::Matrix3d::Identity();
      const Eigen::Vector3d v =
          system * (linear ? node.body.initial_linear_velocity : node.body.initial_angular_velocity);
      b.initial_vector = {v.x(), v.y(), v.z()};
      return mapped(b, linear ? Quantity::KinematicLinearVelocity : Quantity::KinematicAngularVelocity,
                    MjObject::Body, std::move(body));
    }
    if (free_roots_.count(n)) {
      return mapped(b, linear ? Quantity::FreeLinearVelocity : Quantity::FreeAngularVelocity, MjObject::Joint,
                    std::move(body));
    }
    return unmapped(b, concat({"`", system_.nodes[n].path,
                               "` moves through its joints in MuJoCo; its velocity cannot be set"}));
  }
  const Quantity q = stem == "Position3D" || stem == "Position" ? Quantity::BodyPosition
                     : stem == "RPY"                            ? Quantity::BodyRPY
                     : stem == "LinearVelocity3D"               ? Quantity::BodyLinearVelocity
                     : stem == "AngularVelocity3D"              ? Quantity::BodyAngularVelocity
                     : stem == "Acceleration3D"                 ? Quantity::BodyLinearAcceleration
                                                                : Quantity::None;
  if (q == Quantity::None) {
    return unmapped(b, concat({"a body's outputs are its position, RPY, velocities and linear acceleration; ",
                               stem, " is none of them"}));
  }
  return mapped(b, q, MjObject::Body, std::move(body));
}

void Lowering::bind_connector(SignalBinding& b, std::string_view stem, const sn::Signal& s) {
  if (b.input) return unmapped(b, "a mate connector takes no input: MuJoCo moves its site with its body");
  if (!s.relative_to_path.empty()) {
    return unmapped(
        b, concat({"its relative_to `", s.relative_to_path, "` is not a mate connector of this model"}));
  }
  const bool relative = s.relative_to >= 0;
  using Q = Quantity;
  const Q q =
      stem == "Position3D" || stem == "Position" ? (relative ? Q::SiteRelativePosition : Q::SitePosition)
      : stem == "RPY"                            ? (relative ? Q::SiteRelativeRPY : Q::SiteRPY)
      : stem == "LinearVelocity3D"  ? (relative ? Q::SiteRelativeLinearVelocity : Q::SiteLinearVelocity)
      : stem == "AngularVelocity3D" ? (relative ? Q::SiteRelativeAngularVelocity : Q::SiteAngularVelocity)
      : stem == "Acceleration3D" ? (relative ? Q::SiteRelativeLinearAcceleration : Q::SiteLinearAcceleration)
      : stem == "AngularAcceleration3D"
          ? (relative ? Q::SiteRelativeAngularAcceleration : Q::SiteAngularAcceleration)
          : Q::None;
  if (q == Q::None) {
    return unmapped(b, concat({"a mate connector's outputs are its position, RPY, velocities and "
                               "accelerations; ",
                               stem, " is none of them"}));
  }
  mapped(b, q, MjObject::Site, site_for(s.source));
  if (relative) b.names.push_back(site_for(s.relative_to));
}

// A Torque3DInput on a body: a pure torque through xfrc_applied, which moves only a body with degrees of
// freedom of its own.
void Lowering::bind_body_torque(SignalBinding& b, int n, std::string body) {
  const std::string& path = system_.nodes[n].path;
  if (is_static(n)) {
    return unmapped(
        b,
        concat({"`", path, "` is static (is_dynamic: false): nothing moves it, so a torque has no effect"}));
  }
  if (mocap_.count(n)) {
    return unmapped(b, concat({"`", path,
                               "` is kinematic (a MuJoCo mocap body): it moves as its velocity inputs say, "
                               "and forces do not act on it"}));
  }
  mapped(b, Quantity::BodyTorque, MjObject::Body, std::move(body));
}

// A site at a mate connector, in the MuJoCo body that carries it (the world for system connectors).
std::string Lowering::site_for(int c) {
  const std::string site = name(system_.connectors[c].path);
  if (!sites_.insert(c).second) return site;
  const auto [parent, frame] = connector_mount(c);
  parent->add("site").set("name", site).set("pos", frame.position).set_quat("quat", frame.rotation);
  return site;
}

// Where a connector's sites go: its body's element and its frame there, or the world and its world frame
// (system connectors).
std::pair<Element*, sn::Transform> Lowering::connector_mount(int c) {
  const int owner = vertex_of_connector(c);
  auto body = body_element_.find(owner);
  if (owner >= 0 && body != body_element_.end()) return {body->second, system_.connectors[c].local};
  return {world_, snap_.connector_world[c]};
}

void Lowering::add_sensor(SignalBinding& b) {
  struct Sensor {
    const char* element;
    const char* objtype;  // frame sensors; nullptr: the element names its object by attribute
    const char* attribute;
    bool relative = false;  // names[1] is the reference site (reftype="site")
  };
  Sensor sensor{};
  switch (b.quantity) {
    case Quantity::JointPosition:
      sensor = {"jointpos", nullptr, "joint"};
      break;
    case Quantity::JointVelocity:
      sensor = {"jointvel", nullptr, "joint"};
      break;
    case Quantity::JointLimitForce:
      sensor = {"jointlimitfrc", nullptr, "joint"};
      break;
    case Quantity::TendonVelocity:
      sensor = {"tendonvel", nullptr, "tendon"};
      break;
    case Quantity::ActuatorForce:
      sensor = {"actuatorfrc", nullptr, "actuator"};
      break;
    case Quantity::MateForce:
    case Quantity::MateForceInFrame:
      sensor = {"force", nullptr, "site"};
      break;
    case Quantity::MateTorque:
    case Quantity::MateTorqueInFrame:
      sensor = {"torque", nullptr, "site"};
      break;
    case Quantity::BodyPosition:
      sensor = {"framepos", "xbody", nullptr};
      break;
    case Quantity::BodyRPY:
      sensor = {"framequat", "xbody", nullptr};
      break;  // the runtime gives RPY
    case Quantity::BodyLinearVelocity:
      sensor = {"framelinvel", "xbody", nullptr};
      break;
    case Quantity::BodyAngularVelocity:
      sensor = {"frameangvel", "xbody", nullptr};
      break;
    case Quantity::BodyLinearAcceleration:
      sensor = {"framelinacc", "xbody", nullptr};
      break;
    case Quantity::SitePosition:
      sensor = {"framepos", "site", nullptr};
      break;
    case Quantity::SiteRPY:
      sensor = {"framequat", "site", nullptr};
      break;
    case Quantity::SiteLinearVelocity:
      sensor = {"framelinvel", "site", nullptr};
      break;
    case Quantity::SiteAngularVelocity:
      sensor = {"frameangvel", "site", nullptr};
      break;
    case Quantity::SiteLinearAcceleration:  // proper acceleration: the runtime adds gravity
      sensor = {"framelinacc", "site", nullptr};
      break;
    case Quantity::SiteAngularAcceleration:
      sensor = {"frameangacc", "site", nullptr};
      break;
    case Quantity::SiteRelativePosition:
      sensor = {"framepos", "site", nullptr, true};
      break;
    case Quantity::SiteRelativeRPY:
      sensor = {"framequat", "site", nullptr, true};
      break;
    case Quantity::SiteRelativeLinearVelocity:
      sensor = {"framelinvel", "site", nullptr, true};
      break;
    case Quantity::SiteRelativeAngularVelocity:
      sensor = {"frameangvel", "site", nullptr, true};
      break;
    default:
      return;  // computed by the runtime
  }
  Element& e = sensors_->add(sensor.element);
  e.set("name", name(b.path));
  if (sensor.objtype) {
    e.set("objtype", sensor.objtype).set("objname", b.names.front());
    if (sensor.relative) e.set("reftype", "site").set("refname", b.names[1]);
  } else {
    e.set(sensor.attribute, b.names.front());
  }
  b.sensor = name(b.path);
}

}  // namespace openplx::mjcf
