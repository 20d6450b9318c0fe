// Golden tests: each tests/golden/diagnostics/NAME.spire is compiled by spirec
// in-process and its exit code and complete stderr are compared exactly with
// NAME.expected. Run with SPIRE_UPDATE_GOLDENS=1 to rewrite the expectations
// after an intended change, then review the diff.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "driver/spirec.h"

namespace spire {
namespace {

namespace fs = std::filesystem;

const fs::path kGoldenDir = "tests/golden/diagnostics";

std::vector<std::string> goldenCases() {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(fs::path(SPIRE_SOURCE_DIR) / kGoldenDir)) {
    if (entry.path().extension() == ".spire") names.push_back(entry.path().stem().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

std::string readFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

class GoldenDiagnostics : public testing::TestWithParam<std::string> {};

TEST_P(GoldenDiagnostics, MatchesExpectedOutput) {
  // Relative paths keep the rendered locations independent of the checkout.
  fs::current_path(SPIRE_SOURCE_DIR);
  const fs::path source = kGoldenDir / (GetParam() + ".spire");
  const fs::path expectedPath = kGoldenDir / (GetParam() + ".expected");
  std::ostringstream out, err;
  const int exitCode = runSpirec({source.string()}, out, err);
  const std::string actual = "exit code: " + std::to_string(exitCode) + "\n" + err.str();
  if (std::getenv("SPIRE_UPDATE_GOLDENS")) {
    std::ofstream(expectedPath, std::ios::binary) << actual;
    GTEST_SKIP() << "updated " << expectedPath;
  }
  ASSERT_TRUE(fs::exists(expectedPath)) << "missing " << expectedPath << "; run with SPIRE_UPDATE_GOLDENS=1";
  EXPECT_EQ(actual, readFile(expectedPath));
  // Every golden case is an error case: one clear error, exit code 1.
  EXPECT_EQ(exitCode, kExitInputError);
}

INSTANTIATE_TEST_SUITE_P(Spirec, GoldenDiagnostics, testing::ValuesIn(goldenCases()),
                         [](const testing::TestParamInfo<std::string>& param) { return param.param; });

}  // namespace
}  // namespace spire
