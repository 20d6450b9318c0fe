// Per-instance level selection, every frame: the band of the object's
// distance from the camera, with hysteresis at band edges, and a cross-fade
// of transitionFrames frames after each switch (the transitions of He et
// al. 2015, section 6): the object is drawn at the level it leaves, opaque,
// and at the level it enters blended over it with a weight that grows to 1,
// so that the switch does not pop. A switch back during a fade turns the
// fade round; a switch to a third level waits for the fade to end.
#pragma once

#include <glm/vec3.hpp>

#include <cstdint>
#include <span>
#include <vector>

#include "lod/lod_policy.h"
#include "lod/scene_instance.h"

namespace spire::lod {

// The level for an object at `distance` that is now at `current`: one band
// farther only beyond the band's edge times (1 + hysteresis), one nearer
// only within the nearer band's edge times (1 - hysteresis); repeated, so a
// jump across several bands lands in the right one. An edge next to a blend
// band has no hysteresis, and an object whose farthest point (`farthest`;
// by default `distance`) reaches past its band into a blend band draws
// that.
uint32_t levelFor(const LodPolicy& policy, float distance, uint32_t current, float farthest = -1.0F);

struct LodState {
  uint8_t level = 0;      // the level switched to
  uint8_t from = 0;       // the level switched from, while fading
  uint16_t fadeLeft = 0;  // frames of the cross-fade still to come; 0: not fading
};

// One level an instance is drawn at this frame, with its lodFade value:
// 1 opaque; f in (0, 1) blended over what is drawn (the level the object
// leaves) with weight f, so the image is f * new + (1 - f) * old.
struct LevelDraw {
  uint32_t level = 0;
  float fade = 1.0F;
};

class LodSelector {
 public:
  LodSelector(LodPolicy policy, size_t instances);

  // An instance's distance is from the camera to the nearest point of its
  // bounds (ObjectBounds::nearest), so that a large object the camera is
  // near, a terrain tile, is near, and one the camera is only inside the
  // bounding sphere of, high above a flat tile, is not.
  //
  // Starts every instance at the level of its distance, without fading (the
  // first frame of a camera path).
  void reset(std::span<const SceneInstance> instances, const glm::vec3& camera);
  // One frame: each instance's level from its distance, fades advanced.
  void update(std::span<const SceneInstance> instances, const glm::vec3& camera);

  const LodState& state(size_t instance) const { return states_[instance]; }
  // The draws of `instance` this frame: one, or two while it fades (the
  // level it leaves, opaque, then the one it enters, blended).
  uint32_t draws(size_t instance, LevelDraw out[2]) const;
  const LodPolicy& policy() const { return policy_; }

 private:
  LodPolicy policy_;
  std::vector<LodState> states_;
};

}  // namespace spire::lod
