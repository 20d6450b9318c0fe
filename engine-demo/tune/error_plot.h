// The tuner's picture of the trade: every measured variant as a point of
// frame time (x) against RMSE (y), the Pareto front highlighted and joined.
#pragma once

#include <vector>

#include "scene/texture.h"
#include "tune/pareto.h"

namespace spire::tune {

scene::Image plotErrorAgainstTime(const std::vector<Measured>& points, const std::vector<size_t>& front,
                                  uint32_t width = 800, uint32_t height = 560);

}  // namespace spire::tune
