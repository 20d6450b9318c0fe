// Every minimized failure the generator found (tests/gen/regressions/, listed
// in tests/gen/FINDINGS.md), checked with the generator's property in both
// import orders: one ctest test per `.spire` file, with the `.decisions`
// file of the same name (if any).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "gen/campaign.h"
#include "support/file_io.h"

namespace spire::testgen {
namespace {

namespace fs = std::filesystem;

const fs::path kDir = fs::path(SPIRE_SOURCE_DIR) / "tests" / "gen" / "regressions";

std::vector<std::string> caseNames() {
  std::vector<std::string> names;
  if (!fs::is_directory(kDir)) return names;
  for (const auto& entry : fs::directory_iterator(kDir)) {
    if (entry.path().extension() == ".spire") names.push_back(entry.path().stem().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

class GeneratorRegression : public testing::TestWithParam<std::string> {};

TEST_P(GeneratorRegression, IsRefusedCleanlyOrValid) {
  const fs::path spire = kDir / (GetParam() + ".spire");
  const auto source = readWholeFile(spire.string());
  ASSERT_TRUE(source) << spire;
  const auto decisions = readWholeFile((kDir / (GetParam() + ".decisions")).string());
  ProgramChecker checker(*source, spire.string());
  ProgramChecker reordered(withImportsReversed(*source), spire.string(), false);
  const VariantReport front = checkFrontEnd(checker, reordered);
  ASSERT_FALSE(front.failed()) << verdictName(front.verdict) << "\n" << front.detail;
  if (front.verdict != Verdict::Accepted) return;  // refused cleanly in both orders
  for (const VariantReport& r : checkVariants(checker, reordered, decisions.value_or(""))) {
    EXPECT_FALSE(r.failed()) << r.shader << ": " << verdictName(r.verdict) << "\n" << r.detail;
  }
}

INSTANTIATE_TEST_SUITE_P(Cases, GeneratorRegression, testing::ValuesIn(caseNames()),
                         [](const testing::TestParamInfo<std::string>& param) { return param.param; });
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(GeneratorRegression);

}  // namespace
}  // namespace spire::testgen
