// Sharing values within a world (value_keys.h) over generated programs:
// for every live definition of every variant tried, what it costs beside
// the others in its world is at most what it costs alone, never negative,
// and the same when costed again. A failure names the seed; the program is
// tests/gen's generateProgram(seed).
#include <gtest/gtest.h>

#include <iostream>
#include <map>
#include <string>

#include "driver/shader_library.h"
#include "gen/program_generator.h"
#include "simplify/cost_model.h"
#include "simplify/variant_cost.h"

namespace spire::simplify {
namespace {

constexpr uint32_t kSeeds = 150;

// Decision maps for `shader`: the defaults, then each choice's alternatives
// in turn for every choice at once (alternative k % count).
std::vector<std::map<std::string, std::string>> decisionMaps(const ShaderLibrary& library, const std::string& shader) {
  std::vector<std::map<std::string, std::string>> maps(1);
  const std::vector<graph::Choice> choices = library.choices(shader);
  for (size_t k = 0; k < 4 && !choices.empty(); ++k) {
    std::map<std::string, std::string> decisions;
    for (const graph::Choice& choice : choices) {
      decisions[choice.key.substr(choice.key.rfind('.') + 1)] = choice.names[k % choice.names.size()];
    }
    maps.push_back(std::move(decisions));
  }
  return maps;
}

void checkVariant(const ShaderLibrary& library, const graph::Variant& variant, uint32_t seed) {
  const VariantCost shared = variantCost(library.model(), variant);
  const VariantCost again = variantCost(library.model(), variant);
  EXPECT_EQ(shared.totalTenths(), again.totalTenths()) << "seed " << seed;
  CostModel alone(library.model());
  std::map<std::string, int64_t> aloneOps;
  for (sem::ComponentId c : variant.live()) {
    const graph::ComponentNode& node = variant.graph().node(c);
    if (node.isInput) continue;
    aloneOps[node.component->name] = alone.definition(*node.alternatives[*variant.choice(c)].definition->decl);
  }
  for (const ComponentCost& row : shared.components) {
    EXPECT_GE(row.ops, 0) << "seed " << seed << ", " << row.component;
    if (const auto it = aloneOps.find(row.component); it != aloneOps.end()) {
      EXPECT_LE(row.ops, it->second) << "seed " << seed << ", " << row.component << " in " << row.world;
    }
  }
}

TEST(CostSharingProperty, ADefinitionNeverCostsMoreBesideOthersThanAlone) {
  size_t variants = 0;
  for (uint32_t seed = 0; seed < kSeeds; ++seed) {
    FrontEndOptions options;
    options.readFile = [](const std::string&) -> std::optional<std::string> { return std::nullopt; };
    ShaderLibrary library(std::move(options));
    library.addSource("generated.spire", testgen::generateProgram(seed).text);
    if (!library.compile()) continue;
    for (const std::string& shader : library.shaderNames()) {
      for (const auto& decisions : decisionMaps(library, shader)) {
        const std::optional<graph::Variant> variant = library.buildVariant(shader, decisions);
        if (!variant) continue;
        checkVariant(library, *variant, seed);
        ++variants;
      }
    }
  }
  std::cout << variants << " variants of " << kSeeds << " generated programs\n";
  // Enough of the generator's programs compile for the property to say much.
  EXPECT_GE(variants, kSeeds);
}

}  // namespace
}  // namespace spire::simplify
