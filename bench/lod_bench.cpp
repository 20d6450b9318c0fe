// Level-of-detail CPU cost per frame (Google Benchmark; not a CTest test).
// Run it with bench/lod-frame, or directly: build/bin/spire_bench_lod.
//
// BM_LodFrame/10000   selection, culling and batching of 10,000 instances
//                     (three object types and a terrain, four draw groups
//                     per level as if unlocked, 8x8 blocks) for one frame
//                     of a camera moving along a line through the scene
//                     (target: under 1 ms)
//
// The scene is made here, seeded, so the benchmark needs no files or GPU.
#include <benchmark/benchmark.h>

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

#include "lod/instance_batches.h"
#include "lod/lod_selection.h"

namespace {

using spire::lod::DrawGroups;
using spire::lod::FrameBatches;
using spire::lod::InstanceBatcher;
using spire::lod::LodPolicy;
using spire::lod::LodSelector;
using spire::lod::SceneInstance;

constexpr uint32_t kPrototypes = 4;
constexpr uint32_t kLevels = 3;
constexpr uint32_t kBlocksPerSide = 8;
constexpr float kSceneSize = 160.0F;

// splitmix32-style hash: placements independent of the standard library.
float unitRandom(uint32_t& state) {
  state += 0x9E3779B9U;
  uint32_t z = state;
  z = (z ^ (z >> 16)) * 0x85EBCA6BU;
  z = (z ^ (z >> 13)) * 0xC2B2AE35U;
  z ^= z >> 16;
  return static_cast<float>(z >> 8) / static_cast<float>(1U << 24);
}

std::vector<SceneInstance> makeInstances(uint32_t count) {
  std::vector<SceneInstance> instances;
  instances.reserve(count);
  uint32_t state = 1;
  const float cell = kSceneSize / kBlocksPerSide;
  for (uint32_t i = 0; i < count; ++i) {
    SceneInstance instance;
    const glm::vec3 center{(unitRandom(state) - 0.5F) * kSceneSize, 1.0F, (unitRandom(state) - 0.5F) * kSceneSize};
    instance.bounds = spire::lod::ObjectBounds::sphere(center, 0.5F + unitRandom(state));
    instance.prototype = i == 0 ? 0 : 1 + i % (kPrototypes - 1);
    const auto bx = static_cast<uint32_t>((center.x + kSceneSize / 2) / cell);
    const auto bz = static_cast<uint32_t>((center.z + kSceneSize / 2) / cell);
    instance.block = std::min(bz, kBlocksPerSide - 1) * kBlocksPerSide + std::min(bx, kBlocksPerSide - 1);
    instances.push_back(instance);
  }
  // The terrain: one instance covering everything.
  instances[0] = {spire::lod::ObjectBounds::box({-kSceneSize / 2, -5.0F, -kSceneSize / 2},
                                                {kSceneSize / 2, 5.0F, kSceneSize / 2}, kSceneSize * 0.71F),
                  0, 0};
  return instances;
}

// Every (prototype, level) its own group: the most work for the batcher.
DrawGroups makeGroups() {
  DrawGroups groups;
  groups.groupOf.assign(kPrototypes, std::vector<uint32_t>(kLevels));
  for (uint32_t p = 0; p < kPrototypes; ++p) {
    for (uint32_t l = 0; l < kLevels; ++l) groups.groupOf[p][l] = l * kPrototypes + p;
    groups.meshOf.push_back(p);
  }
  groups.groupCount = kPrototypes * kLevels;
  return groups;
}

LodPolicy makePolicy() {
  LodPolicy policy;
  policy.levels = {
      {"HQ", 12.0F, {}, {}}, {"MQ", 35.0F, {}, {}}, {"LQ", std::numeric_limits<float>::infinity(), {}, {}}};
  policy.hysteresis = 0.1F;
  policy.transitionFrames = 8;
  return policy;
}

void BM_LodFrame(benchmark::State& state) {
  const auto count = static_cast<uint32_t>(state.range(0));
  const std::vector<SceneInstance> instances = makeInstances(count);
  LodSelector selector(makePolicy(), instances.size());
  InstanceBatcher batcher(makeGroups(), kBlocksPerSide * kBlocksPerSide);
  FrameBatches batches;
  const glm::mat4 projection = glm::perspective(glm::radians(55.0F), 16.0F / 9.0F, 0.1F, 400.0F);
  uint64_t frame = 0;
  uint64_t visible = 0;
  for (auto _ : state) {
    // A camera flying across the scene and back, looking ahead.
    const float t = static_cast<float>(frame++ % 600) / 600.0F;
    const glm::vec3 eye(-70.0F + 140.0F * t, 3.0F, -50.0F + 100.0F * t);
    const glm::mat4 viewProj = projection * glm::lookAt(eye, eye + glm::vec3(1.0F, -0.05F, 0.7F), {0.0F, 1.0F, 0.0F});
    selector.update(instances, eye);
    batcher.build(instances, selector, viewProj, batches);
    visible += batches.visibleInstances;
    benchmark::DoNotOptimize(batches.draws.data());
  }
  state.counters["visible"] = static_cast<double>(visible) / static_cast<double>(std::max<uint64_t>(frame, 1));
}
BENCHMARK(BM_LodFrame)->Arg(10000)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
