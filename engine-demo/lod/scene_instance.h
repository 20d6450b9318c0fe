// One drawn object of a level-of-detail scene, as selection, culling and
// batching see it: where it is, what type of object it is, and which
// spatial block it is batched in.
#pragma once

#include <cstdint>

#include "lod/object_bounds.h"

namespace spire::lod {

struct SceneInstance {
  ObjectBounds bounds;     // world space; selected by both bounds, culled by the sphere
  uint32_t prototype = 0;  // the scene instance it is a copy of
  uint32_t block = 0;
};

}  // namespace spire::lod
