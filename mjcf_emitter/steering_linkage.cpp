// Kinematic steering linkages: exact loop closure and quartic fits (geometry in steering_linkage.h).
#include "mjcf_emitter/steering_linkage.h"

#include <Eigen/Dense>
#include <cmath>
#include <optional>
#include <utility>

namespace openplx::mjcf {
namespace {

using Eigen::Vector2d;

constexpr int kSteps = 120;  // samples per side of the range

// The angle that turns `arm` (from kingpin `k`, of length `radius`) so that its end lies `tie` from
// `anchor`, the solution nearest `near`; nullopt where the two circles do not meet.
std::optional<double> arm_angle(const Vector2d& k, const Vector2d& arm, double radius, const Vector2d& anchor,
                                double tie, double near) {
  const Vector2d d = anchor - k;
  const double dist = d.norm();
  if (dist > radius + tie || dist < std::abs(radius - tie) || dist == 0) return std::nullopt;
  const double a = (radius * radius - tie * tie + dist * dist) / (2 * dist);
  const double h = std::sqrt(std::max(0.0, radius * radius - a * a));
  const Vector2d mid = k + a * d / dist, across(-d.y() / dist, d.x() / dist);
  std::optional<double> best;
  for (const Vector2d& p : {Vector2d(mid + h * across), Vector2d(mid - h * across)}) {
    const Vector2d r = p - k;
    const double angle = std::atan2(arm.x() * r.y() - arm.y() * r.x(), arm.dot(r));
    if (!best || std::abs(angle - near) < std::abs(*best - near)) best = angle;
  }
  return best;
}

QuarticFit fit_quartic(const std::vector<std::pair<double, double>>& xy) {
  // No constant term: straight ahead is straight ahead, so the equalities hold at the start.
  Eigen::MatrixXd a(xy.size(), 4);
  Eigen::VectorXd b(xy.size());
  for (size_t s = 0; s < xy.size(); ++s) {
    for (int p = 1; p < 5; ++p) a(static_cast<int>(s), p - 1) = std::pow(xy[s].first, p);
    b(static_cast<int>(s)) = xy[s].second;
  }
  const Eigen::Vector4d c = a.colPivHouseholderQr().solve(b);
  QuarticFit fit;
  for (int p = 1; p < 5; ++p) fit.c[static_cast<size_t>(p)] = c(p - 1);
  for (size_t s = 0; s < xy.size(); ++s)
    fit.max_error = std::max(fit.max_error, std::abs((a.row(static_cast<int>(s)) * c)(0) - xy[s].second));
  return fit;
}

struct Knuckles {
  Vector2d kl, kr, arm_l, arm_r;
};

Knuckles knuckles(const SteeringGeometry& g) {
  const double l = g.knuckle_length, beta = std::abs(g.knuckle_angle) - M_PI / 2;
  return {Vector2d(0, g.track / 2), Vector2d(0, -g.track / 2),
          Vector2d(-l * std::cos(beta), -l * std::sin(beta)),
          Vector2d(-l * std::cos(beta), l * std::sin(beta))};
}

// The tie rods' inner ends for input θ (left, right), of a steering column mechanism.
struct Column {
  Knuckles k;
  Vector2d inner_l, inner_r;  // at rest
  double tie_l = 0, tie_r = 0;
  bool lever = false;  // BellCrank: both ends on the lever's end; RackAndPinion: on the rack's
  Vector2d pivot;      // BellCrank: the lever's pivot

