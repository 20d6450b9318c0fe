// Racing (tune/paired_timing.h): after every variant has a time ratio from a
// few pairs of frames, only those that could still be on the front get
// more. A variant is out of the race when another is certainly faster (its
// whole interval lies below) and at most as wrong; every other measured,
// finite variant is a candidate.
#pragma once

#include <cstdint>
#include <set>
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

// What racing knows about who measured what.
struct RaceState {
  std::set<uint64_t> measuredHere;  // rows this process measured (not a worker, not an earlier run)
  std::set<uint64_t> raced;         // rows racing has measured again already
};

// The candidates for the front (frontCandidates) that racing measures again
// next: those not raced yet whose time is not tight or was measured in
// another process. Process-to-process differences (each has its own
// reference frames and placement in memory) are a few percent, more than
// one process's interval says, so every time the front is decided from comes
// from this process. Racing repeats this until it is empty: a variant raced
// slower than first measured can uncover one that it had certainly
// dominated, which must then be measured too, and each round only takes
// variants not raced before, so it ends.
std::vector<size_t> nextToRace(const std::vector<VariantResult>& results, const RaceState& state, double relativeWidth);

}  // namespace spire::tune
