#include "lod/policy_choice.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace spire::lod {

double toleratedError(const std::vector<float>& distances, size_t index, const ChoiceRule& rule) {
  if (distances.size() < 2) return 0.0;
  const double nearest = distances.front();
  const double span = static_cast<double>(distances.back()) - nearest;
  const double t = std::clamp((static_cast<double>(distances[index]) - nearest) / span, 0.0, 1.0);
  return std::pow(t, rule.exponent) * rule.maxError;
}

std::vector<uint32_t> chooseLevels(const LevelMeasurements& m, const ChoiceRule& rule) {
  const size_t levels = m.cost.size();
  const size_t samples = m.distances.size();
  constexpr double kInfinite = std::numeric_limits<double>::infinity();
  const double unit = m.cost.front() > 0.0 ? m.cost.front() : 1.0;
  // best[s][l]: the least total for samples 0..s ending at level l; from[s][l]
  // the level at s - 1 it came from.
  std::vector<std::vector<double>> best(samples, std::vector<double>(levels, kInfinite));
  std::vector<std::vector<uint32_t>> from(samples, std::vector<uint32_t>(levels, 0));
  for (size_t s = 0; s < samples; ++s) {
    const double tolerated = toleratedError(m.distances, s, rule);
    for (uint32_t l = 0; l < levels; ++l) {
      if (l > 0 && !(m.error[l][s] <= tolerated)) continue;
      const double here = m.cost[l] / unit;
      if (s == 0) {
        best[s][l] = here;
        continue;
      }
      for (uint32_t k = 0; k <= l; ++k) {
        const double total = best[s - 1][k] + here + (k == l ? 0.0 : rule.switchPenalty);
        if (total < best[s][l]) {
          best[s][l] = total;
          from[s][l] = k;
        }
      }
    }
  }
  std::vector<uint32_t> chosen(samples, 0);
  if (samples == 0) return chosen;
  // The cheapest end, the nearer level on a tie; then back along `from`.
  uint32_t level = 0;
  for (uint32_t l = 1; l < levels; ++l) {
    if (best.back()[l] < best.back()[level]) level = l;
  }
  for (size_t s = samples; s-- > 0;) {
    chosen[s] = level;
    level = from[s][level];
  }
  return chosen;
}

LodPolicy policyFromChoice(const std::vector<LodLevel>& measured, const std::vector<float>& distances,
                           const std::vector<uint32_t>& levels, float hysteresis, uint32_t transitionFrames) {
  LodPolicy policy;
  policy.hysteresis = hysteresis;
  policy.transitionFrames = transitionFrames;
  for (size_t s = 0; s < levels.size(); ++s) {
    if (s > 0 && levels[s] == levels[s - 1]) continue;
    if (!policy.levels.empty()) {
      // Coming back, the camera returns to the nearer level at
      // until * (1 - hysteresis): no nearer than this sample.
      const float until = distances[s] / std::max(1.0F - hysteresis, 1e-3F);
      policy.levels.back().until = std::ceil(until * 100.0F) / 100.0F;
    }
    LodLevel level = measured[levels[s]];
    level.until = std::numeric_limits<float>::infinity();
    level.range = {};
    policy.levels.push_back(std::move(level));
  }
  return policy;
}

}  // namespace spire::lod