  std::pair<Vector2d, Vector2d> inner(const SteeringGeometry& g, double theta) const {
    if (lever) {
      const Vector2d end = pivot + Eigen::Rotation2Dd(g.gear * theta) * Vector2d(-g.column_distance, 0);
      return {end, end};
    }
    const Vector2d shift(0, -g.column_distance * g.gear * theta);
    return {inner_l + shift, inner_r + shift};
  }
};

SteeringLinkage column_linkage(const SteeringGeometry& g, bool lever) {
  SteeringLinkage out;
  if (!(g.track > 0) || !(g.knuckle_length > 0)) {
    out.problem = "needs a positive track and knuckle_length";
    return out;
  }
  if (!(std::cos(g.tie_rod_angle) > 1e-6)) {
    out.problem = "has tie rods along the vehicle (initial_angle_right_tie_rod must be within ±90°)";
    return out;
  }
  Column c;
  c.k = knuckles(g);
  c.lever = lever;
  // Each tie rod runs inward from its arm end, sloping forward by the tie-rod angle, to the centre line
  // (BellCrank) or to the rack's end (RackAndPinion).
  const Vector2d arm_end_l = c.k.kl + c.k.arm_l, arm_end_r = c.k.kr + c.k.arm_r;
  const double inner_y = lever ? 0.0 : g.rack_length / 2;
  const double along = (arm_end_l.y() - inner_y) / std::cos(g.tie_rod_angle);
  if (!(along > 1e-9)) {
    out.problem = lever ? "has its knuckle arm ends across the centre line"
                        : "has a rack reaching past the knuckle arm ends (rack_length too long)";
    return out;
  }
  const double x = arm_end_l.x() + along * std::sin(g.tie_rod_angle);
  c.inner_l = Vector2d(x, inner_y);
  c.inner_r = Vector2d(x, -inner_y);
  c.pivot = c.inner_l + Vector2d(g.column_distance, 0);
  c.tie_l = (arm_end_l - c.inner_l).norm();
  c.tie_r = (arm_end_r - c.inner_r).norm();
  const double l = g.knuckle_length;
  auto solve = [&](double theta, double near_l, double near_r) -> std::optional<std::pair<double, double>> {
    const auto [il, ir] = c.inner(g, theta);
    const std::optional<double> left = arm_angle(c.k.kl, c.k.arm_l, l, il, c.tie_l, near_l);
    const std::optional<double> right = arm_angle(c.k.kr, c.k.arm_r, l, ir, c.tie_r, near_r);
    if (!left || !right) return std::nullopt;
    return std::make_pair(*left, *right);
  };
  // The input's scale: how fast the left wheel turns straight ahead.
  constexpr double kProbe = 1e-6;
  const auto probe = solve(kProbe, 0, 0);
  const double slope = probe ? probe->first / kProbe : 0;
  if (!probe || !std::isfinite(slope) || std::abs(slope) < 1e-9) {
    out.problem = probe ? "does not turn the wheels (gear or steering_column_distance is zero)"
                        : "cannot close its tie-rod loops straight ahead";
    return out;
  }
  const double step = kSteeringRange / std::abs(slope) / kSteps;
  out.samples.push_back({0, 0, 0});
  for (const double direction : {1.0, -1.0}) {
    double near_l = 0, near_r = 0;
    bool edge = false;
    for (int k = 1; k <= 4 * kSteps; ++k) {
      const double theta = direction * step * k;
      const auto angles = solve(theta, near_l, near_r);
      if (!angles) break;
      const auto [left, right] = *angles;
      if (std::abs(left) > kSteeringRange || std::abs(right) > kSteeringRange) {
        edge = true;
        break;
      }
      if ((left - near_l) * direction * slope <= 0) break;  // past a dead point: no longer one-to-one
      out.samples.push_back({theta, left, right});
      near_l = left;
      near_r = right;
    }
    out.closes = out.closes && edge;
  }
  std::vector<std::pair<double, double>> in_left, left_right;
  for (const SteeringSample& s : out.samples) {
    in_left.emplace_back(s.input, s.left);
    left_right.emplace_back(s.left, s.right);
    out.low = std::min(out.low, s.input);
    out.high = std::max(out.high, s.input);
  }
  out.input_to_left = fit_quartic(in_left);
  out.linkage = fit_quartic(left_right);
  return out;
}

}  // namespace

SteeringLinkage ackermann_linkage(const SteeringGeometry& g) {
  const Knuckles k = knuckles(g);
  const double tie = ((k.kl + k.arm_l) - (k.kr + k.arm_r)).norm();
  SteeringLinkage out;
  out.samples.push_back({0, 0, 0});
  for (const double direction : {1.0, -1.0}) {
    double near = 0;
    bool edge = false;
    for (int s = 1; s <= kSteps; ++s) {
      const double left = direction * kSteeringRange * s / kSteps;
      const Vector2d pl = k.kl + Eigen::Rotation2Dd(left) * k.arm_l;
      const std::optional<double> right = arm_angle(k.kr, k.arm_r, g.knuckle_length, pl, tie, near);
      if (!right) break;
      edge = std::abs(*right) > kSteeringRange || s == kSteps;
      if (std::abs(*right) > kSteeringRange) break;
      out.samples.push_back({left, left, *right});
      near = *right;
    }
    out.closes = out.closes && edge;
  }
  std::vector<std::pair<double, double>> left_right;
  for (const SteeringSample& s : out.samples) {
    left_right.emplace_back(s.left, s.right);
    out.low = std::min(out.low, s.input);
    out.high = std::max(out.high, s.input);
  }
  out.input_to_left.c[1] = 1;
  out.linkage = fit_quartic(left_right);
  return out;
}

SteeringLinkage bell_crank_linkage(const SteeringGeometry& g) {
  SteeringGeometry lever = g;
  lever.rack_length = 0;
  return column_linkage(lever, true);
}

SteeringLinkage rack_and_pinion_linkage(const SteeringGeometry& g) {
  return column_linkage(g, false);
}

}  // namespace openplx::mjcf
