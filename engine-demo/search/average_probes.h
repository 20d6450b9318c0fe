// Averages over the scene, measured by rendering for spire-simplify
// --search (Pellacini 2005): a value is shown in the pipeline's exported
// color, three scalars at a time, with alpha -1 to mark the probed shader's
// pixels; the tuner renders every camera view under every parameter sample
// (the domain the search's errors are measured over), and the average is
// the mean over the marked pixels: a Monte Carlo estimate over the inputs
// the scene gives the shader. The values are the subtrees of the average
// rule and ACSE (simplify/average_sites.h), each a component of its own
// computed where the definition it comes from is, rendered once per step
// for both rules; the live components ACSE compares them with; and the
// components that renormalization shifts.
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
  std::string moduleText;  // the module the probes are added to
  std::string path;        // where the probe module is written
};

// Per value, its average (one number per scalar), or nullopt when no pixel
// shows it or it is not finite.
using Averages = std::vector<std::optional<std::vector<double>>>;

// A component of the module, and the variant in which to average it.
struct ComponentValue {
  std::string component;
  Placement placement;
};

// The average of each component in its variant.
Expected<Averages, Failure> measureComponents(const ProbeSetup& setup, const std::vector<ComponentValue>& values);

// A value's average, and its profile: its scalars at a fixed sample of the
// marked pixels (every 16th, image after image), which two values of one
// type share, so that they can be compared pixel for pixel.
struct ValueProfile {
  std::optional<std::vector<double>> average;  // nullopt: no pixel shows it, or it is not finite
  std::vector<float> profile;
};

// The probes' subtrees (with the other components placed as `placement`
// places them), then `components`, each in its variant.
Expected<std::vector<ValueProfile>, Failure> profileValues(const ProbeSetup& setup,
                                                           const std::vector<AverageProbe>& probes,
                                                           const std::vector<ComponentValue>& components,
                                                           const Placement& placement);

}  // namespace spire::search
