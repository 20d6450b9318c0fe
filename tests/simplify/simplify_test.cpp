// Automatic simplification: the rules on the typed tree (each rewrite keeps
// the expression's type; constants, built-ins and loops), [Immutable], the
// module it writes (it compiles, its variations are choices, the compiler
// generates different kernels for them), determinism, and the tool's errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <string>

#include "driver/compiler.h"
#include "simplify/rewrite_rules.h"
#include "simplify/simplification.h"
#include "simplify/simplify_tool.h"
#include "simplify_fixture.h"
#include "support/file_io.h"

namespace spire::simplify {
namespace {

namespace fs = std::filesystem;

class SimplifyTest : public SimplifyFixture {
 protected:
  std::vector<Rewrite> rewritesOf(const std::string& shaderName, const std::string& component) {
    const sem::Shader* shader = library_->model().findShader(shaderName);
    const sem::Component& c = shader->components[shader->componentByName.at(component)];
    return proposeRewrites(library_->model(), library_->sources(), *c.definitions.front().decl);
  }
  // The module written to `path`, compiled with its sources.
  static std::unique_ptr<ShaderLibrary> compiledModule(const std::string& path, const std::string& module) {
    EXPECT_TRUE(writeFileAtomically(path, module));
    auto library = std::make_unique<ShaderLibrary>(frontEnd());
    EXPECT_TRUE(library->addFile(path));
    EXPECT_TRUE(library->compile());
    return library;
  }
  // Whether a choice of `shader` offers `name`.
  static bool offers(const ShaderLibrary& library, const std::string& shader, const std::string& name) {
    for (const graph::Choice& choice : library.choices(shader)) {
      if (std::find(choice.names.begin(), choice.names.end(), name) != choice.names.end()) return true;
    }
    return false;
  }
};

constexpr const char* kShader = R"(using "pipelines/engine.spire";
shader S using EnginePipeline {
    @FrameUniform mat4 mvp;
    @MaterialUniform vec3 tint;
    @MaterialUniform float gain;
    vec4 projPos = mvp * vec4(vert_pos, 1.0);
    vec3 lit = tint * 0.5 + vec3(0.1);
    vec3 typed = vec3(1.0) * gain;
    float clamped = clamp(gain, 0.0, 1.0) * 2.0;
    float summed {
        float s = 0.0;
        for (int i = 0; i < 4; i++) { s += gain; }
        return s;
    }
    [Immutable] vec3 kept = tint * 0.5;
    vec4 output = vec4(lit + typed + kept, clamped + summed);
}
)";

TEST_F(SimplifyTest, RulesRewriteToExpressionsOfTheSameType) {
  load(kShader);
  std::vector<std::string> lit;
  for (const Rewrite& r : rewritesOf("S", "lit")) lit.push_back(r.rule + ": " + r.before + " -> " + r.replacement);
  EXPECT_EQ(lit, (std::vector<std::string>{"constant-operand: tint * 0.5 + vec3(0.1) -> (tint * 0.5)",
                                           "constant-operand: tint * 0.5 -> (tint)"}));
  // vec3(1.0) * gain is a vec3, gain a float: nothing of the same type to keep.
  EXPECT_TRUE(rewritesOf("S", "typed").empty());
  std::vector<std::string> clamped;
  for (const Rewrite& r : rewritesOf("S", "clamped")) clamped.push_back(r.before + " -> " + r.replacement);
  // The rewrite that removes more source comes first.
  EXPECT_EQ(clamped, (std::vector<std::string>{"clamp(gain, 0.0, 1.0) -> (gain)",
                                               "clamp(gain, 0.0, 1.0) * 2.0 -> (clamp(gain, 0.0, 1.0))"}));
  const std::vector<Rewrite> loop = rewritesOf("S", "summed");
  ASSERT_EQ(loop.size(), 1U);
  EXPECT_EQ(loop[0].rule, "loop-iteration");
  EXPECT_EQ(loop[0].before + " -> " + loop[0].replacement, "4 -> 3");
}

// Nothing inside an [Immutable] statement or block is rewritten, however
// deep, while the rest of the same definition still is.
TEST_F(SimplifyTest, ImmutableStatementsAndBlocksAreNeverRewritten) {
  load(R"(using "pipelines/engine.spire";
shader S using EnginePipeline {
    @FrameUniform mat4 mvp;
    @MaterialUniform float gain;
    vec4 projPos = mvp * vec4(vert_pos, 1.0);
    float guarded {
        [Immutable] float a = gain * 2.0;
        [Immutable] {
            a = clamp(a, 0.0, 1.0);
            for (int i = 0; i < 4; i++) { a += gain * 0.5; }
        }
        if (gain > 0.5) [Immutable] a = mix(a, gain, 0.25);
        for (int j = 0; j < 2; j++) [Immutable] { a -= gain + 1.0; }
        return a * 0.5;
    }
    vec4 output = vec4(guarded);
}
)");
  std::vector<std::string> rewrites;
  for (const Rewrite& r : rewritesOf("S", "guarded")) rewrites.push_back(r.rule + ": " + r.before);
  // The loop's iteration (a -= gain + 1.0, with j < 2 and j++: 4) saves more
  // than a * 0.5 (1).
  EXPECT_EQ(rewrites, (std::vector<std::string>{"loop-iteration: 2", "constant-operand: a * 0.5"}));

  auto result = simplifyS();
  ASSERT_TRUE(result) << result.error().message;
  ASSERT_EQ(result->variations.size(), 2U) << result->module;
  // The variation keeps the immutable statements byte for byte.
  EXPECT_NE(result->module.find("[Immutable] float a = gain * 2.0;"), std::string::npos) << result->module;
  EXPECT_NE(result->module.find("return (a);"), std::string::npos) << result->module;
}

TEST_F(SimplifyTest, TheModuleCompilesAndItsVariationsAreChoicesWithTheirOwnKernels) {
  ShaderLibrary& library = load(kShader);
  SimplifyOptions options;
  options.shader = "S";
  options.outputPath = (dir_ / "out" / "s_simplified.spire").string();
  options.frontEnd = frontEnd();
  auto result = simplifyShader(library, options);
  ASSERT_TRUE(result) << result.error().message;
  EXPECT_TRUE(result->dropped.empty());
  for (const Variation& v : result->variations) EXPECT_NE(v.component, "kept") << "[Immutable] is left alone";
  EXPECT_NE(result->module.find("using \"../s.spire\";"), std::string::npos) << result->module;
  EXPECT_NE(result->module.find("shader SSimplified : S {"), std::string::npos);
  EXPECT_NE(result->module.find("vec3 lit:simplified1 = (tint * 0.5);"), std::string::npos) << result->module;

  fs::create_directories(dir_ / "out");
  const std::unique_ptr<ShaderLibrary> compiled = compiledModule(options.outputPath, result->module);
  ShaderLibrary& simplified = *compiled;
  EXPECT_TRUE(offers(simplified, "SSimplified", "Fragment:simplified2"))
      << "a simplified variation is a choice like a written one";
  auto plain = compileVariant(simplified, "SSimplified", Decisions{{{"lit", "Fragment"}}, {}}, {});
  auto simpler = compileVariant(simplified, "SSimplified", Decisions{{{"lit", "Fragment:simplified2"}}, {}}, {});
  ASSERT_TRUE(plain && simpler);
  EXPECT_NE((*plain)->kernels.back().glsl, (*simpler)->kernels.back().glsl);
}

TEST_F(SimplifyTest, TheExamplesSimplifyDeterministically) {
  for (const std::string example : {"terrain", "couch"}) {
    ShaderLibrary library;
    ASSERT_TRUE(library.addFile("examples/" + example + ".spire"));
    ASSERT_TRUE(library.compile());
    SimplifyOptions options;
    options.shader = example == "terrain" ? "Terrain" : "Couch";
    options.outputPath = (dir_ / (example + "_simplified.spire")).string();
    auto first = simplifyShader(library, options);
    auto second = simplifyShader(library, options);
    ASSERT_TRUE(first && second) << (first ? second.error().message : first.error().message);
    EXPECT_EQ(first->module, second->module);
    EXPECT_GE(first->variations.size(), 4U) << example;
    EXPECT_TRUE(first->dropped.empty()) << first->dropped.front();
  }
}

TEST_F(SimplifyTest, TheToolWritesTheModuleAndRefusesWhatItCannotDo) {
  load(kShader);
  std::ostringstream out;
  std::ostringstream err;
  const std::string output = (dir_ / "m.spire").string();
  ASSERT_EQ(runSimplifyTool({source_.string(), "-I", SPIRE_SOURCE_DIR, "--shader", "S", "-o", output}, out, err), 0)
      << err.str();
  EXPECT_NE(out.str().find("spire-simplify: wrote "), std::string::npos) << out.str();
  EXPECT_TRUE(fs::exists(output));
  std::ostringstream err2;
  EXPECT_EQ(
      runSimplifyTool({source_.string(), "-I", SPIRE_SOURCE_DIR, "--shader", "S", "--component", "kept", "-o", output},
                      out, err2),
      1);
  EXPECT_EQ(err2.str(), "spire-simplify: error: 'kept' cannot be simplified: it is marked [Immutable]\n");
  std::ostringstream err3;
  EXPECT_EQ(runSimplifyTool({source_.string(), "-I", SPIRE_SOURCE_DIR, "--shader", "Nope", "-o", output}, out, err3),
            1);
  EXPECT_EQ(err3.str(), "spire-simplify: error: no shader named 'Nope'\n");
  const fs::path broken = dir_ / "broken.spire";
  std::ofstream(broken) << "shader X using Missing {}\n";
  std::ostringstream err4;
  EXPECT_EQ(runSimplifyTool({broken.string(), "--shader", "X", "-o", output}, out, err4), 1);
  EXPECT_NE(err4.str().find("broken.spire:1:"), std::string::npos) << err4.str();
}

constexpr const char* kLockedShader = R"(using "pipelines/engine.spire";
shader Base using EnginePipeline {
    @FrameUniform mat4 mvp;
    @MaterialUniform vec3 tint;
    vec4 projPos = mvp * vec4(vert_pos, 1.0);
    @Vertex vec3 shade = tint * 0.5 + vec3(0.1);
    @Fragment vec3 lit = tint * 0.25 + vec3(0.2);
    vec4 output = vec4(shade + lit, 1.0);
}
shader S : Base finalizes Vertex {
    @Fragment vec3 glow = tint * 0.75 + vec3(0.3);
}
)";

