// Numeric core of the const model Math.Functions (../shared/spec/bundles-api.md §1, Appendix A): all static,
// Real in, Real out. Plain functions on double and std::span<const double>; no project deps. The names shadow
// <cmath> ones (sin, sqrt, min, ...), so call them qualified (natives::sin) rather than through
// using-directives. Empty lists: sum -> 0, every other list function -> NaN. NaN inputs propagate.
#pragma once

#include <span>

namespace openplx::natives {

double sin(double x);
double cos(double x);
double tan(double x);
double arcsin(double x);
double arccos(double x);
double arctan(double x);
// DECISION: follows numpy.arctan2(x1, x2) == std::atan2(x, y): the FIRST argument is the ordinate, so
// arctan2(1, 0) == pi/2. The OpenPLX doc only gives the signature arctan2(x, y).
double arctan2(double x, double y);
double sqrt(double x);
double pow(double base, double exponent);

double mean(std::span<const double> values);
// Even count -> mean of the two middle values.
double median(std::span<const double> values);
// n / Σ(1/x_i). A zero element makes it 0 (as scipy.stats.hmean); negative elements are used as they are.
double harmonic_mean(std::span<const double> values);
double min(std::span<const double> values);
double max(std::span<const double> values);
double sum(std::span<const double> values);

// |value - ref| <= 1e-9 · max(1, |ref|): relative to ref for |ref| > 1, absolute 1e-9 below. Equal values
// (also equal infinities) are approx-equal; NaN never is.
bool equals_approx(double value, double ref);

double inf();
double neg_inf();
double rad_to_deg(double rad);
double deg_to_rad(double deg);

}  // namespace openplx::natives
