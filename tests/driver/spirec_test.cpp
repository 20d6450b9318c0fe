#include "driver/spirec.h"
#include "spirec_run.h"
#include "support/diagnostic.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

namespace spire {
namespace {

namespace fs = std::filesystem;
using test::spirec;
using test::SpirecRun;

fs::path sourceDir() { return SPIRE_SOURCE_DIR; }

TEST(Spirec, HelpAndVersionSucceed) {
  const SpirecRun help = spirec({"--help"});
  EXPECT_EQ(help.exitCode, kExitSuccess);
  EXPECT_NE(help.out.find("--diagnostics-format"), std::string::npos);
  const SpirecRun version = spirec({"--version"});
  EXPECT_EQ(version.exitCode, kExitSuccess);
  EXPECT_EQ(version.out.rfind("spirec ", 0), 0u);
}

TEST(Spirec, BadUsageExitsWithTwo) {
  EXPECT_EQ(spirec({}).exitCode, kExitUsageError);
  EXPECT_EQ(spirec({"--no-such-flag", "a.spire"}).exitCode, kExitUsageError);
  EXPECT_EQ(spirec({"--diagnostics-format=xml", "a.spire"}).exitCode, kExitUsageError);
}

TEST(Spirec, IncludeDirectoriesAreSearchedAfterTheIncludingFolder) {
  const fs::path dir = fs::temp_directory_path() / "spirec_include_test";
  fs::create_directories(dir);
  const fs::path source = dir / "lit.spire";
  std::ofstream(source) << "using \"engine.spire\";\n"
                           "shader Lit using EnginePipeline {\n"
                           "  @FrameUniform mat4 matMVP;\n"
                           "  vec4 projPos = matMVP * vec4(vert_pos, 1.0);\n"
                           "  vec4 output = vec4(vert_normal, 1.0);\n"
                           "}\n";
  const SpirecRun without = spirec({source.string()});
  EXPECT_EQ(without.exitCode, kExitInputError);
  EXPECT_NE(without.err.find("E1101"), std::string::npos) << without.err;
  const SpirecRun with = spirec({source.string(), "-I", (sourceDir() / "pipelines").string(), "--choices"});
  EXPECT_EQ(with.exitCode, kExitSuccess) << with.err;
  fs::remove_all(dir);
}

// --pipeline retargets: the Terrain example, unedited, gets the multi-rate
// pipeline's worlds as choices and its kernels.
TEST(Spirec, PipelineRetargetsEveryUsingShader) {
  const std::string terrain = (sourceDir() / "examples/terrain.spire").string();
  const std::string multiRate = (sourceDir() / "pipelines/multi_rate.spire").string();
  const SpirecRun choices = spirec({terrain, multiRate, "--pipeline", "MultiRatePipeline", "--choices"});
  ASSERT_EQ(choices.exitCode, kExitSuccess) << choices.err;
  EXPECT_NE(choices.out.find("Terrain.albedo = {PrebakeUniform,PrebakeVertex,PrebakeTex,LowResVertex,LowResFragment,"
                             "Vertex,Fragment}"),
            std::string::npos)
      << choices.out;
  const SpirecRun original = spirec({terrain, multiRate, "--choices"});
  EXPECT_EQ(original.out.find("LowResFragment"), std::string::npos) << original.out;
  EXPECT_EQ(spirec({terrain, "--pipeline", ""}).exitCode, kExitUsageError);
  const SpirecRun unknown = spirec({terrain, "--pipeline", "MultiRatePipeline"});
  EXPECT_EQ(unknown.exitCode, kExitInputError);
  EXPECT_NE(unknown.err.find("cannot retarget 'Terrain' to pipeline 'MultiRatePipeline'"), std::string::npos)
      << unknown.err;
}

TEST(Spirec, KernelsAreWrittenOnlyWhenEveryShaderCompiles) {
  const fs::path dir = fs::temp_directory_path() / "spirec_partial_test";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path source = dir / "two.spire";
  std::ofstream(source) << "using \"" << (sourceDir() / "pipelines/engine.spire").string() << "\";\n"
                        << "shader Good using EnginePipeline {\n"
                           "  @FrameUniform mat4 matMVP;\n"
                           "  vec4 projPos = matMVP * vec4(vert_pos, 1.0);\n"
                           "  vec4 output = vec4(vert_normal, 1.0);\n"
                           "}\n"
                           "shader Bad using EnginePipeline {\n"
                           "  @FrameUniform mat4 matMVP;\n"
                           "  vec4 projPos = matMVP * vec4(vert_pos, 1.0);\n"
                           "  @PrebakeTex int cell = int(vert_uv.x * 8.0);\n"
                           "  vec4 output = vec4(float(cell));\n"
                           "}\n";
  const SpirecRun run = spirec({source.string(), "-o", (dir / "out").string(), "--emit=glsl"});
  EXPECT_EQ(run.exitCode, kExitInputError);
  EXPECT_NE(run.err.find("E6001"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(dir / "out")) << "a failed run wrote kernels";
  const SpirecRun good = spirec({source.string(), "-o", (dir / "out").string(), "--shader", "Good"});
  EXPECT_EQ(good.exitCode, kExitSuccess) << good.err;
  EXPECT_TRUE(fs::exists(dir / "out/Good/Fragment.spv"));
  EXPECT_TRUE(fs::exists(dir / "out/Good/reflection.json"));
  fs::remove_all(dir);
}

TEST(Spirec, MissingInputFileIsAnInputError) {
  const SpirecRun run = spirec({"does/not/exist.spire"});
  EXPECT_EQ(run.exitCode, kExitInputError);
  EXPECT_NE(run.err.find("E1101"), std::string::npos);
}

TEST(Spirec, EveryExampleCompilesWithoutAnyDiagnostic) {
  size_t examples = 0;
  for (const auto& entry : fs::directory_iterator(sourceDir() / "examples")) {
    if (entry.path().extension() != ".spire") continue;
    ++examples;
    const SpirecRun run = spirec({entry.path().string()});
    EXPECT_EQ(run.exitCode, kExitSuccess) << entry.path();
    EXPECT_EQ(run.err, "") << entry.path();
  }
  EXPECT_GE(examples, 2u);
}

TEST(Spirec, JsonDiagnosticsCarryCodeAndLocation) {
  const fs::path source = sourceDir() / "tests/golden/diagnostics/undefined_identifier.spire";
  const SpirecRun run = spirec({"--diagnostics-format=json", source.string()});
  EXPECT_EQ(run.exitCode, kExitInputError);
  const auto json = nlohmann::json::parse(run.err);
  ASSERT_EQ(json["diagnostics"].size(), 1u);
  const auto& d = json["diagnostics"][0];
  EXPECT_EQ(d["code"], "E3001");
  EXPECT_EQ(d["severity"], "error");
  EXPECT_EQ(d["range"]["line"], 7);
  EXPECT_EQ(d["range"]["column"], 27);
  EXPECT_EQ(json["errorCount"], 1);
}

TEST(Spirec, TerrainChoicesMatchThePaper) {
  const fs::path terrain = sourceDir() / "examples/terrain.spire";
  const SpirecRun first = spirec({terrain.string(), "--choices"});
  ASSERT_EQ(first.exitCode, kExitSuccess) << first.err;
  // The paper's Listing 2 (top), with projPos pinned to Vertex by the
  // pipeline and therefore not a choice.
  EXPECT_EQ(first.out,
            "Terrain.mixFactor = {PrebakeTex,Vertex,Fragment}\n"
            "Terrain.albedo = {PrebakeTex,Vertex,Fragment}\n"
            "Terrain.normal = {Vertex,Fragment}\n"
            "Terrain.lighting = {Vertex:basic,Fragment:basic,Vertex:ggx,Fragment:ggx}\n");
  EXPECT_EQ(first.out, spirec({terrain.string(), "--choices"}).out);
}

TEST(Spirec, ChoicesFileIsWrittenWhole) {
  const fs::path dir = fs::temp_directory_path() / "spirec_choices_test";
  fs::create_directories(dir);
  const fs::path target = dir / "terrain.choices";
  const SpirecRun run = spirec({(sourceDir() / "examples/terrain.spire").string(), "--choices", target.string()});
  ASSERT_EQ(run.exitCode, kExitSuccess) << run.err;
  std::ifstream in(target);
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_NE(text.str().find("Terrain.albedo"), std::string::npos);
  // No temporary is left beside the output.
  size_t files = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir)) ++files;
  EXPECT_EQ(files, 1u);
  fs::remove_all(dir);
}

TEST(Spirec, UnwritableChoicesPathFailsCleanly) {
  const SpirecRun run =
      spirec({(sourceDir() / "examples/terrain.spire").string(), "--choices", "/nonexistent/dir/x.choices"});
  EXPECT_EQ(run.exitCode, kExitInputError);
  EXPECT_NE(run.err.find("cannot write"), std::string::npos);
}

TEST(Spirec, ErrorLimitCapsOutput) {
  std::string source = "pipeline P { world W : \"GLSL\" export standardExport; }\n";
  for (int i = 0; i < 100; ++i) source += "shader S" + std::to_string(i) + " using Q {}\n";
  const fs::path path = fs::temp_directory_path() / "spirec_many_errors.spire";
  std::ofstream(path) << source;
  const SpirecRun run = spirec({path.string(), "--max-errors", "5"});
  EXPECT_EQ(run.exitCode, kExitInputError);
  EXPECT_NE(run.err.find("too many errors"), std::string::npos);
  fs::remove(path);
}

}  // namespace
}  // namespace spire

namespace spire {
namespace {

TEST(Docs, DiagnosticsPageListsEveryCode) {
  std::ifstream in(std::filesystem::path(SPIRE_SOURCE_DIR) / "docs/diagnostics.md");
  std::stringstream text;
  text << in.rdbuf();
  for (DiagCode code : allDiagCodes()) {
    const std::string name(diagCodeInfo(code).name);
    EXPECT_NE(text.str().find("| " + name + " |"), std::string::npos) << name << " is missing from docs/diagnostics.md";
  }
}

}  // namespace
}  // namespace spire
