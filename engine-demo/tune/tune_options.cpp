#include "tune/tune_options.h"

#include "driver/tool_arguments.h"

namespace spire::tune {

namespace {

void defineLodPolicyOptions(CLI::App& app, TuneOptions& options, CLI::Option* shader) {
  app.add_option("--lod-policy", options.lodPolicyPath,
                 "Instead of tuning a shader, measure each level of the scene's level-of-detail policy and write the "
                 "policy chosen from the measurements to PATH (docs/lod.md)")
      ->excludes(shader)
      ->type_name("PATH");
  addPolicyChoiceOptions(app, options.policyChoice, "--lod-policy");
}

}  // namespace

void defineTuneOptions(CLI::App& app, TuneOptions& options) {
  addVersionFlag(app);
  app.add_option("scene", options.scenePath, "Scene file (docs/scene.md)")->required()->type_name("SCENE.json");
  auto* shader = app.add_option("--shader", options.shader,
                                "The shader to tune (an instance of the scene must use it; or --lod-policy)")
                     ->type_name("NAME");
  app.add_option("--components", options.components,
                 "Components to explore (default: every choice); NAME@World keeps only World's placements for NAME "
                 "(repeat it for more worlds)")
      ->delimiter(',')
      ->type_name("A,B,...");
  app.add_option("--only", options.only, "Keep placements in these worlds or with these variation names")
      ->delimiter(',')
      ->type_name("NAME,...");
  app.add_option("--max-variants", options.maxVariants, "Sample the product when it has more variants")->type_name("N");
  app.add_option("--seed", options.seed, "Seed of the sample")->type_name("N");
  app.add_option("--frames", options.frames,
                 "Pairs of frames (variant, reference) measured per variant (at least 3); with --lod-policy, "
                 "frames per level")
      ->check(CLI::Range(3U, 1000U))
      ->type_name("N");
  app.add_option("--max-frames", options.maxFrames,
                 "Candidates for the front are measured again, adding pairs while the time ratio's 95% interval "
                 "is wider than 6%, up to N")
      ->check(CLI::Range(3U, 1000U))
      ->type_name("N");
  addWarmupAndBakeSizeOptions(app, options.warmup, options.bakeSize);
  engine::addResolutionOption(app, options.resolution);
  app.add_option("-j,--jobs", options.jobs, "Worker processes (default: one per core)")
      ->check(CLI::Range(1U, 64U))
      ->type_name("N");
  addOutputDirectory(app, options.outputDir, "Output directory (an interrupted run resumes from it)");
  app.add_option("--time-budget", options.timeBudgetMs, "Write the most accurate variant within MS per frame")
      ->type_name("MS");
  app.add_option("--error-budget", options.errorBudget, "Write the fastest variant within RMSE E")->type_name("E");
  app.add_option("--reference", options.reference,
                 "Decision file of the reference (default: the scene's first variant)")
      ->type_name("PATH");
  app.add_option("--device", options.device, "Vulkan device whose name contains TEXT")->type_name("TEXT");
  app.add_flag("--validation", options.validation, "Enable VK_LAYER_KHRONOS_validation; any message fails the run");
  app.add_option("--param", options.params,
                 "Measure error over samples of a material parameter's range (repeatable): its minimum, its maximum "
                 "and random values; a texture is swept as solid colors, over its own texels' range when given as "
                 "NAME alone")
      ->type_name("NAME=MIN:MAX");
  app.add_option("--param-samples", options.paramSamples, "Random samples besides the minimum and maximum")
      ->check(CLI::Range(0U, 100U))
      ->type_name("N");
  app.add_flag("--extremes", options.extremes,
               "Measure error over the extremes of every material input, unnamed ones too (a number v from 0 to "
               "max(1, 2|v|) on its side of 0; a texture as solid colors from 0 to 1 per channel and its own darkest "
               "and brightest texels; --param overrides an input's range): the scene's values, every input at its "
               "minimum, every one at its maximum, each input alone at its minimum and at its maximum (a texture "
               "also at its own two), and N random draws; 3 + 2 per input + 2 per automatic texture + N samples. "
               "Writes stability.csv: which input's extreme makes which component NaN or Inf");
  app.add_option(
         "--shader-cache", options.shaderCache,
         "lavapipe's shader cache: 'run' (default) a fresh one for this run, shared by its workers, so a kernel "
         "that variants share is compiled once; 'off' compiles every pipeline in full; 'inherit' keeps the "
         "environment's MESA_SHADER_CACHE_* settings")
      ->check(CLI::IsMember({"run", "off", "inherit"}))
      ->type_name("MODE");
  defineLodPolicyOptions(app, options, shader);
  app.add_option("--worker", options.worker, "Internal: measure shard K")->group("");
}

void addPolicyChoiceOptions(CLI::App& app, PolicyChoiceOptions& options, const std::string& what) {
  app.add_option("--distances", options.distances,
                 what +
                     ": camera distances to measure at, increasing (default: 1, 2, 4, ... up to half the camera's far "
                     "plane)")
      ->delimiter(',')
      ->check(CLI::PositiveNumber)
      ->type_name("D,D,...");
  app.add_option("--max-error", options.maxError, what + ": RMSE tolerated at the farthest distance (default 0.25)")
      ->check(CLI::PositiveNumber)
      ->type_name("E");
  app.add_option("--error-exponent", options.errorExponent,
                 what + ": tolerance curve ((d - nearest) / (farthest - nearest))^Q * max error (default 0.5)")
      ->check(CLI::PositiveNumber)
      ->type_name("Q");
  app.add_option("--switch-penalty", options.switchPenalty,
                 what + ": cost of a level switch, as a share of a full-quality frame (default 0.05)")
      ->check(CLI::NonNegativeNumber)
      ->type_name("P");
}

void addWarmupAndBakeSizeOptions(CLI::App& app, uint32_t& warmup, uint32_t& bakeSize) {
  app.add_option("--warmup", warmup,
                 "Unmeasured frames before the measured ones (the captures of the camera views count)")
      ->check(CLI::Range(1U, 100U))
      ->type_name("N");
  app.add_option("--bake-size", bakeSize, "PrebakeTex size without a TextureSize hint")
      ->check(CLI::Range(1U, 8192U))
      ->type_name("N");
}

}  // namespace spire::tune
