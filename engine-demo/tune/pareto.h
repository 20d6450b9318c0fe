// The speed/accuracy Pareto front of measured variants: a variant is on it
// when no other variant is at least as fast and at least as accurate and
// strictly better in one. Variants with non-finite error (NaN or Inf pixels)
// or that failed never qualify.
#pragma once

#include <cstddef>
#include <vector>

namespace spire::tune {

struct Measured {
  double frameMs = 0.0;
  double error = 0.0;  // RMSE against the reference; infinite for hazards
  bool valid = true;
};

// Indices into `points` of the front, fastest first.
std::vector<size_t> paretoFront(const std::vector<Measured>& points);

}  // namespace spire::tune
