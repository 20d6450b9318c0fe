#include "tune/level_measurement.h"

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <memory>
#include <set>

#include "renderer/lod_scene.h"
#include "renderer/view_error.h"

namespace spire::tune {

namespace {

using LevelScenes = std::vector<std::unique_ptr<engine::LodScene>>;

// One material measured alone, through the first of its objects.
struct Probe {
  std::string material;   // the shader its objects use
  uint32_t instance = 0;  // in the level scenes, which place every instance alike
};

// One scene per level of the policy, every object fixed at that level.
engine::Expected<LevelScenes> createLevelScenes(engine::SceneRenderer& renderer, const lod::LodPolicy& policy) {
  LevelScenes scenes;
  for (uint32_t level = 0; level < policy.levels.size(); ++level) {
    auto scene = engine::LodScene::create(renderer, policy, {level, false});
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

// `distance` from the object's bounds as selection measures it (their
// nearest point), looking at its centre along the scene's first view
// direction (so at the elevation the scene is seen).
scene::CameraView probeView(const lod::SceneInstance& object, const scene::CameraDesc& camera, float distance) {
  const scene::CameraView& first = camera.views.front();
  glm::vec3 back = first.position - first.target;
  back = glm::length(back) > 1e-6F ? glm::normalize(back) : glm::vec3(0.0F, 0.0F, 1.0F);
  const lod::ObjectBounds& bounds = object.bounds;
  // Along the ray from the centre the distance to the bounds only grows;
  // at the sphere's radius plus `distance` it is at least `distance`.
  float inside = 0.0F;
  float outside = bounds.radius + distance;
  for (int step = 0; step < 40; ++step) {
    const float t = 0.5F * (inside + outside);
    (bounds.nearest(bounds.center + back * t) < distance ? inside : outside) = t;
  }
  scene::CameraView view;
  view.position = bounds.center + back * outside;
  view.target = bounds.center;
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
                                     const scene::CameraDesc& camera, LevelMeasurement& m) {
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
engine::Expected<void> measureCosts(LevelScenes& scenes, const scene::CameraDesc& camera, const LevelSampling& sampling,
                                    LevelMeasurement& m) {
  std::vector<std::vector<double>> frameMs(scenes.size());
  for (uint32_t f = 0; f < sampling.warmup + sampling.frames; ++f) {
    const scene::CameraView& view = camera.views[f % camera.views.size()];
    for (size_t l = 0; l < scenes.size(); ++l) {
      scenes[l]->drawOnly({});
      scenes[l]->resetLevels(view);
      auto timing = scenes[l]->draw(view, 0.0F);
      if (!timing) return timing.error();
      if (f >= sampling.warmup) frameMs[l].push_back(timing->gpuMs);
    }
  }
  for (const auto& frames : frameMs) m.levels.cost.push_back(median(frames));
  return {};
}

}  // namespace

std::vector<float> defaultDistances(const scene::CameraDesc& camera) {
  std::vector<float> distances;
  for (float d = 1.0F; d <= camera.farPlane * 0.5F; d *= 2.0F) distances.push_back(d);
  while (distances.size() < 2) distances.push_back(distances.empty() ? 1.0F : distances.back() * 2.0F);
  return distances;
}

std::optional<std::string> distancesProblem(const std::vector<float>& distances) {
  if (distances.size() == 1) return "--distances needs at least two distances";
  for (size_t i = 1; i < distances.size(); ++i) {
    if (!(distances[i] > distances[i - 1])) {
      return fmt::format("--distances must increase, but {} follows {}", distances[i], distances[i - 1]);
    }
  }
  return std::nullopt;
}

engine::Expected<LevelMeasurement> measureLevels(engine::SceneRenderer& renderer, const lod::LodPolicy& policy,
                                                 const LevelSampling& sampling) {
  auto scenes = createLevelScenes(renderer, policy);
  if (!scenes) return scenes.error();
  const scene::CameraDesc& camera = renderer.scene().camera;
  LevelMeasurement m;
  m.levels.distances = sampling.distances.empty() ? defaultDistances(camera) : sampling.distances;
  const std::vector<Probe> probes = findProbes(*scenes->front(), renderer.scene());
  m.materials = probes.size();
  if (auto ok = measureErrors(*scenes, probes, camera, m); !ok) return ok.error();
  if (auto ok = measureCosts(*scenes, camera, sampling, m); !ok) return ok.error();
  return m;
}

ChosenPolicy choosePolicy(const LevelMeasurement& m, const lod::LodPolicy& measured, const lod::ChoiceRule& rule) {
  ChosenPolicy chosen;
  chosen.levelAt = lod::chooseLevels(m.levels, rule);
  chosen.policy = lod::policyFromChoice(measured.levels, m.levels.distances, chosen.levelAt, measured.hysteresis,
                                        measured.transitionFrames);
  return chosen;
}

lod::ChoiceRule choiceRule(const PolicyChoiceOptions& options) {
  return {options.maxError, options.errorExponent, options.switchPenalty};
}

std::string levelTable(const LevelMeasurement& m, const lod::LodPolicy& measured, const ChosenPolicy& chosen,
                       const lod::ChoiceRule& rule) {
  std::vector<std::string> names;
  for (const lod::LodLevel& level : measured.levels) names.push_back(lod::levelName(level));
  std::string text = m.costName + ":";
  for (size_t l = 0; l < names.size(); ++l) {
    text += fmt::format(" {} {:.2f}{}", names[l], m.levels.cost[l], m.costUnit);
  }
  text += "\n| distance | tolerated |";
  for (size_t l = 1; l < names.size(); ++l) text += fmt::format(" {} RMSE (worst material) |", names[l]);
  text += " chosen |\n| --- | --- |";
  for (size_t l = 0; l < names.size(); ++l) text += " --- |";
  text += "\n";
  for (size_t s = 0; s < m.levels.distances.size(); ++s) {
    text += fmt::format("| {:g} | {:.4f} |", m.levels.distances[s], lod::toleratedError(m.levels.distances, s, rule));
    for (size_t l = 1; l < names.size(); ++l) {
      text += fmt::format(" {:.4f} ({}) |", m.levels.error[l][s], m.worst[l][s]);
    }
    text += fmt::format(" {} |\n", names[chosen.levelAt[s]]);
  }
  text += "bands:";
  for (const lod::LodLevel& level : chosen.policy.levels) {
    text += std::isfinite(level.until) ? fmt::format(" {} until {:g},", lod::levelName(level), level.until)
                                       : fmt::format(" {} beyond\n", lod::levelName(level));
  }
  return text;
}

}  // namespace spire::tune
