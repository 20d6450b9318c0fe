// The pairing and the stopping rule on synthetic timings with known noise:
// the machine's speed drifts and jitters the way a shared CI machine's does,
// and the tests check what the tuner relies on.
#include "tune/paired_timing.h"
#include "tune/racing.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace spire::tune {
namespace {

// A machine whose speed wanders slowly, jumps now and then to another level
// between 0.7x and 1.5x (another process starts or stops), and jitters by
// `jitter` (log-normal) from frame to frame.
class NoisyMachine {
 public:
  NoisyMachine(uint32_t seed, double jitter) : random_(seed), jitter_(0.0, jitter) {}
  double frame(double trueMs) {
    if (chance_(random_) < 0.05) {
      speed_ = level_(random_);
    } else {
      speed_ = std::clamp(speed_ * std::exp(wander_(random_)), 0.7, 1.5);
    }
    return trueMs * speed_ * std::exp(jitter_(random_));
  }

 private:
  std::mt19937 random_;
  std::normal_distribution<double> jitter_;
  std::normal_distribution<double> wander_{0.0, 0.005};
  std::uniform_real_distribution<double> chance_{0.0, 1.0};
  std::uniform_real_distribution<double> level_{0.7, 1.5};
  double speed_ = 1.0;
};

TEST(PairedTiming, MedianIntervalHoldsTheMedianAtLeast95PercentOfTheTime) {
  std::mt19937 random(3);
  std::lognormal_distribution<double> draw(std::log(10.0), 0.3);  // median 10
  for (size_t n : {6U, 9U, 15U, 40U}) {
    int held = 0;
    constexpr int kTrials = 4000;
    for (int t = 0; t < kTrials; ++t) {
      std::vector<double> values(n);
      for (double& v : values) v = draw(random);
      const Interval interval = medianInterval(values);
      held += interval.low <= 10.0 && 10.0 <= interval.high ? 1 : 0;
    }
    EXPECT_GE(held, kTrials * 94 / 100) << "n = " << n;
  }
  EXPECT_EQ(medianInterval({3, 1, 2}).low, 1.0);  // too few for 95%: the range
  EXPECT_EQ(medianInterval({3, 1, 2}).high, 3.0);
}

// Two runs of the same variant on a drifting machine: times measured in
// blocks (every variant frame, then every reference frame) disagree by the
// drift; ratios of alternate frames agree within a few percent.
TEST(PairedTiming, PairingCancelsTheMachinesDrift) {
  double worstBlocks = 1.0;
  double worstPaired = 1.0;
  for (uint32_t seed = 1; seed <= 20; ++seed) {
    NoisyMachine machine(seed, 0.02);
    std::vector<double> blockRatios;
    std::vector<double> paired;
    for (int run = 0; run < 2; ++run) {
      std::vector<double> variant;
      std::vector<double> reference;
      for (int f = 0; f < 9; ++f) variant.push_back(machine.frame(8.0));
      for (int f = 0; f < 9; ++f) reference.push_back(machine.frame(10.0));
      blockRatios.push_back(medianOf(variant) / medianOf(reference));
      std::vector<double> ratios;
      for (int f = 0; f < 9; ++f) {
        const double v = machine.frame(8.0);
        ratios.push_back(v / machine.frame(10.0));
      }
      paired.push_back(medianOf(ratios));
    }
    worstBlocks =
        std::max(worstBlocks, std::max(blockRatios[0], blockRatios[1]) / std::min(blockRatios[0], blockRatios[1]));
    worstPaired = std::max(worstPaired, std::max(paired[0], paired[1]) / std::min(paired[0], paired[1]));
    EXPECT_NEAR(paired[0], 0.8, 0.8 * 0.1) << "seed " << seed;
  }
  EXPECT_LT(worstPaired, 1.1);
  EXPECT_GT(worstBlocks, worstPaired * 1.2) << "the drift should show in block timings";
}

// Over 50 machines per noise level: a run stops as soon as its interval is
// within 6% of the median (or at the limit), so quiet machines need few
// pairs, noisy ones the limit, and more noise never fewer pairs on average.
TEST(PairedTiming, TheStoppingRuleAddsPairsOnlyWhileTheIntervalIsWide) {
  const StoppingRule rule{3, 15, 0.06};
  const auto averagePairs = [&](double jitter) {
    double sum = 0.0;
    for (uint32_t seed = 1; seed <= 50; ++seed) {
      NoisyMachine machine(seed, jitter);
      std::vector<double> ratios;
      while (!enoughPairs(ratios, rule)) {
        const double v = machine.frame(8.0);
        ratios.push_back(v / machine.frame(10.0));
      }
      const TimeRatio time = summarizeRatios(ratios);
      EXPECT_TRUE(time.pairs == 15U || time.interval.high - time.interval.low <= 0.06 * time.median)
          << "jitter " << jitter << " seed " << seed;
      EXPECT_LE(time.interval.low, time.median);
      EXPECT_GE(time.interval.high, time.median);
      if (jitter < 0.01) {
        EXPECT_NEAR(time.median, 0.8, 0.01) << "seed " << seed;
      }
      sum += time.pairs;
    }
    return sum / 50.0;
  };
  const double quiet = averagePairs(0.001);
  const double moderate = averagePairs(0.015);
  const double noisy = averagePairs(0.3);
  EXPECT_LT(quiet, 5.0);
  EXPECT_GT(moderate, quiet);
  EXPECT_GT(noisy, moderate);
  EXPECT_EQ(noisy, 15.0) << "noise this large never gets within 6%";
}

TEST(PairedTiming, OverlappingIntervalsAreWithinTheNoise) {
  const TimeRatio a{0.80, {0.78, 0.82}, 9};
  const TimeRatio b{0.83, {0.81, 0.85}, 9};
  const TimeRatio c{0.90, {0.86, 0.93}, 9};
  EXPECT_TRUE(withinNoise(a, b));
  EXPECT_TRUE(withinNoise(b, a));
  EXPECT_FALSE(withinNoise(a, c));
}

VariantResult measured(uint64_t index, double ratio, double low, double high, double rmse) {
  VariantResult r;
  r.index = index;
  r.time = {ratio, {low, high}, 9};
  r.rmse = rmse;
  return r;
}

// Only a variant that another is certainly faster than (whole interval
// below) at no more error is out of the race; failed, hazardous and
// shared-kernel rows never race.
TEST(Racing, CandidatesAreTheVariantsNotCertainlyDominated) {
  std::vector<VariantResult> results{
      measured(0, 1.00, 0.98, 1.02, 0.0),   // the reference: most accurate
      measured(1, 0.50, 0.48, 0.52, 0.02),  // fast, some error
      measured(2, 0.60, 0.58, 0.62, 0.03),  // slower than 1 for sure and worse: out
      measured(3, 0.53, 0.45, 0.60, 0.03),  // overlaps 1: might be faster, stays
      measured(4, 0.40, 0.39, 0.41, 0.10),  // fastest, worst: on the front
  };
  results.push_back(measured(5, 0.30, 0.29, 0.31, 0.0));
  results.back().status = "failed: no";
  results.push_back(measured(6, 0.30, 0.29, 0.31, 0.0));
  results.back().nanPixels = 4;
  results.back().rmse = std::numeric_limits<double>::infinity();
  results.push_back(measured(7, 0.50, 0.48, 0.52, 0.02));
  results.back().sameAs = 1;
  EXPECT_EQ(frontCandidates(results), (std::vector<size_t>{0, 1, 3, 4}));
  EXPECT_TRUE(tight(results[1].time, 0.1));
  EXPECT_FALSE(tight(results[3].time, 0.1));
  // Three pairs give the range, not a 95% interval: never tight enough,
  // however narrow.
  TimeRatio few = results[1].time;
  few.pairs = 3;
  EXPECT_FALSE(tight(few, 0.1));
  few.pairs = kPairsFor95;
  EXPECT_TRUE(tight(few, 0.1));
}

// Racing measures again, once each, the candidates whose time is loose or
// came from another process; a variant that a raced one no longer
// dominates joins the next round.
TEST(Racing, NextRoundTakesLooseOrForeignCandidatesNotRacedYet) {
  std::vector<VariantResult> results{
      measured(0, 1.00, 0.99, 1.01, 0.0),   // tight, measured here
      measured(1, 0.50, 0.49, 0.51, 0.02),  // tight, from a worker
      measured(2, 0.70, 0.60, 0.80, 0.01),  // loose, measured here
      measured(3, 0.60, 0.55, 0.65, 0.03),  // loose, certainly dominated by 1
  };
  RaceState state;
  state.measuredHere = {0, 2, 3};
  EXPECT_EQ(nextToRace(results, state, 0.06), (std::vector<size_t>{1, 2}));
  state.raced = {1, 2};
  results[1].time = {0.60, {0.58, 0.62}, 9};  // raced slower: 3 is uncovered
  results[2].time = {0.75, {0.74, 0.76}, 9};
  EXPECT_EQ(nextToRace(results, state, 0.06), (std::vector<size_t>{3}));
  state.raced.insert(3);
  EXPECT_TRUE(nextToRace(results, state, 0.06).empty());
}

}  // namespace
}  // namespace spire::tune
