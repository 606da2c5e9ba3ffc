// MJCF and manifest numbers: write_number's fast paths give exactly std::to_chars's shortest round trip.
#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <random>
#include <string>

#include "mjcf_emitter/xml.h"

namespace {

namespace mj = openplx::mjcf;

std::string written(double value) {
  char buffer[mj::kNumberChars];
  return std::string(buffer, mj::write_number(buffer, value));
}

std::string shortest(double value) {
  char buffer[64];
  return std::string(buffer, std::to_chars(buffer, buffer + sizeof(buffer), value).ptr);
}

void expect_shortest(double value) {
  if (value == 0) return;  // -0 is written 0, below
  ASSERT_EQ(written(value), shortest(value)) << std::hexfloat << value;
  ASSERT_EQ(written(-value), shortest(-value)) << std::hexfloat << -value;
}

TEST(Number, DecimalsAreTheShortestRoundTrip) {
  for (int decimals = 1; decimals <= 7; ++decimals) {
    const double scale = std::pow(10.0, decimals);
    for (long k = 1; k <= 30000; ++k) expect_shortest(static_cast<double>(k) / scale);
    // Across the whole range of the fast path and past it, with neighbours that are no short decimal.
    for (long k = 30001; k < 2e4 * scale; k += static_cast<long>(scale) + 7) {  // some 20,000 of them
      const double value = static_cast<double>(k) / scale;
      expect_shortest(value);
      expect_shortest(std::nextafter(value, 0.0));
      expect_shortest(std::nextafter(value, 1e9));
    }
  }
}

TEST(Number, OtherNumbersAreTheShortestRoundTrip) {
  for (double value : {1e-3, 9.99e-4, 0.00099999999999999, 1e4, 9999.999999, 9999.9999999, 0.1 + 0.2, 1.0 / 3,
                       0.7071067811865476, 1e-7, 123456.5, 1e300, 5e-324, 0.5, 2.5e-3, 1234.000001}) {
    expect_shortest(value);
    expect_shortest(std::nextafter(value, 0.0));
    expect_shortest(std::nextafter(value, 1e308));
  }
  std::mt19937_64 random(20261125);
  std::uniform_real_distribution<double> range(1e-4, 2e4);
  std::uniform_int_distribution<int> decimals(0, 8);
  for (int k = 0; k < 200000; ++k) {
    const double value = range(random);
    expect_shortest(value);
    const double scale = std::pow(10.0, decimals(random));
    expect_shortest(std::round(value * scale) / scale);  // a decimal of a few places
  }
  EXPECT_EQ(written(-0.0), "0");  // the one departure: MuJoCo reads -0 as 0
  EXPECT_EQ(written(0.5), "0.5");
  EXPECT_EQ(written(-12.25), "-12.25");
  EXPECT_EQ(written(0.001), "0.001");
  EXPECT_EQ(written(0.0001), "1e-04");
}

}  // namespace