// A shader derived from one that finalizes a world may not redefine what
// that world may compute (paper section 6.2): such components are left out
// with why, never proposed and then dropped by the compile.
TEST_F(SimplifyTest, ComponentsALockedWorldKeepsAreLeftOutWithWhy) {
  load(kLockedShader);
  auto result = simplifyS();
  ASSERT_TRUE(result) << result.error().message;
  EXPECT_TRUE(result->dropped.empty()) << result->dropped.front();
  std::set<std::string> rewritten;
  for (const Variation& v : result->variations) rewritten.insert(v.component);
  EXPECT_EQ(rewritten, (std::set<std::string>{"glow", "lit"})) << result->module;
  ASSERT_EQ(result->lockedOut.size(), 1U);
  EXPECT_EQ(result->lockedOut.front(),
            "'shade' may be computed in world 'Vertex', which is finalized for shaders derived from 'S': they cannot "
            "redefine it");

  std::ostringstream out;
  std::ostringstream err;
  const std::string output = (dir_ / "m.spire").string();
  ASSERT_EQ(runSimplifyTool({source_.string(), "-I", SPIRE_SOURCE_DIR, "--shader", "S", "-o", output}, out, err), 0)
      << err.str();
  EXPECT_NE(out.str().find("spire-simplify: left out 1 component(s):\n  'shade' may be computed in world 'Vertex'"),
            std::string::npos)
      << out.str();
  std::ostringstream named;
  EXPECT_EQ(
      runSimplifyTool({source_.string(), "-I", SPIRE_SOURCE_DIR, "--shader", "S", "--component", "shade", "-o", output},
                      out, named),
      1);
  EXPECT_EQ(named.str(),
            "spire-simplify: error: 'shade' cannot be simplified: 'shade' may be computed in world 'Vertex', which is "
            "finalized for shaders derived from 'S': they cannot redefine it\n");
}

