// The Pareto view's scatter plot as numbers, without ImGui: the axes' ranges
// and ticks over the tuned variants (x frame time in ms, y RMSE), where a
// point lands in the plot's rectangle, and which point the cursor is on.
// The panel (pareto_panel.cpp) only turns these into draw-list calls.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "explore/tune_results.h"

namespace spire::explore {

struct PlotAxis {
  double low = 0.0;
  double high = 1.0;
  std::vector<double> ticks;  // round values within [low, high], ascending

  // Where `value` falls between low (0) and high (1).
  double fraction(double value) const;
};

struct ParetoPlot {
  PlotAxis time;   // frame ms
  PlotAxis error;  // RMSE, from 0: a variant's error is read against no error at all
};

// Axes covering every variant with a margin; ticks at 1, 2 or 5 times a power
// of ten, about `ticks` per axis.
ParetoPlot planPlot(const std::vector<TunedVariant>& variants, size_t ticks = 5);

struct PlotPoint {
  float x = 0.0F;
  float y = 0.0F;
};

// Each variant's position in a plot `width` x `height` pixels whose top left
// is (left, top); larger errors are higher up.
std::vector<PlotPoint> placePoints(const ParetoPlot& plot, const std::vector<TunedVariant>& variants, PlotPoint topLeft,
                                   float width, float height);

// The point nearest `cursor` within `radius` pixels, if any.
std::optional<size_t> pointUnder(const std::vector<PlotPoint>& points, PlotPoint cursor, float radius);

}  // namespace spire::explore
