// Golden tests: spirec runs in-process and its exit code, stdout and stderr
// are compared exactly with a checked-in `.expected` file.
//  - tests/golden/diagnostics/NAME.spire: every error class, one file each;
//  - tests/golden/choices/NAME.expected: `--choices` of examples/NAME.spire;
//  - decision files in examples/decisions/ and tests/golden/decisions/,
//    applied to examples/terrain.spire with --dump-placement.
// After an intended change, run with SPIRE_UPDATE_GOLDENS=1 to rewrite the
// expectations, then review the diff.
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

struct GoldenCase {
  std::string name;
  std::vector<std::string> args;
  fs::path expected;
  int exitCode;
};

// Failure messages name the case instead of dumping its bytes.
void PrintTo(const GoldenCase& golden, std::ostream* os) { *os << golden.name; }

std::vector<fs::path> filesIn(const fs::path& dir, const std::string& extension) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(fs::path(SPIRE_SOURCE_DIR) / dir)) {
    if (entry.path().extension() == extension) files.push_back(dir / entry.path().filename());
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::vector<GoldenCase> goldenCases() {
  std::vector<GoldenCase> cases;
  for (const fs::path& source : filesIn("tests/golden/diagnostics", ".spire")) {
    cases.push_back({"diagnostics_" + source.stem().string(), {source.string()},
                     fs::path(source).replace_extension(".expected"), 1});
  }
  for (const fs::path& example : filesIn("examples", ".spire")) {
    cases.push_back({"choices_" + example.stem().string(), {example.string(), "--choices"},
                     "tests/golden/choices" / example.stem().concat(".expected"), 0});
  }
  for (const std::string dir : {"examples/decisions", "tests/golden/decisions"}) {
    for (const fs::path& decisions : filesIn(dir, ".decisions")) {
      cases.push_back({"decisions_" + decisions.stem().string(),
                       {"examples/terrain.spire", "--decisions", decisions.string(), "--dump-placement"},
                       "tests/golden/decisions" / decisions.stem().concat(".expected"), 0});
    }
  }
  return cases;
}

std::string readFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

class Golden : public testing::TestWithParam<GoldenCase> {};

TEST_P(Golden, MatchesExpectedOutput) {
  // Relative paths keep the rendered locations independent of the checkout.
  fs::current_path(SPIRE_SOURCE_DIR);
  const GoldenCase& golden = GetParam();
  std::ostringstream out, err;
  const int exitCode = runSpirec(golden.args, out, err);
  const std::string actual = "exit code: " + std::to_string(exitCode) + "\n--- stdout\n" + out.str() +
                             "--- stderr\n" + err.str();
  if (std::getenv("SPIRE_UPDATE_GOLDENS")) {
    std::ofstream(golden.expected, std::ios::binary) << actual;
    GTEST_SKIP() << "updated " << golden.expected;
  }
  ASSERT_TRUE(fs::exists(golden.expected)) << "missing " << golden.expected << "; run with SPIRE_UPDATE_GOLDENS=1";
  EXPECT_EQ(actual, readFile(golden.expected));
  EXPECT_EQ(exitCode, golden.exitCode);
}

INSTANTIATE_TEST_SUITE_P(Spirec, Golden, testing::ValuesIn(goldenCases()),
                         [](const testing::TestParamInfo<GoldenCase>& param) { return param.param.name; });

// Kernels and reflection of the paper's Figure 3 variants of Terrain, one
// golden folder per decision file: tests/golden/kernels/<decisions>/.
class GoldenKernels : public testing::TestWithParam<fs::path> {};

TEST_P(GoldenKernels, MatchExpectedFiles) {
  fs::current_path(SPIRE_SOURCE_DIR);
  const fs::path decisions = GetParam();
  const fs::path out = fs::temp_directory_path() / ("spire_golden_" + decisions.stem().string());
  fs::remove_all(out);
  std::ostringstream stdoutText, stderrText;
  ASSERT_EQ(runSpirec({"examples/terrain.spire", "--decisions", decisions.string(), "-o", out.string(), "--emit=glsl"},
                      stdoutText, stderrText),
            kExitSuccess)
      << stderrText.str();
  EXPECT_EQ(stderrText.str(), "");
  const fs::path expectedDir = fs::path("tests/golden/kernels") / decisions.stem();
  std::vector<std::string> produced;
  for (const auto& entry : fs::directory_iterator(out / "Terrain")) produced.push_back(entry.path().filename().string());
  std::sort(produced.begin(), produced.end());
  if (std::getenv("SPIRE_UPDATE_GOLDENS")) {
    fs::remove_all(expectedDir);
    fs::create_directories(expectedDir);
    for (const std::string& name : produced) fs::copy_file(out / "Terrain" / name, expectedDir / name);
    fs::remove_all(out);
    GTEST_SKIP() << "updated " << expectedDir;
  }
  std::vector<std::string> expected;
  for (const auto& entry : fs::directory_iterator(expectedDir)) expected.push_back(entry.path().filename().string());
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(produced, expected);
  for (const std::string& name : expected) {
    EXPECT_EQ(readFile(out / "Terrain" / name), readFile(expectedDir / name)) << name;
  }
  fs::remove_all(out);
}

INSTANTIATE_TEST_SUITE_P(Spirec, GoldenKernels, testing::ValuesIn(filesIn("examples/decisions", ".decisions")),
                         [](const testing::TestParamInfo<fs::path>& param) { return param.param.stem().string(); });

}  // namespace
}  // namespace spire
