#pragma once
// The median of a benchmark's repeats: the middle value, or the mean of the two middle ones; NaN
// when any value is (a figure a run does not have).
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace tongue::benchmarks {

inline double median(std::vector<double> v) {
  if (v.empty() || std::any_of(v.begin(), v.end(), [](double x) { return std::isnan(x); }))
    return std::numeric_limits<double>::quiet_NaN();
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace tongue::benchmarks
