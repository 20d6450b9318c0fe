#include "tune/pareto.h"

#include <algorithm>
#include <cmath>

namespace spire::tune {

namespace {

bool qualifies(const Measured& m) { return m.valid && std::isfinite(m.error) && std::isfinite(m.frameMs); }
double low(const Measured& m) { return m.highMs > 0.0 ? std::min(m.lowMs, m.frameMs) : m.frameMs; }
double high(const Measured& m) { return m.highMs > 0.0 ? std::max(m.highMs, m.frameMs) : m.frameMs; }

// Whether `q` leaves `p` off the front.
bool outdoes(const Measured& q, const Measured& p) {
  if (q.error < p.error - kSameError) return low(q) <= high(p);
  if (q.error > p.error + kSameError) return false;
  // As accurate: only measurably faster counts, so tied variants both stay.
  return high(q) < low(p);
}

}  // namespace

std::vector<size_t> paretoFront(const std::vector<Measured>& points) {
  std::vector<size_t> front;
  for (size_t p = 0; p < points.size(); ++p) {
    if (!qualifies(points[p])) continue;
    bool kept = true;
    for (size_t q = 0; q < points.size() && kept; ++q) {
      kept = q == p || !qualifies(points[q]) || !outdoes(points[q], points[p]);
    }
    if (kept) front.push_back(p);
  }
  std::sort(front.begin(), front.end(), [&](size_t a, size_t b) {
    if (points[a].frameMs != points[b].frameMs) return points[a].frameMs < points[b].frameMs;
    return a < b;
  });
  return front;
}

}  // namespace spire::tune
