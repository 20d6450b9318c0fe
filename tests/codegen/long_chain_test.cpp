// Long operator chains, as node-graph tools and the simplifier generate them:
// the GLSL writer computes them in steps of temporaries so that glslang, which
// recurses along a chain, compiles them; where no temporary can take a chain,
// a too-long one is an error instead of a crash.
#include <gtest/gtest.h>

#include <regex>
#include <string>

#include "codegen/glsl_writer.h"
#include "codegen/kernel_generator.h"
#include "codegen/spirv_compiler.h"
#include "driver/shader_library.h"
#include "support/diagnostic_renderer.h"

namespace spire::codegen {
namespace {

// `terms` operands over `operand`, with the operators cycling through
// `operators` (mixed precedence makes the left spine change operator).
std::string chain(int terms, const std::string& operand, const std::vector<std::string>& operators) {
  std::string text = operand;
  for (int i = 1; i < terms; ++i) text += " " + operators[static_cast<size_t>(i) % operators.size()] + " " + operand;
  return text;
}

std::string shaderWith(const std::string& functions, const std::string& body) {
  return "using \"" + std::string(SPIRE_SOURCE_DIR) + "/pipelines/engine.spire\";\n" + functions +
         "shader S using EnginePipeline {\n"
         "  @MaterialUniform float a;\n"
         "  @FrameUniform mat4 matMVP;\n"
         "  vec4 projPos = matMVP * vec4(vert_pos, 1.0);\n" +
         body + "}\n";
}

struct Generated {
  std::string fragment;     // empty when generation failed
  std::string diagnostics;  // rendered
};

// The Fragment kernel of the default variant, checked by glslang and spirv-val.
Generated fragmentOf(const std::string& source) {
  ShaderLibrary library;
  library.addSource("chain.spire", source);
  Generated result;
  if (!library.compile()) {
    result.diagnostics = renderDiagnostics(library.sources(), library.diagnostics(), DiagnosticFormat::Text);
    return result;
  }
  const auto variant = library.buildVariant("S", {});
  if (!variant) return result;
  const auto kernels =
      generateKernels(library.model(), library.sources(), *variant, StrategyRegistry::builtin(), library.diagnostics());
  result.diagnostics = renderDiagnostics(library.sources(), library.diagnostics(), DiagnosticFormat::Text);
  if (!kernels) return result;
  for (const Kernel& kernel : kernels->kernels) {
    const SpirvResult spirv = compileGlslToSpirv(kernel.stage, kernel.glsl, kernel.world + ".glsl");
    EXPECT_TRUE(spirv.ok()) << spirv.log;
    if (spirv.ok()) {
      EXPECT_TRUE(validateSpirv(spirv.words));
    }
    if (kernel.world == "Fragment") result.fragment = kernel.glsl;
  }
  return result;
}

size_t count(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// The expression `name` is assigned, with every temporary it reads replaced
// by its parenthesized definition, then stripped of parentheses and spaces:
// what remains is the operand and operator sequence, which splitting must
// keep exactly.
std::string flattened(const std::string& glsl, const std::string& assigned) {
  std::map<std::string, std::string> temporaries;
  const std::regex declaration(R"(float (spire_chain\d+) = (.*);)");
  for (std::sregex_iterator it(glsl.begin(), glsl.end(), declaration), end; it != end; ++it) {
    temporaries[(*it)[1]] = (*it)[2];
  }
  const std::regex assignment("\\b" + assigned + " = (.*);");
  std::smatch match;
  if (!std::regex_search(glsl, match, assignment)) return "";
  std::string text = match[1];
  const std::regex temporary(R"(spire_chain\d+)");
  for (std::smatch use; std::regex_search(text, use, temporary);) {
    text = use.prefix().str() + "(" + temporaries.at(use.str()) + ")" + use.suffix().str();
  }
  std::erase_if(text, [](char c) { return c == '(' || c == ')' || c == ' '; });
  return text;
}

TEST(LongChains, AreComputedInStepsThatKeepTheOrderOfOperations) {
  const int terms = 5 * static_cast<int>(GlslWriter::kChainSegment) + 5;
  const std::string mixed = chain(terms, "a", {"+", "*", "-", "/"});
  const Generated generated =
      fragmentOf(shaderWith("", "  float stepped = " + mixed + ";\n  float inline = a > 0.5 ? " + mixed +
                                    " : 0.0;\n  vec4 output = vec4(stepped, inline, 0.0, 1.0);\n"));
  ASSERT_FALSE(generated.fragment.empty()) << generated.diagnostics;
  // The chain's left spine holds its additive operators (the others bind
  // tighter): one temporary per full segment of them and one for the rest;
  // the conditional branch keeps its chain inline.
  const size_t spine = static_cast<size_t>(terms - 1) / 2;
  const size_t segments = (spine + GlslWriter::kChainSegment - 1) / GlslWriter::kChainSegment;
  EXPECT_EQ(count(generated.fragment, "float spire_chain"), segments) << generated.fragment;
  const std::string stepped = flattened(generated.fragment, "stepped");
  ASSERT_FALSE(stepped.empty()) << generated.fragment;
  const std::string inlineText = flattened(generated.fragment, "inline_");
  ASSERT_NE(inlineText.find(stepped), std::string::npos) << stepped << "\n" << inlineText;
}

TEST(LongChains, OfAHundredThousandTermsCompileToValidSpirv) {
  const Generated generated =
      fragmentOf(shaderWith("", "  float s = " + chain(100000, "a", {"+"}) + ";\n  vec4 output = vec4(s);\n"));
  ASSERT_FALSE(generated.fragment.empty()) << generated.diagnostics;
  EXPECT_EQ(count(generated.fragment, " + a"), 99999U);
}

TEST(LongChains, TemporariesNeverTakeAUserName) {
  const std::string function =
      "float f(float x) {\n  float spire_chain0 = x;\n  float r = " + chain(200, "spire_chain0", {"+"}) +
      ";\n  float spire_chain1 = r;\n  return spire_chain1 + spire_chain0;\n}\n";
  const Generated generated = fragmentOf(shaderWith(function, "  vec4 output = vec4(f(a));\n"));
  ASSERT_FALSE(generated.fragment.empty()) << generated.diagnostics;
  // Generated names are spire_-prefixed and user names with that prefix are
  // renamed, so the two never meet.
  EXPECT_NE(generated.fragment.find("float spire_chain0_ = x;"), std::string::npos) << generated.fragment;
  EXPECT_NE(generated.fragment.find("float spire_chain0 = spire_chain0_ + "), std::string::npos) << generated.fragment;
}

TEST(LongChains, ThatAssignOrRunUnderAConditionStayInline) {
  const std::string function = "float f(float x) {\n  float y = 0.0;\n  float r = (y = x) + " + chain(200, "x", {"+"}) +
                               ";\n  bool b = x > 0.0 && " + chain(200, "x", {"+"}) +
                               " > 1.0;\n  return b ? r + y : y;\n}\n";
  const Generated generated = fragmentOf(shaderWith(function, "  vec4 output = vec4(f(a));\n"));
  ASSERT_FALSE(generated.fragment.empty()) << generated.diagnostics;
  EXPECT_EQ(generated.fragment.find("spire_chain"), std::string::npos) << generated.fragment;
}

TEST(LongChains, TooLongWhereNoTemporaryFitsIsAnErrorAtTheChain) {
  const int terms = static_cast<int>(GlslWriter::kMaxInlineChain) + 10;
  const std::string function = "float f(float x) {\n  float r = 0.0;\n  while (r < " + chain(terms, "x", {"+"}) +
                               ") {\n    r += 1.0;\n  }\n  return r;\n}\n";
  const Generated generated = fragmentOf(shaderWith(function, "  vec4 output = vec4(f(a));\n"));
  EXPECT_TRUE(generated.fragment.empty());
  EXPECT_NE(generated.diagnostics.find("chain.spire:4:"), std::string::npos) << generated.diagnostics.substr(0, 2000);
  EXPECT_NE(generated.diagnostics.find("error[E6001]"), std::string::npos) << generated.diagnostics.substr(0, 2000);
  EXPECT_NE(generated.diagnostics.find("compute it in a local variable first"), std::string::npos);
}

}  // namespace
}  // namespace spire::codegen
