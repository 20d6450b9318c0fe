#include "tune/paired_timing.h"

#include <algorithm>
#include <cmath>

namespace spire::tune {
namespace {

// P(X < k) for X ~ Binomial(n, 1/2).
double binomialBelow(size_t n, size_t k) {
  double sum = 0.0;
  double term = std::pow(0.5, static_cast<double>(n));  // P(X = 0)
  for (size_t i = 0; i < k && i <= n; ++i) {
    sum += term;
    term *= static_cast<double>(n - i) / static_cast<double>(i + 1);
  }
  return sum;
}

}  // namespace

double medianOf(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

Interval medianInterval(std::vector<double> values) {
  if (values.empty()) return {};
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  // The largest j with P(X < j) <= 2.5%: then [x_(j), x_(n+1-j)] (1-based)
  // misses the median with probability at most 5%.
  size_t j = 0;
  while (j + 1 <= n / 2 && binomialBelow(n, j + 1) <= 0.025) ++j;
  if (j == 0) return {values.front(), values.back()};
  return {values[j - 1], values[n - j]};
}

bool enoughPairs(const std::vector<double>& ratios, const StoppingRule& rule) {
  if (ratios.size() >= rule.maxPairs) return true;
  if (ratios.size() < rule.minPairs) return false;
  const Interval interval = medianInterval(ratios);
  const double median = medianOf(ratios);
  return median > 0.0 && (interval.high - interval.low) <= rule.relativeWidth * median;
}

TimeRatio summarizeRatios(const std::vector<double>& ratios) {
  return {medianOf(ratios), medianInterval(ratios), static_cast<uint32_t>(ratios.size())};
}

bool withinNoise(const TimeRatio& a, const TimeRatio& b) {
  return a.interval.low <= b.interval.high && b.interval.low <= a.interval.high;
}

}  // namespace spire::tune
