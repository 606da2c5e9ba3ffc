// Lowering pass, kinematic steering (Vehicles.Steering.Kinematic): the left wheel's steering hinge is held by
// a joint equality on it alone (`.angle`), whose constant the runtime sets from the steering input, and the
// right wheel follows the linkage by a joint equality right = q(left) (`.linkage`), q the quartic MuJoCo's
// joint equality takes, fitted to the exact linkage over every input it reaches (steering_linkage.h has
// AGX's geometry, lengths relative to the track). Ackermann's input is the left wheel's angle itself;
// BellCrank's and RackAndPinion's is the steering-wheel angle θ, and the left wheel is held at p(θ), a
// polynomial fitted to the exact linkage that the runtime evaluates (and inverts for the steering angle
// output). The input's range is the linkage's reach; the runtime clamps inputs to it.
#include <Eigen/Dense>
#include <algorithm>
#include <iomanip>
#include <sstream>

#include "contract/steering_linkage.h"
#include "mjcf_emitter/lowering.h"

namespace openplx::mjcf {
namespace {

std::string coefficients(const std::vector<double>& c) {
  std::string out;
  for (size_t p = 0; p < c.size(); ++p) out += (p ? " " : "") + number(c[p]);
  return out;
}

// A figure for a message: four significant digits.
std::string figure(double v) {
  std::ostringstream out;
  out << std::setprecision(4) << v;
  return out.str();
}

SteeringMechanism mechanism_of(const std::string& name) {
  return name == "BellCrank"       ? SteeringMechanism::BellCrank
         : name == "RackAndPinion" ? SteeringMechanism::RackAndPinion
                                   : SteeringMechanism::Ackermann;
}

// The geometry as the user gave it: each attribute's value, lengths also in metres on this track.
std::string parameters(const sn::Interaction1D& i, double track) {
  std::string out = "track " + figure(track) + " m, knuckle_length " + figure(i.knuckle_length) + " (" +
                    figure(i.knuckle_length * track) + " m), knuckle_angle " + figure(i.knuckle_angle) +
                    " rad";
  if (i.mechanism == "Ackermann") return out;
  out += ", initial_angle_right_tie_rod " + figure(i.tie_rod_angle) + " rad, steering_column_distance " +
         figure(i.column_distance) + " (" + figure(i.column_distance * i.knuckle_length * track) + " m)";
  if (i.mechanism == "RackAndPinion")
    out += ", rack_length " + figure(i.rack_length) + " (" + figure(i.rack_length * track) + " m)";
  return out + ", gear " + figure(i.gear);
}

// The user's line of the first of `attributes` the user wrote, else the steering's own line.
frontend::SourceRange line_of(const sn::Interaction1D& i, const std::vector<std::string>& attributes) {
  for (const std::string& a : attributes) {
    for (const auto& [name, where] : i.written)
      if (name == a) return where;
  }
  return i.where;
}

}  // namespace

void Lowering::emit_steering(Element& root, const sn::Interaction1D& i) {
  Element* joints[2] = {nullptr, nullptr};
  for (int side = 0; side < 2; ++side) {
    const int m = i.steered[side];
    if (m < 0 || !joint_of_mate_.count(m)) continue;
    for (Element* j : joint_of_mate_.at(m)) {
      const std::string& n = *j->get("name");
      if (n.size() > 9 && n.compare(n.size() - 9, 9, ".steering") == 0) joints[side] = j;
    }
  }
  if (!joints[0] || !joints[1]) {
    warn(i.where, "`" + i.path + "` needs two steerable suspensions (with Vehicles.Suspensions.Properties." +
                      "Steering) joined in MuJoCo's tree; it was left out");
    return;
  }
  // The track: between the two kingpins, the suspensions' chassis connectors.
  const sn::Mate& left = system_.mates[i.steered[0]];
  const sn::Mate& right = system_.mates[i.steered[1]];
  const Eigen::Vector3d kl = snap_.connector_world[left.connectors[0]].position;
  const Eigen::Vector3d kr = snap_.connector_world[right.connectors[0]].position;
  SteeringGeometry g;
  g.mechanism = mechanism_of(i.mechanism);
  g.track = (kl - kr).norm();
  g.knuckle_length = i.knuckle_length;
  g.knuckle_angle = i.knuckle_angle;
  g.tie_rod_angle = i.tie_rod_angle;
  g.column_distance = i.column_distance;
  g.rack_length = i.rack_length;
  g.gear = i.gear;
  SteeringLinkage fit = steering_linkage(g);
  const bool closes = fit.problem.empty();
  if (!closes) {
    warn(line_of(i, fit.attributes), "`" + i.path + "`'s " + i.mechanism + " linkage (" +
                                         parameters(i, g.track) + ") " + fit.problem +
                                         "; its wheels are held straight ahead (the steering input is "
                                         "clamped to 0)");
    fit.low = fit.high = 0;
    fit.input_to_left.c = {0.0};  // the left wheel at 0 whatever the input, and the right at 0 with it
    fit.linkage.c = {0, 0, 0, 0, 0};
  } else if (fit.input_to_left.max_error > 1e-2 || fit.linkage.max_error > 1e-2) {
    std::string held = "MuJoCo's quartic holds the right wheel within " + figure(fit.linkage_fitted) +
                       " rad of the linkage for inputs " + figure(fit.fitted_low) + " to " +
                       figure(fit.fitted_high) + " rad and within " + figure(fit.linkage.max_error) +
                       " rad beyond, where the linkage bends towards its dead points as no quartic does";
    if (g.mechanism != SteeringMechanism::Ackermann) {
      held += "; the left wheel is held within " + figure(fit.input_to_left_fitted) +
              " rad of its angle for inputs " + figure(fit.input_fitted_low) + " to " +
              figure(fit.input_fitted_high) + " rad and within " + figure(fit.input_to_left.max_error) +
              " rad beyond";
    }
    warn(i.where, "`" + i.path + "`'s " + i.mechanism + " linkage (" + parameters(i, g.track) +
                      ") reaches steering inputs " + figure(fit.low) + " to " + figure(fit.high) +
                      " rad (its dead points; inputs are clamped there); " + held);
  }
  Element* equality = root.child("equality");
  if (!equality) equality = &root.add("equality");
  const std::string base = name(i.path);
  equality->add("joint")
      .set("name", base + ".angle")
      .set("joint1", *joints[0]->get("name"))
      .set("polycoef", "0 0 0 0 0");
  equality->add("joint")
      .set("name", base + ".linkage")
      .set("joint1", *joints[1]->get("name"))
      .set("joint2", *joints[0]->get("name"))
      .set("polycoef", coefficients(fit.linkage.c));
  SteeringElements& elements = steering_[index_in(system_.interactions, i)];
  elements = {base + ".angle", *joints[0]->get("name"), fit.linkage.max_error, {}, fit.low, fit.high};
  if (g.mechanism != SteeringMechanism::Ackermann || !closes) elements.input_polynomial = fit.input_to_left.c;
}

}  // namespace openplx::mjcf
