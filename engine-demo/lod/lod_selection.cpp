#include "lod/lod_selection.h"

#include <algorithm>

namespace spire::lod {

namespace {

// The hysteresis at band `band`'s far edge: none next to a blend band,
// whose pixels at the edge are the neighbour's exactly.
float hysteresisAt(const LodPolicy& policy, uint32_t band) {
  return policy.levels[band].blend || policy.levels[band + 1].blend ? 0.0F : policy.hysteresis;
}

}  // namespace

uint32_t levelFor(const LodPolicy& policy, float distance, uint32_t current, float farthest) {
  const auto last = static_cast<uint32_t>(policy.levels.size() - 1);
  uint32_t level = std::min(current, last);
  while (level < last && distance > policy.levels[level].until * (1.0F + hysteresisAt(policy, level))) ++level;
  while (level > 0 && distance < policy.levels[level - 1].until * (1.0F - hysteresisAt(policy, level - 1))) --level;
  if (level < last && policy.levels[level + 1].blend && std::max(distance, farthest) > policy.levels[level].until) {
    ++level;
  }
  return level;
}

LodSelector::LodSelector(LodPolicy policy, size_t instances) : policy_(std::move(policy)), states_(instances) {}

void LodSelector::reset(std::span<const SceneInstance> instances, const glm::vec3& camera) {
  // Without hysteresis: the band the distance is in.
  LodPolicy exact = policy_;
  exact.hysteresis = 0.0F;
  for (size_t i = 0; i < states_.size(); ++i) {
    const ObjectBounds& bounds = instances[i].bounds;
    const uint32_t level = levelFor(exact, bounds.nearest(camera), 0, bounds.farthest(camera));
    states_[i] = {static_cast<uint8_t>(level), static_cast<uint8_t>(level), 0};
  }
}

void LodSelector::update(std::span<const SceneInstance> instances, const glm::vec3& camera) {
  const auto frames = static_cast<uint16_t>(policy_.transitionFrames);
  for (size_t i = 0; i < states_.size(); ++i) {
    LodState& s = states_[i];
    if (s.fadeLeft > 0) --s.fadeLeft;
    const ObjectBounds& bounds = instances[i].bounds;
    const uint32_t level = levelFor(policy_, bounds.nearest(camera), s.level, bounds.farthest(camera));
    if (level == s.level) continue;
    if (s.fadeLeft == 0) {
      s.from = s.level;
      s.level = static_cast<uint8_t>(level);
      s.fadeLeft = frames;
    } else if (level == s.from) {
      // Back to the level it is leaving: the fade turns round from where it
      // is, so no pixel jumps.
      std::swap(s.from, s.level);
      s.fadeLeft = static_cast<uint16_t>(frames + 1 - s.fadeLeft);
    }
    // A third level waits for this fade to end: two draws cannot blend
    // three levels, and cutting the fade short would pop.
  }
}

uint32_t LodSelector::draws(size_t instance, LevelDraw out[2]) const {
  const LodState& s = states_[instance];
  if (s.fadeLeft == 0 || s.from == s.level) {
    out[0] = {s.level, 1.0F};
    return 1;
  }
  // The new level's weight grows by 1/(T+1) a frame: 1/(T+1) on the
  // switch's frame, 1 (no longer fading) T frames later.
  const float f = 1.0F - static_cast<float>(s.fadeLeft) / static_cast<float>(policy_.transitionFrames + 1);
  out[0] = {s.from, 1.0F};
  out[1] = {s.level, f};
  return 2;
}

}  // namespace spire::lod
