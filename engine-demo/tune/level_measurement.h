// What each level of a level-of-detail policy costs and how far it is from
// full quality at each camera distance (He et al. 2015, section 5), and the
// policy chosen from that. spire-tune --lod-policy measures a scene's own
// policy this way; spire-simplify --search, the levels of its chain.
//
// Each material of the scene is probed alone: the first of its objects is
// drawn at every level from each distance (to the nearest point of its
// bounding sphere, along the scene's first view direction), and a level's
// error is the RMSE of the pixels either image covers against level 0's.
// A level's cost is the scene's median frame time with every object at that
// level, the levels taking turns each frame. One policy serves every
// material, so a level's error at a distance is the largest over them.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "lod/lod_policy.h"
#include "lod/policy_choice.h"
#include "renderer/scene_renderer.h"
#include "scene/scene_file.h"
#include "tune/tune_options.h"

namespace spire::tune {

struct LevelSampling {
  std::vector<float> distances;  // increasing, at least two
  uint32_t warmup = 1;           // unmeasured frames before the costs' frames
  uint32_t frames = 3;           // 0: no frame is timed, and every cost is 0 (a caller that has its own)
};

struct LevelMeasurement {
  lod::LevelMeasurements levels;
  // What levels.cost is, for the table: measureLevels' frame times, unless
  // a caller puts another cost in their place.
  std::string costName = "frame time with every object at one level";
  std::string costUnit = " ms";
  std::vector<std::vector<std::string>> worst;  // [level][distance]: the material whose error that is
  size_t materials = 0;
};

// Doubling from 1 to half the far plane: the camera sees an object's level
// change over about one octave of distance, so each octave gets a sample.
std::vector<float> defaultDistances(const scene::CameraDesc& camera);

// The usage problem with `distances` (fewer than two, not increasing), if any.
std::optional<std::string> distancesProblem(const std::vector<float>& distances);

// Every level of `policy` measured on `renderer`'s scene.
engine::Expected<LevelMeasurement> measureLevels(engine::SceneRenderer& renderer, const lod::LodPolicy& policy,
                                                 const LevelSampling& sampling);

struct ChosenPolicy {
  std::vector<uint32_t> levelAt;  // per distance: the index of the level chosen in the measured policy
  lod::LodPolicy policy;          // the bands of the levels chosen, with the measured policy's fades
};

ChosenPolicy choosePolicy(const LevelMeasurement& m, const lod::LodPolicy& measured, const lod::ChoiceRule& rule);

// The rule the options ask for.
lod::ChoiceRule choiceRule(const PolicyChoiceOptions& options);

// The measurements and the choice as Markdown: each level's frame time, a
// row per distance (the tolerated error, each level's, the level chosen),
// and the bands.
std::string levelTable(const LevelMeasurement& m, const lod::LodPolicy& measured, const ChosenPolicy& chosen,
                       const lod::ChoiceRule& rule);

}  // namespace spire::tune
