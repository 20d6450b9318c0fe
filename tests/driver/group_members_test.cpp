// Shaders derived from groups and shared bases, past semantic analysis:
// optional members that fail later are left out (W4101), and a base's
// decisions appear once in the choice file of all its derived shaders.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/test_pipeline.h"
#include "driver/shader_library.h"
#include "driver/spirec.h"
#include "support/diagnostic_renderer.h"

namespace spire {
namespace {

namespace fs = std::filesystem;

using testing_util::kPipeline;

// Three members that differ only in where `shade` comes from. Material's
// `k` needs `shade` in Bake, which VertexShade cannot give (E4015); its
// world-less `mixed` needs `shade` (Bake) and `v` (Vertex) together, which
// meet only in Fragment, and Locked finalizes Fragment (E4014).
constexpr const char* kMembers = R"(
shader Common using P {
  @Uniform mat4 mvp;
  vec4 projPos = mvp * vec4(pos, 1.0);
  abstract vec4 color;
  vec4 output = color;
}
shader HQ : Common { @Uniform float shade; }
shader VertexShade : Common { @Vertex float shade = 0.5; }
shader Locked : Common finalizes Fragment { @Bake float shade = 0.5; }
)";

constexpr const char* kMaterialBody = R"( {
  @Bake float k = shade * 2.0;
  @Vertex float v = pos.x;
  float mixed = shade + v;
  vec4 color = vec4(k, mixed, 0.0, 1.0);
}
)";

struct Library {
  std::unique_ptr<ShaderLibrary> library;
  bool ok = false;

  std::vector<std::string> codes() const {
    std::vector<std::string> result;
    for (const Diagnostic& d : library->diagnostics().all()) result.emplace_back(diagCodeInfo(d.code).name);
    return result;
  }
  std::string rendered() const {
    return renderDiagnostics(library->sources(), library->diagnostics(), DiagnosticFormat::Text);
  }
};

Library compileLibrary(const std::string& source) {
  Library l;
  l.library = std::make_unique<ShaderLibrary>();
  l.library->addSource("groups.spire", std::string(kPipeline) + kMembers + source);
  l.ok = l.library->compile();
  return l;
}

TEST(OptionalGroupMembers, AMemberFailingOnWorldAvailabilityIsLeftOutWithTheReason) {
  const Library l = compileLibrary(std::string("group Family { shader HQ; optional shader VertexShade; optional shader "
                                               "Locked; }\nshader Material : Family") +
                                   kMaterialBody);
  ASSERT_TRUE(l.ok) << l.rendered();
  EXPECT_EQ(l.library->shaderNames(), std::vector<std::string>{"Material<HQ>"});
  ASSERT_EQ(l.codes(), (std::vector<std::string>{"W4101", "W4101"})) << l.rendered();
  const std::string text = l.rendered();
  EXPECT_NE(text.find("optional group member 'VertexShade' is left out of 'Material': 'shade' is not available in "
                      "world 'Bake'"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("optional group member 'Locked' is left out of 'Material': component 'mixed' can be defined "
                      "nowhere"),
            std::string::npos)
      << text;
  // Each original error is a note at its own location.
  const auto& vertexShade = l.library->diagnostics().all()[0];
  ASSERT_FALSE(vertexShade.notes.empty());
  EXPECT_NE(vertexShade.notes[0].message.find("error[E4015]"), std::string::npos);
  EXPECT_EQ(l.library->sources().text(vertexShade.notes[0].range), "shade");
  const auto& locked = l.library->diagnostics().all()[1];
  ASSERT_FALSE(locked.notes.empty());
  EXPECT_NE(locked.notes[0].message.find("error[E4014]"), std::string::npos);
  EXPECT_EQ(l.library->sources().text(locked.notes[0].range), "mixed");
}

TEST(OptionalGroupMembers, ARequiredMemberThatFailsStillFailsTheCompile) {
  const Library vertex = compileLibrary(std::string("group Family { shader VertexShade; optional shader HQ; optional "
                                                    "shader Locked; }\nshader Material : Family") +
                                        kMaterialBody);
  EXPECT_FALSE(vertex.ok);
  EXPECT_EQ(vertex.codes(), (std::vector<std::string>{"E4015", "W4101"})) << vertex.rendered();
  const Library locked = compileLibrary(std::string("group Family { shader Locked; optional shader HQ; optional "
                                                    "shader VertexShade; }\nshader Material : Family") +
                                        kMaterialBody);
  EXPECT_FALSE(locked.ok);
  EXPECT_EQ(locked.codes(), (std::vector<std::string>{"E4014", "W4101"})) << locked.rendered();
}

TEST(OptionalGroupMembers, SpirecWarnsAndCompilesTheOtherMembers) {
  const fs::path dir = fs::temp_directory_path() / "spire_optional_members";
  fs::create_directories(dir);
  const fs::path source = dir / "groups.spire";
  std::ofstream(source) << kPipeline << kMembers
                        << "group Family { shader HQ; optional shader VertexShade; optional shader Locked; }\n"
                        << "shader Material : Family" << kMaterialBody;
  std::ostringstream out, err;
  EXPECT_EQ(runSpirec({source.string(), "-o", (dir / "out").string(), "--emit=glsl"}, out, err), kExitSuccess)
      << err.str();
  EXPECT_NE(err.str().find("warning[W4101]: optional group member 'VertexShade'"), std::string::npos) << err.str();
  EXPECT_TRUE(fs::exists(dir / "out" / "Material-HQ" / "reflection.json"));
  EXPECT_FALSE(fs::exists(dir / "out" / "Material-VertexShade"));
  fs::remove_all(dir);
}

// Two shaders deriving from one base: the base's `nDotL` is Vertex-only in
// VertexLit and free in FragmentLit; `ambient` is free in both.
constexpr const char* kSharedBase = R"(
shader Lit using P {
  @Uniform mat4 mvp; @Uniform vec3 light;
  vec4 projPos = mvp * vec4(pos, 1.0);
  float nDotL = max(dot(normalize(light), vec3(0.0, 0.0, 1.0)), 0.0);
  float ambient = light.x * 0.1;
  abstract vec4 color;
  vec4 output = color + vec4(ambient);
}
shader VertexLit : Lit { @Vertex float lit = nDotL * 2.0; vec4 color = vec4(lit); }
shader FragmentLit : Lit { @Fragment float lit = nDotL * 2.0; vec4 color = vec4(lit); }
)";

