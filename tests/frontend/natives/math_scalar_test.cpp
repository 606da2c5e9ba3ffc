// Hand values for Math.Functions. Exact comparisons where the result is exactly representable; 1e-15 where a
// library call (sin, acos, ...) may be off by an ulp.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "frontend/natives/math_scalar.h"

namespace nat = openplx::natives;

namespace {
constexpr double kPi = std::numbers::pi;
constexpr double kUlp = 1e-15;
using V = std::vector<double>;

TEST(MathFunctions, Trigonometry) {
  EXPECT_EQ(nat::sin(0), 0.0);
  EXPECT_NEAR(nat::sin(kPi / 6), 0.5, kUlp);
  EXPECT_NEAR(nat::cos(kPi / 3), 0.5, kUlp);
  EXPECT_EQ(nat::cos(0), 1.0);
  EXPECT_NEAR(nat::tan(kPi / 4), 1.0, kUlp);
  EXPECT_NEAR(nat::arcsin(0.5), kPi / 6, kUlp);
  EXPECT_NEAR(nat::arccos(0.5), kPi / 3, kUlp);
  EXPECT_NEAR(nat::arccos(-1), kPi, kUlp);
  EXPECT_NEAR(nat::arctan(1), kPi / 4, kUlp);
  EXPECT_TRUE(std::isnan(nat::arcsin(2)));
}

TEST(MathFunctions, Arctan2TakesOrdinateFirstLikeNumpy) {
  EXPECT_NEAR(nat::arctan2(1, 0), kPi / 2, kUlp);  // numpy.arctan2(1, 0) = pi/2
  EXPECT_EQ(nat::arctan2(0, 1), 0.0);
  EXPECT_NEAR(nat::arctan2(1, -1), 3 * kPi / 4, kUlp);
  EXPECT_NEAR(nat::arctan2(-1, -1), -3 * kPi / 4, kUlp);
  EXPECT_NEAR(nat::arctan2(0, -1), kPi, kUlp);
}

TEST(MathFunctions, SqrtAndPow) {
  EXPECT_EQ(nat::sqrt(16), 4.0);  // Appendix B case 86
  EXPECT_EQ(nat::sqrt(2.25), 1.5);
  EXPECT_TRUE(std::isnan(nat::sqrt(-1)));
  EXPECT_EQ(nat::pow(2, 10), 1024.0);
  EXPECT_EQ(nat::pow(9, 0.5), 3.0);
  EXPECT_EQ(nat::pow(2, -2), 0.25);
  EXPECT_EQ(nat::pow(5, 0), 1.0);
}

TEST(MathFunctions, MeanMedianHarmonicMean) {
  EXPECT_EQ(nat::mean(V{1, 2, 3, 4}), 2.5);
  EXPECT_EQ(nat::mean(V{-2}), -2.0);
  EXPECT_EQ(nat::median(V{3, 1, 2}), 2.0);
  EXPECT_EQ(nat::median(V{4, 1, 3, 2}), 2.5);  // middle two 2 and 3
  EXPECT_EQ(nat::median(V{7, 7, 1, 100}), 7.0);
  EXPECT_EQ(nat::median(V{-1e308, 1e308}), 0.0);  // no overflow in the midpoint
  EXPECT_EQ(nat::median(V{5}), 5.0);
  EXPECT_NEAR(nat::harmonic_mean(V{1, 2, 4}), 12.0 / 7.0, kUlp);  // 3 / (1 + 1/2 + 1/4)
  EXPECT_EQ(nat::harmonic_mean(V{2, 2}), 2.0);
  EXPECT_EQ(nat::harmonic_mean(V{1, 0, 3}), 0.0);  // a zero element gives 0, as scipy.stats.hmean
  EXPECT_TRUE(std::isnan(nat::mean(V{})));
  EXPECT_TRUE(std::isnan(nat::median(V{})));
  EXPECT_TRUE(std::isnan(nat::harmonic_mean(V{})));
}

TEST(MathFunctions, MinMaxSum) {
  EXPECT_EQ(nat::min(V{3, -1, 2}), -1.0);
  EXPECT_EQ(nat::max(V{3, -1, 2}), 3.0);
  EXPECT_EQ(nat::sum(V{1, 2, 3.5}), 6.5);
  EXPECT_EQ(nat::sum(V{}), 0.0);
  EXPECT_TRUE(std::isnan(nat::min(V{})));
  EXPECT_TRUE(std::isnan(nat::max(V{})));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(std::isnan(nat::min(V{1, nan, 0})));
  EXPECT_TRUE(std::isnan(nat::max(V{nan, 1})));
  EXPECT_TRUE(std::isnan(nat::median(V{1, nan, 2})));
  EXPECT_EQ(nat::max(V{1, nat::inf()}), nat::inf());
}

TEST(MathFunctions, EqualsApprox) {
  EXPECT_TRUE(nat::equals_approx(1.0, 1.0));
  EXPECT_TRUE(nat::equals_approx(1.0 + 5e-10, 1.0));
  EXPECT_FALSE(nat::equals_approx(1.0 + 2e-9, 1.0));
  EXPECT_TRUE(nat::equals_approx(0.0, 1e-9 / 2));  // absolute below |ref| = 1
  EXPECT_FALSE(nat::equals_approx(0.0, 2e-9));
  EXPECT_TRUE(nat::equals_approx(1e6 + 1e-4, 1e6));  // relative: 1e-9 · 1e6 = 1e-3
  EXPECT_FALSE(nat::equals_approx(1e6 + 1e-2, 1e6));
  EXPECT_TRUE(nat::equals_approx(nat::inf(), nat::inf()));
  EXPECT_FALSE(nat::equals_approx(nat::inf(), nat::neg_inf()));
  EXPECT_FALSE(nat::equals_approx(1e300, nat::inf()));
  EXPECT_FALSE(nat::equals_approx(nat::inf(), 1e300));
  EXPECT_FALSE(nat::equals_approx(std::nan(""), std::nan("")));
}

TEST(MathFunctions, InfinitiesAndAngleUnits) {
  EXPECT_TRUE(std::isinf(nat::inf()) && nat::inf() > 0);
  EXPECT_TRUE(std::isinf(nat::neg_inf()) && nat::neg_inf() < 0);
  EXPECT_NEAR(nat::rad_to_deg(kPi), 180.0, 1e-13);
  EXPECT_NEAR(nat::rad_to_deg(kPi / 2), 90.0, 1e-13);
  EXPECT_NEAR(nat::deg_to_rad(180), kPi, kUlp);
  EXPECT_NEAR(nat::deg_to_rad(-45), -kPi / 4, kUlp);
  EXPECT_EQ(nat::rad_to_deg(0), 0.0);
}

}  // namespace
