// Kinematic steering linkages: closed-form loop closure, the reachable input range, polynomial fits
// (geometry in steering_linkage.h).
#include "contract/steering_linkage.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace openplx::mjcf {
namespace {

using Eigen::Vector2d;

double angle_of(const Vector2d& v) {
  return std::atan2(v.y(), v.x());
}

// One loop: an arm `arm` (at rest) turning about kingpin `k`, whose end must lie `tie` from `anchor`. The arm
// turned by δ has (R(δ) arm)·v = (|arm|² + |v|² - tie²) / 2 with v = anchor - k, so δ = angle(v) -
// angle(arm) + side·acos(...): `side` (±1) is the side of v the arm lies on straight ahead, which it keeps
// until arm and tie rod line up (a dead point, where the two circles touch and the loop stops closing).
struct Loop {
  Vector2d k, arm;
  double tie = 0;
  double side = 1;

  std::optional<double> angle(const Vector2d& anchor) const {
    const Vector2d v = anchor - k;
    const double b = arm.norm(), d = v.norm();
    if (!(d > 0)) return std::nullopt;
    const double c = (b * b + d * d - tie * tie) / (2 * b * d);
    if (!(std::abs(c) <= 1)) return std::nullopt;
    return std::remainder(angle_of(v) - angle_of(arm) + side * std::acos(c), 2 * M_PI);
  }
  // The side straight ahead (0: the arm along the line to its anchor, a dead point at rest).
  double side_at(const Vector2d& anchor) const {
    const double a = std::remainder(angle_of(arm) - angle_of(anchor - k), 2 * M_PI);
    return a > 0 ? 1.0 : a < 0 ? -1.0 : 0.0;
  }
};

// The whole mechanism: both loops and where the tie rods' inner ends are for an input.
struct Mechanism {
  SteeringGeometry g;
  Loop left, right;
  double inner_x = 0, half_rack = 0, arm = 0;  // the inner ends at rest (x, ±y) and the steering arm s

  // Inner ends (left, right) for input θ; nullopt past the rack's reach (tan at 90°).
  std::optional<std::pair<Vector2d, Vector2d>> inner(double theta) const {
    const double psi = g.gear * theta;
    if (g.mechanism == SteeringMechanism::BellCrank) {
      const Vector2d end(inner_x + arm - arm * std::cos(psi), -arm * std::sin(psi));
      return std::make_pair(end, end);
    }
    if (!(std::abs(psi) < M_PI / 2)) return std::nullopt;
    const double shift = -arm * std::tan(psi);
    return std::make_pair(Vector2d(inner_x, half_rack + shift), Vector2d(inner_x, -half_rack + shift));
  }

