#include "lod/policy_choice.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "support/diagnostic_renderer.h"

namespace spire::lod {
namespace {

constexpr double kInfinite = std::numeric_limits<double>::infinity();

// The objective chooseLevels minimizes, or infinity for a sequence it must
// not give (a coarser level out of tolerance, or a level going back).
double total(const LevelMeasurements& m, const ChoiceRule& rule, const std::vector<uint32_t>& levels) {
  double sum = 0.0;
  for (size_t s = 0; s < levels.size(); ++s) {
    const uint32_t l = levels[s];
    if (l > 0 && !(m.error[l][s] <= toleratedError(m.distances, s, rule))) return kInfinite;
    if (s > 0 && l < levels[s - 1]) return kInfinite;
    sum += m.cost[l] / m.cost[0] + (s > 0 && l != levels[s - 1] ? rule.switchPenalty : 0.0);
  }
  return sum;
}

// Every sequence of levels, by counting in base `levels`.
double bruteForceBest(const LevelMeasurements& m, const ChoiceRule& rule) {
  const size_t samples = m.distances.size();
  const size_t levels = m.cost.size();
  std::vector<uint32_t> sequence(samples, 0);
  double best = kInfinite;
  while (true) {
    best = std::min(best, total(m, rule, sequence));
    size_t s = 0;
    while (s < samples && ++sequence[s] == levels) sequence[s++] = 0;
    if (s == samples) return best;
  }
}

LevelMeasurements threeLevels() {
  LevelMeasurements m;
  m.distances = {1, 2, 4, 8, 16, 32};
  m.error = {{0, 0, 0, 0, 0, 0}, {0.2, 0.1, 0.04, 0.03, 0.02, 0.01}, {0.5, 0.3, 0.2, 0.1, 0.05, 0.04}};
  m.cost = {100, 70, 50};
  return m;
}

TEST(PolicyChoiceTest, ToleranceGrowsFromZeroToTheMaximumAlongHeCurve) {
  const std::vector<float> d = {2, 4, 10};
  const ChoiceRule rule{0.1, 0.5, 0.0};
  EXPECT_DOUBLE_EQ(toleratedError(d, 0, rule), 0.0);
  EXPECT_DOUBLE_EQ(toleratedError(d, 1, rule), 0.1 * std::sqrt(2.0 / 8.0));
  EXPECT_DOUBLE_EQ(toleratedError(d, 2, rule), 0.1);
}

TEST(PolicyChoiceTest, TakesTheCheapestLevelWithinTolerance) {
  const LevelMeasurements m = threeLevels();
  // Tolerance 0, 0.032, 0.056, 0.086, 0.125, 0.18 (maxError 0.18).
  const ChoiceRule rule{0.18, 0.5, 0.0};
  EXPECT_EQ(chooseLevels(m, rule), (std::vector<uint32_t>{0, 0, 1, 1, 2, 2}));
}

TEST(PolicyChoiceTest, ASwitchPenaltySkipsALevelWorthOneSample) {
  LevelMeasurements m = threeLevels();
  m.error[2] = {0.5, 0.3, 0.2, 0.1, 0.05, 0.04};
  m.error[1] = {0.2, 0.1, 0.1, 0.1, 0.02, 0.01};
  const ChoiceRule cheap{0.18, 0.5, 0.0};
  EXPECT_EQ(chooseLevels(m, cheap), (std::vector<uint32_t>{0, 0, 0, 0, 2, 2}));
  m.error[1][3] = 0.05;  // level 1 now pays off at one sample only
  EXPECT_EQ(chooseLevels(m, cheap), (std::vector<uint32_t>{0, 0, 0, 1, 2, 2}));
  const ChoiceRule penalised{0.18, 0.5, 0.5};
  EXPECT_EQ(chooseLevels(m, penalised), (std::vector<uint32_t>{0, 0, 0, 0, 2, 2}));
}

TEST(PolicyChoiceTest, NoLevelWithinToleranceKeepsFullQuality) {
  LevelMeasurements m = threeLevels();
  const ChoiceRule rule{0.001, 0.5, 0.0};
  EXPECT_EQ(chooseLevels(m, rule), std::vector<uint32_t>(6, 0));
}

// Over random measurements: the choice is a valid sequence (coarser only,
// within tolerance) and no valid sequence costs less.
TEST(PolicyChoiceTest, RandomMeasurementsGiveTheLeastCostValidSequence) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 400; ++trial) {
    SCOPED_TRACE(trial);
    LevelMeasurements m;
    const size_t samples = 1 + random() % 6;
    const size_t levels = 1 + random() % 4;
    float d = 0.5F;
    for (size_t s = 0; s < samples; ++s) m.distances.push_back(d += static_cast<float>(unit(random) * 10 + 0.1));
    m.error.assign(levels, std::vector<double>(samples, 0.0));
    for (size_t l = 1; l < levels; ++l) {
      for (double& e : m.error[l]) e = unit(random) < 0.05 ? std::nan("") : unit(random) * 0.2;
    }
    for (size_t l = 0; l < levels; ++l) m.cost.push_back(1.0 + unit(random) * 9.0);
    const ChoiceRule rule{unit(random) * 0.2, 0.25 + unit(random), unit(random) * 0.3};
    const std::vector<uint32_t> chosen = chooseLevels(m, rule);
    ASSERT_EQ(chosen.size(), samples);
    const double got = total(m, rule, chosen);
    ASSERT_TRUE(std::isfinite(got)) << "an invalid sequence";
    EXPECT_NEAR(got, bruteForceBest(m, rule), 1e-9);
  }
}

TEST(PolicyChoiceTest, PolicyBandsEndWhereTheNextLevelWasChosenAndReadBack) {
  std::vector<LodLevel> members(3);
  members[0].member = "LodHQ";
  members[1].member = "LodMQ";
  members[2].member = "LodLQ";
  const LodPolicy policy = policyFromChoice(members, {1, 2, 4, 8, 16}, {0, 0, 2, 2, 2}, 0.2F, 6);
  ASSERT_EQ(policy.levels.size(), 2U);
  EXPECT_EQ(policy.levels[0].member, "LodHQ");
  EXPECT_FLOAT_EQ(policy.levels[0].until, 5.0F);  // 4 / (1 - 0.2)
  EXPECT_EQ(policy.levels[1].member, "LodLQ");
  EXPECT_TRUE(std::isinf(policy.levels[1].until));

  SourceManager sources;
  DiagnosticList diags;
  const auto back = parseLodPolicy("tuned.json", formatLodPolicy(policy), sources, diags);
  ASSERT_TRUE(back) << renderDiagnostics(sources, diags, DiagnosticFormat::Text);
  EXPECT_EQ(back->levels.size(), 2U);
  EXPECT_FLOAT_EQ(back->levels[0].until, 5.0F);
  EXPECT_FLOAT_EQ(back->hysteresis, 0.2F);
  EXPECT_EQ(back->transitionFrames, 6U);

  const LodPolicy single = policyFromChoice(members, {1, 2}, {0, 0}, 0.1F, 8);
  ASSERT_EQ(single.levels.size(), 1U);
  EXPECT_TRUE(std::isinf(single.levels[0].until));
}

}  // namespace
}  // namespace spire::lod
