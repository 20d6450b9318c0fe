// The spirec flags that fit it into a build: --depfile, -Werror and --quiet,
// and the Spire library found through SpirecEnvironment (what an installed
// spirec finds beside itself).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "driver/spirec.h"
#include "spirec_run.h"
#include "support/file_io.h"

namespace spire {
namespace {

namespace fs = std::filesystem;
using test::spirec;
using test::SpirecRun;

// lit.spire uses shared.spire (next to it) and the engine pipeline from the
// Spire library; a folder name with a space and a '#' shows the depfile's
// escaping.
class BuildIntegration : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("spire build#" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
            std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    std::ofstream(dir_ / "shared.spire") << "float halve(float x) { return x * 0.5; }\n";
    std::ofstream(dir_ / "lit.spire") << "using \"shared.spire\";\n"
                                         "using \"pipelines/engine.spire\";\n"
                                         "shader Lit using EnginePipeline {\n"
                                         "  @FrameUniform mat4 matMVP;\n"
                                         "  vec4 projPos = matMVP * vec4(vert_pos, 1.0);\n"
                                         "  float h = halve(vert_uv.x);\n"
                                         "  vec4 output = vec4(vert_normal * h, 1.0);\n"
                                         "}\n";
    // One decision that applies and one with an unknown world (W5001).
    std::ofstream(dir_ / "lit.decisions") << "Lit.h = Vertex\nLit.projPos = Vertx\n";
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  // spirec on lit.spire with the source tree as the Spire library.
  SpirecRun run(std::vector<std::string> args) const {
    args.insert(args.begin(), path("lit.spire"));
    return spirec(args, SpirecEnvironment{SPIRE_SOURCE_DIR});
  }
  // `path` as a depfile spells it.
  std::string escaped(const std::string& name) const {
    std::string text = path(name);
    for (size_t at = text.find_first_of(" #"); at != std::string::npos; at = text.find_first_of(" #", at + 2)) {
      text.insert(at, "\\");
    }
    return text;
  }

  fs::path dir_;
};

std::string readText(const std::string& file) { return readWholeFile(file).value_or(""); }

TEST_F(BuildIntegration, DepfileListsEverySourceUsingFileAndDecisionFile) {
  const SpirecRun compiled = run({"-o", path("out"), "--emit=glsl", "--depfile", path("lit.d")});
  ASSERT_EQ(compiled.exitCode, kExitSuccess) << compiled.err;
  const std::string engine = (fs::path(SPIRE_SOURCE_DIR) / "pipelines/engine.spire").string();
  EXPECT_EQ(readText(path("lit.d")), escaped("out") + ": \\\n  " + escaped("lit.spire") + " \\\n  " +
                                         escaped("shared.spire") + " \\\n  " + engine + "\n");
  const SpirecRun decided = run({"--decisions", path("lit.decisions"), "--choices", path("lit.choices"), "--depfile",
                                 path("lit.d"), "--depfile-target", "shaders.stamp"});
  ASSERT_EQ(decided.exitCode, kExitSuccess) << decided.err;
  const std::string depfile = readText(path("lit.d"));
  EXPECT_EQ(depfile.rfind("shaders.stamp: \\\n", 0), 0u) << depfile;
  EXPECT_NE(depfile.find(escaped("shared.spire") + " \\\n"), std::string::npos) << depfile;
  EXPECT_NE(depfile.find("  " + escaped("lit.decisions") + "\n"), std::string::npos) << depfile;
}

TEST_F(BuildIntegration, DepfileTargetDefaultsToTheChoiceFileAndIsRequired) {
  ASSERT_EQ(run({"--choices", path("lit.choices"), "--depfile", path("lit.d")}).exitCode, kExitSuccess);
  EXPECT_EQ(readText(path("lit.d")).rfind(escaped("lit.choices") + ": \\\n", 0), 0u);
  const SpirecRun noTarget = run({"--choices", "--depfile", path("other.d")});
  EXPECT_EQ(noTarget.exitCode, kExitUsageError);
  EXPECT_NE(noTarget.err.find("--depfile needs a target"), std::string::npos) << noTarget.err;
  EXPECT_EQ(run({"--depfile-target", "x", "--choices"}).exitCode, kExitUsageError);
  EXPECT_EQ(run({"--depfile", "", "-o", path("out")}).exitCode, kExitUsageError);
  EXPECT_FALSE(fs::exists(path("other.d")));
}

// With -Werror a warning fails the run and nothing is written: no kernels,
// no choice file, no depfile.
TEST_F(BuildIntegration, WarningWithWerrorExitsNonZeroAndWritesNothing) {
  const std::vector<std::string> args = {"--decisions", path("lit.decisions"), "-o",        path("out"),
                                         "--depfile",   path("lit.d"),         "--choices", path("lit.choices")};
  const SpirecRun lenient = run(args);
  ASSERT_EQ(lenient.exitCode, kExitSuccess) << lenient.err;
  EXPECT_NE(lenient.err.find("warning[W5001]"), std::string::npos) << lenient.err;
  for (const char* output : {"out", "lit.d", "lit.choices"}) fs::remove_all(path(output));
  std::vector<std::string> strict = args;
  strict.push_back("-Werror");
  const SpirecRun failed = run(strict);
  EXPECT_EQ(failed.exitCode, kExitInputError);
  EXPECT_NE(failed.err.find("error[W5001]"), std::string::npos) << failed.err;
  for (const char* output : {"out", "lit.d", "lit.choices"}) EXPECT_FALSE(fs::exists(path(output))) << output;
}

TEST_F(BuildIntegration, QuietPrintsErrorsOnly) {
  const std::vector<std::string> args = {"--decisions", path("lit.decisions"), "--choices", path("lit.choices")};
  for (const char* flag : {"--quiet", "-q"}) {
    std::vector<std::string> quiet = args;
    quiet.push_back(flag);
    const SpirecRun run1 = run(quiet);
    EXPECT_EQ(run1.exitCode, kExitSuccess);
    EXPECT_EQ(run1.err, "") << flag;
  }
  std::vector<std::string> json = args;
  json.insert(json.end(), {"--quiet", "--diagnostics-format=json"});
  const SpirecRun quietJson = run(json);
  EXPECT_EQ(quietJson.err.find("W5001"), std::string::npos) << quietJson.err;
  EXPECT_NE(quietJson.err.find("\"warningCount\": 0"), std::string::npos) << quietJson.err;
  std::vector<std::string> strict = args;
  strict.insert(strict.end(), {"--quiet", "-Werror"});
  const SpirecRun failed = run(strict);
  EXPECT_EQ(failed.exitCode, kExitInputError);
  EXPECT_NE(failed.err.find("error[W5001]"), std::string::npos) << failed.err;
}

// `using "pipelines/..."` resolves in the Spire library, after -I; without
// one it is not found.
TEST_F(BuildIntegration, SpireLibraryIsSearchedAfterIncludeDirectories) {
  const SpirecRun without = spirec({path("lit.spire"), "--choices"});
  EXPECT_EQ(without.exitCode, kExitInputError);
  EXPECT_NE(without.err.find("cannot open included file 'pipelines/engine.spire'"), std::string::npos) << without.err;
  EXPECT_EQ(run({"--choices"}).exitCode, kExitSuccess);
  fs::create_directories(dir_ / "inc/pipelines");
  std::ofstream(dir_ / "inc/pipelines/engine.spire") << "pipeline Broken {\n";
  const SpirecRun shadowed = run({"--choices", "-I", path("inc")});
  EXPECT_EQ(shadowed.exitCode, kExitInputError) << "-I is searched before the library";
}

TEST(SpirecHelp, ListsTheBuildFlags) {
  const SpirecRun help = spirec({"--help"});
  for (const char* flag : {"--depfile FILE", "--depfile-target NAME", "-q,--quiet", "--warnings-as-errors"}) {
    EXPECT_NE(help.out.find(flag), std::string::npos) << flag;
  }
}

}  // namespace
}  // namespace spire
