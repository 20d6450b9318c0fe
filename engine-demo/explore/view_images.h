// The explorer's derived views of the variant against the reference, made on
// the host from images read back at the fixed camera view: where they
// differ, where the variant is non-finite, and both side by side.
#pragma once

#include <cstdint>
#include <vector>

#include "measure/image_metrics.h"

namespace spire::explore {

// |variant - reference| per pixel (largest RGB channel), on a black-blue-
// red-yellow ramp from 0 to `scale` (above it: yellow). Pixels that are
// non-finite in either image are magenta; uncovered ones (coverage 0) grey.
measure::FloatImage errorHeatMap(const measure::FloatImage& reference, const measure::FloatImage& variant,
                                 const std::vector<uint8_t>& coverage, float scale);

// The variant darkened to grey, with NaN pixels magenta and Inf pixels white,
// so hazards stand out wherever they are.
measure::FloatImage hazardMask(const measure::FloatImage& variant);

// The reference on the left half and the variant on the right, with a white
// line between them.
measure::FloatImage splitImage(const measure::FloatImage& reference, const measure::FloatImage& variant);

}  // namespace spire::explore
