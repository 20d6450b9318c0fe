// The speed/accuracy Pareto front of measured variants, as far as the
// measurements can tell: a variant is on it unless another is
//   - more accurate and not measurably slower (its time interval does not
//     lie wholly above this one's), or
//   - as accurate (within kSameError) and measurably faster (its interval
//     wholly below), so that tied variants both stay.
// A variant that is faster than a more accurate one only within the noise
// of the two measurements offers more error for no speed that holds up when
// measured again, so it is left off: the front is what a second run finds
// again, not which of two tied variants happened to measure faster. Without
// intervals (zero width) this is the classic front. Variants with
// non-finite error (NaN or Inf pixels) or that failed never qualify.
#pragma once

#include <cstddef>
#include <vector>

namespace spire::tune {

struct Measured {
  double frameMs = 0.0;
  double error = 0.0;  // RMSE against the reference; infinite for hazards
  bool valid = true;
  // The frame time's interval (paired_timing.h); both 0: frameMs alone.
  double lowMs = 0.0;
  double highMs = 0.0;
};

// RMSEs closer than this are the same accuracy: a fortieth of one 8-bit
// step, a difference no display shows, which two variants that make the
// same image up to rounding differ by.
inline constexpr double kSameError = 1e-4;

// Indices into `points` of the front, fastest first.
std::vector<size_t> paretoFront(const std::vector<Measured>& points);

}  // namespace spire::tune
