// Data-layout selection for a chosen variant (paper section 7.4): bake its
// PrebakeTex outputs in 32-bit float, analyse their values
// (renderer/bake_analysis.h), and measure the image error each selected
// format adds against the 32-bit bake, one output at a time and all
// together. The result becomes attributes of the decision file.
#pragma once

#include <string>
#include <vector>

#include "renderer/bake_analysis.h"
#include "renderer/scene_renderer.h"
#include "tune/tune_space.h"

namespace spire::tune {

struct LayoutSelection {
  std::vector<engine::BakeLayout> layouts;
  std::vector<double> addedRmse;  // per layout: RMSE against the RGBA32F bake with only that output in its format
  double totalAddedRmse = 0.0;    // every output in its format
  ShaderLibrary::Attributes attributes;  // [Format], [Encoding] per baked component
};

// `renderer` renders with the selected formats; the 32-bit analysis uses a
// renderer of its own over the same scene. A variant without PrebakeTex
// outputs gives an empty selection.
engine::Expected<LayoutSelection> selectLayouts(engine::SceneRenderer& renderer, size_t instance,
                                                const TunePoint& point, uint32_t bakeSize);

// Markdown table of a selection.
std::string layoutTable(const LayoutSelection& selection);

}  // namespace spire::tune
