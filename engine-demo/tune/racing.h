// Racing (tune/paired_timing.h): after every variant has a time ratio from a
// few pairs of frames, only those that could still be on the front get
// more. A variant is out of the race when another is certainly faster (its
// whole interval lies below) and at most as wrong; every other measured,
// finite variant is a candidate.
#pragma once

#include <vector>

#include "tune/results_csv.h"

namespace spire::tune {

// Indices into `results` of the candidates for the front: ok, finite error,
// measured themselves (not sharing another's kernels), not certainly
// dominated.
std::vector<size_t> frontCandidates(const std::vector<VariantResult>& results);

// Whether `time` is known well enough to order: its interval is a 95% one
// (kPairsFor95 pairs or more; the range of fewer pairs is not, and two runs
// would then disagree about a front point's order more often than its
// interval says) and within `relativeWidth` of its median.
bool tight(const TimeRatio& time, double relativeWidth);

}  // namespace spire::tune
