// How a search step ranks its measured candidates (He et al. 2015, 4.4.3 to
// 4.4.5): the K2 x median filter, the error budget, the bang-for-buck order,
// and the monotone chain.
#include <gtest/gtest.h>

#include "search/candidate_ranking.h"

namespace spire::search {
namespace {

// The numbers are dyadic, so that ratios are exact and ties are ties.
TEST(CandidateRanking, KeepsCandidatesWithinK2TimesTheMedianError) {
  const Measure current{0.0, 1.0};
  const std::vector<Measure> candidates{{0.125, 0.75}, {0.25, 0.25}, {0.375, 0.5}, {4.0, 0.0}, {0.5, 0.875}};
  // The median error is 0.375: with K2 = 1 the 0.5 and 4.0 candidates go;
  // the rest by cost saved per error added (3, 2, 4/3).
  EXPECT_EQ(rankCandidates(current, candidates, {1.0, 1e9}), (std::vector<size_t>{1, 0, 2}));
  // K2 = 2 keeps 0.5 too, last (0.125 saved for 0.5 added).
  EXPECT_EQ(rankCandidates(current, candidates, {2.0, 1e9}), (std::vector<size_t>{1, 0, 2, 4}));
  // The paper's K2 = 0.15 keeps nothing below 0.056 here; the least error
  // stays, so the step narrows instead of ending the chain.
  EXPECT_EQ(rankCandidates(current, candidates, {0.15, 1e9}), (std::vector<size_t>{0}));
}

TEST(CandidateRanking, OrdersByCostSavedPerErrorAddedKeepingTiesInOrder) {
  const Measure current{0.125, 0.75};
  // Saved per error added: 1, 4, 4 (a tie), 1 (a tie).
  const std::vector<Measure> candidates{{0.25, 0.625}, {0.25, 0.25}, {0.1875, 0.5}, {0.5, 0.375}};
  EXPECT_EQ(rankCandidates(current, candidates, {10.0, 1e9}), (std::vector<size_t>{1, 2, 0, 3}));
}

TEST(CandidateRanking, FreeSavingsComeFirstAndNoSavingsLast) {
  const Measure current{0.125, 0.75};
  const std::vector<Measure> candidates{{0.125, 0.75}, {0.375, 0.25}, {0.125, 0.625}, {0.125, 0.5}, {0.125, 0.875}};
  EXPECT_EQ(rankCandidates(current, candidates, {10.0, 1e9}), (std::vector<size_t>{3, 2, 1, 0, 4}));
}

TEST(CandidateRanking, LeavesOutWhatExceedsTheErrorBudget) {
  const Measure current{0.0, 1.0};
  const std::vector<Measure> candidates{{0.375, 0.125}, {0.0625, 0.875}, {0.25, 0.25}};
  // The median is taken over the candidates within the budget (0.0625 and
  // 0.25): K2 = 1 keeps the first of them only.
  EXPECT_EQ(rankCandidates(current, candidates, {1.0, 0.3}), (std::vector<size_t>{1}));
  EXPECT_EQ(rankCandidates(current, candidates, {1.0, 1e9}), (std::vector<size_t>{2, 1}));
  EXPECT_TRUE(rankCandidates(current, candidates, {1.0, 0.01}).empty());
  EXPECT_TRUE(rankCandidates(current, {}, {1.0, 1e9}).empty());
}

TEST(CandidateRanking, AChainNeverLosesErrorOrGainsCost) {
  const Measure current{0.1, 0.8};
  EXPECT_FALSE(keepsChainMonotone(current, {0.1, 0.8})) << "saves nothing";
  EXPECT_FALSE(keepsChainMonotone(current, {0.3, 0.8})) << "saves nothing";
  EXPECT_TRUE(keepsChainMonotone(current, {0.1, 0.79}));
  EXPECT_TRUE(keepsChainMonotone(current, {0.2, 0.5}));
  EXPECT_FALSE(keepsChainMonotone(current, {0.05, 0.5}));
  EXPECT_FALSE(keepsChainMonotone(current, {0.2, 0.81}));
}

}  // namespace
}  // namespace spire::search
