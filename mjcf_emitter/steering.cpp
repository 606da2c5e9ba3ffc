// Lowering pass, kinematic steering (Vehicles.Steering.Kinematic): the left wheel's steering hinge is held by
// a joint equality on it alone (`.angle`), whose constant the runtime sets from the steering input, and the
// right wheel follows the linkage by a joint equality right = q(left) (`.linkage`), q the quartic MuJoCo's
// joint equality takes, fitted to the exact linkage over the steering range (steering_linkage.h has the
// geometry, UNCONFIRMED against AGX). Ackermann's input is the left wheel's angle itself; BellCrank's and
// RackAndPinion's is the steering-wheel angle θ, and the left wheel is held at p(θ), a quartic fitted to
// the exact linkage that the runtime evaluates (and inverts for the steering angle output).
#include <Eigen/Dense>

#include "mjcf_emitter/lowering.h"
#include "mjcf_emitter/steering_linkage.h"

namespace openplx::mjcf {
namespace {

std::string coefficients(const std::array<double, 5>& c) {
  std::string out;
  for (size_t p = 0; p < c.size(); ++p) out += (p ? " " : "") + number(c[p]);
  return out;
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
  // Track width and the linkage geometry, in the plane across the steering axis.
  const sn::Mate& left = view_.mates[i.steered[0]];
  const sn::Mate& right = view_.mates[i.steered[1]];
  const Eigen::Vector3d kl = snap_.connector_world[left.connectors[0]].position;
  const Eigen::Vector3d kr = snap_.connector_world[right.connectors[0]].position;
  SteeringGeometry g;
  g.track = (kl - kr).norm();
  g.knuckle_length = i.knuckle_length;
  g.knuckle_angle = i.knuckle_angle;
  g.tie_rod_angle = i.tie_rod_angle;
  g.column_distance = i.column_distance;
  g.rack_length = i.rack_length;
  g.gear = i.gear;
  const bool column = i.mechanism == "BellCrank" || i.mechanism == "RackAndPinion";
  const SteeringLinkage fit = i.mechanism == "BellCrank"       ? bell_crank_linkage(g)
                              : i.mechanism == "RackAndPinion" ? rack_and_pinion_linkage(g)
                                                               : ackermann_linkage(g);
  const std::string geometry = "track " + number(g.track) + " m, knuckle " + number(i.knuckle_length) +
                               " m at " + number(i.knuckle_angle) + " rad";
  if (!fit.problem.empty()) {
    warn(i.where, "`" + i.path + "`'s " + i.mechanism + " linkage (" + geometry + ") " + fit.problem +
                      "; it was left out");
    return;
  }
  if (!column && (fit.high - fit.low < 0.2 || fit.linkage.max_error > 1e-2)) {
    warn(i.where, "`" + i.path + "`'s linkage (" + geometry + ") covers left angles " + number(fit.low) +
                      " to " + number(fit.high) + " rad, and MuJoCo's quartic is off by up to " +
                      number(fit.linkage.max_error) + " rad there; the right wheel follows that quartic");
  }
  if (column && (!fit.closes || fit.input_to_left.max_error > 1e-2 || fit.linkage.max_error > 1e-2)) {
    double left_low = 0, left_high = 0;
    for (const SteeringSample& s : fit.samples) {
      left_low = std::min(left_low, s.left);
      left_high = std::max(left_high, s.left);
    }
    std::string column_geometry = geometry + ", tie rods at " + number(i.tie_rod_angle) +
                                  " rad, steering arm " + number(i.column_distance) + " m";
    if (i.mechanism == "RackAndPinion") column_geometry += ", rack " + number(i.rack_length) + " m";
    column_geometry += ", gear " + number(i.gear);
    warn(i.where, "`" + i.path + "`'s " + i.mechanism + " linkage (" + column_geometry +
                      ") covers steering inputs " + number(fit.low) + " to " + number(fit.high) +
                      " rad (left wheel " + number(left_low) + " to " + number(left_high) + " rad)" +
                      (fit.closes ? "" : ", short of the wheels' " + number(kSteeringRange) + " rad lock") +
                      ", and MuJoCo's quartics are off by up to " + number(fit.input_to_left.max_error) +
                      " rad (left wheel for the input) and " + number(fit.linkage.max_error) +
                      " rad (right wheel for the left) there; the wheels follow those quartics");
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
  SteeringElements& elements = steering_[index_in(view_.interactions, i)];
  elements = {base + ".angle", *joints[0]->get("name"), fit.linkage.max_error, {}};
  if (column) elements.input_polynomial.assign(fit.input_to_left.c.begin(), fit.input_to_left.c.end());
}

}  // namespace openplx::mjcf
