// What `spire-simplify --search` is asked to do (docs/simplify.md,
// "Search"): He et al. 2015's greedy search over a scene's shader, with the
// paper's K1, K2 and K3, and how its candidates are rendered and measured.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "search/chain.h"
#include "tune/tune_options.h"

namespace CLI {
class App;
}

namespace spire::search {

struct SearchOptions {
  std::string scenePath;
  std::string shader;                   // the shader of the scene's instance to simplify
  std::vector<std::string> components;  // empty: every one spire-simplify may rewrite
  std::vector<std::string> ruleFiles;   // user rule files (--rules), proposing beside the built-in rules
  bool average = true;                  // Pellacini's average rule, whose sites are measured by probes
  bool acse = true;                     // He et al.'s approximate common subexpression elimination
  bool moves = true;                    // components moved to other worlds (He et al.'s m2v and m2p)
  bool renormalize = false;             // Pellacini's renormalization of every candidate
  size_t k1 = 2;                        // rewrites each rule proposes per component and step
  double k2 = 1.0;                      // candidates kept: error <= K2 x the median candidate error
  double k3 = 0.15;                     // a cached error off the fresh one by more than K3 x itself is stale
  size_t maxLevels = 6;                 // levels after the original
  double errorBudget = std::numeric_limits<double>::infinity();  // RMSE no level may exceed
  // Errors and times against this decision file's variant instead of level
  // 0's (full quality, when the search starts from a tuned variant), so
  // that the budget bounds the error against it.
  std::optional<std::string> reference;
  CostKind cost = CostKind::Model;  // what candidates are ranked and the chain ordered by
  // He et al.'s transition shaders at the chain policy's switches
  // (search/transitions.h): the part of each band they blend over, 0 for
  // none, and the distance expression; without one, the default's, and a
  // shader that cannot compute it gets no transitions (with a note).
  double transitionWidth = 0.2;
  std::optional<std::string> transitionDistance;
  std::string outputDir;
  std::string derivedName;  // default: the shader's name + "Search"
  // Measurement, as spire-tune's options of the same names.
  uint32_t frames = 5;  // pairs of frames timed per candidate
  uint32_t warmup = 1;
  uint32_t bakeSize = 512;
  std::optional<engine::ImageSize> resolution;  // --resolution: replaces the scene's
  std::vector<std::string> params;              // NAME=MIN:MAX parameter ranges
  uint32_t paramSamples = 1;
  uint64_t seed = 1;
  std::string device;
  bool validation = false;
  tune::PolicyChoiceOptions policyChoice;  // the chain's level-of-detail policy
};

// Declares the options on `app`, spire-simplify's command line with --search.
void defineSearchOptions(CLI::App& app, SearchOptions& options);

}  // namespace spire::search
