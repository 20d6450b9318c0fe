// User-written simplification rules: the rule file's errors (rendered as
// spirec renders its own), matching on the typed tree (repeated
// metavariables, literals), the variations they make, the type check that
// drops a rewrite of another type, [Immutable], and spire-simplify --rules.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "simplify/rewrite_rules.h"
#include "simplify/simplification.h"
#include "simplify/simplify_tool.h"
#include "simplify/user_rules.h"
#include "simplify_fixture.h"
#include "support/diagnostic_renderer.h"

namespace spire::simplify {
namespace {

namespace fs = std::filesystem;

// The rendered diagnostics of a rule file with `text`, empty when it has none.
std::string errorsOf(const std::string& text) {
  UserRules rules;
  const bool ok = rules.add("r.rules", text);
  const std::string rendered = renderDiagnostics(rules.sources(), rules.diagnostics(), DiagnosticFormat::Text);
  EXPECT_EQ(ok, rendered.empty()) << rendered;
  return rendered;
}

TEST(UserRulesFile, ReadsRulesCommentsAndBlankLines) {
  UserRules rules;
  ASSERT_TRUE(rules.add("r.rules",
                        "# squares\n"
                        "\n"
                        "rule pow-square: pow($x, 2.0) -> $x * $x  # cheaper\n"
                        "  rule drop_fresnel :fresnelSchlick($n, $v, $f0)->$f0\n"));
  ASSERT_EQ(rules.rules().size(), 2U);
  EXPECT_EQ(rules.rules()[0].name, "pow-square");
  EXPECT_EQ(rules.rules()[0].replacement, "$x * $x");
  EXPECT_EQ(rules.rules()[0].metavariables.size(), 1U);
  EXPECT_EQ(rules.rules()[1].name, "drop_fresnel");
  EXPECT_EQ(rules.rules()[1].replacement, "$f0");
  EXPECT_EQ(rules.rules()[1].metavariables.size(), 3U);
}

TEST(UserRulesFile, ErrorsPointAtTheRuleWithACaret) {
  EXPECT_EQ(errorsOf("rule a: pow($x, 2.0)\n"),
            "r.rules:1:21: error[E8001]: expected '->' between the pattern and its replacement\n"
            " 1 | rule a: pow($x, 2.0)\n"
            "   |                     ^\n"
            "1 error generated.\n");
  EXPECT_EQ(errorsOf("\nrule a: pow($x, 2.0) -> $y * $x\n"),
            "r.rules:2:25: error[E8001]: '$y' is not a metavariable of the pattern\n"
            " 2 | rule a: pow($x, 2.0) -> $y * $x\n"
            "   |                         ^~\n"
            "1 error generated.\n");
  EXPECT_EQ(errorsOf("rule a: pow($x, ) -> $x\n"),
            "r.rules:1:17: error[E2002]: expected an expression\n"
            " 1 | rule a: pow($x, ) -> $x\n"
            "   |                 ^\n"
            "1 error generated.\n");
  EXPECT_EQ(errorsOf("rule a: $x -> 1.0\n"),
            "r.rules:1:9: error[E8001]: a pattern that is only a metavariable would match every expression\n"
            " 1 | rule a: $x -> 1.0\n"
            "   |         ^~\n"
            "1 error generated.\n");
  EXPECT_EQ(errorsOf("rule a: $x * 1.0 -> $x\nrule a: $x + 0.0 -> $x\n"),
            "r.rules:2:6: error[E8001]: a rule named 'a' is already defined\n"
            " 2 | rule a: $x + 0.0 -> $x\n"
            "   |      ^\n"
            "r.rules:1:1: note: previous definition is here\n"
            " 1 | rule a: $x * 1.0 -> $x\n"
            "   | ^~~~~~~~~~~~~~~~~~~~~~\n"
            "1 error generated.\n");
}

TEST(UserRulesFile, EveryMalformedLineIsAnError) {
  for (const std::string bad : {
           "pow($x, 2.0) -> $x\n",         // no `rule`
           "rule : $x * 1.0 -> $x\n",      // no name
           "rule a $x * 1.0 -> $x\n",      // no ':'
           "rule a: $x * 1.0 -> \n",       // no replacement
           "rule a: $x * 1.0 -> $x $x\n",  // not one expression
           "rule a: $f($x) -> $x\n",       // a metavariable as a callee
           "rule a: $x.$y -> $x\n",        // ... as a member
           "rule a: a$x * 1.0 -> $x\n",    // glued to a name
           "rule a: $ * 1.0 -> 1.0\n",     // no name after `$`
           "rule a: $1 * 1.0 -> 1.0\n",
       }) {
    EXPECT_NE(errorsOf(bad), "") << bad;
  }
  UserRules rules;
  EXPECT_FALSE(rules.add("r.rules", "rule good: $x * 1.0 -> $x\nrule bad: $x +\n"));
  EXPECT_TRUE(rules.rules().empty()) << "a file with errors adds none of its rules";
}

class UserRulesTest : public SimplifyFixture {
 protected:
  void rules(const std::string& text) { ASSERT_TRUE(rules_.add("r.rules", text)) << text; }
  // "rule: before -> after" for each rewrite of `component`'s definition.
  std::vector<std::string> rewritesOf(const std::string& component) {
    const sem::Shader* shader = library_->model().findShader("S");
    const sem::Component& c = shader->components[shader->componentByName.at(component)];
    std::vector<std::string> texts;
    for (const Rewrite& r :
         proposeRewrites(library_->model(), library_->sources(), *c.definitions.front().decl, rules_.rules())) {
      texts.push_back(r.rule + ": " + r.before + " -> " + r.replacement);
    }
    return texts;
  }
  Expected<Simplified, Failure> simplify() { return simplifyS(&rules_); }

