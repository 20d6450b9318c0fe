// He et al. 2015's greedy simplification search (section 4.4, Listing 2),
// measured by rendering: at each step every selected component's current
// definition gets K1 rewrites per rule; each candidate's error is measured
// by spire-tune's Tuner (RMSE against the original over every camera view
// and parameter sample) or taken from the error cache; the candidates within
// K2 x the median error are ranked by cost (search::costOf: He et al.'s
// model C by default) saved per error added; the chosen one is measured
// fresh, and when its cached error was off by more than K3 x itself the
// cache is emptied and the step chosen again. The accepted level must keep
// the chain monotone (error never falls, cost always falls); otherwise the
// next candidate is tried. The search stops after the
// maximum number of levels, when no candidate is within the error budget, or
// when no rewrite is left.
#pragma once

#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "renderer/scene_renderer.h"
#include "scene/scene_file.h"
#include "search/candidates.h"
#include "search/chain.h"
#include "search/search_options.h"
#include "simplify/user_rules.h"
#include "support/expected.h"
#include "tune/tuner.h"

namespace spire::search {

struct SearchSetup {
  // The renderer's scene: each step points the instance at its module.
  scene::SceneFile* scene = nullptr;
  size_t instance = 0;
  tune::Tuner* tuner = nullptr;   // its reference rendered: the original shader
  std::filesystem::path workDir;  // where the step modules are written for the renderer
  ModuleCompile compile;
  ModuleHeader header;  // of modules in workDir
  Placement original;   // level 0's placement
  std::vector<std::string> components;
  const std::vector<simplify::UserRule>* userRules = nullptr;  // beside the built-in rules; null: none
};

// The chain, level 0 (the original, measured like the others) first.
// `progress` gets a line per step.
Expected<Chain, Failure> greedySearch(const SearchSetup& setup, const SearchOptions& options, std::ostream& progress);

}  // namespace spire::search
