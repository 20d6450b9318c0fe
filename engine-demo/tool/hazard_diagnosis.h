// Diagnosis of a variant that rendered NaN or Inf pixels, for spire-demo and
// spire-tune alike: the same variant compiled with instrumented kernels
// (CompileOptions::instrumentHazards) in a renderer of its own that shares
// the scene's meshes, textures and libraries, rendered once from the view
// and under the parameter sample where the hazard showed, and its records
// read back. The measured renderer never runs an instrumented kernel, so
// timings always come from the normal ones.
#pragma once

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "renderer/hazard_records.h"
#include "renderer/scene_renderer.h"

namespace spire::engine {

// Compiles the variant's programs in the renderer it is given (one per
// instance): the demo compiles a decision file, the tuner its decisions.
using CompileForDiagnosis = std::function<Expected<std::vector<VariantProgram>>(SceneRenderer&)>;

struct HazardSample {
  const scene::CameraView* view = nullptr;
  // Material values that replace the scene's (SceneRenderer::setParameterOverrides).
  std::map<std::string, std::vector<double>> overrides;
};

Expected<std::vector<Hazard>> diagnoseHazards(SceneRenderer& measured, const CompileForDiagnosis& compile,
                                              const HazardSample& sample);

// The hazards as lines: each one's description, instance and definition site.
std::vector<std::string> hazardLines(const std::vector<Hazard>& hazards);

}  // namespace spire::engine
