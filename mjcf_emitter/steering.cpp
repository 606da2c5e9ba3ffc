// Lowering pass, kinematic steering (Vehicles.Steering.Kinematic): the steering input holds the left wheel's
// steering angle (a joint equality on it alone, its constant set by the input), and the right wheel follows
// through the mechanism's linkage, a joint equality right = p(left) with p the quartic MuJoCo's joint
// equality takes, fitted to the exact linkage over the steering range.
//
// The linkage (UNCONFIRMED against AGX, which documents only its parameters): kingpins at the two
// suspensions' chassis connectors, knuckle arms of knuckle_length pointing rearward and tilted inward by
// |knuckle_angle| - 90° (the angle is read from the axle line pointing outward), a tie rod joining the arm
// ends with the length it has straight ahead: the Ackermann trapezoid. The steering angle is the left
// wheel's, positive about the suspension's travel direction (up: a left turn).
#include <Eigen/Dense>
#include <cmath>
#include <optional>

#include "mjcf_emitter/lowering.h"

namespace openplx::mjcf {
namespace {

// The right wheel's angle for the left wheel's angle `left` in the trapezoid linkage (track `w`, arm `l`,
// inward tilt `beta`), continuing from the previous solution `near`; nullopt where the linkage cannot close.
std::optional<double> right_angle(double left, double w, double l, double beta, double near) {
  const Eigen::Vector2d kl(0, w / 2), kr(0, -w / 2);
  const Eigen::Vector2d arm_l(-l * std::cos(beta), -l * std::sin(beta)),
      arm_r(-l * std::cos(beta), l * std::sin(beta));
  const double tie = ((kl + arm_l) - (kr + arm_r)).norm();
  const Eigen::Vector2d pl = kl + Eigen::Rotation2Dd(left) * arm_l;
  // The right arm's end: on the circle about kr of radius l and on the circle about pl of radius tie.
  const Eigen::Vector2d d = pl - kr;
  const double dist = d.norm();
  if (dist > l + tie || dist < std::abs(l - tie) || dist == 0) return std::nullopt;
  const double a = (l * l - tie * tie + dist * dist) / (2 * dist);
  const double h = std::sqrt(std::max(0.0, l * l - a * a));
  const Eigen::Vector2d mid = kr + a * d / dist, across(-d.y() / dist, d.x() / dist);
  std::optional<double> best;
  for (const Eigen::Vector2d& p : {Eigen::Vector2d(mid + h * across), Eigen::Vector2d(mid - h * across)}) {
    const Eigen::Vector2d r = p - kr;
    const double angle = std::atan2(arm_r.x() * r.y() - arm_r.y() * r.x(), arm_r.dot(r));
    if (!best || std::abs(angle - near) < std::abs(*best - near)) best = angle;
  }
  return best;
}

struct SteeringFit {
  Eigen::Matrix<double, 5, 1> coefficients = Eigen::Matrix<double, 5, 1>::Zero();  // a0 .. a4
  double low = 0, high = 0;  // the left angles the fit covers
  double max_error = 0;      // rad, over them
};

// Least squares over the steering range: both wheels within 0.6 rad of straight ahead (about 34°, a road
// vehicle's lock), less where the linkage cannot close.
SteeringFit fit_linkage(double w, double l, double beta) {
  constexpr int kSteps = 120;
  constexpr double kMaxRange = 0.6;
  std::vector<std::pair<double, double>> samples{{0.0, 0.0}};
  for (const double direction : {1.0, -1.0}) {
    double near = 0;
    for (int k = 1; k <= kSteps; ++k) {
      const double left = direction * kMaxRange * k / kSteps;
      const std::optional<double> right = right_angle(left, w, l, beta, near);
      if (!right || std::abs(*right) > kMaxRange) break;
      samples.emplace_back(left, *right);
      near = *right;
    }
  }
  SteeringFit fit;
  // No constant term: straight ahead is straight ahead, so the equality holds at the start.
  Eigen::MatrixXd a(samples.size(), 4);
  Eigen::VectorXd b(samples.size());
  double reach_pos = 0, reach_neg = 0;
  for (size_t s = 0; s < samples.size(); ++s) {
    const double x = samples[s].first;
    for (int p = 1; p < 5; ++p) a(static_cast<int>(s), p - 1) = std::pow(x, p);
    b(static_cast<int>(s)) = samples[s].second;
    reach_pos = std::max(reach_pos, x);
    reach_neg = std::min(reach_neg, x);
  }
  fit.low = reach_neg;
  fit.high = reach_pos;
  fit.coefficients.tail<4>() = a.colPivHouseholderQr().solve(b);
  for (size_t s = 0; s < samples.size(); ++s) {
    const double error =
        std::abs((a.row(static_cast<int>(s)) * fit.coefficients.tail<4>())(0) - samples[s].second);
    fit.max_error = std::max(fit.max_error, error);
  }
  return fit;
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
  // Track width and the knuckle geometry, in the plane across the steering axis.
  const sn::Mate& left = view_.mates[i.steered[0]];
  const sn::Mate& right = view_.mates[i.steered[1]];
  const Eigen::Vector3d kl = snap_.connector_world[left.connectors[0]].position;
  const Eigen::Vector3d kr = snap_.connector_world[right.connectors[0]].position;
  const double w = (kl - kr).norm();
  const double beta = std::abs(i.knuckle_angle) - M_PI / 2;
  const SteeringFit fit = fit_linkage(w, i.knuckle_length, beta);
  if (i.mechanism != "Ackermann") {
    warn(i.where,
         "`" + i.path + "` (" + i.mechanism +
             ") is mapped as the Ackermann linkage of its knuckle geometry: its gear, steering column "
             "and tie-rod parameters are not honoured");
  }
  if (fit.high - fit.low < 0.2 || fit.max_error > 1e-2) {
    warn(i.where, "`" + i.path + "`'s linkage (track " + number(w) + " m, knuckle " +
                      number(i.knuckle_length) + " m at " + number(i.knuckle_angle) +
                      " rad) covers left angles " + number(fit.low) + " to " + number(fit.high) +
                      " rad, and MuJoCo's quartic is off by up to " + number(fit.max_error) +
                      " rad there; the right wheel follows that quartic");
  }
  Element* equality = root.child("equality");
  if (!equality) equality = &root.add("equality");
  const std::string base = name(i.path);
  equality->add("joint")
      .set("name", base + ".angle")
      .set("joint1", *joints[0]->get("name"))
      .set("polycoef", "0 0 0 0 0");
  std::string coefficients;
  for (int p = 0; p < 5; ++p) coefficients += (p ? " " : "") + number(fit.coefficients(p));
  equality->add("joint")
      .set("name", base + ".linkage")
      .set("joint1", *joints[1]->get("name"))
      .set("joint2", *joints[0]->get("name"))
      .set("polycoef", coefficients);
  steering_[index_in(view_.interactions, i)] = {base + ".angle", *joints[0]->get("name"), fit.max_error};
}

}  // namespace openplx::mjcf
