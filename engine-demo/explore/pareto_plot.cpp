#include "explore/pareto_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace spire::explore {
namespace {

constexpr double kMargin = 0.05;  // of the data's span, so no point sits on a border

// The step of about `count` ticks over `span`: 1, 2 or 5 times a power of
// ten, whichever is nearest span / count by ratio.
double tickStep(double span, size_t count) {
  const double raw = span / static_cast<double>(std::max<size_t>(count, 1));
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  double best = power;
  for (double m : {2.0, 5.0, 10.0}) {
    if (std::abs(std::log(m * power / raw)) < std::abs(std::log(best / raw))) best = m * power;
  }
  return best;
}

PlotAxis axisOver(double low, double high, size_t count) {
  if (!(high > low)) {
    // One value (or one point): a span around it, so it shows mid-axis.
    const double pad = low != 0.0 ? std::abs(low) * 0.1 : 1.0;
    low -= pad;
    high += pad;
  }
  const double span = high - low;
  PlotAxis axis{low - span * kMargin, high + span * kMargin, {}};
  const double step = tickStep(axis.high - axis.low, count);
  // Multiples of the step, so labels do not collect rounding errors.
  for (auto k = static_cast<int64_t>(std::ceil(axis.low / step)); static_cast<double>(k) * step <= axis.high; ++k) {
    axis.ticks.push_back(static_cast<double>(k) * step);
  }
  return axis;
}

}  // namespace

double PlotAxis::fraction(double value) const { return high > low ? (value - low) / (high - low) : 0.5; }

ParetoPlot planPlot(const std::vector<TunedVariant>& variants, size_t ticks) {
  double timeLow = std::numeric_limits<double>::infinity();
  double timeHigh = -timeLow;
  double errorHigh = 0.0;
  for (const TunedVariant& v : variants) {
    timeLow = std::min(timeLow, v.frameMs);
    timeHigh = std::max(timeHigh, v.frameMs);
    errorHigh = std::max(errorHigh, v.rmse);
  }
  if (variants.empty()) timeLow = timeHigh = 0.0;
  ParetoPlot plot{axisOver(timeLow, timeHigh, ticks), axisOver(0.0, errorHigh, ticks)};
  // Errors are never negative: the axis starts at 0.
  plot.error.low = 0.0;
  std::erase_if(plot.error.ticks, [](double t) { return t < 0.0; });
  return plot;
}

std::vector<PlotPoint> placePoints(const ParetoPlot& plot, const std::vector<TunedVariant>& variants, PlotPoint topLeft,
                                   float width, float height) {
  std::vector<PlotPoint> points;
  points.reserve(variants.size());
  for (const TunedVariant& v : variants) {
    points.push_back({topLeft.x + static_cast<float>(plot.time.fraction(v.frameMs)) * width,
                      topLeft.y + static_cast<float>(1.0 - plot.error.fraction(v.rmse)) * height});
  }
  return points;
}

std::optional<size_t> pointUnder(const std::vector<PlotPoint>& points, PlotPoint cursor, float radius) {
  std::optional<size_t> nearest;
  float best = radius * radius;
  for (size_t i = 0; i < points.size(); ++i) {
    const float dx = points[i].x - cursor.x;
    const float dy = points[i].y - cursor.y;
    if (dx * dx + dy * dy <= best) {
      best = dx * dx + dy * dy;
      nearest = i;
    }
  }
  return nearest;
}

}  // namespace spire::explore