  std::optional<std::pair<double, double>> angles(double input) const {
    if (g.mechanism == SteeringMechanism::Ackermann) {
      const Vector2d end_l = left.k + Eigen::Rotation2Dd(input) * left.arm;
      const std::optional<double> r = right.angle(end_l);
      if (!r) return std::nullopt;
      return std::make_pair(input, *r);
    }
    const auto ends = inner(input);
    if (!ends) return std::nullopt;
    const std::optional<double> l = left.angle(ends->first), r = right.angle(ends->second);
    if (!l || !r) return std::nullopt;
    return std::make_pair(*l, *r);
  }
};

// Builds the mechanism, or says why it cannot be built (problem and the attributes it is about).
struct Built {
  Mechanism m;
  std::string problem;
  std::vector<std::string> attributes;
};

Built build(const SteeringGeometry& g) {
  Built out;
  Mechanism& m = out.m;
  m.g = g;
  const double w = g.track, l = g.knuckle_length, phi = g.knuckle_angle;
  auto fail = [&](std::string why, std::vector<std::string> attributes) {
    out.problem = std::move(why);
    out.attributes = std::move(attributes);
    return out;
  };
  if (!(w > 0)) return fail("has its two kingpins (the suspensions' chassis connectors) at one place", {});
  if (!(l > 0) || !std::isfinite(l)) return fail("needs a positive knuckle_length", {"knuckle_length"});
  const double b = l * w;
  m.left.k = Vector2d(0, w / 2);
  m.right.k = Vector2d(0, -w / 2);
  m.left.arm = b * Vector2d(std::sin(phi), std::cos(phi));
  m.right.arm = b * Vector2d(std::sin(phi), -std::cos(phi));
  const Vector2d end_l = m.left.k + m.left.arm, end_r = m.right.k + m.right.arm;
  const bool column = g.mechanism != SteeringMechanism::Ackermann;
  const double rack = g.mechanism == SteeringMechanism::RackAndPinion ? g.rack_length : 0.0;
  // The inward room between the arm ends, less the rack: what the tie rods span across the axle line.
  const double span = 1 + 2 * l * std::cos(phi) - rack;
  if (!(span > 0)) {
    std::vector<std::string> attributes = {"knuckle_length", "knuckle_angle"};
    if (rack != 0) attributes.push_back("rack_length");
    return fail(rack != 0 ? "has a rack reaching past its knuckle arms' ends (1 + 2 knuckle_length cos "
                            "knuckle_angle - rack_length is " +
                                std::to_string(span) + ", not positive)"
                          : "has knuckle arms that reach across each other (1 + 2 knuckle_length cos "
                            "knuckle_angle is " +
                                std::to_string(span) + ", not positive)",
                attributes);
  }
  if (!column) {
    m.right.tie = (end_l - end_r).norm();
  } else {
    if (!(std::cos(g.tie_rod_angle) > 1e-6))
      return fail("has tie rods along the vehicle (initial_angle_right_tie_rod must be within ±90°)",
                  {"initial_angle_right_tie_rod"});
    if (!(g.column_distance != 0 && std::isfinite(g.column_distance)) ||
        !(g.gear != 0 && std::isfinite(g.gear)))
      return fail("does not turn the wheels (steering_column_distance or gear is zero)",
                  {"steering_column_distance", "gear"});
    const double tie = span * w / (2 * std::cos(g.tie_rod_angle));
    m.left.tie = m.right.tie = tie;
    m.inner_x = end_l.x() + tie * std::sin(g.tie_rod_angle);
    m.half_rack = rack * w / 2;
    m.arm = g.column_distance * b;
  }
  const auto rest = m.inner(0);
  const Vector2d anchor_l = column ? rest->first : end_r, anchor_r = column ? rest->second : end_l;
  m.left.side = m.left.side_at(anchor_l);
  m.right.side = m.right.side_at(anchor_r);
  if ((column && m.left.side == 0) || m.right.side == 0)
    return fail("has a knuckle arm in line with its tie rod straight ahead (a dead point: it cannot steer)",
                {"knuckle_angle", "initial_angle_right_tie_rod"});
  return out;
}

// A least-squares fit of y = c1 x + ... + cn x^n (through zero) over the samples, in x scaled to [-1, 1],
// then weighted towards the largest errors (Lawson's iteration) to bring the maximum error down.
PolynomialFit fit(const std::vector<std::pair<double, double>>& xy, int degree) {
  double scale = 0;
  for (const auto& [x, y] : xy) scale = std::max(scale, std::abs(x));
  PolynomialFit out;
  out.c.assign(static_cast<size_t>(degree) + 1, 0.0);
  if (!(scale > 0)) return out;
  const int n = static_cast<int>(xy.size());
  Eigen::MatrixXd a(n, degree);
  Eigen::VectorXd b(n), weight = Eigen::VectorXd::Ones(n);
  for (int s = 0; s < n; ++s) {
    const double u = xy[static_cast<size_t>(s)].first / scale;
    double power = 1;
    for (int p = 0; p < degree; ++p) a(s, p) = power *= u;
    b(s) = xy[static_cast<size_t>(s)].second;
  }
  Eigen::VectorXd best;
  double best_error = INFINITY;
  for (int iteration = 0; iteration < 40; ++iteration) {
    const Eigen::VectorXd root = weight.cwiseSqrt();
    const Eigen::VectorXd c = (root.asDiagonal() * a).colPivHouseholderQr().solve(root.asDiagonal() * b);
    const Eigen::VectorXd residual = (a * c - b).cwiseAbs();
    if (residual.maxCoeff() < best_error) {
      best_error = residual.maxCoeff();
      best = c;
    }
    weight = weight.cwiseProduct(residual.array().max(1e-300).matrix());
    weight /= weight.sum();
  }
  for (int p = 0; p < degree; ++p) out.c[static_cast<size_t>(p) + 1] = best(p) / std::pow(scale, p + 1);
  return out;
}

double max_error(const PolynomialFit& f, const std::vector<std::pair<double, double>>& xy) {
  double e = 0;
  for (const auto& [x, y] : xy) e = std::max(e, std::abs(evaluate_polynomial(f.c, x) - y));
  return e;
}

bool monotonic(const PolynomialFit& f, double low, double high) {
  constexpr int kChecks = 4000;
  double previous = evaluate_polynomial(f.c, low);
  const double rising = evaluate_polynomial(f.c, high) > previous ? 1.0 : -1.0;
  for (int k = 1; k <= kChecks; ++k) {
    const double y = evaluate_polynomial(f.c, low + (high - low) * k / kChecks);
    if ((y - previous) * rising <= 0) return false;
    previous = y;
  }
  return true;
}

// The samples within `fraction` of the reach each way, as (x, y) pairs by `pick`.
template <typename Pick>
std::vector<std::pair<double, double>> part_of(const SteeringLinkage& l, double fraction, Pick pick) {
  std::vector<std::pair<double, double>> part;
  for (const SteeringSample& s : l.samples) {
    if (s.input >= fraction * l.low && s.input <= fraction * l.high) part.push_back(pick(s));
  }
  return part;
}

struct PartFit {
  PolynomialFit f;      // max_error: over its part
  double fraction = 0;  // of the reach each way (0: none fits)
};

// The widest part of the reach about straight ahead (down to 5 % of it) over which a polynomial of `degree`
// fits the samples (by `pick`) within `tolerance` and is `acceptable`: scanned down from the whole reach in
// steps of 5 %, then bisected above the first that fits (a high degree fitted on a small part may wander
// off beyond it, so a smaller part is not always better).
template <typename Pick, typename Acceptable>
PartFit fit_part(const SteeringLinkage& l, Pick pick, int degree, double tolerance, Acceptable acceptable) {
  auto within = [&](double fraction) {
    const std::vector<std::pair<double, double>> part = part_of(l, fraction, pick);
    PolynomialFit f = fit(part, degree);
    f.max_error = max_error(f, part);
    return f;
  };
  auto fits = [&](const PolynomialFit& f) { return f.max_error <= tolerance && acceptable(f); };
  for (int step = 20; step >= 1; --step) {
    const double inside = 0.05 * step;
    PolynomialFit f = within(inside);
    if (!fits(f)) continue;
    if (step == 20) return {f, 1.0};
    double low = inside, high = inside + 0.05;
    for (int k = 0; k < 12; ++k) {
      const double mid = (low + high) / 2;
      PolynomialFit g = within(mid);
      if (fits(g)) {
        low = mid;
        f = g;
      } else {
        high = mid;
      }
    }
    return {f, low};
  }
  return {within(0.05), 0};
}

// How far the input reaches in `direction` (±1): both loops close and both wheels keep turning the way they
// start, the left one at least kLeastRate of its rate straight ahead (where a wheel stops turning with the
// input, at a lever's or rack's own dead point, the last stretch of input hardly moves it, and the output,
// read back from the left wheel's angle, could not tell those inputs apart). Marches in steps of about
// 2 mrad of the left wheel, then bisects the last step.
constexpr double kLeastRate = 0.05;
double reach(const Mechanism& m, double direction, double slope) {
  const double step = 2e-3 / std::abs(slope);
  const double eps = 1e-9 / std::abs(slope);
  auto good = [&](double theta) {
    const auto at = m.angles(theta), before = m.angles(theta - direction * eps);
    if (!at || !before) return false;
    const double turn = direction * (slope > 0 ? 1.0 : -1.0);
    return (at->first - before->first) * turn > kLeastRate * std::abs(slope) * eps &&
           (at->second - before->second) * turn > 0;
  };
  double inside = 0, outside = 0;
  bool stopped = false;
  for (int k = 1; k <= 20000; ++k) {  // 40 rad of wheel: every linkage has stopped well before
    if (!good(direction * step * k)) {
      inside = direction * step * (k - 1);
      outside = direction * step * k;
      stopped = true;
      break;
    }
  }
  if (!stopped) return direction * step * 20000;
  for (int k = 0; k < 80; ++k) {
    const double mid = (inside + outside) / 2;
    (good(mid) ? inside : outside) = mid;
  }
  return inside;
}

}  // namespace

