#include "search/search_tool.h"

#include <fmt/format.h>
#include <unistd.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <filesystem>
#include <optional>
#include <ostream>

#include "driver/exit_codes.h"
#include "driver/tool_arguments.h"
#include "measure/image_metrics.h"
#include "scene/texture.h"
#include "search/chain_policy.h"
#include "search/greedy_search.h"
#include "search/search_outputs.h"
#include "search/transitions.h"
#include "simplify/rewrite_target.h"
#include "support/file_io.h"
#include "tool/tool_run.h"
#include "tune/parameter_range.h"

namespace spire::search {

namespace {

namespace fs = std::filesystem;

constexpr const char* kTool = "spire-simplify";

// The folder the step modules are written to, for the renderer to read;
// removed with everything in it when the run ends.
class WorkDir {
 public:
  WorkDir() : path_(fs::temp_directory_path() / fmt::format("spire-search-{}-{}", ::getpid(), counter_++)) {
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~WorkDir() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  WorkDir(const WorkDir&) = delete;
  WorkDir& operator=(const WorkDir&) = delete;
  const fs::path& path() const { return path_; }

 private:
  static inline int counter_ = 0;
  fs::path path_;
};

// The output folder is replaced as a whole: refuse one that holds anything
// but an earlier search's output.
std::optional<std::string> outputProblem(const std::string& dir) {
  std::error_code ec;
  if (!fs::exists(dir, ec)) return std::nullopt;
  if (!fs::is_directory(dir, ec)) return fmt::format("'{}' is not a directory", dir);
  if (fs::is_empty(dir, ec) || fs::exists(fs::path(dir) / "chain.csv", ec)) return std::nullopt;
  return fmt::format("'{}' is not empty and holds no earlier search (no chain.csv); it would be replaced", dir);
}

std::optional<size_t> findInstance(const scene::SceneFile& scene, const std::string& shader) {
  const auto& instances = scene.instances;
  const auto it = std::find_if(instances.begin(), instances.end(),
                               [&](const scene::InstanceDesc& i) { return i.shader == shader && !i.kernels; });
  if (it == instances.end()) return std::nullopt;
  return static_cast<size_t>(it - instances.begin());
}

Expected<tune::TunerOptions, Failure> tunerOptions(const SearchOptions& options, const scene::SceneFile& scene,
                                                   size_t instance) {
  tune::TunerOptions tuner;
  tuner.timing.minPairs = options.frames;
  tuner.timing.maxPairs = options.frames;
  tuner.warmupFrames = options.warmup;
  auto ranges = tune::parseParameters(options.params, scene.instances.at(instance), scene);
  if (!ranges) return ranges.error();
  tuner.parameterSamples = tune::parameterSamples(*ranges, options.paramSamples, options.seed);
  return tuner;
}

ModuleHeader headerIn(const fs::path& folder, const scene::InstanceDesc& instance, const SearchOptions& options) {
  const fs::path source = fs::absolute(instance.source);
  return {fs::relative(source, fs::absolute(folder)).generic_string(), options.shader,
          options.derivedName.empty() ? options.shader + "Search" : options.derivedName};
}

// The components to rewrite and level 0's placement, from the original
// shader as the scene compiles it, before the search points the instance
// elsewhere.
Expected<SearchSetup, Failure> makeSetup(engine::SceneRenderer& renderer, scene::SceneFile& scene, size_t instance,
                                         const SearchOptions& options) {
  auto library = renderer.library(instance);
  if (!library) return Failure{library.error().message + library.error().details};
  // A scene draws concrete shaders by name, so a shader derived from a group
  // (whose base is a group's too) never gets here: the scene's compile
  // refuses it first.
  auto base = simplify::shaderToDerive((*library)->model(), options.shader);
  if (!base) return base.error();
  auto components = simplify::selectComponents(*base, options.components);
  if (!components) return components.error();
  auto programs = renderer.compile(std::nullopt);
  if (!programs) return Failure{programs.error().message + programs.error().details};
  const scene::InstanceDesc& desc = scene.instances.at(instance);
  SearchSetup setup;
  setup.scene = &scene;
  setup.instance = instance;
  for (const sem::Component* c : components->components) setup.components.push_back(c->name);
  setup.original = programs->at(instance).placement;
  for (const fs::path& dir : scene.includePaths) setup.compile.frontEnd.includeDirs.push_back(dir.string());
  setup.compile.frontEnd.pipeline = desc.pipeline;
  if (desc.pipelineSource) setup.compile.pipelineSource = desc.pipelineSource->string();
  return setup;
}

void printSummary(const Chain& chain, const SearchOptions& options, std::ostream& out) {
  const Level& last = chain.levels.back();
  out << fmt::format(
      "{}: wrote a chain of {} level(s) after the original to {} (last: RMSE {:.6f}, time ratio {:.3f}); "
      "stopped: {}\n",
      kTool, chain.steps.size(), options.outputDir, last.error, last.timeRatio, chain.stopReason);
}

// `placement` drawn from the first camera view, as PNG: the instance must
// point at a module that defines what it names.
Expected<std::string, Failure> imageOf(tune::Tuner& tuner, const Placement& placement) {
  tune::TunePoint point;
  point.decisions = {placement.begin(), placement.end()};
  auto capture = tuner.capture(point);
  if (!capture) return Failure{fmt::format("cannot be drawn: {}", capture.error().message)};
  auto png = scene::encodePng(measure::toRgba8(capture->color));
  if (!png) return Failure{fmt::format("its image cannot be encoded: {}", png.error().message)};
  return std::move(png).value();
}

// Each level of `chain` from the first camera view, as PNG.
Expected<std::vector<std::string>, Failure> levelImages(tune::Tuner& tuner, const Chain& chain) {
  std::vector<std::string> images;
  for (size_t k = 0; k < chain.levels.size(); ++k) {
    auto png = imageOf(tuner, chain.levels[k].placement);
    if (!png) return Failure{fmt::format("level {} {}", k, png.error().message)};
    images.push_back(std::move(png).value());
  }
  return images;
}

// The chain's module with `transitions`' definitions, written to the work
// folder and compiled; the instance is pointed at it.
Expected<void, Failure> useTransitionModule(const Chain& chain, const SearchSetup& setup,
                                            const Transitions& transitions) {
  const std::string text = chainModuleText(setup.header, chain, transitionDefinitions(transitions));
  const fs::path path = setup.workDir / "transitions.spire";
  auto compiled = compileModule(setup.compile, path.string(), text, setup.header.derived);
  if (!compiled) return compiled.error();
  if (auto written = writeFileAtomically(path.string(), text); !written) return written.error();
  setup.scene->instances.at(setup.instance).source = path;
  return {};
}

// The distance the transitions blend by: the user's, or the eye's in world
// units.
Expected<FadeDistance, Failure> fadeDistance(const ShaderLibrary& module, const std::string& derived,
                                             const SearchOptions& options) {
  if (options.transitionDistance) return FadeDistance{*options.transitionDistance, {}};
  const sem::Shader* shader = module.model().findShader(derived);
  if (!shader) return Failure{fmt::format("the chain's module has no shader '{}'", derived)};
  return eyeDistanceInWorld(*shader);
}

// He et al.'s transition shaders at the switches of the chain's policy, each
// drawn from the first camera view (so that it compiles and validates). None,
// with a note saying why, where the policy does not switch or where the
// shader cannot compute the default distance; a distance the user gave must
// compile.
Expected<ChainTransitions, Failure> makeTransitions(const Chain& chain, const ChainPolicy& policy,
                                                    const SearchSetup& setup, const SearchOptions& options,
                                                    tune::Tuner& tuner) {
  ChainTransitions made;
  if (options.transitionWidth <= 0.0) {
    made.note = "--transition-width is 0";
    return made;
  }
  auto module = compileModule(setup.compile, (setup.workDir / "chain.spire").string(),
                              chainModuleText(setup.header, chain), setup.header.derived);
  if (!module) return module.error();
  auto distance = fadeDistance(**module, setup.header.derived, options);
  if (!distance) {
    made.note = "the shader cannot compute the eye's distance in world units: " + distance.error().message +
                " (--transition-distance gives a distance it can compute)";
    return made;
  }
  const TransitionShape shape{options.transitionWidth, std::move(distance).value()};
  auto transitions = chainTransitions(chain, policy.policy, **module, setup.header.derived, shape);
  if (!transitions) return transitions.error();
  if (transitions->list.empty()) {
    made.note = "the policy draws one level of the chain at every distance";
    return made;
  }
  if (auto used = useTransitionModule(chain, setup, *transitions); !used) {
    const std::string why = fmt::format("the transition shaders do not compile with the distance '{}': {}",
                                        shape.distance.expression, used.error().message);
    if (options.transitionDistance) return Failure{why};
    made.note = why + " (--transition-distance gives a distance the shader can compute)";
    return made;
  }
  for (const Transition& t : transitions->list) {
    const auto failed = [&](const std::string& why) {
      return Failure{fmt::format("the transition from level {} to level {}: {}", t.from, t.to, why)};
    };
    auto png = imageOf(tuner, t.placement);
    if (!png) return failed(png.error().message);
    tune::TunePoint point;
    point.decisions = {t.placement.begin(), t.placement.end()};
    const tune::VariantResult timed = tuner.measure(point);
    if (!timed.ok()) return failed(timed.status);
    made.drawn.push_back({std::move(png).value(), timed.time.median});
  }
  made.transitions = std::move(transitions).value();
  return made;
}

// "transition shaders: N" and each one's band and cost, or why there are
// none.
void printTransitions(const Chain& chain, const ChainTransitions& made, std::ostream& out) {
  const std::vector<Transition>& list = made.transitions.list;
  if (list.empty()) {
    out << "transition shaders: none: " << made.note << "\n";
    return;
  }
  out << fmt::format("transition shaders: {}\n", list.size());
  for (size_t i = 0; i < list.size(); ++i) {
    const Transition& t = list[i];
    out << fmt::format("  level {} to {}, from {:.4g} to {:.4g}: time ratio {:.3f} (the levels: {:.3f}, {:.3f})\n",
                       t.from, t.to, t.nearDistance, t.farDistance, made.drawn.at(i).timeRatio,
                       chain.levels.at(t.from).timeRatio, chain.levels.at(t.to).timeRatio);
  }
}

// The search on the renderer, then its outputs; the exit status.
int search(const SearchOptions& options, const simplify::UserRules& rules, engine::ToolRun& run,
           engine::SceneRenderer& renderer, scene::SceneFile& scene, size_t instance, std::ostream& out) {
  const auto fail = [&](const std::string& message) { return run.fail(engine::Error{message, {}, {}}); };
  auto measurement = tunerOptions(options, scene, instance);
  if (!measurement) return fail(measurement.error().message);
  tune::Tuner tuner(renderer, instance, {}, std::move(measurement).value());
  const auto referencePath =
      options.reference ? std::optional<std::filesystem::path>(*options.reference) : std::nullopt;
  if (auto reference = tuner.renderReference(referencePath); !reference) return run.fail(reference.error());
  auto setup = makeSetup(renderer, scene, instance, options);
  if (!setup) return fail(setup.error().message);
  const WorkDir work;
  setup->tuner = &tuner;
  setup->userRules = &rules.rules();
  setup->workDir = work.path();
  setup->header = headerIn(work.path(), scene.instances.at(instance), options);
  const ModuleHeader outputHeader = headerIn(options.outputDir, scene.instances.at(instance), options);
  auto chain = greedySearch(*setup, options, out);
  if (!chain) return fail(chain.error().message);
  if (options.reference) chain->measuredAgainst = fmt::format("the variant of `{}`", *options.reference);
  std::optional<ChainPolicy> policy;
  ChainTransitions transitions;
  if (!chain->steps.empty()) {
    auto chosen = chainPolicy(*chain, *setup, renderer, options, options.outputDir);
    if (!chosen) return fail(chosen.error().message);
    policy = std::move(chosen).value();
    out << "level-of-detail policy of the chain:\n" << policy->table;
    auto made = makeTransitions(*chain, *policy, *setup, options, tuner);
    if (!made) return fail(made.error().message);
    transitions = std::move(made).value();
    printTransitions(*chain, transitions, out);
  }
  auto images = levelImages(tuner, *chain);
  if (!images) return fail(images.error().message);
  auto files = searchOutputs(*chain, {outputHeader, &options, tuner.referenceMs(), policy ? &*policy : nullptr,
                                      std::move(images).value(), std::move(transitions)});
  if (!files) return fail(files.error().message);
  if (auto written = replaceDirectoryAtomically(options.outputDir, *files); !written) {
    return fail(written.error().message);
  }
  printSummary(*chain, options, out);
  return kExitSuccess;
}

}  // namespace

bool wantsSearch(const std::vector<std::string>& args) {
  return std::find(args.begin(), args.end(), "--search") != args.end();
}

int runSearchTool(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  CLI::App app{
      "spire-simplify --search: He et al. 2015's greedy simplification of a scene's shader, measured by "
      "rendering, written as a level-of-detail chain",
      kTool};
  SearchOptions options;
  defineSearchOptions(app, options);
  if (const auto status = parseToolArguments(app, args, out, err)) return *status;
  if (const auto problem = tune::distancesProblem(options.policyChoice.distances)) {
    return usageError(kTool, *problem, err);
  }
  if (const auto problem = outputProblem(options.outputDir)) {
    err << fmt::format("{}: error: {}\n", kTool, *problem);
    return kExitUsageError;
  }
  simplify::UserRules rules;
  if (!simplify::readRuleFiles(options.ruleFiles, rules, kTool, err)) return kExitInputError;
  engine::ToolRun run(kTool, err);
  if (const auto status = run.loadScene(options.scenePath, options.resolution)) return *status;
  const auto instance = findInstance(run.scene(), options.shader);
  if (!instance) {
    return run.fail(engine::Error{
        fmt::format("no instance of '{}' compiles shader '{}' from source", options.scenePath, options.shader),
        {},
        {}});
  }
  if (const auto status = run.openDevice({options.device, options.validation, {}, {}})) return *status;
  // A copy of the scene the search can point its instance at each step's
  // module; the renderer keeps its meshes, textures and bakes throughout.
  scene::SceneFile scene = run.scene();
  engine::TextureBakeOptions bakeOptions;
  bakeOptions.defaultSize = options.bakeSize;
  engine::SceneRenderer renderer(run.context(), scene, run.diagnostics(), bakeOptions);
  return run.finish(search(options, rules, run, renderer, scene, *instance, out));
}

}  // namespace spire::search
