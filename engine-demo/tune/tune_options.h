// The spire-tune command line: what a tuning run explores, how it measures
// and where it writes (docs/engine.md, "The tuner").
#pragma once

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdint>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "tool/engine_options.h"

namespace spire::tune {

// How a level-of-detail policy is chosen from measurements (docs/lod.md,
// "Policies from measurements"): spire-tune --lod-policy and
// spire-simplify --search take the same options.
struct PolicyChoiceOptions {
  std::vector<float> distances;  // empty: doubling from 1 to half the camera's far plane
  double maxError = 0.25;
  double errorExponent = 0.5;
  double switchPenalty = 0.05;
};

struct TuneOptions {
  std::string scenePath;
  std::string shader;
  std::vector<std::string> components;
  std::vector<std::string> only;
  uint64_t maxVariants = 4096;
  uint64_t seed = 1;
  uint32_t frames = 3;      // pairs of frames per variant
  uint32_t maxFrames = 15;  // pairs at most for a candidate for the front (racing)
  uint32_t warmup = 1;
  uint32_t jobs = std::max(1U, std::thread::hardware_concurrency());
  uint32_t bakeSize = 512;
  std::string outputDir = "out/tune";
  std::optional<double> timeBudgetMs;
  std::optional<double> errorBudget;
  std::string reference;
  std::string device;
  bool validation = false;
  std::optional<engine::ImageSize> resolution;  // --resolution: replaces the scene's
  int worker = -1;                              // a worker process (--worker K); -1 in the coordinator
  std::string shaderCache = "run";
  std::vector<std::string> params;  // NAME=MIN:MAX
  uint32_t paramSamples = 1;
  bool extremes = false;  // a range for every material input, and per-input corners (tune/extremes.h)
  // --lod-policy: derive a level-of-detail policy instead of tuning a shader.
  std::string lodPolicyPath;
  PolicyChoiceOptions policyChoice;
};

// Adds every option of spire-tune to `app`, read into `options`.
void defineTuneOptions(CLI::App& app, TuneOptions& options);

// --warmup and --bake-size, as every tool that measures through the tuner
// (spire-tune, spire-simplify --search) offers them.
void addWarmupAndBakeSizeOptions(CLI::App& app, uint32_t& warmup, uint32_t& bakeSize);

// --distances, --max-error, --error-exponent and --switch-penalty; `what`
// says in their help what they apply to ("--lod-policy").
void addPolicyChoiceOptions(CLI::App& app, PolicyChoiceOptions& options, const std::string& what);

}  // namespace spire::tune
