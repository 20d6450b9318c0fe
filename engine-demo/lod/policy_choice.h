// A level-of-detail policy chosen from measurements (He et al. 2015,
// section 5): at each sampled camera distance, the cheapest level whose
// error is within an error tolerance that grows with distance, with a
// penalty for every switch so that a level worth only a sliver of distance
// is skipped. Levels can only get coarser with distance, because a policy's
// bands go from nearest to farthest.
//
// Pure: spire-tune --lod-policy measures the errors and costs on the device
// and hands them here.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "lod/lod_policy.h"

namespace spire::lod {

struct LevelMeasurements {
  std::vector<float> distances;            // strictly increasing, > 0
  std::vector<std::vector<double>> error;  // [level][distance]: against level 0 (level 0's row is zero)
  std::vector<double> cost;                // [level]: e.g. frame milliseconds with every object at the level
};

struct ChoiceRule {
  double maxError = 0.25;  // per-pixel RMSE tolerated at the farthest distance
  // He'15's tolerance curve, tol(d) = ((d - near) / (far - near))^exponent
  // * maxError: below 1 it tolerates error early, above 1 late.
  double exponent = 0.5;
  // Per switch, in units of level 0's cost (so 0.05 is 5% of a full-quality
  // frame at one distance sample).
  double switchPenalty = 0.05;
};

// The tolerated error at sample `index` of `distances`.
double toleratedError(const std::vector<float>& distances, size_t index, const ChoiceRule& rule);

// A level per distance sample: non-decreasing, each within tolerance (level 0
// always is), minimizing the summed relative cost plus the switch penalties.
// Ties go to the nearer level. `m` must be consistent (checked by the caller):
// at least one level, every error row as long as `distances`.
std::vector<uint32_t> chooseLevels(const LevelMeasurements& m, const ChoiceRule& rule);

// `levels` per sample as a policy on the `measured` levels (nearest first;
// their bands are not used): levels never chosen are left out, and a band ends where the
// next level was chosen, moved out by the hysteresis so that a camera coming
// back does not return to the coarser level nearer than where it was measured
// to be within tolerance.
LodPolicy policyFromChoice(const std::vector<LodLevel>& measured, const std::vector<float>& distances,
                           const std::vector<uint32_t>& levels, float hysteresis, uint32_t transitionFrames);

}  // namespace spire::lod
