#include "tool/hazard_diagnosis.h"

#include <fmt/format.h>

namespace spire::engine {

Expected<std::vector<Hazard>> diagnoseHazards(SceneRenderer& measured, const CompileForDiagnosis& compile,
                                              const HazardSample& sample) {
  // Problems with the scene's values were reported when the variant was
  // measured; the diagnosis renders the same scene again.
  DiagnosticList diags;
  SceneRenderer renderer(measured, diags, measured.textureBakeOptions());
  HazardCollector collector;
  renderer.collectHazards(&collector);
  renderer.setParameterOverrides(sample.overrides);
  auto programs = compile(renderer);
  if (!programs) return programs.error();
  auto prepared = renderer.prepare(*programs);
  if (!prepared) return prepared.error();
  const scene::CameraView& view = sample.view ? *sample.view : measured.scene().camera.views.front();
  auto captured = renderer.capture(*prepared, view);
  if (!captured) return captured.error();
  return collector.read();
}

std::vector<std::string> hazardLines(const std::vector<Hazard>& hazards) {
  std::vector<std::string> lines;
  for (const Hazard& h : hazards) {
    lines.push_back(
        fmt::format("{} [{}, first at {}, defined at {}]", describeHazard(h), h.instance, h.where, h.source));
  }
  return lines;
}

}  // namespace spire::engine
