#include "tune/pareto.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace spire::tune {

std::vector<size_t> paretoFront(const std::vector<Measured>& points) {
  std::vector<size_t> order;
  for (size_t i = 0; i < points.size(); ++i) {
    if (points[i].valid && std::isfinite(points[i].error) && std::isfinite(points[i].frameMs)) order.push_back(i);
  }
  // Fastest first; among equally fast, most accurate first, so a sweep that
  // keeps each strictly more accurate variant yields the front.
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    if (points[a].frameMs != points[b].frameMs) return points[a].frameMs < points[b].frameMs;
    if (points[a].error != points[b].error) return points[a].error < points[b].error;
    return a < b;
  });
  std::vector<size_t> front;
  double bestError = std::numeric_limits<double>::infinity();
  for (size_t i : order) {
    if (points[i].error < bestError) {
      front.push_back(i);
      bestError = points[i].error;
    }
  }
  return front;
}

}  // namespace spire::tune
