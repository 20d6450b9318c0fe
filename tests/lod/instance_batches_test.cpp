#include "lod/instance_batches.h"

#include <gtest/gtest.h>
#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>

#include <map>
#include <random>
#include <set>

namespace spire::lod {
namespace {

LodPolicy twoLevels() {
  LodPolicy policy;
  policy.levels = {{"HQ", 10.0F, {}, {}}, {"LQ", std::numeric_limits<float>::infinity(), {}, {}}};
  policy.hysteresis = 0.0F;
  policy.transitionFrames = 0;
  return policy;
}

glm::mat4 viewProj(const glm::vec3& eye, const glm::vec3& target) {
  glm::mat4 projection = glm::perspectiveRH_ZO(glm::radians(60.0F), 1.0F, 0.1F, 1000.0F);
  projection[1][1] *= -1.0F;
  return projection * glm::lookAt(eye, target, glm::vec3(0, 1, 0));
}

TEST(InstanceBatchesTest, FrustumKeepsWhatIsInFrontAndDropsWhatIsBehind) {
  const auto planes = frustumPlanes(viewProj(glm::vec3(0), glm::vec3(0, 0, -1)));
  EXPECT_TRUE(sphereVisible(planes, {0, 0, -5}, 0.5F));
  EXPECT_FALSE(sphereVisible(planes, {0, 0, 5}, 0.5F));
  EXPECT_FALSE(sphereVisible(planes, {100, 0, -5}, 0.5F));
  EXPECT_TRUE(sphereVisible(planes, {3.3F, 0, -5}, 0.5F));  // straddles the right plane
  EXPECT_FALSE(sphereVisible(planes, {0, 0, -2000}, 1.0F));
}

// Two prototypes whose far level shares a group (locked kernels), one
// whose far level does not: the shared group's instances of different
// prototypes land in one batch per block, one draw per mesh.
TEST(InstanceBatchesTest, PrototypesSharingAGroupLandInOneBatchPerBlock) {
  DrawGroups groups;
  groups.groupOf = {{0, 3}, {1, 3}, {2, 4}};  // [prototype][level]: groups 3 shared by prototypes 0 and 1
  groups.meshOf = {0, 1, 2};
  groups.groupCount = 5;
  std::vector<SceneInstance> instances;
  for (uint32_t block = 0; block < 2; ++block) {
    for (uint32_t p = 0; p < 3; ++p) {
      for (int k = 0; k < 4; ++k)
        instances.push_back({ObjectBounds::sphere({float(k), 0, -50.0F - float(block)}, 1.0F), p, block});
    }
  }
  LodSelector selector(twoLevels(), instances.size());
  selector.reset(instances, glm::vec3(0));
  InstanceBatcher batcher(groups, 2);
  FrameBatches out;
  batcher.build(instances, selector, viewProj(glm::vec3(0), glm::vec3(0, 0, -1)), out);
  EXPECT_EQ(out.visibleInstances, instances.size());
  ASSERT_EQ(out.batches.size(), 4U);  // per block: group 3 (prototypes 0 and 1) and group 4
  for (const Batch& batch : out.batches) {
    EXPECT_EQ(batch.drawCount, batch.group == 3 ? 2U : 1U);
    for (uint32_t d = batch.firstDraw; d < batch.firstDraw + batch.drawCount; ++d) {
      const MeshDraw& draw = out.draws[d];
      EXPECT_EQ(draw.instanceCount, 4U);
      for (uint32_t r = draw.firstInstance; r < draw.firstInstance + draw.instanceCount; ++r) {
        const SceneInstance& instance = instances[out.records[batch.group][r].instance];
        EXPECT_EQ(instance.block, batch.block);
        EXPECT_EQ(groups.meshOf[instance.prototype], draw.mesh);
      }
    }
  }
  EXPECT_EQ(out.records[3].size(), 16U);
  EXPECT_EQ(out.records[4].size(), 8U);
}

// A switch into a level whose group cannot fade (its kernels do not read
// lodFade) draws that level at once, opaque; into one that can, both
// levels, the new one blended.
TEST(InstanceBatchesTest, ASwitchIntoAGroupThatCannotFadeIsDrawnAtOnce) {
  for (const bool canFade : {true, false}) {
    SCOPED_TRACE(canFade);
    DrawGroups groups;
    groups.groupOf = {{0, 1}};
    groups.meshOf = {0};
    groups.groupCount = 2;
    groups.fades = {1, canFade ? uint8_t{1} : uint8_t{0}};
    const std::vector<SceneInstance> instances{{ObjectBounds::sphere({0, 0, -5.0F}, 0.5F), 0, 0}};
    LodPolicy policy = twoLevels();
    policy.transitionFrames = 4;
    LodSelector selector(policy, 1);
    selector.reset(instances, glm::vec3(0));
    selector.update(instances, glm::vec3(0, 0, 20.0F));  // now 25 away: switching to LQ
    InstanceBatcher batcher(groups, 1);
    FrameBatches out;
    batcher.build(instances, selector, viewProj(glm::vec3(0, 0, 20.0F), glm::vec3(0, 0, -1)), out);
    ASSERT_EQ(out.batches.size(), canFade ? 2U : 1U);
    EXPECT_EQ(out.records[1].size(), 1U);
    EXPECT_EQ(out.records[1][0].fade == 1.0F, !canFade);
    EXPECT_EQ(out.records[0].size(), canFade ? 1U : 0U);
  }
}

// A subset (one object alone, as spire-tune --lod-policy draws it) batches
// only the instances it lists, keeping their indices into the scene.
TEST(InstanceBatchesTest, ASubsetDrawsOnlyTheInstancesItLists) {
  DrawGroups groups;
  groups.groupOf = {{0, 1}, {0, 1}};
  groups.meshOf = {0, 1};
  groups.groupCount = 2;
  std::vector<SceneInstance> instances;
  for (uint32_t k = 0; k < 6; ++k)
    instances.push_back({ObjectBounds::sphere({0.4F * float(k), 0, -5.0F}, 0.2F), k % 2, 0});
  LodSelector selector(twoLevels(), instances.size());
  selector.reset(instances, glm::vec3(0));
  InstanceBatcher batcher(groups, 1);
  FrameBatches out;
  const std::vector<uint32_t> subset{3};
  batcher.build(instances, selector, viewProj(glm::vec3(0), glm::vec3(0, 0, -1)), out, subset);
  EXPECT_EQ(out.visibleInstances, 1U);
  ASSERT_EQ(out.draws.size(), 1U);
  EXPECT_EQ(out.draws[0].mesh, 1U);
  ASSERT_EQ(out.records[0].size(), 1U);
  EXPECT_EQ(out.records[0][0].instance, 3U);
  batcher.build(instances, selector, viewProj(glm::vec3(0), glm::vec3(0, 0, -1)), out);
  EXPECT_EQ(out.records[0].size(), 6U);
}

// Property over random scenes: every visible instance is drawn exactly once
// per level it is drawn at, in the group of its (prototype, level), in a
// batch of its block and a draw of its mesh; no batch repeats a (block,
// group) pair.
TEST(InstanceBatchesTest, RandomScenesDrawEveryVisibleInstanceOnceInItsGroup) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 20; ++trial) {
    const uint32_t prototypes = 1 + rng() % 5;
    const uint32_t blocks = 1 + rng() % 9;
    DrawGroups groups;
    groups.groupCount = 1 + rng() % 6;
    for (uint32_t p = 0; p < prototypes; ++p) {
      groups.groupOf.push_back(
          {static_cast<uint32_t>(rng() % groups.groupCount), static_cast<uint32_t>(rng() % groups.groupCount)});
      groups.meshOf.push_back(rng() % 3);
    }
    std::uniform_real_distribution<float> pos(-40.0F, 40.0F);
    std::vector<SceneInstance> instances(200 + rng() % 300);
    for (auto& i : instances) {
      i = {ObjectBounds::sphere({pos(rng), 0.0F, pos(rng)}, 1.0F), static_cast<uint32_t>(rng() % prototypes),
           static_cast<uint32_t>(rng() % blocks)};
    }
    LodSelector selector(twoLevels(), instances.size());
    selector.reset(instances, glm::vec3(0, 5, 30));
    const glm::mat4 vp = viewProj(glm::vec3(0, 5, 30), glm::vec3(0));
    InstanceBatcher batcher(groups, blocks);
    FrameBatches out;
    batcher.build(instances, selector, vp, out);
    const auto planes = frustumPlanes(vp);
    std::multiset<uint32_t> drawn;
    std::set<std::pair<uint32_t, uint32_t>> seen;
    for (const Batch& batch : out.batches) {
      ASSERT_TRUE(seen.insert({batch.block, batch.group}).second);
      for (uint32_t d = batch.firstDraw; d < batch.firstDraw + batch.drawCount; ++d) {
        for (uint32_t r = out.draws[d].firstInstance; r < out.draws[d].firstInstance + out.draws[d].instanceCount;
             ++r) {
          const uint32_t index = out.records[batch.group][r].instance;
          const SceneInstance& i = instances[index];
          ASSERT_EQ(i.block, batch.block);
          ASSERT_EQ(groups.meshOf[i.prototype], out.draws[d].mesh);
          ASSERT_EQ(groups.groupOf[i.prototype][selector.state(index).level], batch.group);
          drawn.insert(index);
        }
      }
    }
    for (uint32_t i = 0; i < instances.size(); ++i) {
      const bool visible = sphereVisible(planes, instances[i].bounds.center, instances[i].bounds.radius);
      ASSERT_EQ(drawn.count(i), visible ? 1U : 0U) << "instance " << i;
    }
  }
}

}  // namespace
}  // namespace spire::lod
