#include "tune/tune_session.h"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>

#include "driver/exit_codes.h"
#include "tune/extremes.h"
#include "tune/parameter_range.h"
#include "tune/run_settings.h"

namespace spire::tune {
namespace {

namespace fs = std::filesystem;

std::optional<int> findInstance(const TuneOptions& options, engine::ToolRun& run, TuneSession& session) {
  const std::vector<scene::InstanceDesc>& instances = run.scene().instances;
  const auto instance = std::find_if(instances.begin(), instances.end(),
                                     [&](const scene::InstanceDesc& i) { return i.shader == options.shader; });
  if (instance == instances.end()) {
    return run.fail(fmt::format("no instance of '{}' uses shader '{}'", options.scenePath, options.shader));
  }
  session.instance = &*instance;
  session.instanceIndex = static_cast<size_t>(instance - instances.begin());
  return std::nullopt;
}

// The points of the shader's choices that the options select.
std::optional<int> buildSpace(const TuneOptions& options, engine::ToolRun& run, TuneSession& session) {
  auto library = run.renderer().library(session.instanceIndex);
  if (!library) return run.fail(library.error());
  SpaceRequest request;
  request.components = options.components;
  request.only = options.only;
  request.maxVariants = options.maxVariants;
  request.seed = options.seed;
  if (const graph::ChoiceSpace* choices = (*library)->choiceSpace(options.shader)) {
    request.transitions = transitionPlacements(*choices);
  }
  auto space = buildTuneSpace((*library)->choices(options.shader), request);
  if (!space) return run.fail({space.error().message, session.instance->shaderRange, {}});
  session.space = std::move(*space);
  for (const Axis& axis : session.space.axes) session.components.push_back(axis.component);
  return std::nullopt;
}

// The reference, the parameter samples and the tuner.
std::optional<int> startTuner(const TuneOptions& options, engine::ToolRun& run, TuneSession& session,
                              std::ostream& err) {
  if (!options.reference.empty())
    session.reference = options.reference;
  else if (!run.scene().variants.empty())
    session.reference = run.scene().variants.front().decisions;
  auto parsed = parseParameters(options.params, *session.instance, run.scene());
  if (!parsed) {
    err << fmt::format("spire-tune: error: {}\n", parsed.error().message);
    return kExitUsageError;
  }
  const std::vector<ParameterRange>& ranges = *parsed;
  TunerOptions tunerOptions;
  // Every variant gets `frames` pairs; only candidates for the front get
  // more, when racing.
  tunerOptions.timing.minPairs = options.frames;
  tunerOptions.timing.maxPairs = options.frames;
  tunerOptions.warmupFrames = options.warmup;
  if (options.extremes) {
    auto all = extremeRanges(*session.instance, run.scene(), ranges);
    if (!all) return run.fail(all.error().message);
    SamplePlan plan = extremeSamples(*all, options.paramSamples, options.seed);
    tunerOptions.parameterSamples = std::move(plan.samples);
    tunerOptions.sampleLabels = std::move(plan.labels);
    tunerOptions.extremes = true;
  } else {
    tunerOptions.parameterSamples = parameterSamples(ranges, options.paramSamples, options.seed);
  }
  session.tuner.emplace(run.renderer(), session.instanceIndex, session.space.axes, tunerOptions);
  return std::nullopt;
}

// The output directory, and the rows an earlier run left in it, which are
// resumed only under the settings they were measured with.
std::optional<int> openOutput(const TuneOptions& options, engine::ToolRun& run, TuneSession& session) {
  std::error_code ec;
  fs::create_directories(options.outputDir, ec);
  if (ec) return run.fail(fmt::format("cannot create '{}': {}", options.outputDir, ec.message()));
  auto done = loadDone(options, session.components);
  if (!done) return run.fail(done.error().message);
  auto library = run.renderer().library(session.instanceIndex);
  if (!library) return run.fail(library.error());
  const RunSettings settings =
      runSettings(options, run, session.reference ? session.reference->string() : "", (*library)->sources());
  if (auto checked = recordOrCheckSettings(options.outputDir, settings, !done->empty()); !checked) {
    return run.fail(checked.error().message);
  }
  session.done = std::move(*done);
  return std::nullopt;
}

}  // namespace

std::optional<int> startSession(const TuneOptions& options, engine::ToolRun& run, TuneSession& session,
                                std::ostream& err) {
  if (const auto status = run.loadScene(options.scenePath, options.resolution)) return status;
  if (const auto status = findInstance(options, run, session)) return status;
  if (const auto status = run.openDevice({options.device, options.validation, {}, {}})) return status;
  run.startRenderer(options.bakeSize);
  if (const auto status = buildSpace(options, run, session)) return status;
  if (const auto status = startTuner(options, run, session, err)) return status;
  return openOutput(options, run, session);
}

fs::path shardPath(const TuneOptions& options, int worker) {
  return fs::path(options.outputDir) / fmt::format("shard-{}.csv", worker);
}

fs::path splitPath(const TuneOptions& options, int worker) {
  return fs::path(options.outputDir) / fmt::format("shard-{}.time", worker);
}

fs::path queuePath(const TuneOptions& options) { return fs::path(options.outputDir) / "work-queue"; }

Expected<std::map<uint64_t, VariantResult>, Failure> loadDone(const TuneOptions& options,
                                                              const std::vector<std::string>& components) {
  std::map<uint64_t, VariantResult> done;
  std::vector<fs::path> files{fs::path(options.outputDir) / "variants.csv"};
  if (fs::exists(options.outputDir)) {
    for (const auto& entry : fs::directory_iterator(options.outputDir)) {
      const std::string name = entry.path().filename().string();
      if (name.starts_with("shard-") && entry.path().extension() == ".csv") files.push_back(entry.path());
    }
  }
  for (const fs::path& file : files) {
    auto rows = readResults(file, components);
    if (!rows) return rows.error();
    for (VariantResult& row : *rows) done[row.index] = std::move(row);
  }
  return done;
}

void appendRow(const fs::path& path, const std::vector<std::string>& components, const VariantResult& result) {
  const bool fresh = !fs::exists(path);
  // A row an interruption cut short ends without a newline; the next row
  // starts on a line of its own, so only the cut one is lost.
  bool torn = false;
  if (!fresh) {
    std::ifstream in(path, std::ios::binary | std::ios::ate);
    if (in.tellg() > 0) {
      in.seekg(-1, std::ios::end);
      torn = in.get() != '\n';
    }
  }
  std::ofstream file(path, std::ios::app);
  if (fresh) file << csvHeader(components);
  if (torn) file << '\n';
  file << csvRow(result);
  file.flush();
}

}  // namespace spire::tune
