// He et al. 2015's performance model for a whole shader variant
// (../shared/seeds/000, section 4.4.4):
//
//   C = 0.3·C_v + 0.7·C_f + 10·N_var
//
// C_v and C_f add up the costs (cost_model.h) of the components computed at
// vertex and at fragment rate; N_var counts the scalars passed from the
// vertex to the fragment kernel. What a world's rate is comes from the
// pipeline, never from world names:
//   - fragment rate: a world whose kernel is a fragment stage (its [Stage],
//     or what its export strategy implies) and that holds one of the
//     pipeline's requirements (the exported output): the draw's fragment
//     kernel;
//   - vertex rate: a vertex-stage world with an interpolating import
//     (standardImport) into a fragment-rate world;
//   - any other world (the prebake worlds, which run at load, and passes of
//     their own such as a low-resolution one) costs nothing, as He et al.'s
//     parameter stage. A value one of them hands to a vertex- or
//     fragment-rate world through a texture (a resampling import:
//     textureImport) costs one texture fetch there.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "codegen/strategy_registry.h"
#include "graph/variant.h"
#include "sema/semantic_model.h"

namespace spire::simplify {

enum class WorldRate : uint8_t { Vertex, Fragment, Other };

// Each world of the variant's pipeline's rate, by WorldId.
std::vector<WorldRate> worldRates(const graph::ShaderGraph& graph, const codegen::StrategyRegistry& strategies);

struct ComponentCost {
  std::string component;
  std::string world;
  WorldRate rate = WorldRate::Other;
  int64_t ops = 0;  // its definition's cost; 0 for an input
  // The vertex- or fragment-rate worlds that fetch it from a texture, each
  // paying kTextureFetchCost.
  std::vector<std::string> fetchedIn;
};

struct VariantCost {
  std::vector<ComponentCost> components;  // computed or fetched ones, in dependency order
  std::vector<std::string> vertexWorlds;  // the pipeline's world order
  std::vector<std::string> fragmentWorlds;
  int64_t vertexOps = 0;     // C_v
  int64_t fragmentOps = 0;   // C_f
  int64_t varyings = 0;      // N_var, in scalars
  size_t varyingValues = 0;  // the values those scalars belong to
  // C in tenths: the weights have one decimal, so this is exact.
  int64_t totalTenths() const { return 3 * vertexOps + 7 * fragmentOps + 100 * varyings; }
};

VariantCost variantCost(const sem::Model& model, const graph::Variant& variant,
                        const codegen::StrategyRegistry& strategies = codegen::StrategyRegistry::builtin());

// A table of the components and their costs, then C_v, C_f, N_var and C,
// as spire-simplify --costs prints it.
std::string formatVariantCost(const VariantCost& cost, std::string_view title);

}  // namespace spire::simplify
