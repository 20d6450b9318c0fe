#include "tune/lod_policy_tune.h"

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include <algorithm>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "driver/exit_codes.h"
#include "driver/tool_arguments.h"
#include "lod/policy_choice.h"
#include "renderer/lod_scene.h"
#include "renderer/view_error.h"
#include "support/file_io.h"
#include "tool/tool_run.h"

namespace spire::tune {

namespace {

constexpr const char* kTool = "spire-tune";

using LevelScenes = std::vector<std::unique_ptr<engine::LodScene>>;

// One material measured alone, through the first of its objects.
struct Probe {
  std::string material;   // the shader its objects use
  uint32_t instance = 0;  // in the level scenes, which place every instance alike
};

struct Measured {
  lod::LevelMeasurements levels;
  std::vector<std::vector<std::string>> worst;  // [level][distance]: the material whose error that is
  std::vector<std::vector<double>> frameMs;     // [level]: each measured frame
};

std::optional<int> checkDistances(const std::vector<float>& distances, std::ostream& err) {
  if (distances.size() == 1) return usageError(kTool, "--distances needs at least two distances", err);
  for (size_t i = 1; i < distances.size(); ++i) {
    if (!(distances[i] > distances[i - 1])) {
      return usageError(
          kTool, fmt::format("--distances must increase, but {} follows {}", distances[i], distances[i - 1]), err);
    }
  }
  return std::nullopt;
}

// Doubling from 1 to half the far plane: the camera sees an object's level
// change over about one octave of distance, so each octave gets a sample.
std::vector<float> defaultDistances(const scene::CameraDesc& camera) {
  std::vector<float> distances;
  for (float d = 1.0F; d <= camera.farPlane * 0.5F; d *= 2.0F) distances.push_back(d);
  while (distances.size() < 2) distances.push_back(distances.empty() ? 1.0F : distances.back() * 2.0F);
  return distances;
}

// One scene per level of the policy, every object fixed at that level.
engine::Expected<LevelScenes> createLevelScenes(engine::ToolRun& run) {
  LevelScenes scenes;
  for (uint32_t level = 0; level < run.lodPolicy().levels.size(); ++level) {
    auto scene = engine::LodScene::create(run.renderer(), run.lodPolicy(), {level, false});
    if (!scene) return scene.error();
    scenes.push_back(std::move(scene).value());
  }
  return scenes;
}

std::vector<Probe> findProbes(const engine::LodScene& scene, const scene::SceneFile& file) {
  std::vector<Probe> probes;
  std::set<std::string> seen;
  for (uint32_t i = 0; i < scene.instanceCount(); ++i) {
    const std::string& shader = file.instances[scene.instance(i).prototype].shader;
    if (seen.insert(shader).second) probes.push_back({shader, i});
  }
  return probes;
}

// `distance` from the object's bounding sphere, looking at its centre along
// the scene's first view direction (so at the elevation the scene is seen).
scene::CameraView probeView(const lod::SceneInstance& object, const scene::CameraDesc& camera, float distance) {
  const scene::CameraView& first = camera.views.front();
  glm::vec3 back = first.position - first.target;
  back = glm::length(back) > 1e-6F ? glm::normalize(back) : glm::vec3(0.0F, 0.0F, 1.0F);
  scene::CameraView view;
  view.position = object.center + back * (object.radius + distance);
  view.target = object.center;
  return view;
}

engine::Expected<engine::Capture> shoot(engine::LodScene& scene, uint32_t instance, const scene::CameraView& view) {
  scene.drawOnly({instance});
  scene.resetLevels(view);
  if (auto drawn = scene.draw(view, 0.0F); !drawn) return drawn.error();
  auto color = scene.readColor();
  if (!color) return color.error();
  auto coverage = scene.readCoverage();
  if (!coverage) return coverage.error();
  return engine::Capture{std::move(color).value(), std::move(coverage).value(), {}};
}

// Every level's error at every distance: the largest over the materials.
engine::Expected<void> measureErrors(LevelScenes& scenes, const std::vector<Probe>& probes,
                                     const scene::CameraDesc& camera, Measured& m) {
  const size_t samples = m.levels.distances.size();
  m.levels.error.assign(scenes.size(), std::vector<double>(samples, 0.0));
  m.worst.assign(scenes.size(), std::vector<std::string>(samples));
  for (const Probe& probe : probes) {
    for (size_t s = 0; s < samples; ++s) {
      const scene::CameraView view = probeView(scenes.front()->instance(probe.instance), camera, m.levels.distances[s]);
      auto reference = shoot(*scenes.front(), probe.instance, view);
      if (!reference) return reference.error();
      for (size_t l = 1; l < scenes.size(); ++l) {
        auto shot = shoot(*scenes[l], probe.instance, view);
        if (!shot) return shot.error();
        // Over the pixels either image covers, so the background, the same
        // in both, does not dilute it.
        auto error = engine::viewError(*reference, *shot);
        if (!error) return engine::Error{error.error().message, {}, {}};
        if (m.worst[l][s].empty() || error->rmse > m.levels.error[l][s]) {
          m.levels.error[l][s] = error->rmse;
          m.worst[l][s] = probe.material;
        }
      }
    }
  }
  return {};
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values.empty() ? 0.0 : values[values.size() / 2];
}

// Each level's median frame time over the scene's views, every object
// drawn; the levels take turns each frame, so a slow moment of the machine
// falls on all of them alike.
engine::Expected<void> measureCosts(LevelScenes& scenes, const scene::CameraDesc& camera, const TuneOptions& options,
                                    Measured& m) {
  m.frameMs.assign(scenes.size(), {});
  for (uint32_t f = 0; f < options.warmup + options.frames; ++f) {
    const scene::CameraView& view = camera.views[f % camera.views.size()];
    for (size_t l = 0; l < scenes.size(); ++l) {
      scenes[l]->drawOnly({});
      scenes[l]->resetLevels(view);
      auto timing = scenes[l]->draw(view, 0.0F);
      if (!timing) return timing.error();
      if (f >= options.warmup) m.frameMs[l].push_back(timing->gpuMs);
    }
  }
  for (const auto& frames : m.frameMs) m.levels.cost.push_back(median(frames));
  return {};
}

std::string report(const TuneOptions& options, const Measured& m, const std::vector<std::string>& members,
                   size_t materials, const std::vector<uint32_t>& chosen, const lod::LodPolicy& policy) {
  const lod::ChoiceRule rule{options.maxError, options.errorExponent, options.switchPenalty};
  std::string text = fmt::format("level-of-detail policy for '{}': {} levels, {} materials, {} distances\n",
                                 options.scenePath, members.size(), materials, m.levels.distances.size());
  text += "frame time with every object at one level (median of " + std::to_string(options.frames) + "):";
  for (size_t l = 0; l < members.size(); ++l) text += fmt::format(" {} {:.2f} ms", members[l], m.levels.cost[l]);
  text += "\n| distance | tolerated |";
  for (size_t l = 1; l < members.size(); ++l) text += fmt::format(" {} RMSE (worst material) |", members[l]);
  text += " chosen |\n| --- | --- |";
  for (size_t l = 0; l < members.size(); ++l) text += " --- |";
  text += "\n";
  for (size_t s = 0; s < m.levels.distances.size(); ++s) {
    text += fmt::format("| {:g} | {:.4f} |", m.levels.distances[s], lod::toleratedError(m.levels.distances, s, rule));
    for (size_t l = 1; l < members.size(); ++l) {
      text += fmt::format(" {:.4f} ({}) |", m.levels.error[l][s], m.worst[l][s]);
    }
    text += fmt::format(" {} |\n", members[chosen[s]]);
  }
  text += fmt::format("wrote {}:", options.lodPolicyPath);
  for (const lod::LodLevel& level : policy.levels) {
    text += std::isfinite(level.until) ? fmt::format(" {} until {:g},", level.member, level.until)
                                       : fmt::format(" {} beyond\n", level.member);
  }
  return text;
}

}  // namespace

int runLodPolicyTune(const TuneOptions& options, std::ostream& out, std::ostream& err) {
  if (const auto status = checkDistances(options.distances, err)) return *status;
  engine::ToolRun run(kTool, err);
  if (const auto status = run.loadScene(options.scenePath)) return *status;
  if (const auto status = run.loadLodPolicy()) return *status;
  if (const auto status = run.openDevice({options.device, options.validation, {}, {}})) return *status;
  run.startRenderer(options.bakeSize);
  auto scenes = createLevelScenes(run);
  if (!scenes) return run.fail(scenes.error());
  const scene::CameraDesc& camera = run.scene().camera;
  Measured m;
  m.levels.distances = options.distances.empty() ? defaultDistances(camera) : options.distances;
  const std::vector<Probe> probes = findProbes(*scenes->front(), run.scene());
  if (auto ok = measureErrors(*scenes, probes, camera, m); !ok) return run.fail(ok.error());
  if (auto ok = measureCosts(*scenes, camera, options, m); !ok) return run.fail(ok.error());

  const lod::LodPolicy& measuredPolicy = run.lodPolicy();
  std::vector<std::string> members;
  for (const lod::LodLevel& level : measuredPolicy.levels) members.push_back(level.member);
  const lod::ChoiceRule rule{options.maxError, options.errorExponent, options.switchPenalty};
  const std::vector<uint32_t> chosen = lod::chooseLevels(m.levels, rule);
  const lod::LodPolicy policy = lod::policyFromChoice(members, m.levels.distances, chosen, measuredPolicy.hysteresis,
                                                      measuredPolicy.transitionFrames);
  if (auto written = writeFileAtomically(options.lodPolicyPath, lod::formatLodPolicy(policy)); !written) {
    return run.fail(written.error().message);
  }
  out << report(options, m, members, probes.size(), chosen, policy);
  return run.finish(kExitSuccess);
}

}  // namespace spire::tune
