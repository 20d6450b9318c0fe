// spire-simplify over generated programs (tests/gen): for every shader a
// generated program declares, the module of simplified variations compiles,
// no rule proposes a rewrite that does not compile (the module would drop
// it) but for a base's locked worlds, and every variation, chosen in every world that offers it, gives
// kernels that glslang compiles, the SPIR-V validator accepts and whose
// interfaces agree; where the definition it rewrites is accepted in a
// world, so is the variation. A failure names the seed; the program is
// tests/gen's generateProgram(seed).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <string>

#include <unistd.h>

#include "gen/program_generator.h"
#include "gen/variant_checker.h"
#include "simplify/rewrite_target.h"
#include "simplify/simplification.h"

namespace spire::simplify {
namespace {

namespace fs = std::filesystem;

constexpr uint32_t kSeeds = 300;

struct Tally {
  size_t shaders = 0;
  size_t variations = 0;
  size_t acceptedVariants = 0;
  size_t droppedForLockedReads = 0;
  size_t lockedOut = 0;
  size_t byUserRules = 0;  // variations a user rule made
  size_t fromGroups = 0;   // shaders derived from a group
};

// "Fragment:simplified2" -> "Fragment", "Fragment:ggx_simplified1" -> "Fragment:ggx":
// the choice that picks the definition the variation rewrites.
std::string rewrittenChoice(const std::string& name) {
  const size_t colon = name.find(':');
  const std::string world = name.substr(0, colon);
  const std::string variation = name.substr(colon + 1);
  const size_t mark = variation.rfind("simplified");
  if (mark == 0) return world;
  return world + ":" + variation.substr(0, mark - 1);
}

bool isGenerated(const std::string& name) {
  const size_t colon = name.find(':');
  return colon != std::string::npos && name.find("simplified", colon) != std::string::npos;
}

// The verdict on the variant of `derived` that differs from the defaults in
// the choice `key` only.
testgen::VariantReport verdictOn(testgen::ProgramChecker& checker, const std::string& derived, const std::string& key,
                                 const std::string& choice) {
  for (testgen::VariantReport& report : checker.check(key + " = " + choice + "\n")) {
    if (report.shader == derived || report.shader.empty()) return report;
  }
  return {derived, testgen::Verdict::InternalError, {}, "no report for the derived shader", {}, {}};
}

// The components of `shader` with one definition, whose choice names say
// which definition a variation rewrote: "F1:simplified1" rewrites what "F1"
// picks. With two, "F1" may pick an explicit @F1 one while the variation
// rewrote an implicit one placed in F1.
std::set<std::string> singlyDefined(const sem::Shader& shader) {
  std::set<std::string> names;
  for (const sem::Component& c : shader.components) {
    if (std::count_if(c.definitions.begin(), c.definitions.end(),
                      [](const sem::Definition& d) { return !d.isInput(); }) == 1) {
      names.insert(c.name);
    }
  }
  return names;
}

void checkDerived(testgen::ProgramChecker& checker, const std::string& derived, const std::string& module,
                  const std::set<std::string>& comparable, uint32_t seed, Tally& tally) {
  for (const graph::Choice& choice : checker.choices(derived)) {
    for (const std::string& name : choice.names) {
      if (!isGenerated(name)) continue;
      const testgen::VariantReport simplified = verdictOn(checker, derived, choice.key, name);
      EXPECT_FALSE(simplified.failed()) << "seed " << seed << ", " << choice.key << " = " << name << ": "
                                        << testgen::verdictName(simplified.verdict) << "\n"
                                        << simplified.detail << "\n"
                                        << module;
      if (simplified.verdict == testgen::Verdict::Accepted) {
        ++tally.acceptedVariants;
        continue;
      }
      // Only where the rewritten definition is a possible placement there too
      // (a rewrite that reads less may be placed where its original cannot).
      const std::string rewritten = rewrittenChoice(name);
      if (!comparable.contains(choice.key.substr(choice.key.rfind('.') + 1)) ||
          std::find(choice.names.begin(), choice.names.end(), rewritten) == choice.names.end()) {
        continue;
      }
      const testgen::VariantReport original = verdictOn(checker, derived, choice.key, rewritten);
      EXPECT_NE(original.verdict, testgen::Verdict::Accepted)
          << "seed " << seed << ": " << choice.key << " = " << rewritten << " is accepted, " << name
          << " refused: " << simplified.detail << "\n"
          << module;
    }
  }
}

// The shaders of the module named `derived`: itself, or from a group the
// ones it makes (`DSimplified<A>`).
std::vector<std::string> derivedShaders(const testgen::ProgramChecker& checker, const std::string& derived) {
  std::vector<std::string> names;
  for (const std::string& name : checker.shaders()) {
    if (name == derived || name.starts_with(derived + "<")) names.push_back(name);
  }
  return names;
}

void checkModule(const fs::path& modulePath, const std::string& module, const std::string& derivedName,
                 const std::set<std::string>& comparable, uint32_t seed, Tally& tally) {
  testgen::ProgramChecker checker(module, modulePath.string());
  ASSERT_EQ(checker.frontEnd().verdict, testgen::Verdict::Accepted)
      << "seed " << seed << ": " << checker.frontEnd().detail << "\n"
      << module;
  const std::vector<std::string> shaders = derivedShaders(checker, derivedName);
  EXPECT_FALSE(shaders.empty()) << "seed " << seed << ": no shader " << derivedName << "\n" << module;
  for (const std::string& derived : shaders) checkDerived(checker, derived, module, comparable, seed, tally);
}

void checkProgram(const fs::path& dir, uint32_t seed, const UserRules* rules, Tally& tally) {
  const fs::path source = dir / ("generated" + std::to_string(seed) + ".spire");
  std::ofstream(source) << testgen::generateProgram(seed).text;
  FrontEndOptions frontEnd;
  ShaderLibrary library(frontEnd);
  if (!library.addFile(source.string()) || !library.compile()) return;
  // A group's shaders are simplified through the shader derived from it.
  std::set<std::string> names;
  for (const std::string& name : library.shaderNames()) {
    const sem::Shader* shader = library.model().findShader(name);
    names.insert(shader && shader->derivedFrom ? shader->derivedFrom->name : name);
  }
  for (const std::string& name : names) {
    auto base = shaderToDerive(library.model(), name);
    ASSERT_TRUE(base) << "seed " << seed << ", " << name << ": " << base.error().message;
    tally.fromGroups += base->fromGroup ? 1 : 0;
    SimplifyOptions options;
    options.shader = name;
    options.maxPerComponent = 3;
    options.outputPath = (dir / (name + std::to_string(seed) + "_simplified.spire")).string();
    options.frontEnd = frontEnd;
    options.userRules = rules;
    auto result = simplifyShader(library, options);
    ASSERT_TRUE(result) << "seed " << seed << ", " << name << ": " << result.error().message;
    ++tally.shaders;
    tally.lockedOut += result->lockedOut.size();
    for (const std::string& dropped : result->dropped) {
      // A rewrite may keep a read that the shader's base routes through a
      // world it finalizes: only the base may read there, and only the
      // compile knows the route. Any other reason is a rule's bug.
      EXPECT_NE(dropped.find("through a finalized world"), std::string::npos) << "seed " << seed << ": " << dropped;
      ++tally.droppedForLockedReads;
    }
    if (result->variations.empty()) continue;
    tally.variations += result->variations.size();
    for (const Variation& v : result->variations) {
      const bool builtIn = v.rule == "constant-operand" || v.rule == "call-to-argument" || v.rule == "loop-iteration";
      tally.byUserRules += builtIn ? 0 : 1;
    }
    checkModule(options.outputPath, result->module, name + "Simplified", singlyDefined(base->shader()), seed, tally);
  }
}

// The property over kSeeds programs, with `rules` besides the built-in ones.
// Returns how many variations user rules made.
size_t checkPrograms(const std::string& name, const UserRules* rules) {
  const fs::path dir = fs::temp_directory_path() / ("spire-simplify-property-" + name + "-" + std::to_string(getpid()));
  fs::create_directories(dir);
  Tally tally;
  for (uint32_t seed = 0; seed < kSeeds; ++seed) checkProgram(dir, seed, rules, tally);
  std::cout << tally.shaders << " shaders (" << tally.fromGroups << " derived from groups) of " << kSeeds
            << " generated programs, " << tally.variations << " variations, " << tally.acceptedVariants
            << " variants accepted; " << tally.lockedOut << " components left out and " << tally.droppedForLockedReads
            << " rewrites dropped for a base's finalized worlds\n";
  // Enough of the generator's programs give variations for the property to say much.
  EXPECT_GE(tally.variations, size_t{kSeeds});
  EXPECT_GE(tally.acceptedVariants, size_t{kSeeds});
  EXPECT_GE(tally.fromGroups, size_t{kSeeds / 10});
  if (!::testing::Test::HasFailure()) fs::remove_all(dir);
  return tally.byUserRules;
}

TEST(SimplifyProperty, EveryVariationOfAGeneratedShaderCompilesAndValidates) {
  EXPECT_EQ(checkPrograms("builtin", nullptr), 0U);
}

// User rules whose replacements keep the type of what they match, on the
// shapes the generator writes (its helpers call sin, max, mix, normalize and
// multiply): the same property, so no rewrite of theirs may be dropped.
TEST(SimplifyProperty, UserRulesOnGeneratedShadersCompileAndValidate) {
  UserRules rules;
  ASSERT_TRUE(rules.add("property.rules", R"(rule sin-argument: sin($x) -> $x
rule max-first: max($a, $b) -> $a
rule mix-middle: mix($a, $b, $t) -> ($a + $b) * 0.5
rule square-root: $x * $x -> $x
rule normalize-identity: normalize($v) -> $v
)"));
  ASSERT_EQ(rules.rules().size(), 5U);
  EXPECT_GE(checkPrograms("user", &rules), size_t{kSeeds}) << "the user rules made too few variations to test";
}

}  // namespace
}  // namespace spire::simplify
