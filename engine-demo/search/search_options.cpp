#include "search/search_options.h"

#include <CLI/CLI.hpp>

#include <map>
#include <string>

#include "driver/tool_arguments.h"
#include "tool/engine_options.h"
#include "tune/tune_options.h"

namespace spire::search {

namespace {

void defineMeasurement(CLI::App& app, SearchOptions& options) {
  app.add_option("--frames", options.frames, "Pairs of frames (candidate, reference) timed per candidate (default 5)")
      ->check(CLI::Range(3U, 1000U))
      ->type_name("N");
  tune::addWarmupAndBakeSizeOptions(app, options.warmup, options.bakeSize);
  engine::addResolutionOption(app, options.resolution);
  app.add_option("--param", options.params,
                 "Measure error over samples of a material parameter's range (repeatable), as spire-tune does")
      ->type_name("NAME=MIN:MAX");
  app.add_option("--param-samples", options.paramSamples, "Random samples besides the minimum and maximum")
      ->check(CLI::Range(0U, 100U))
      ->type_name("N");
  app.add_option("--seed", options.seed, "Seed of the parameter samples")->type_name("N");
  app.add_option("--device", options.device, "Vulkan device whose name contains TEXT")->type_name("TEXT");
  app.add_flag("--validation", options.validation, "Enable VK_LAYER_KHRONOS_validation; any message fails the run");
}

}  // namespace

void defineSearchOptions(CLI::App& app, SearchOptions& options) {
  addVersionFlag(app);
  app.add_flag("--search")->description("Search: He et al. 2015's greedy search on a scene (this command line)");
  app.add_option("--scene", options.scenePath, "Scene file (docs/scene.md)")->required()->type_name("SCENE.json");
  app.add_option("--shader", options.shader, "The shader to simplify (an instance of the scene must use it)")
      ->required()
      ->type_name("NAME");
  app.add_option("--component", options.components,
                 "Simplify only this component (repeatable; default: every one the shader defines)")
      ->type_name("NAME");
  app.add_option("--rules", options.ruleFiles,
                 "Also propose the rewrites of the user rules of FILE (repeatable; docs/simplify.md, \"User "
                 "rules\")")
      ->type_name("FILE");
  app.add_flag("--no-average{false}", options.average,
               "Leave out Pellacini's average rule (a subtree replaced by its average over the scene's views and "
               "parameter samples, measured by rendering a probe of each site)");
  app.add_flag("--no-acse{false}", options.acse,
               "Leave out approximate common subexpression elimination (a subtree replaced by the component whose "
               "values at the scene's pixels are closest to its own, measured by rendering each)");
  app.add_flag("--no-moves{false}", options.moves,
               "Leave out moves: a component's current definition put in another world its choices offer (He et "
               "al.'s move to vertex and move to parameter stage), chosen jointly with the rewrites");
  app.add_flag("--renormalize", options.renormalize,
               "Shift every candidate so that its component's average over the scene is the original's, as "
               "Pellacini 2005 renormalizes (one more render per candidate)");
  app.add_option("--k1", options.k1, "Rewrites each rule proposes per component and step (default 2)")
      ->check(CLI::Range(size_t{1}, size_t{100}))
      ->type_name("N");
  app.add_option("--k2", options.k2, "Keep candidates whose error is at most K2 x the median error (default 1)")
      ->check(CLI::PositiveNumber)
      ->type_name("X");
  app.add_option("--k3", options.k3,
                 "A cached error off the fresh one by more than K3 x itself empties the cache and the step is "
                 "chosen again (default 0.15)")
      ->check(CLI::NonNegativeNumber)
      ->type_name("X");
  app.add_option("--max-levels", options.maxLevels, "Levels after the original (default 6)")
      ->check(CLI::Range(size_t{1}, size_t{1000}))
      ->type_name("N");
  app.add_option("--error-budget", options.errorBudget, "Stop before a level whose RMSE exceeds E")
      ->check(CLI::NonNegativeNumber)
      ->type_name("E");
  app.add_option("--reference", options.reference,
                 "Measure every level's error and time against the variant of this decision file (full quality, "
                 "when the scene's instance starts from a tuned variant) instead of level 0; --error-budget then "
                 "bounds the error against it")
      ->type_name("DECISIONS");
  app.add_option("--cost", options.cost,
                 "What candidates are ranked and the chain ordered by: 'model', He et al.'s C = 0.3 C_v + 0.7 C_f + "
                 "10 N_var of the program (default), or 'time', the measured frame time")
      ->transform(CLI::CheckedTransformer(
          std::map<std::string, CostKind>{{"model", CostKind::Model}, {"time", CostKind::Time}}))
      ->type_name("model|time");
  app.add_option("--transition-width", options.transitionWidth,
                 "The part of each policy band, before its edge, over which a transition shader blends it into the "
                 "next (default 0.2; 0: no transition shaders)")
      ->check(CLI::Range(0.0, 0.9))
      ->type_name("F");
  app.add_option("--transition-distance", options.transitionDistance,
                 "The distance the transition shaders blend by: a Spire expression over the shader's components "
                 "(default: the eye's distance in world units, 'length(cameraPosWorld - (matModel * vec4(vert_pos, "
                 "1.0)).xyz)')")
      ->type_name("EXPR");
  app.add_option("--name", options.derivedName, "The derived shader's name (default: SHADER + Search)")
      ->type_name("NAME");
  addOutputDirectory(app, options.outputDir, "Write the chain (module, decision files, report) to DIR")->required();
  defineMeasurement(app, options);
  tune::addPolicyChoiceOptions(app, options.policyChoice, "The chain's policy");
}

}  // namespace spire::search
