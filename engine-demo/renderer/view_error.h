// The error of a variant's renderings against the reference's, view by view:
// the one place that decides which pixels count (those either image covers,
// so the background dilutes nothing and a surface one variant loses still
// counts) and how views combine (ErrorAccumulator: one RMSE over every
// covered pixel of every view). The demo, the tuner and data-layout selection
// all measure through it, so their numbers agree.
#pragma once

#include <span>

#include "measure/image_metrics.h"
#include "renderer/scene_renderer.h"
#include "scene/expected.h"

namespace spire::engine {

// `test` against `reference` over the pixels either covers. Captures of
// different sizes are an error.
scene::Expected<measure::ImageError> viewError(const Capture& reference, const Capture& test);

// Every view of `test` against the same view of `reference`, combined. Lists
// of different lengths are an error.
scene::Expected<measure::ImageError> viewsError(std::span<const Capture> reference, std::span<const Capture> test);

// Below this share of the reference's covered pixels a variant's image is
// degenerate (a mesh collapsed to a point, a surface gone): it is fast
// because it draws almost nothing, so its time is no speedup, whatever its
// error says.
inline constexpr double kDegenerateCoverage = 0.5;

// The pixels the reference's and a variant's captures cover, summed over
// views.
struct Coverage {
  uint64_t reference = 0;
  uint64_t test = 0;

  void add(const Capture& referenceView, const Capture& testView);
  // The variant's covered pixels over the reference's (1 when the reference
  // covers none).
  [[nodiscard]] double ratio() const;
  [[nodiscard]] bool degenerate() const { return ratio() < kDegenerateCoverage; }
};

}  // namespace spire::engine
