#include "frontend/natives/math_scalar.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <vector>

namespace openplx::natives {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

bool any_nan(std::span<const double> values) {
  return std::any_of(values.begin(), values.end(), [](double v) { return std::isnan(v); });
}

}  // namespace

double sin(double x) {
  return std::sin(x);
}
double cos(double x) {
  return std::cos(x);
}
double tan(double x) {
  return std::tan(x);
}
double arcsin(double x) {
  return std::asin(x);
}
double arccos(double x) {
  return std::acos(x);
}
double arctan(double x) {
  return std::atan(x);
}
double arctan2(double x, double y) {
  return std::atan2(x, y);
}
double sqrt(double x) {
  return std::sqrt(x);
}
double pow(double base, double exponent) {
  return std::pow(base, exponent);
}

double mean(std::span<const double> values) {
  if (values.empty()) return kNaN;
  return sum(values) / static_cast<double>(values.size());
}

double median(std::span<const double> values) {
  // nth_element needs a strict weak order, which NaN breaks.
  if (values.empty() || any_nan(values)) return kNaN;
  std::vector<double> v(values.begin(), values.end());
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  if (v.size() % 2 == 1) return *mid;
  const double below = *std::max_element(v.begin(), mid);
  return std::midpoint(below, *mid);  // no overflow for huge values of either sign
}

double harmonic_mean(std::span<const double> values) {
  if (values.empty()) return kNaN;
  double reciprocal_sum = 0.0;
  for (double v : values) reciprocal_sum += 1.0 / v;
  return static_cast<double>(values.size()) / reciprocal_sum;
}

double min(std::span<const double> values) {
  if (values.empty() || any_nan(values)) return kNaN;
  return *std::min_element(values.begin(), values.end());
}

double max(std::span<const double> values) {
  if (values.empty() || any_nan(values)) return kNaN;
  return *std::max_element(values.begin(), values.end());
}

double sum(std::span<const double> values) {
  return std::accumulate(values.begin(), values.end(), 0.0);
}

bool equals_approx(double value, double ref) {
  if (value == ref) return true;
  // Unequal infinities would pass the test below (inf <= 1e-9·inf).
  if (std::isinf(value) || std::isinf(ref)) return false;
  return std::abs(value - ref) <= 1e-9 * std::max(1.0, std::abs(ref));
}

double inf() {
  return std::numeric_limits<double>::infinity();
}
double neg_inf() {
  return -std::numeric_limits<double>::infinity();
}
double rad_to_deg(double rad) {
  return rad * 180.0 / std::numbers::pi;
}
double deg_to_rad(double deg) {
  return deg * std::numbers::pi / 180.0;
}

}  // namespace openplx::natives
