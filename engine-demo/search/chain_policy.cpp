#include "search/chain_policy.h"

#include <fmt/format.h>

#include <limits>

#include "search/search_outputs.h"
#include "support/file_io.h"

namespace spire::search {

namespace {

namespace fs = std::filesystem;

// The chain's module and decision files in the work folder, the instance
// pointed at the module, and a policy whose level k draws the derived
// shader with level k's file (bands follow the levels' order; only the
// order matters to the measurement).
Expected<lod::LodPolicy, Failure> measuredPolicy(const Chain& chain, const SearchSetup& setup) {
  const fs::path module = setup.workDir / "chain.spire";
  if (auto written = writeFileAtomically(module.string(), chainModuleText(setup.header, chain)); !written) {
    return written.error();
  }
  // A folder of their own, so that the files have the names the output
  // folder gives them (the levels' names in the report).
  const fs::path levels = setup.workDir / "levels";
  std::error_code ec;
  fs::create_directories(levels, ec);
  if (ec) return Failure{fmt::format("cannot create '{}': {}", levels.string(), ec.message())};
  lod::LodPolicy policy;
  for (size_t k = 0; k < chain.levels.size(); ++k) {
    const fs::path file = levels / levelFileName(k);
    if (auto written = writeFileAtomically(file.string(), levelDecisionText(chain, k, setup.header)); !written) {
      return written.error();
    }
    lod::LodLevel level;
    level.until = k + 1 < chain.levels.size() ? static_cast<float>(k + 1) : std::numeric_limits<float>::infinity();
    level.decisions.emplace(setup.header.derived, file);
    policy.levels.push_back(std::move(level));
  }
  setup.scene->instances.at(setup.instance).source = module;
  setup.scene->instances.at(setup.instance).shader = setup.header.derived;
  return policy;
}

}  // namespace

Expected<ChainPolicy, Failure> chainPolicy(const Chain& chain, const SearchSetup& setup,
                                           engine::SceneRenderer& renderer, const SearchOptions& options,
                                           const fs::path& outputDir) {
  auto measured = measuredPolicy(chain, setup);
  if (!measured) return measured.error();
  // With C as the cost no frame is timed: the costs come from the chain.
  const bool model = options.cost == CostKind::Model;
  const tune::LevelSampling sampling{options.policyChoice.distances, model ? 0U : options.warmup,
                                     model ? 0U : options.frames};
  auto m = tune::measureLevels(renderer, *measured, sampling);
  if (!m) return Failure{fmt::format("the chain's levels cannot be measured as a policy: {}", m.error().message)};
  if (model) {
    // The chain is ordered by C, which falls at every level; a measured
    // frame time can move more between two levels than a rewrite saves.
    m->costName = "He et al.'s cost C of each level";
    m->costUnit = "";
    for (size_t k = 0; k < chain.levels.size(); ++k) m->levels.cost[k] = costOf(chain.levels[k], options.cost);
  }
  const lod::ChoiceRule rule = tune::choiceRule(options.policyChoice);
  tune::ChosenPolicy chosen = tune::choosePolicy(*m, *measured, rule);
  ChainPolicy result;
  result.table = tune::levelTable(*m, *measured, chosen, rule);
  // The same levels, named by the files the output folder will hold.
  for (lod::LodLevel& level : chosen.policy.levels) {
    for (auto& [shader, file] : level.decisions) {
      file = outputDir / file.filename();
    }
  }
  result.policy = std::move(chosen.policy);
  return result;
}

}  // namespace spire::search