double steering_input_for(const std::vector<double>& c, double left, double low, double high) {
  if (c.empty()) return left;  // the input is the left wheel's angle itself
  if (c.size() < 2) return 0;
  const double at_low = evaluate_polynomial(c, low), at_high = evaluate_polynomial(c, high);
  const double rising = at_high > at_low ? 1.0 : -1.0;
  auto slope = [&](double x) {
    double d = 0;
    for (size_t p = c.size() - 1; p >= 1; --p) d = d * x + static_cast<double>(p) * c[p];
    return d;
  };
  // Past an end (the equality's residual at a dead point): Newton from that end, where p is smooth.
  const bool past_high = (left - at_high) * rising > 0, past_low = (at_low - left) * rising > 0;
  if (past_high || past_low) {
    double x = past_high ? high : low;
    for (int k = 0; k < 8; ++k) {
      const double d = slope(x);
      if (d == 0 || !std::isfinite(d)) break;
      x -= (evaluate_polynomial(c, x) - left) / d;
    }
    return x;
  }
  // Inside: Newton kept within a bracket that bisection shrinks (p is monotonic over [low, high]).
  double lo = low, hi = high, x = c[1] != 0 ? std::clamp(left / c[1], low, high) : (low + high) / 2;
  for (int k = 0; k < 100; ++k) {
    const double f = evaluate_polynomial(c, x) - left;
    if (f == 0) return x;
    ((f * rising < 0) ? lo : hi) = x;
    const double d = slope(x);
    double next = d != 0 && std::isfinite(d) ? x - f / d : (lo + hi) / 2;
    if (!(next > lo && next < hi)) next = (lo + hi) / 2;
    if (std::abs(next - x) <= 1e-15 * std::max(1.0, std::abs(x))) return next;
    x = next;
  }
  return x;
}

