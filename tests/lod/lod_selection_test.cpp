#include "lod/lod_selection.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>

#include <glm/vec3.hpp>

namespace spire::lod {
namespace {

// An instance whose bounds are a sphere (a point by default) at `center`.
SceneInstance at(const glm::vec3& center, float radius = 0.0F) { return {ObjectBounds::sphere(center, radius), 0, 0}; }

LodPolicy threeLevels(float hysteresis = 0.1F, uint32_t transitionFrames = 0) {
  LodPolicy policy;
  policy.levels = {
      {"HQ", 10.0F, {}, {}}, {"MQ", 30.0F, {}, {}}, {"LQ", std::numeric_limits<float>::infinity(), {}, {}}};
  policy.hysteresis = hysteresis;
  policy.transitionFrames = transitionFrames;
  return policy;
}

TEST(LodSelectionTest, BandsWithHysteresisAtEachEdge) {
  const LodPolicy policy = threeLevels(0.1F);
  EXPECT_EQ(levelFor(policy, 5.0F, 0), 0U);
  EXPECT_EQ(levelFor(policy, 10.5F, 0), 0U);  // within the band's edge * 1.1: stays
  EXPECT_EQ(levelFor(policy, 11.5F, 0), 1U);
  EXPECT_EQ(levelFor(policy, 9.5F, 1), 1U);  // within edge * 0.9 of the nearer band: stays
  EXPECT_EQ(levelFor(policy, 8.5F, 1), 0U);
  EXPECT_EQ(levelFor(policy, 100.0F, 0), 2U);  // several bands at once
  EXPECT_EQ(levelFor(policy, 1.0F, 2), 0U);
}

// A blend band (a transition shader's) between HQ and MQ, from 8 to 10.
LodPolicy withBlend() {
  LodPolicy policy = threeLevels(0.1F);
  policy.levels[0].until = 8.0F;
  policy.levels.insert(policy.levels.begin() + 1, LodLevel{"", 10.0F, {}, {}, true});
  return policy;
}

TEST(LodSelectionTest, ABlendBandIsDrawnByEveryObjectReachingIntoItAndItsEdgesHaveNoHysteresis) {
  const LodPolicy policy = withBlend();
  EXPECT_EQ(levelFor(policy, 5.0F, 0, 7.9F), 0U);   // all of the object is before the blend
  EXPECT_EQ(levelFor(policy, 5.0F, 0, 8.5F), 1U);   // its far side reaches into it
  EXPECT_EQ(levelFor(policy, 8.1F, 0), 1U);         // no hysteresis into it
  EXPECT_EQ(levelFor(policy, 7.9F, 1, 7.95F), 0U);  // nor out of it, nearer
  EXPECT_EQ(levelFor(policy, 10.1F, 1), 2U);        // nor farther
  EXPECT_EQ(levelFor(policy, 9.9F, 2, 12.0F), 1U);
  EXPECT_EQ(levelFor(policy, 32.0F, 2), 2U);  // the other edges keep theirs
  EXPECT_EQ(levelFor(policy, 33.5F, 2), 3U);

  // Starting a path: the same choice, from the bounding spheres.
  LodSelector selector(policy, 2);
  // Nearest 5.5 and 3.5, farthest 8.5 and 6.5.
  const std::array objects{at({7.0F, 0.0F, 0.0F}, 1.5F), at({5.0F, 0.0F, 0.0F}, 1.5F)};
  selector.reset(objects, glm::vec3(0.0F));
  EXPECT_EQ(selector.state(0).level, 1U);
  EXPECT_EQ(selector.state(1).level, 0U);
  selector.update(objects, glm::vec3(0.0F));
  EXPECT_EQ(selector.state(0).level, 1U);
  EXPECT_EQ(selector.state(1).level, 0U);
}

// Property: over random walks of distances, a level only changes when the
// distance has left the current band by more than the hysteresis margin,
// and the level is always one whose band (widened by the margin) holds the
// distance.
TEST(LodSelectionTest, RandomWalksSwitchOnlyBeyondTheMargin) {
  const LodPolicy policy = threeLevels(0.15F);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> step(-2.0F, 2.0F);
  for (int walk = 0; walk < 50; ++walk) {
    float d = 20.0F;
    uint32_t level = levelFor(policy, d, 1);
    for (int i = 0; i < 500; ++i) {
      d = std::max(0.0F, d + step(rng));
      const uint32_t next = levelFor(policy, d, level);
      const float lo = next == 0 ? 0.0F : policy.levels[next - 1].until * (1.0F - policy.hysteresis);
      const float hi = policy.levels[next].until * (1.0F + policy.hysteresis);
      ASSERT_GE(d, lo);
      ASSERT_LE(d, hi);
      if (next > level) {
        ASSERT_GT(d, policy.levels[level].until * (1.0F + policy.hysteresis));
      }
      if (next < level) {
        ASSERT_LT(d, policy.levels[level - 1].until * (1.0F - policy.hysteresis));
      }
      level = next;
    }
  }
}

TEST(LodSelectionTest, ASwitchCrossFadesFromTheOldLevelToTheNew) {
  LodSelector selector(threeLevels(0.0F, 3), 1);
  std::array objects{at({0.0F, 0.0F, 5.0F})};
  selector.reset(objects, glm::vec3(0.0F));
  LevelDraw draws[2];
  ASSERT_EQ(selector.draws(0, draws), 1U);
  EXPECT_EQ(draws[0].level, 0U);
  objects[0] = at({0.0F, 0.0F, 20.0F});  // into MQ
  std::vector<float> fades;
  for (int frame = 0; frame < 5; ++frame) {
    selector.update(objects, glm::vec3(0.0F));
    const uint32_t n = selector.draws(0, draws);
    if (n == 1) {
      EXPECT_EQ(draws[0].level, 1U);
      EXPECT_EQ(draws[0].fade, 1.0F);
      fades.push_back(1.0F);
      continue;
    }
    EXPECT_EQ(draws[0].level, 0U);  // the level it leaves, opaque
    EXPECT_EQ(draws[0].fade, 1.0F);
    EXPECT_EQ(draws[1].level, 1U);  // the level it enters, blended over it
    fades.push_back(draws[1].fade);
  }
  // Weights 1/4, 2/4, 3/4, then the new level alone.
  EXPECT_EQ(fades, (std::vector<float>{0.25F, 0.5F, 0.75F, 1.0F, 1.0F}));
}

// Each level's share of the image this frame: the opaque draw's level gets
// 1 - f, the blended draw's level f.
std::array<float, 3> levelWeights(const LodSelector& selector) {
  LevelDraw draws[2];
  std::array<float, 3> weights{};
  const uint32_t n = selector.draws(0, draws);
  if (n == 1) {
    weights[draws[0].level] = 1.0F;
  } else {
    weights[draws[0].level] += 1.0F - draws[1].fade;
    weights[draws[1].level] += draws[1].fade;
  }
  return weights;
}

// Property: however the distance moves, switches included that come while
// a fade is still running (back to the level being left, or on to a third
// one), no level's share of the image changes by more than one fade step
// between two frames: nothing pops.
TEST(LodSelectionTest, RandomWalksNeverChangeALevelsShareByMoreThanOneStep) {
  constexpr uint32_t kFrames = 6;
  const LodPolicy policy = threeLevels(0.05F, kFrames);
  const float step = 1.0F / (kFrames + 1);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> move(-6.0F, 6.0F);
  size_t reversals = 0;
  for (int walk = 0; walk < 40; ++walk) {
    LodSelector selector(policy, 1);
    float z = 20.0F;
    selector.reset(std::array{at({0.0F, 0.0F, z})}, glm::vec3(0.0F));
    std::array<float, 3> before = levelWeights(selector);
    for (int frame = 0; frame < 400; ++frame) {
      z = std::clamp(z + move(rng), 0.0F, 60.0F);
      const LodState previous = selector.state(0);
      selector.update(std::array{at({0.0F, 0.0F, z})}, glm::vec3(0.0F));
      const LodState& now = selector.state(0);
      reversals += previous.fadeLeft > 1 && now.level == previous.from && now.from == previous.level ? 1 : 0;
      const std::array<float, 3> weights = levelWeights(selector);
      for (size_t l = 0; l < weights.size(); ++l) ASSERT_LE(std::abs(weights[l] - before[l]), step + 1e-5F);
      before = weights;
    }
  }
  EXPECT_GT(reversals, 0U);  // the walks did turn fades round
}

}  // namespace
}  // namespace spire::lod
