// --extremes: every material input of the tuned instance gets a range
// without the user naming it, and the samples include per-input corners
// (Pellacini 2005's extremes): each input alone at its minimum and alone at
// its maximum with the others at the scene's values, so that a hazard found
// there is attributable to that one input.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "scene/scene_file.h"
#include "support/expected.h"
#include "tune/parameter_range.h"
#include "tune/tuner.h"

namespace spire::tune {

// The range of a number input whose scene value is `values`, per component
// v: from 0 to max(1, 2|v|) on v's side of 0 ([0, max(1, 2v)] for v >= 0,
// [min(-1, 2v), 0] for v < 0). Zero is always an end (divisions,
// normalizations, logarithms); the other end reaches 1 (a unit-range input
// saturated) or twice the scene's magnitude (exponents, scales).
ParameterRange numberRange(const std::string& component, const std::vector<double>& values);

// A texture input: per channel from min(0, darkest texel) to max(1,
// brightest texel) as solid textures, with the texture's own darkest and
// brightest texels as extra corners ("texture-min", "texture-max").
Expected<ParameterRange, Failure> automaticTextureRange(const scene::MaterialBinding& binding,
                                                        const scene::SceneFile& scene);

// A range for every material input the instance binds (numbers and textures,
// not engine values), in the material's order; `explicitRanges` (--param)
// replace the automatic range of their input.
Expected<std::vector<ParameterRange>, Failure> extremeRanges(const scene::InstanceDesc& instance,
                                                             const scene::SceneFile& scene,
                                                             const std::vector<ParameterRange>& explicitRanges);

// The samples of an --extremes run, with their labels: the scene's own
// values first (time is measured there, and a reference non-finite there
// stops the run), every input at its minimum, every one at its maximum, then
// for each input in order its minimum, its maximum and its extra corners
// alone, then `randomCount` seeded uniform draws of every input.
struct SamplePlan {
  std::vector<ParameterSample> samples;
  std::vector<SampleLabel> labels;  // one per sample
};
SamplePlan extremeSamples(const std::vector<ParameterRange>& ranges, uint32_t randomCount, uint64_t seed);

// How many samples extremeSamples makes: 3 + 2 per input + its extra
// corners + randomCount.
size_t extremeSampleCount(const std::vector<ParameterRange>& ranges, uint32_t randomCount);

}  // namespace spire::tune
