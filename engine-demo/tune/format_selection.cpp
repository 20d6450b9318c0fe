#include "tune/format_selection.h"

#include <fmt/format.h>

#include "renderer/view_error.h"
#include "renderer/world_roles.h"

namespace spire::tune {

namespace {

using engine::Capture;
using engine::Expected;

Expected<std::vector<Capture>> renderViews(engine::SceneRenderer& renderer, size_t instance, const TunePoint& point,
                                           const ShaderLibrary::Attributes& attributes,
                                           const engine::TextureBakeResult** textureBake = nullptr) {
  auto own = renderer.compile(std::nullopt);
  if (!own) return own.error();
  auto program = renderer.compileVariant(instance, point.decisions, nullptr, attributes);
  if (!program) return program.error();
  std::vector<engine::VariantProgram> programs = std::move(own).value();
  programs[instance] = std::move(program).value();
  auto prepared = renderer.prepare(programs);
  if (!prepared) return prepared.error();
  if (textureBake) *textureBake = prepared->textureBakes[instance];
  std::vector<Capture> views;
  for (const scene::CameraView& view : renderer.scene().camera.views) {
    auto capture = renderer.capture(*prepared, view);
    if (!capture) return capture.error();
    views.push_back(std::move(capture).value());
  }
  return views;
}

Expected<double> viewsRmse(const std::vector<Capture>& reference, const std::vector<Capture>& test) {
  auto error = engine::viewsError(reference, test);
  if (!error) return engine::Error(error.error());
  return error->rmse;
}

std::vector<std::pair<std::string, std::string>> attributesOf(const engine::BakeLayout& layout) {
  std::vector<std::pair<std::string, std::string>> attributes{{"Format", layout.format}};
  if (layout.signedEncoding) attributes.emplace_back("Encoding", "signed");
  return attributes;
}

}  // namespace

Expected<LayoutSelection> selectLayouts(engine::SceneRenderer& renderer, size_t instance, const TunePoint& point,
                                        uint32_t bakeSize) {
  auto program = renderer.compileVariant(instance, point.decisions);
  if (!program) return program.error();
  const engine::KernelProgram* kernel = program->kernelWithRole(engine::WorldRole::TextureBake);
  LayoutSelection selection;
  // Nothing baked into a texture, no layout to choose: known before any bake.
  if (!kernel) return selection;
  DiagnosticList analysisDiags;
  engine::TextureBakeOptions analysisOptions;
  analysisOptions.defaultSize = bakeSize;
  analysisOptions.forceFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
  engine::SceneRenderer analysis(renderer, analysisDiags, analysisOptions);
  const engine::TextureBakeResult* baked = nullptr;
  auto reference = renderViews(analysis, instance, point, {}, &baked);
  if (!reference) return reference.error();
  if (!baked) return selection;
  auto layouts = engine::selectBakeLayouts(*kernel, *baked);
  if (!layouts) return layouts.error();
  selection.layouts = std::move(layouts).value();
  for (const engine::BakeLayout& layout : selection.layouts) {
    selection.attributes[layout.component] = attributesOf(layout);
    ShaderLibrary::Attributes one{{layout.component, attributesOf(layout)}};
    // The other outputs stay in 32-bit float, so only this format's error shows.
    for (const engine::BakeLayout& other : selection.layouts) {
      if (other.component != layout.component)
        one[other.component] = {{"Format", other.channels == 1 ? "R32F" : "RGBA32F"}};
    }
    auto views = renderViews(renderer, instance, point, one);
    if (!views) return views.error();
    auto rmse = viewsRmse(*reference, *views);
    if (!rmse) return rmse.error();
    selection.addedRmse.push_back(*rmse);
  }
  auto all = renderViews(renderer, instance, point, selection.attributes);
  if (!all) return all.error();
  auto total = viewsRmse(*reference, *all);
  if (!total) return total.error();
  selection.totalAddedRmse = *total;
  return selection;
}

std::string layoutTable(const LayoutSelection& selection) {
  std::string table =
      "| component | channels | range | unit vectors | format | RMSE added vs RGBA32F |\n|---|---|---|---|---|---|\n";
  for (size_t i = 0; i < selection.layouts.size(); ++i) {
    const engine::BakeLayout& l = selection.layouts[i];
    std::string range;
    for (uint32_t c = 0; c < l.channels; ++c) {
      range += fmt::format("{}[{:.3g}, {:.3g}]", range.empty() ? "" : " ", l.minimum[c], l.maximum[c]);
    }
    table += fmt::format("| {} | {} | {} | {} | {}{} | {:.3g} |\n", l.component, l.channels, range,
                         l.unitVectors ? "yes" : "no", l.format, l.signedEncoding ? " (signed remap)" : "",
                         selection.addedRmse[i]);
  }
  table += fmt::format("| all together | | | | | {:.3g} |\n", selection.totalAddedRmse);
  return table;
}

}  // namespace spire::tune
