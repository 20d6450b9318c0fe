// Culling and batching of a scene's instances for one frame. Each instance
// is drawn at the levels its LodSelector state gives; a level of an object
// type (a "prototype") belongs to a draw group: objects whose programs have
// the same Vertex and Fragment kernel keys and read the same shared values
// share one pipeline and its descriptors, whatever their shader is called.
// A batch is one group's objects in one spatial block (the paper's engine
// pre-records one command list per block and kernel pair): one pipeline
// bind, then one instanced draw per mesh.
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "lod/lod_selection.h"
#include "lod/scene_instance.h"

namespace spire::lod {

// What the batcher knows of the object types: the group of each
// (prototype, level), and each prototype's mesh.
struct DrawGroups {
  std::vector<std::vector<uint32_t>> groupOf;  // [prototype][level]
  std::vector<uint32_t> meshOf;                // [prototype]
  uint32_t groupCount = 0;
  // [group]: whether its kernels read lodFade, the weight a cross-fade
  // blends with, which they write as the output's alpha. A switch into a
  // group that does not is drawn at once, opaque: blended by an alpha that
  // is not lodFade, the fade would show other colors. Empty: every group.
  std::vector<uint8_t> fades;

  bool canFade(uint32_t group) const { return fades.empty() || fades[group] != 0; }
};

// One instance in a group's record buffer.
struct InstanceRecord {
  uint32_t instance = 0;
  float fade = 1.0F;
};

struct MeshDraw {
  uint32_t mesh = 0;
  uint32_t firstInstance = 0;  // into the group's records
  uint32_t instanceCount = 0;
};

struct Batch {
  uint32_t block = 0;
  uint32_t group = 0;
  // Instances fading into this level (fade < 1), drawn blended after every
  // opaque batch so that the level they leave is already in the image.
  bool overlay = false;
  uint32_t firstDraw = 0;  // into FrameBatches::draws
  uint32_t drawCount = 0;
};

struct FrameBatches {
  std::vector<Batch> batches;                        // by block, then group
  std::vector<MeshDraw> draws;                       // of every batch, in order
  std::vector<std::vector<InstanceRecord>> records;  // per group, in draw order
  uint32_t visibleInstances = 0;
};

// The six planes (xyz normal, w offset) of the view frustum of `viewProj`,
// for Vulkan's [0, 1] depth; a point p is inside when dot(plane, (p, 1)) >= 0
// for all six.
std::array<glm::vec4, 6> frustumPlanes(const glm::mat4& viewProj);
bool sphereVisible(const std::array<glm::vec4, 6>& planes, const glm::vec3& center, float radius);

class InstanceBatcher {
 public:
  InstanceBatcher(DrawGroups groups, uint32_t blockCount);

  // Culls `instances` (only those `subset` lists, when it is not empty)
  // against `viewProj` and batches the visible ones at the levels `selector`
  // gives. `out` is reused from frame to frame.
  void build(std::span<const SceneInstance> instances, const LodSelector& selector, const glm::mat4& viewProj,
             FrameBatches& out, std::span<const uint32_t> subset = {});

  const DrawGroups& groups() const { return groups_; }

 private:
  struct Entry {
    uint32_t bucket;  // (overlay * blockCount + block) * groupCount + group
    uint32_t mesh;
    InstanceRecord record;
  };
  void add(const SceneInstance& instance, uint32_t index, const LodSelector& selector);
  void emit(FrameBatches& out) const;
  DrawGroups groups_;
  uint32_t blockCount_;
  std::vector<Entry> entries_;
  std::vector<Entry> sorted_;
  std::vector<uint32_t> counts_;
};

}  // namespace spire::lod
