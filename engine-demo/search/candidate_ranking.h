// How a search step picks among its measured candidates (He et al. 2015,
// section 4.4.3-4.4.5): keep those whose error is at most K2 times the median
// candidate error, then take the best "bang for buck", the cost saved per
// error added over the current level.
#pragma once

#include <cstddef>
#include <limits>
#include <vector>

namespace spire::search {

struct Measure {
  double error = 0.0;  // RMSE against the original
  double cost = 0.0;   // search::costOf: lower is cheaper
};

struct RankOptions {
  double k2 = 1.0;
  double errorBudget = std::numeric_limits<double>::infinity();
};

// Indices into `candidates`, best first, of those within the budget and K2 x
// the median error of the candidates within the budget (and always the one
// of least error). A candidate that
// saves cost without adding error comes before every trade (more saved
// first); then the trades, by cost saved per error added; then those that
// add no error and save nothing. Ties keep proposal order.
std::vector<size_t> rankCandidates(const Measure& current, const std::vector<Measure>& candidates,
                                   const RankOptions& options);

// Whether `next` may follow `current` in a chain: error never falls and
// cost always falls, so each level is a step along the error-against-cost
// curve, and a rewrite that saves nothing (of code the level no longer
// reads) makes no level.
bool keepsChainMonotone(const Measure& current, const Measure& next);

}  // namespace spire::search
