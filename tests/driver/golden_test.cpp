// Golden tests: spirec runs in-process and its exit code, stdout and stderr
// are compared exactly with a checked-in `.expected` file.
//  - tests/golden/diagnostics/NAME.spire: every error class, one file each;
//  - tests/golden/choices/NAME.expected: `--choices` of examples/NAME.spire;
//  - decision files in examples/decisions/ and tests/golden/decisions/,
//    applied to examples/terrain.spire with --dump-placement;
//  - decision files in examples/decisions/five_world/, applied to
//    examples/terrain_five_world.spire with --dump-placement
//    (tests/golden/decisions/five_world/NAME.expected);
//  - decision files in examples/decisions/couch/, applied to
//    examples/couch.spire with --dump-placement
//    (tests/golden/decisions/couch/NAME.expected);
//  - kernels and reflection of some of those variants (GoldenKernels below).
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
    cases.push_back({"diagnostics_" + source.stem().string(),
                     {source.string()},
                     fs::path(source).replace_extension(".expected"),
                     1});
  }
  for (const fs::path& example : filesIn("examples", ".spire")) {
    cases.push_back({"choices_" + example.stem().string(),
                     {example.string(), "--choices"},
                     "tests/golden/choices" / example.stem().concat(".expected"),
                     0});
  }
  for (const std::string dir : {"examples/decisions", "tests/golden/decisions"}) {
    for (const fs::path& decisions : filesIn(dir, ".decisions")) {
      cases.push_back({"decisions_" + decisions.stem().string(),
                       {"examples/terrain.spire", "--decisions", decisions.string(), "--dump-placement"},
                       "tests/golden/decisions" / decisions.stem().concat(".expected"),
                       0});
    }
  }
  for (const fs::path& decisions : filesIn("examples/decisions/five_world", ".decisions")) {
    cases.push_back({"decisions_five_world_" + decisions.stem().string(),
                     {"examples/terrain_five_world.spire", "--decisions", decisions.string(), "--dump-placement"},
                     "tests/golden/decisions/five_world" / decisions.stem().concat(".expected"),
                     0});
  }
  for (const fs::path& decisions : filesIn("examples/decisions/couch", ".decisions")) {
    cases.push_back({"decisions_couch_" + decisions.stem().string(),
                     {"examples/couch.spire", "--decisions", decisions.string(), "--dump-placement"},
                     "tests/golden/decisions/couch" / decisions.stem().concat(".expected"),
                     0});
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
  const std::string actual =
      "exit code: " + std::to_string(exitCode) + "\n--- stdout\n" + out.str() + "--- stderr\n" + err.str();
  if (std::getenv("SPIRE_UPDATE_GOLDENS")) {
    fs::create_directories(golden.expected.parent_path());
    std::ofstream(golden.expected, std::ios::binary) << actual;
    GTEST_SKIP() << "updated " << golden.expected;
  }
  ASSERT_TRUE(fs::exists(golden.expected)) << "missing " << golden.expected << "; run with SPIRE_UPDATE_GOLDENS=1";
  EXPECT_EQ(actual, readFile(golden.expected));
  EXPECT_EQ(exitCode, golden.exitCode);
}

INSTANTIATE_TEST_SUITE_P(Spirec, Golden, testing::ValuesIn(goldenCases()),
                         [](const testing::TestParamInfo<GoldenCase>& param) { return param.param.name; });

// Kernels and reflection of shader variants, one golden folder per decision
// file: the paper's Figure 3 variants of Terrain (every file in
// examples/decisions/, into tests/golden/kernels/<decisions>/) and the
// TerrainFive variants that use the compute worlds of FiveWorldPipeline (into
// tests/golden/kernels/five_world/<decisions>/). The other TerrainFive
// variants, lod0_full_quality and lod1_baked_albedo, generate the kernels of
// terrain_full_quality and terrain_baked_vertex_normal up to names, #line
// numbers and the order of declarations (same bindings and locations).
struct KernelCase {
  std::string name;
  fs::path source;
  fs::path decisions;
  std::string shaderDirectory;  // under spirec's -o directory
  fs::path expected;
};

void PrintTo(const KernelCase& golden, std::ostream* os) { *os << golden.name; }

std::vector<KernelCase> kernelCases() {
  std::vector<KernelCase> cases;
  for (const fs::path& decisions : filesIn("examples/decisions", ".decisions")) {
    cases.push_back({decisions.stem().string(), "examples/terrain.spire", decisions, "Terrain",
                     fs::path("tests/golden/kernels") / decisions.stem()});
  }
  for (const char* name : {"lod2_uniform_albedo", "vertex_baked_mix"}) {
    const fs::path decisions = fs::path("examples/decisions/five_world") / (std::string(name) + ".decisions");
    cases.push_back({std::string("five_world_") + name, "examples/terrain_five_world.spire", decisions, "TerrainFive",
                     fs::path("tests/golden/kernels/five_world") / name});
  }
  return cases;
}

class GoldenKernels : public testing::TestWithParam<KernelCase> {};

TEST_P(GoldenKernels, MatchExpectedFiles) {
  fs::current_path(SPIRE_SOURCE_DIR);
  const KernelCase& golden = GetParam();
  const fs::path out = fs::temp_directory_path() / ("spire_golden_" + golden.name);
  fs::remove_all(out);
  std::ostringstream stdoutText, stderrText;
  ASSERT_EQ(
      runSpirec({golden.source.string(), "--decisions", golden.decisions.string(), "-o", out.string(), "--emit=glsl"},
                stdoutText, stderrText),
      kExitSuccess)
      << stderrText.str();
  EXPECT_EQ(stderrText.str(), "");
  const fs::path producedDir = out / golden.shaderDirectory;
  std::vector<std::string> produced;
  for (const auto& entry : fs::directory_iterator(producedDir)) produced.push_back(entry.path().filename().string());
  std::sort(produced.begin(), produced.end());
  if (std::getenv("SPIRE_UPDATE_GOLDENS")) {
    fs::remove_all(golden.expected);
    fs::create_directories(golden.expected);
    for (const std::string& name : produced) fs::copy_file(producedDir / name, golden.expected / name);
    fs::remove_all(out);
    GTEST_SKIP() << "updated " << golden.expected;
  }
  std::vector<std::string> expected;
  for (const auto& entry : fs::directory_iterator(golden.expected))
    expected.push_back(entry.path().filename().string());
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(produced, expected);
  for (const std::string& name : expected) {
    EXPECT_EQ(readFile(producedDir / name), readFile(golden.expected / name)) << name;
  }
  fs::remove_all(out);
}

INSTANTIATE_TEST_SUITE_P(Spirec, GoldenKernels, testing::ValuesIn(kernelCases()),
                         [](const testing::TestParamInfo<KernelCase>& param) { return param.param.name; });

}  // namespace
}  // namespace spire
