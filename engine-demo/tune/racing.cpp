#include "tune/racing.h"

#include <cmath>

namespace spire::tune {
namespace {

bool onTheTrade(const VariantResult& r) {
  return r.ok() && !r.sameAs && std::isfinite(r.rmse) && r.nanPixels + r.infPixels == 0 && r.time.pairs > 0;
}

// `a` is certainly faster than `b` and at most as wrong.
bool certainlyDominates(const VariantResult& a, const VariantResult& b) {
  return a.time.interval.high < b.time.interval.low && a.rmse <= b.rmse;
}

}  // namespace

std::vector<size_t> frontCandidates(const std::vector<VariantResult>& results) {
  std::vector<size_t> candidates;
  for (size_t i = 0; i < results.size(); ++i) {
    if (!onTheTrade(results[i])) continue;
    bool dominated = false;
    for (size_t j = 0; j < results.size() && !dominated; ++j) {
      dominated = j != i && onTheTrade(results[j]) && certainlyDominates(results[j], results[i]);
    }
    if (!dominated) candidates.push_back(i);
  }
  return candidates;
}

bool tight(const TimeRatio& time, double relativeWidth) {
  return time.pairs >= kPairsFor95 && time.median > 0.0 &&
         time.interval.high - time.interval.low <= relativeWidth * time.median;
}

std::vector<size_t> nextToRace(const std::vector<VariantResult>& results, const RaceState& state,
                               double relativeWidth) {
  std::vector<size_t> next;
  for (size_t i : frontCandidates(results)) {
    const VariantResult& r = results[i];
    if (state.raced.contains(r.index)) continue;
    if (!state.measuredHere.contains(r.index) || !tight(r.time, relativeWidth)) next.push_back(i);
  }
  return next;
}

}  // namespace spire::tune
