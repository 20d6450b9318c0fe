// The moving camera of spire-demo --window: a closed loop through the scene's
// camera views, and an orbit the user adds by dragging the mouse.
#pragma once

#include <glm/vec3.hpp>

#include <cstdint>
#include <span>

#include "scene/scene_file.h"

namespace spire::demo {

// The camera at `t` on a loop through `views` (at least one): at t = i it is
// exactly views[i mod n]; in between, position and target ease in and out
// (smoothstep) from one view to the next, so the camera rests a moment at
// each view the demo measures. The last view leads back to the first.
scene::CameraView cameraOnLoop(std::span<const scene::CameraView> views, double t);

// Frame `frame` of a fly-through of `frames` frames (at least one) once
// round that loop: the frames spire-demo measures a level-of-detail scene
// at, and spire-explore's LOD mode shows.
scene::CameraView flyThroughView(std::span<const scene::CameraView> views, double frame, uint32_t frames);

// `view` with its position turned about its target: `yaw` radians about
// `up`, then `pitch` radians towards `up` (negative: away from it), stopping
// short of looking straight along `up` so the view never flips. The distance
// to the target is kept.
scene::CameraView orbit(const scene::CameraView& view, glm::vec3 up, float yaw, float pitch);

}  // namespace spire::demo