double evaluate_polynomial(const std::vector<double>& c, double x) {
  double y = 0;
  for (size_t p = c.size(); p-- > 0;) y = y * x + c[p];  // Horner
  return y;
}

std::optional<std::pair<double, double>> steering_angles(const SteeringGeometry& g, double input) {
  const Built built = build(g);
  if (!built.problem.empty()) return std::nullopt;
  return built.m.angles(input);
}

SteeringLinkage steering_linkage(const SteeringGeometry& g) {
  SteeringLinkage out;
  const Built built = build(g);
  if (!built.problem.empty()) {
    out.problem = built.problem;
    out.attributes = built.attributes;
    return out;
  }
  const Mechanism& m = built.m;
  constexpr double kProbe = 1e-7;
  const auto probe = m.angles(kProbe);
  const double slope = probe ? probe->first / kProbe : 0;
  if (!probe || !std::isfinite(slope) || std::abs(slope) < 1e-9) {
    out.problem = "cannot turn its wheels from straight ahead";
    out.attributes = {"knuckle_angle", "knuckle_length"};
    return out;
  }
  out.low = reach(m, -1, slope);
  out.high = reach(m, 1, slope);
  // Samples clustered towards the ends (Chebyshev points), where a dead point bends the curves most.
  constexpr int kSamples = 600;
  for (int k = 0; k <= kSamples; ++k) {
    const double t = 0.5 - 0.5 * std::cos(M_PI * k / kSamples);
    const double input = out.low + (out.high - out.low) * t;
    if (const auto a = m.angles(input)) out.samples.push_back({input, a->first, a->second});
  }
  std::vector<std::pair<double, double>> in_left, left_right;
  for (const SteeringSample& s : out.samples) {
    in_left.emplace_back(s.input, s.left);
    left_right.emplace_back(s.left, s.right);
  }
  // Near a dead point a wheel's angle bends like a square root, which no polynomial follows: p and q are
  // each fitted over the widest part of the reach about straight ahead (the same fraction of it each way)
  // where they stay within a tolerance, and extrapolate beyond; their errors over the whole reach are what
  // they report as max_error.
  double fraction = 1;  // p's part of the reach
  if (g.mechanism == SteeringMechanism::Ackermann) {
    out.input_to_left.c = {0.0, 1.0};
  } else {
    // The runtime evaluates p (any degree): the lowest degree up to 12 within 1e-7 rad over the whole
    // reach, else degree 12 within 1e-4 over the widest part. It must rise (or fall) with the input over
    // the whole reach, for the output inverts it there (steering_input_for).
    auto rising = [&](const PolynomialFit& f) { return monotonic(f, out.low, out.high); };
    PolynomialFit best;
    best.max_error = INFINITY;
    for (int degree = 4; degree <= 12 && best.max_error > 1e-7; ++degree) {
      PolynomialFit f = fit(in_left, degree);
      f.max_error = max_error(f, in_left);
      if (f.max_error < best.max_error && rising(f)) best = f;
    }
    if (best.max_error > 1e-4) {
      const PartFit part = fit_part(
          out, [](const SteeringSample& s) { return std::make_pair(s.input, s.left); }, 12, 1e-4, rising);
      if (part.fraction > 0) {
        best = part.f;
        fraction = part.fraction;
      }
    }
    if (best.c.empty()) best = fit(in_left, 1);  // a line rises throughout
    out.input_to_left = best;
  }
  out.input_fitted_low = fraction * out.low;
  out.input_fitted_high = fraction * out.high;
  out.input_to_left.max_error = max_error(out.input_to_left, in_left);
  out.input_to_left_fitted = max_error(out.input_to_left, part_of(out, fraction, [](const SteeringSample& s) {
                                         return std::make_pair(s.input, s.left);
                                       }));
  // q: a quartic (MuJoCo's), within 2e-3 rad over its part.
  const PartFit q_part = fit_part(
      out, [](const SteeringSample& s) { return std::make_pair(s.left, s.right); }, 4, 2e-3,
      [](const PolynomialFit&) { return true; });
  const PolynomialFit q = q_part.f;
  out.linkage_fitted = q.max_error;
  out.fitted_low = q_part.fraction * out.low;
  out.fitted_high = q_part.fraction * out.high;
  out.linkage = q;
  out.linkage.max_error = max_error(out.linkage, left_right);
  return out;
}

}  // namespace openplx::mjcf