  UserRules rules_;
};

constexpr const char* kShader = R"(using "pipelines/engine.spire";
shader S using EnginePipeline {
    @FrameUniform mat4 mvp;
    @MaterialUniform vec3 tint;
    @MaterialUniform float gain;
    @MaterialUniform float other;
    vec4 projPos = mvp * vec4(vert_pos, 1.0);
    float squared = pow(gain, 2.) + other;
    float same = gain * gain;
    float different = gain * other;
    float chained = (gain + other) * (gain+other);
    vec3 scaled = normalize(tint) * tint;
    float suffixed = pow(gain, 2.0f) * float(0x2) * float(2u);
    [Immutable] float keptPow = pow(gain, 2.0);
    vec4 output = vec4(tint + scaled, squared + same + different + chained + keptPow);
}
)";

TEST_F(UserRulesTest, ARuleMakesAVariationOfItsReplacement) {
  load(kShader);
  rules("rule pow-square: pow($x, 2.0) -> $x * $x\n");
  EXPECT_EQ(rewritesOf("squared"), (std::vector<std::string>{
                                       "call-to-argument: pow(gain, 2.) -> (gain)",
                                       "pow-square: pow(gain, 2.) -> ((gain) * (gain))",
                                   }));
  auto result = simplify();
  ASSERT_TRUE(result) << result.error().message;
  EXPECT_TRUE(result->dropped.empty()) << result->dropped.front();
  EXPECT_NE(result->module.find(
                "    // squared:simplified2 (pow-square at s.spire:8:21, saves 0 scalar ops): 'pow(gain, 2.)' -> "
                "'((gain) * (gain))'\n"
                "    float squared:simplified2 = ((gain) * (gain)) + other;\n"),
            std::string::npos)
      << result->module;
}

TEST_F(UserRulesTest, ARepeatedMetavariableMatchesOnlyEqualTrees) {
  load(kShader);
  rules("rule square: $x * $x -> $x\n");
  EXPECT_EQ(rewritesOf("same"), (std::vector<std::string>{"square: gain * gain -> ((gain))"}));
  EXPECT_TRUE(rewritesOf("different").empty());
  // Parentheses and spaces are not part of the tree.
  EXPECT_EQ(rewritesOf("chained"),
            (std::vector<std::string>{"square: (gain + other) * (gain+other) -> ((gain + other))"}));
}

TEST_F(UserRulesTest, LiteralsMatchByKindAndValue) {
  load(kShader);
  rules("rule int-two: pow($x, 2) -> $x\nrule float-two: pow($x, 2.0e0) -> $x\n");
  // 2.0e0 matches `2.`; the int literal 2 does not.
  EXPECT_EQ(rewritesOf("squared"), (std::vector<std::string>{"call-to-argument: pow(gain, 2.) -> (gain)",
                                                             "float-two: pow(gain, 2.) -> ((gain))"}));
}

TEST_F(UserRulesTest, AReplacementOfAnotherTypeIsDroppedAndReported) {
  load(kShader);
  // `length(tint) * tint` still compiles, as a vec3 from a float: the
  // check on the compiled module drops it all the same.
  rules("rule to-length: normalize($v) -> length($v)\nrule to-swizzle: pow($x, 2.0) -> $x.xy\n");
  auto result = simplify();
  ASSERT_TRUE(result) << result.error().message;
  const auto dropped = [&](const std::string& line) {
    return std::find(result->dropped.begin(), result->dropped.end(), line) != result->dropped.end();
  };
  EXPECT_TRUE(
      dropped("squared:simplified2 (to-swizzle at s.spire:8:21): "
              "swizzle 'xy' selects a component beyond the one of 'float'"))
      << result->module;
  EXPECT_TRUE(
      dropped("scaled:simplified2 (to-length at s.spire:12:19): '(length((tint)))' has type 'float', not 'vec3'"));
  for (const Variation& v : result->variations) EXPECT_TRUE(v.rule != "to-length" && v.rule != "to-swizzle");
}

TEST_F(UserRulesTest, ImmutableComponentsAreLeftAlone) {
  load(kShader);
  rules("rule pow-square: pow($x, 2.0) -> $x * $x\n");
  auto result = simplify();
  ASSERT_TRUE(result) << result.error().message;
  for (const Variation& v : result->variations) EXPECT_NE(v.component, "keptPow") << "[Immutable] is left alone";
  EXPECT_EQ(result->module.find("keptPow:"), std::string::npos);
}

TEST_F(UserRulesTest, ImmutableStatementsAndBlocksAreLeftAlone) {
  load(R"(using "pipelines/engine.spire";
shader S using EnginePipeline {
    @FrameUniform mat4 mvp;
    @MaterialUniform float gain;
    vec4 projPos = mvp * vec4(vert_pos, 1.0);
    float guarded {
        [Immutable] float a = pow(gain, 2.0);
        [Immutable] { a += pow(a, 2.0); }
        return pow(a, 2.0);
    }
    vec4 output = vec4(guarded);
}
)");
  rules("rule pow-square: pow($x, 2.0) -> $x * $x\n");
  EXPECT_EQ(rewritesOf("guarded"), (std::vector<std::string>{"call-to-argument: pow(a, 2.0) -> (a)",
                                                             "pow-square: pow(a, 2.0) -> ((a) * (a))"}));
}

TEST_F(UserRulesTest, TheToolAppliesRuleFilesAndReportsTheirErrors) {
  load(kShader);
  const fs::path good = dir_ / "good.rules";
  std::ofstream(good) << "rule pow-square: pow($x, 2.0) -> $x * $x\n";
  const fs::path more = dir_ / "more.rules";
  std::ofstream(more) << "# a second file\nrule square: $x * $x -> $x\n";
  const std::string output = (dir_ / "m.spire").string();
  std::ostringstream out;
  std::ostringstream err;
  ASSERT_EQ(runSimplifyTool({source_.string(), "-I", SPIRE_SOURCE_DIR, "--shader", "S", "--rules", good.string(),
                             "--rules", more.string(), "-o", output},
                            out, err),
            0)
      << err.str();
  std::ifstream written(output);
  const std::string module((std::istreambuf_iterator<char>(written)), std::istreambuf_iterator<char>());
  EXPECT_NE(module.find("(pow-square at s.spire:8:21, saves 0 scalar ops)"), std::string::npos) << module;
  EXPECT_NE(module.find("float same:simplified1 = ((gain));"), std::string::npos) << module;

  const fs::path bad = dir_ / "bad.rules";
  std::ofstream(bad) << "rule pow-square: pow($x, 2.0) -> $y\n";
  std::ostringstream err2;
  EXPECT_EQ(runSimplifyTool({source_.string(), "--shader", "S", "--rules", bad.string(), "-o", output}, out, err2), 1);
  EXPECT_EQ(err2.str(), bad.string() +
                            ":1:34: error[E8001]: '$y' is not a metavariable of the pattern\n"
                            " 1 | rule pow-square: pow($x, 2.0) -> $y\n"
                            "   |                                  ^~\n"
                            "1 error generated.\n");
  std::ostringstream err3;
  EXPECT_EQ(
      runSimplifyTool({source_.string(), "--shader", "S", "--rules", (dir_ / "none.rules").string(), "-o", output}, out,
                      err3),
      1);
  EXPECT_NE(err3.str().find("spire-simplify: error: cannot read rule file"), std::string::npos) << err3.str();
  std::ostringstream help;
  EXPECT_EQ(runSimplifyTool({"--help"}, help, err3), 0);
  EXPECT_NE(help.str().find("--rules FILE"), std::string::npos) << help.str();
}

}  // namespace
}  // namespace spire::simplify
