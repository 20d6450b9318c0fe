// Pellacini 2005's averages, measured by rendering for spire-simplify
// --search: each probe's subtree (simplify/average_sites.h) becomes a
// component of its own, computed where the definition it comes from is, and
// variations of the pipeline's exported color show its value, three scalars
// at a time, with alpha -1 to mark the shader's pixels. The tuner renders
// every camera view under every parameter sample (the domain the search's
// errors are measured over), and the average is the mean over the marked
// pixels: a Monte Carlo estimate over the inputs the scene gives the shader.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "scene/scene_file.h"
#include "search/candidates.h"
#include "search/chain.h"
#include "support/expected.h"
#include "tune/tuner.h"

namespace spire::search {

struct ProbeSetup {
  scene::SceneFile* scene = nullptr;  // its instance is pointed at the probe module
  size_t instance = 0;
  tune::Tuner* tuner = nullptr;
  ModuleCompile compile;
  std::string derived;     // the shader the module derives
  std::string moduleText;  // the current level's module, which the probes are added to
  std::string path;        // where the probe module is written
  Placement placement;     // the current level's
};

// Per probe, its subtree's average (one value per scalar), or nullopt when
// no pixel shows it or it is not finite. Fails when the probe module does
// not compile or the pipeline exports no vec4 color to show probes in.
Expected<std::vector<std::optional<std::vector<double>>>, Failure> measureAverages(
    const ProbeSetup& setup, const std::vector<AverageProbe>& probes);

}  // namespace spire::search