struct SpirecRun {
  int exitCode;
  std::string out;
  std::string err;
};

SpirecRun spirecOnSource(const std::string& text, std::vector<std::string> args) {
  // One folder per test: CTest runs the tests of this file in parallel processes.
  const fs::path dir = fs::temp_directory_path() / (std::string("spire_shared_base_") +
                                                    ::testing::UnitTest::GetInstance()->current_test_info()->name());
  fs::create_directories(dir);
  std::ofstream(dir / "lit.spire") << text;
  std::ofstream(dir / "choice.decisions") << "Lit.nDotL = Vertex\n";
  for (std::string& a : args) {
    if (a == "DECISIONS") a = (dir / "choice.decisions").string();
  }
  args.insert(args.begin(), (dir / "lit.spire").string());
  std::ostringstream out, err;
  const int code = runSpirec(args, out, err);
  fs::remove_all(dir);
  return {code, out.str(), err.str()};
}

TEST(SharedBaseChoices, ABaseDecisionIsListedOnceWithWhatEveryDerivedShaderAllows) {
  const SpirecRun run = spirecOnSource(std::string(kPipeline) + kSharedBase, {"--choices"});
  ASSERT_EQ(run.exitCode, kExitSuccess) << run.err;
  EXPECT_EQ(run.out,
            "// Bake is possible only for FragmentLit\n"
            "// Fragment is possible only for FragmentLit\n"
            "Lit.nDotL = {Vertex}\n"
            "Lit.ambient = {Bake,Vertex,Fragment}\n"
            "VertexLit.color = {Vertex,Fragment}\n");
}

TEST(SharedBaseChoices, WithoutAnAlternativeForAllOnlyTheCommentsAreWritten) {
  const std::string bakeLit = "shader BakeLit : Lit { @Bake float lit = nDotL * 2.0; vec4 color = vec4(lit); }\n";
  const SpirecRun run = spirecOnSource(std::string(kPipeline) + kSharedBase + bakeLit, {"--choices"});
  ASSERT_EQ(run.exitCode, kExitSuccess) << run.err;
  EXPECT_EQ(run.out.substr(0, run.out.find("Lit.ambient")),
            "// Vertex is possible only for VertexLit, FragmentLit\n"
            "// Bake is possible only for FragmentLit, BakeLit\n"
            "// Fragment is possible only for FragmentLit\n");
}

TEST(SharedBaseChoices, ADecisionWithTheBaseKeyAppliesToEveryDerivedShader) {
  const SpirecRun run =
      spirecOnSource(std::string(kPipeline) + kSharedBase, {"--decisions", "DECISIONS", "--dump-placement"});
  ASSERT_EQ(run.exitCode, kExitSuccess) << run.err;
  EXPECT_EQ(run.err, "");
  const size_t vertexLit = run.out.find("// variant of VertexLit");
  const size_t fragmentLit = run.out.find("// variant of FragmentLit");
  ASSERT_NE(vertexLit, std::string::npos) << run.out;
  ASSERT_NE(fragmentLit, std::string::npos) << run.out;
  const std::string first = run.out.substr(vertexLit, fragmentLit - vertexLit);
  const std::string second = run.out.substr(fragmentLit);
  EXPECT_NE(first.find("Lit.nDotL = Vertex"), std::string::npos) << first;
  EXPECT_NE(second.find("Lit.nDotL = Vertex"), std::string::npos) << second;
}

TEST(SharedBaseChoices, TwoShadersOnALockedBaseShareItsDecisionLine) {
  // The paper's Listing 4 with a second material on the same group.
  const fs::path dir = fs::temp_directory_path() / "spire_shared_locked_base";
  fs::create_directories(dir);
  std::ofstream(dir / "rock.spire") << "shader RockLOD : BaseMaterial {\n"
                                       "    @MaterialUniform sampler2D rockMap;\n"
                                       "    vec4 albedo = texture(rockMap, vert_uv);\n"
                                       "    vec3 normal = vert_normal;\n"
                                       "}\n";
  std::ostringstream out, err;
  const std::string library = std::string(SPIRE_SOURCE_DIR) + "/examples/lod_library.spire";
  ASSERT_EQ(runSpirec({library, (dir / "rock.spire").string(), "--choices"}, out, err), kExitSuccess) << err.str();
  fs::remove_all(dir);
  const std::string choices = out.str();
  const size_t first = choices.find("BaseMaterialLQ.nDotL = {Vertex,Fragment}\n");
  EXPECT_NE(first, std::string::npos) << choices;
  EXPECT_EQ(choices.find("BaseMaterialLQ.nDotL", first + 1), std::string::npos) << choices;
}

}  // namespace
}  // namespace spire