constexpr const char* kGroupShader = R"(using "pipelines/engine.spire";
shader A using EnginePipeline {
    @FrameUniform mat4 mvp;
    abstract vec3 tint;
    abstract float gain;
    vec4 projPos = mvp * vec4(vert_pos, 1.0);
    vec3 lit = tint * 0.5 + vec3(0.1);
    vec4 output = vec4(lit, gain);
}
shader B : A finalizes Fragment {
}
group G {
    shader A;
    optional shader B;
}
shader M : G {
    vec3 tint = vec3(1.0, 0.5, 0.25) * 0.5;
    float gain = 2.0;
}
)";

// A shader derived from a group (paper section 6.1) gets a module derived
// from it, which is a group's too: its variations are of what it defines
// itself, they must suit the shaders made from the required members, and
// an optional member they do not suit is left out, with the compiler's
// word on why.
TEST_F(SimplifyTest, AShaderDerivedFromAGroupGetsAModuleDerivedFromIt) {
  load(kGroupShader);
  SimplifyOptions options;
  options.shader = "M";
  options.outputPath = (dir_ / "m_simplified.spire").string();
  options.frontEnd = frontEnd();
  auto result = simplifyShader(*library_, options);
  ASSERT_TRUE(result) << result.error().message;
  EXPECT_TRUE(result->dropped.empty());
  ASSERT_EQ(result->variations.size(), 1U) << result->module;
  EXPECT_EQ(result->variations.front().name, "tint:simplified1") << "lit is A's, not M's";
  EXPECT_NE(result->module.find("shader MSimplified : M {"), std::string::npos) << result->module;
  ASSERT_EQ(result->membersLeftOut.size(), 1U);
  EXPECT_NE(result->membersLeftOut.front().find("optional group member 'M<B>' is left out of 'MSimplified'"),
            std::string::npos)
      << result->membersLeftOut.front();

  EXPECT_TRUE(offers(*compiledModule(options.outputPath, result->module), "MSimplified<A>", "Fragment:simplified1"));

  std::ostringstream out;
  std::ostringstream err;
  ASSERT_EQ(
      runSimplifyTool({source_.string(), "-I", SPIRE_SOURCE_DIR, "--shader", "M", "-o", options.outputPath}, out, err),
      0)
      << err.str();
  EXPECT_NE(out.str().find("spire-simplify: optional group member 'M<B>' is left out of 'MSimplified': "),
            std::string::npos)
      << out.str();

  options.components = {"lit"};
  auto named = simplifyShader(*library_, options);
  ASSERT_FALSE(named);
  EXPECT_EQ(named.error().message,
            "'lit' cannot be simplified: the group's members define it, each its own way, and the shader derived "
            "from the group does not");
}

// Variations go into a shader derived from the one simplified: an abstract
// one is refused, and a shader a group makes points to the one it is made
// for.
TEST_F(SimplifyTest, AbstractShadersAndTheShadersAGroupMakesAreRefusedWithWhy) {
  load(kGroupShader);
  const std::map<std::string, std::string> refusals{
      {"A",
       "'A' is abstract: it leaves 'tint', 'gain' to the shaders derived from it, and a shader derived from it to "
       "hold its variations would have to define them"},
      {"M<A>", "'M<A>' is one of the shaders that 'M' makes from the members of a group; simplify 'M'"},
      {"N", "no shader named 'N'"}};
  for (const auto& [shader, message] : refusals) {
    SimplifyOptions options;
    options.shader = shader;
    options.outputPath = (dir_ / "out.spire").string();
    options.frontEnd = frontEnd();
    auto result = simplifyShader(*library_, options);
    ASSERT_FALSE(result) << shader;
    EXPECT_EQ(result.error().message, message);
  }
}

}  // namespace
}  // namespace spire::simplify
