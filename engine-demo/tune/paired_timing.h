// Frame times that hold up when measured again. A variant's frames are
// timed alternately with the reference's, and its time is the median of the
// per-pair ratios: a slow moment of the machine slows both frames of a pair
// and cancels. Pairs are added until a distribution-free interval of that
// median is tight enough to order the variant against its neighbours, up to
// a limit; the tuner then re-measures only the variants that could be on the
// front (racing), so a whole run stays short.
#pragma once

#include <cstdint>
#include <vector>

namespace spire::tune {

struct Interval {
  double low = 0.0;
  double high = 0.0;
};

// An interval that holds the median of the distribution `values` were drawn
// from with probability at least 95% (order statistics: the binomial
// distribution of how many values fall below the median). With fewer than
// six values no pair of order statistics reaches 95%, and it is
// [min, max].
Interval medianInterval(std::vector<double> values);

// The fewest values whose medianInterval is a 95% interval.
inline constexpr uint32_t kPairsFor95 = 6;

double medianOf(std::vector<double> values);

struct StoppingRule {
  uint32_t minPairs = 3;
  uint32_t maxPairs = 15;
  // Stop once the interval's width is at most this share of the median.
  double relativeWidth = 0.06;
};

// Whether `ratios` pin their median down by `rule`, or may not grow.
bool enoughPairs(const std::vector<double>& ratios, const StoppingRule& rule);

// The measured ratio of one variant to the reference.
struct TimeRatio {
  double median = 0.0;
  Interval interval;
  uint32_t pairs = 0;
};

TimeRatio summarizeRatios(const std::vector<double>& ratios);

// Whether two variants' times are within the noise: their intervals overlap.
bool withinNoise(const TimeRatio& a, const TimeRatio& b);

}  // namespace spire::tune
