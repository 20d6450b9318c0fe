// The generator's property over thousands of random variants (issue 12,
// "Testing at the scale of the space"): every variant of every generated
// program is refused with a diagnostic that is not an internal error, or
// compiles to kernels that glslang accepts, that pass spirv-val and whose
// stage interfaces match; the same program with its imports declared in
// reverse order means the same; shaders derived from a base that locks a
// world share its kernel. A failure prints the seed, the program and the
// decision map; `SPIRE_GEN_SEED=N` runs that seed alone.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "gen/campaign.h"
#include "gen/program_generator.h"

namespace spire::testgen {
namespace {

// Shards run as separate ctest tests, so `ctest -j2` uses both cores.
constexpr int kShards = 4;
constexpr int kDecisionMaps = 6;
#if defined(SPIRE_GEN_UNDER_SANITIZER)
constexpr uint32_t kSeedsPerShard = 30;  // our code under ASan and UBSan (Debug) is ~10x slower
constexpr uint64_t kMinVariantsPerShard = 200;
#else
constexpr uint32_t kSeedsPerShard = 120;
constexpr uint64_t kMinVariantsPerShard = 500;  // 4 shards: at least 2,000 variants
#endif

void expectNoFailures(const CampaignStats& stats) {
  for (const Failure& f : stats.failures) ADD_FAILURE() << f.format();
  EXPECT_EQ(stats.count(Verdict::InternalError), 0u) << stats.summaryLine();
  EXPECT_EQ(stats.count(Verdict::InvalidKernel), 0u) << stats.summaryLine();
  EXPECT_EQ(stats.count(Verdict::InterfaceMismatch), 0u) << stats.summaryLine();
  EXPECT_EQ(stats.count(Verdict::OrderDependentRoute), 0u) << stats.routesAndLocksLine();
  EXPECT_EQ(stats.count(Verdict::LockedKernelNotShared), 0u) << stats.routesAndLocksLine();
}

class GeneratorProperty : public testing::TestWithParam<int> {};

TEST_P(GeneratorProperty, EveryVariantIsRefusedCleanlyOrValid) {
  if (const char* seed = std::getenv("SPIRE_GEN_SEED")) {
    if (GetParam() != 0) GTEST_SKIP() << "SPIRE_GEN_SEED runs in shard 0";
    const auto value = static_cast<uint32_t>(std::stoul(seed));
    const CampaignStats stats = runSeed(value, kDecisionMaps);
    std::cout << generateProgram(value).text << stats.refusalTable() << stats.summaryLine() << "\n";
    expectNoFailures(stats);
    return;
  }
  CampaignStats stats;
  const uint32_t first = static_cast<uint32_t>(GetParam()) * kSeedsPerShard;
  for (uint32_t seed = first; seed < first + kSeedsPerShard; ++seed) stats.merge(runSeed(seed, kDecisionMaps));
  std::cout << stats.refusalTable() << stats.count(Verdict::Accepted) << " accepted\n"
            << stats.routesAndLocksLine() << "\n"
            << stats.summaryLine() << "\n";
  EXPECT_GE(stats.variants, kMinVariantsPerShard);
  // Most variants must get as far as kernels, or the property says little.
  EXPECT_GE(stats.count(Verdict::Accepted) * 2, stats.variants) << stats.refusalTable();
  expectNoFailures(stats);
}

INSTANTIATE_TEST_SUITE_P(Shards, GeneratorProperty, testing::Range(0, kShards));

}  // namespace
}  // namespace spire::testgen
