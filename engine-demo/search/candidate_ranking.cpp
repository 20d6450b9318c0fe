#include "search/candidate_ranking.h"

#include <algorithm>
#include <utility>

namespace spire::search {

namespace {

// Below this an error difference is measurement rounding, not error added.
constexpr double kNoError = 1e-12;

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

// The sort key, larger first: the tier (2 free savings, 1 trades, 0 no
// saving without error), then the tier's value.
std::pair<int, double> score(const Measure& current, const Measure& candidate) {
  const double saved = current.cost - candidate.cost;
  const double added = candidate.error - current.error;
  if (added <= kNoError) return saved > 0.0 ? std::pair{2, saved} : std::pair{0, saved};
  return {1, saved / added};
}

}  // namespace

std::vector<size_t> rankCandidates(const Measure& current, const std::vector<Measure>& candidates,
                                   const RankOptions& options) {
  std::vector<size_t> within;
  std::vector<double> errors;
  for (size_t i = 0; i < candidates.size(); ++i) {
    if (candidates[i].error > options.errorBudget) continue;
    within.push_back(i);
    errors.push_back(candidates[i].error);
  }
  if (within.empty()) return {};
  // The least error always passes, so that a strict K2 (the paper's 0.15)
  // narrows the step to its safest candidate rather than ending the chain.
  const double cutoff = std::max(options.k2 * median(errors), *std::min_element(errors.begin(), errors.end()));
  std::vector<size_t> kept;
  for (const size_t i : within) {
    if (candidates[i].error <= cutoff) kept.push_back(i);
  }
  std::stable_sort(kept.begin(), kept.end(),
                   [&](size_t a, size_t b) { return score(current, candidates[a]) > score(current, candidates[b]); });
  return kept;
}

bool keepsChainMonotone(const Measure& current, const Measure& next) {
  return next.error >= current.error && next.cost < current.cost;
}

}  // namespace spire::search
