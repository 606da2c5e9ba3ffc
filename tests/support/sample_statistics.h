// The mean and (n - 1) standard deviation of a sample, for the sensor-noise tests.
#pragma once

#include <cmath>
#include <vector>

namespace openplx::testing {

struct SampleStatistics {
  double mean = 0, deviation = 0;
};

inline SampleStatistics sample_statistics(const std::vector<double>& xs) {
  SampleStatistics s;
  if (xs.size() < 2) return s;
  for (double x : xs) s.mean += x;
  s.mean /= static_cast<double>(xs.size());
  double squares = 0;
  for (double x : xs) squares += (x - s.mean) * (x - s.mean);
  s.deviation = std::sqrt(squares / static_cast<double>(xs.size() - 1));
  return s;
}

}  // namespace openplx::testing
