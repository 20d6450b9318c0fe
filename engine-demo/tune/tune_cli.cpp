#include "tune/tune_cli.h"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <random>
#include <set>
#include <thread>

#include "measure/image_metrics.h"
#include "renderer/error_report.h"
#include "driver/tool_arguments.h"
#include "graph/decision_file.h"
#include "renderer/host_allocator.h"
#include "renderer/scene_renderer.h"
#include "support/file_io.h"
#include "tune/error_plot.h"
#include "tune/format_selection.h"
#include "tune/pareto.h"
#include "tune/tuner.h"
#include "tune/work_queue.h"
#include "vk/context.h"
#include "vk/timer.h"

extern char** environ;

namespace spire::tune {

namespace {

namespace fs = std::filesystem;

struct Options {
  std::string scenePath;
  std::string shader;
  std::vector<std::string> components;
  std::vector<std::string> only;
  uint64_t maxVariants = 4096;
  uint64_t seed = 1;
  uint32_t frames = 3;
  uint32_t warmup = 1;
  uint32_t jobs = std::max(1U, std::thread::hardware_concurrency());
  uint32_t bakeSize = 512;
  std::string outputDir = "out/tune";
  std::optional<double> timeBudgetMs;
  std::optional<double> errorBudget;
  std::string reference;
  std::string device;
  bool validation = false;
  int worker = -1;
  std::string shaderCache = "run";
  std::vector<std::string> params;  // NAME=MIN:MAX
  uint32_t paramSamples = 1;
};

struct ParameterRange {
  std::string component;
  double minimum = 0.0;
  double maximum = 0.0;
  size_t arity = 1;
};

// Parameter samples as in Pellacini 2005: every parameter at its minimum,
// every one at its maximum, then `randomSamples` uniform draws (seeded, so
// workers and reruns agree).
std::vector<ParameterSample> parameterSamples(const std::vector<ParameterRange>& ranges, uint32_t randomSamples,
                                              uint64_t seed) {
  if (ranges.empty()) return {};
  std::vector<ParameterSample> samples(2);
  for (const ParameterRange& r : ranges) {
    samples[0][r.component] = std::vector<double>(r.arity, r.minimum);
    samples[1][r.component] = std::vector<double>(r.arity, r.maximum);
  }
  std::mt19937_64 rng(seed);
  for (uint32_t k = 0; k < randomSamples; ++k) {
    ParameterSample sample;
    for (const ParameterRange& r : ranges) {
      std::uniform_real_distribution<double> draw(r.minimum, r.maximum);
      std::vector<double> values(r.arity);
      for (double& v : values) v = draw(rng);
      sample[r.component] = std::move(values);
    }
    samples.push_back(std::move(sample));
  }
  return samples;
}

// Parses NAME=MIN:MAX against the instance's material, which gives the
// value's arity (every component of a vector gets the same range).
std::optional<ParameterRange> parseParameter(const std::string& text, const scene::InstanceDesc& instance,
                                             std::string& error) {
  const size_t equals = text.find('=');
  const size_t colon = text.find(':', equals == std::string::npos ? 0 : equals);
  ParameterRange range;
  if (equals == std::string::npos || colon == std::string::npos) {
    error = fmt::format("--param '{}': expected NAME=MIN:MAX", text);
    return std::nullopt;
  }
  range.component = text.substr(0, equals);
  const std::string low = text.substr(equals + 1, colon - equals - 1);
  const std::string high = text.substr(colon + 1);
  const auto [lowEnd, lowError] = std::from_chars(low.data(), low.data() + low.size(), range.minimum);
  const auto [highEnd, highError] = std::from_chars(high.data(), high.data() + high.size(), range.maximum);
  if (lowError != std::errc{} || highError != std::errc{} || lowEnd != low.data() + low.size() ||
      highEnd != high.data() + high.size() || !(range.minimum <= range.maximum)) {
    error = fmt::format("--param '{}': MIN and MAX must be numbers with MIN <= MAX", text);
    return std::nullopt;
  }
  for (const scene::MaterialBinding& binding : instance.material) {
    if (binding.component == range.component && !binding.texture) {
      range.arity = binding.numbers.size();
      return range;
    }
  }
  error = fmt::format("--param '{}': the instance's material binds no numbers to '{}'", text, range.component);
  return std::nullopt;
}

// lavapipe's (Mesa's) on-disk shader cache for one run. In mode "run", a
// fresh directory that every worker shares and that is removed at the end:
// kernels that many variants share (the vertex and bake kernels) then reach
// LLVM once per run rather than once per variant, while nothing that an
// earlier run or another program cached can make a first use look cheap.
// "off" compiles every pipeline in full; "inherit" leaves the environment
// alone. Mesa reads the variables when a Vulkan device is created, so this
// comes first; the workers inherit them; the destructor restores what the
// environment had, for callers that run the tuner in their own process.
class ShaderCacheSetting {
 public:
  ShaderCacheSetting() = default;
  ShaderCacheSetting(const ShaderCacheSetting&) = delete;
  ShaderCacheSetting& operator=(const ShaderCacheSetting&) = delete;
  ~ShaderCacheSetting() {
    for (const auto& [name, value] : saved_) {
      if (value) ::setenv(name.c_str(), value->c_str(), 1);
      else ::unsetenv(name.c_str());
    }
    std::error_code ec;
    if (!directory_.empty()) fs::remove_all(directory_, ec);
  }

  std::optional<std::string> apply(const std::string& mode) {
    if (mode == "inherit") return std::nullopt;
    if (mode == "off") {
      set("MESA_SHADER_CACHE_DISABLE", "true");
      return std::nullopt;
    }
    std::string pattern = (fs::temp_directory_path() / "spire-tune-shader-cache.XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) {
      return fmt::format("cannot create a shader cache directory like '{}': {}", pattern, std::strerror(errno));
    }
    directory_ = pattern;
    set("MESA_SHADER_CACHE_DISABLE", "false");
    set("MESA_SHADER_CACHE_DIR", pattern);
    return std::nullopt;
  }

 private:
  void set(const std::string& name, const std::string& value) {
    const char* old = std::getenv(name.c_str());
    saved_.emplace_back(name, old ? std::optional<std::string>(old) : std::nullopt);
    ::setenv(name.c_str(), value.c_str(), 1);
  }

  std::vector<std::pair<std::string, std::optional<std::string>>> saved_;
  fs::path directory_;
};

fs::path shardPath(const Options& o, int worker) { return fs::path(o.outputDir) / fmt::format("shard-{}.csv", worker); }
fs::path splitPath(const Options& o, int worker) { return fs::path(o.outputDir) / fmt::format("shard-{}.time", worker); }
fs::path queuePath(const Options& o) { return fs::path(o.outputDir) / "work-queue"; }

// The points that differ only in the last component form a chunk (see
// WorkQueue).
size_t chunkSize(const TuneSpace& space) { return space.axes.empty() ? 1 : space.axes.back().placements.size(); }

std::vector<std::string> componentNames(const TuneSpace& space) {
  std::vector<std::string> names;
  for (const Axis& axis : space.axes) names.push_back(axis.component);
  return names;
}

// Rows already measured: the merged table of an earlier run plus any shard a
// worker appended to before an interruption.
std::optional<std::map<uint64_t, VariantResult>> loadDone(const Options& o, const TuneSpace& space, std::string& error) {
  std::map<uint64_t, VariantResult> done;
  std::vector<fs::path> files{fs::path(o.outputDir) / "variants.csv"};
  if (fs::exists(o.outputDir)) {
    for (const auto& entry : fs::directory_iterator(o.outputDir)) {
      const std::string name = entry.path().filename().string();
      if (name.starts_with("shard-") && entry.path().extension() == ".csv") files.push_back(entry.path());
    }
  }
  for (const fs::path& file : files) {
    auto rows = readResults(file, componentNames(space), error);
    if (!rows) return std::nullopt;
    for (VariantResult& row : *rows) done[row.index] = std::move(row);
  }
  return done;
}

void appendRow(const fs::path& path, const std::vector<std::string>& components, const VariantResult& result) {
  const bool fresh = !fs::exists(path);
  std::ofstream file(path, std::ios::app);
  if (fresh) file << csvHeader(components);
  file << csvRow(result);
  file.flush();
}

class Progress {
 public:
  Progress(std::ostream& err, size_t total, size_t already)
      : err_(err), total_(total), already_(already), tty_(::isatty(STDERR_FILENO) == 1) {}

  void update(size_t done) {
    if (done == last_) return;
    last_ = done;
    const double elapsed = timer_.elapsedMs() / 1000.0;
    const size_t measured = done - already_;
    const double eta = measured == 0 ? 0.0 : elapsed / double(measured) * double(total_ - done);
    if (tty_) {
      const size_t filled = total_ == 0 ? 30 : done * 30 / total_;
      err_ << fmt::format("\r[{}{}] {}/{} variants, ETA {:.0f} s ", std::string(filled, '#'),
                          std::string(30 - filled, '.'), done, total_, eta)
           << std::flush;
      if (done == total_) err_ << "\n";
    } else {
      err_ << fmt::format("tune: {}/{} variants, ETA {:.0f} s\n", done, total_, eta);
    }
  }

 private:
  std::ostream& err_;
  size_t total_;
  size_t already_;
  bool tty_;
  size_t last_ = static_cast<size_t>(-1);
  vk::HostTimer timer_;
};

size_t countRows(const fs::path& path) {
  std::ifstream in(path);
  size_t lines = 0;
  for (std::string line; std::getline(in, line);) lines += line.empty() ? 0 : 1;
  return lines == 0 ? 0 : lines - 1;
}

// Runs `jobs` copies of this program as workers, which take chunks of the
// points from the work queue, with lavapipe limited to one thread so that
// the workers share the cores instead of fighting over them.
bool runWorkers(const Options& o, const std::string& program, const std::vector<std::string>& args, size_t already,
                size_t total, std::ostream& err) {
  std::vector<std::string> env;
  for (char** e = environ; *e; ++e) {
    if (!std::string_view(*e).starts_with("LP_NUM_THREADS=")) env.emplace_back(*e);
  }
  env.emplace_back("LP_NUM_THREADS=1");
  std::vector<char*> envp;
  for (std::string& e : env) envp.push_back(e.data());
  envp.push_back(nullptr);
  std::vector<pid_t> pids;
  for (uint32_t k = 0; k < o.jobs; ++k) {
    std::vector<std::string> workerArgs{"spire-tune"};
    workerArgs.insert(workerArgs.end(), args.begin(), args.end());
    workerArgs.insert(workerArgs.end(), {"--worker", std::to_string(k)});
    std::vector<char*> argv;
    for (std::string& a : workerArgs) argv.push_back(a.data());
    argv.push_back(nullptr);
    pid_t pid = 0;
    if (posix_spawn(&pid, program.c_str(), nullptr, nullptr, argv.data(), envp.data()) != 0) {
      err << "spire-tune: error: cannot start a worker process\n";
      return false;
    }
    pids.push_back(pid);
  }
  Progress progress(err, total, already);
  bool ok = true;
  size_t running = pids.size();
  while (running > 0) {
    size_t done = already;
    for (uint32_t k = 0; k < o.jobs; ++k) done += countRows(shardPath(o, static_cast<int>(k)));
    progress.update(std::min(done, total));
    for (pid_t& pid : pids) {
      if (pid == 0) continue;
      int status = 0;
      if (waitpid(pid, &status, WNOHANG) == pid) {
        ok = ok && WIFEXITED(status) && WEXITSTATUS(status) == 0;
        pid = 0;
        --running;
      }
    }
    if (running > 0) std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  progress.update(total);
  return ok;
}

std::string decisionFile(const std::string& shader, const engine::VariantProgram& program, const std::string& why,
                         const ShaderLibrary::Attributes& attributes) {
  std::string comment = "spire-tune: " + why;
  if (!attributes.empty()) comment += "\nFormats of the baked textures chosen from their values (data-layout selection).";
  graph::DecisionFile decisions;
  for (const auto& [component, placement] : program.placement) {
    const auto found = attributes.find(component);
    decisions.lines.push_back(graph::makeDecision(shader, component, placement,
                                                  found == attributes.end() ? decltype(found->second){} : found->second));
  }
  return graph::writeDecisionFile(decisions, comment);
}

std::string placementsText(const std::vector<std::string>& components, const VariantResult& r) {
  std::string text;
  for (size_t i = 0; i < components.size(); ++i) {
    text += fmt::format("{}{}={}", text.empty() ? "" : " ", components[i], r.placements[i]);
  }
  return text;
}

}  // namespace

int runTune(const std::vector<std::string>& args, std::ostream& out, std::ostream& err,
            const std::string& workerProgram) {
  CLI::App app{"spire-tune: explores a shader's optimization choices on a scene and measures the speed/accuracy trade",
               "spire-tune"};
  Options o;
  addVersionFlag(app);
  app.add_option("scene", o.scenePath, "Scene file (docs/scene.md)")->required()->type_name("SCENE.json");
  app.add_option("--shader", o.shader, "The shader to tune (an instance of the scene must use it)")
      ->required()
      ->type_name("NAME");
  app.add_option("--components", o.components, "Components to explore (default: every choice); NAME@World keeps one world for NAME")
      ->delimiter(',')
      ->type_name("A,B,...");
  app.add_option("--only", o.only, "Keep placements in these worlds or with these variation names")
      ->delimiter(',')
      ->type_name("NAME,...");
  app.add_option("--max-variants", o.maxVariants, "Sample the product when it has more variants")->type_name("N");
  app.add_option("--seed", o.seed, "Seed of the sample")->type_name("N");
  app.add_option("--frames", o.frames, "Measured frames per variant (median; at least 3)")
      ->check(CLI::Range(3U, 1000U))
      ->type_name("N");
  app.add_option("--warmup", o.warmup,
                 "Unmeasured frames before the measured ones (the captures of the camera views count)")
      ->check(CLI::Range(1U, 100U))
      ->type_name("N");
  app.add_option("-j,--jobs", o.jobs, "Worker processes (default: one per core)")->check(CLI::Range(1U, 64U))->type_name("N");
  app.add_option("--bake-size", o.bakeSize, "PrebakeTex size without a TextureSize hint")
      ->check(CLI::Range(1U, 8192U))
      ->type_name("N");
  addOutputDirectory(app, o.outputDir, "Output directory (an interrupted run resumes from it)");
  app.add_option("--time-budget", o.timeBudgetMs, "Write the most accurate variant within MS per frame")->type_name("MS");
  app.add_option("--error-budget", o.errorBudget, "Write the fastest variant within RMSE E")->type_name("E");
  app.add_option("--reference", o.reference, "Decision file of the reference (default: the scene's first variant)")
      ->type_name("PATH");
  app.add_option("--device", o.device, "Vulkan device whose name contains TEXT")->type_name("TEXT");
  app.add_flag("--validation", o.validation, "Enable VK_LAYER_KHRONOS_validation; any message fails the run");
  app.add_option("--param", o.params,
                 "Measure error over samples of a material parameter's range (repeatable): its minimum, its maximum "
                 "and random values")
      ->type_name("NAME=MIN:MAX");
  app.add_option("--param-samples", o.paramSamples, "Random samples besides the minimum and maximum")
      ->check(CLI::Range(0U, 100U))
      ->type_name("N");
  app.add_option("--shader-cache", o.shaderCache,
                 "lavapipe's shader cache: 'run' (default) a fresh one for this run, shared by its workers, so a kernel "
                 "that variants share is compiled once; 'off' compiles every pipeline in full; 'inherit' keeps the "
                 "environment's MESA_SHADER_CACHE_* settings")
      ->check(CLI::IsMember({"run", "off", "inherit"}))
      ->type_name("MODE");
  app.add_option("--worker", o.worker, "Internal: measure shard K")->group("");
  if (const auto status = parseToolArguments(app, args, out, err)) return *status;
  const vk::HostTimer wall;
  engine::stabilizeHostAllocator();
  // Workers inherit the coordinator's setting.
  ShaderCacheSetting shaderCache;
  if (o.worker < 0) {
    if (const auto failed = shaderCache.apply(o.shaderCache)) {
      err << fmt::format("spire-tune: error: {}\n", *failed);
      return kExitInputError;
    }
  }

  SourceManager sources;
  DiagnosticList diags;
  engine::ErrorReporter reporter(sources, diags, err, "spire-tune");
  const auto scene = scene::loadSceneFile(o.scenePath, sources, diags);
  if (!scene) {
    reporter.flush();
    return kExitInputError;
  }
  const auto instance = std::find_if(scene->instances.begin(), scene->instances.end(),
                                     [&](const scene::InstanceDesc& i) { return i.shader == o.shader; });
  if (instance == scene->instances.end()) {
    return reporter.fail({fmt::format("no instance of '{}' uses shader '{}'", o.scenePath, o.shader), {}, {}});
  }
  const size_t instanceIndex = static_cast<size_t>(instance - scene->instances.begin());

  vk::ContextOptions contextOptions;
  contextOptions.validation = o.validation;
  contextOptions.deviceFilter = o.device;
  contextOptions.applicationName = "spire-tune";
  auto ctx = vk::Context::create(contextOptions);
  if (!ctx) {
    err << fmt::format("spire-tune: error: no usable Vulkan device: {}\n", ctx.error().message());
    return kExitNoDevice;
  }
  engine::TextureBakeOptions bakeOptions;
  bakeOptions.defaultSize = o.bakeSize;
  engine::SceneRenderer renderer(*ctx, *scene, diags, bakeOptions);
  auto library = renderer.library(instanceIndex);
  if (!library) return reporter.fail(library.error());

  SpaceRequest request;
  request.components = o.components;
  request.only = o.only;
  request.maxVariants = o.maxVariants;
  request.seed = o.seed;
  std::string spaceError;
  const auto space = buildTuneSpace((*library)->choices(o.shader), request, spaceError);
  if (!space) return reporter.fail({spaceError, instance->shaderRange, {}});
  const std::vector<std::string> components = componentNames(*space);

  std::optional<fs::path> reference;
  if (!o.reference.empty()) reference = o.reference;
  else if (!scene->variants.empty()) reference = scene->variants.front().decisions;

  std::vector<ParameterRange> ranges;
  for (const std::string& text : o.params) {
    auto range = parseParameter(text, *instance, spaceError);
    if (!range) {
      err << fmt::format("spire-tune: error: {}\n", spaceError);
      return kExitUsageError;
    }
    ranges.push_back(*range);
  }
  TunerOptions tunerOptions;
  tunerOptions.frames = o.frames;
  tunerOptions.warmupFrames = o.warmup;
  tunerOptions.parameterSamples = parameterSamples(ranges, o.paramSamples, o.seed);
  Tuner tuner(renderer, instanceIndex, space->axes, tunerOptions);

  std::error_code ec;
  fs::create_directories(o.outputDir, ec);
  if (ec) return reporter.fail({fmt::format("cannot create '{}': {}", o.outputDir, ec.message()), {}, {}});
  std::string error;
  auto done = loadDone(o, *space, error);
  if (!done) return reporter.fail({error, {}, {}});

  // Measures the points not done yet: all of them in a serial run, a worker's
  // chunks from the queue otherwise.
  const auto measureShard = [&](int worker, Progress* progress) -> int {
    if (auto ok = tuner.renderReference(reference); !ok) return reporter.fail(ok.error());
    size_t finished = done->size();
    const auto measureRange = [&](size_t begin, size_t end) {
      for (size_t i = begin; i < std::min(end, space->points.size()); ++i) {
        const TunePoint& point = space->points[i];
        if (done->contains(point.index)) continue;
        appendRow(shardPath(o, std::max(worker, 0)), components, tuner.measure(point));
        if (progress) progress->update(++finished);
      }
    };
    if (worker < 0) {
      measureRange(0, space->points.size());
    } else {
      const size_t chunk = chunkSize(*space);
      const size_t chunks = (space->points.size() + chunk - 1) / chunk;
      WorkQueue queue(queuePath(o));
      std::string queueError;
      while (const auto next = queue.next(chunks, queueError)) measureRange(*next * chunk, (*next + 1) * chunk);
      if (!queueError.empty()) return reporter.fail({queueError, {}, {}});
    }
    const TimeSplit& s = tuner.timeSplit();
    if (auto failed = writeFileAtomically(splitPath(o, std::max(worker, 0)).string(),
                                          fmt::format("{} {} {} {}\n", s.compileMs, s.firstUseMs, s.renderMs, s.errorMs))) {
      return reporter.fail({*failed, {}, {}});
    }
    // Exploring variants leaves some material values unused by design, so
    // only errors are worth printing here.
    if (diags.hasErrors()) reporter.flush();
    return engine::reportValidation(*ctx, kExitSuccess, err);
  };
  if (o.worker >= 0) return measureShard(o.worker, nullptr);

  const size_t total = space->points.size();
  out << fmt::format("tuning {} of '{}': {} components, {} variants{}{}\n", o.shader, o.scenePath, components.size(),
                     space->productSize,
                     space->sampled ? fmt::format(" (too many: measuring a sample of {})", total) : std::string(),
                     done->empty() ? std::string() : fmt::format(", resuming with {} measured", done->size()));
  size_t already = 0;
  for (const TunePoint& point : space->points) already += done->contains(point.index) ? 1 : 0;
  if (already < total) {
    if (o.jobs == 1 || workerProgram.empty()) {
      Progress progress(err, total, already);
      if (const int status = measureShard(-1, &progress); status != kExitSuccess) return status;
    } else if (const auto failed = WorkQueue::create(queuePath(o))) {
      return reporter.fail({*failed, {}, {}});
    } else if (!runWorkers(o, workerProgram, args, already, total, err)) {
      err << "spire-tune: error: a worker failed (its messages are above); rerun to resume\n";
      return kExitInputError;
    }
  }

  // Merge: one row per point of this run, in index order.
  done = loadDone(o, *space, error);
  if (!done) return reporter.fail({error, {}, {}});
  std::vector<VariantResult> results;
  for (const TunePoint& point : space->points) {
    if (const auto it = done->find(point.index); it != done->end()) results.push_back(it->second);
  }
  std::string table = csvHeader(components);
  for (const VariantResult& r : results) table += csvRow(r);
  if (auto failed = writeFileAtomically((fs::path(o.outputDir) / "variants.csv").string(), table)) {
    return reporter.fail({*failed, {}, {}});
  }
  TimeSplit split;
  for (uint32_t k = 0; k < std::max(o.jobs, 1U); ++k) {
    std::ifstream in(splitPath(o, static_cast<int>(k)));
    double c = 0, f = 0, r = 0, e = 0;
    if (in >> c >> f >> r >> e) {
      split.compileMs += c;
      split.firstUseMs += f;
      split.renderMs += r;
      split.errorMs += e;
    }
    fs::remove(shardPath(o, static_cast<int>(k)), ec);
    fs::remove(splitPath(o, static_cast<int>(k)), ec);
  }
  fs::remove(queuePath(o), ec);

  std::vector<Measured> measured;
  size_t hazards = 0;
  size_t infeasible = 0;
  size_t reused = 0;
  for (const VariantResult& r : results) {
    const bool hazard = r.nanPixels + r.infPixels > 0;
    hazards += hazard ? 1 : 0;
    infeasible += r.status == "infeasible" ? 1 : 0;
    reused += r.sameAs ? 1 : 0;
    measured.push_back({r.frameMs, hazard ? std::numeric_limits<double>::infinity() : r.rmse, r.ok()});
  }
  const std::vector<size_t> front = paretoFront(measured);
  std::string frontCsv = csvHeader(components);
  for (size_t i : front) frontCsv += csvRow(results[i]);
  if (auto failed = writeFileAtomically((fs::path(o.outputDir) / "pareto.csv").string(), frontCsv)) {
    return reporter.fail({*failed, {}, {}});
  }
  if (auto written = scene::writePng(fs::path(o.outputDir) / "plot.png", plotErrorAgainstTime(measured, front)); !written) {
    return reporter.fail({written.error(), {}, {}});
  }

  // Budgets: by default, half the reference's frame time and an RMSE of 0.01.
  double referenceMs = 0.0;
  for (size_t i : front) referenceMs = std::max(referenceMs, results[i].frameMs);
  const double timeBudget = o.timeBudgetMs.value_or(referenceMs / 2.0);
  const double errorBudget = o.errorBudget.value_or(0.01);
  std::optional<size_t> bestInTime;
  std::optional<size_t> bestInError;
  for (size_t i : front) {
    if (results[i].frameMs <= timeBudget && (!bestInTime || results[i].rmse < results[*bestInTime].rmse)) bestInTime = i;
    if (measured[i].error <= errorBudget && (!bestInError || results[i].frameMs < results[*bestInError].frameMs)) bestInError = i;
  }
  std::string layoutReport;
  const auto writeBest = [&](std::optional<size_t> best, const std::string& file, const std::string& why) -> int {
    if (!best) {
      out << fmt::format("no variant meets the {}; {} not written\n", why, file);
      return kExitSuccess;
    }
    const TunePoint point = pointAt(space->axes, results[*best].index);
    auto program = tuner.program(point);
    if (!program) return reporter.fail(program.error());
    auto layouts = selectLayouts(renderer, instanceIndex, point, o.bakeSize);
    if (!layouts) return reporter.fail(layouts.error());
    if (!layouts->layouts.empty()) {
      layoutReport += fmt::format("\n### Data layout of `{}`\n\n{}", file, layoutTable(*layouts));
    }
    const std::string text = decisionFile(o.shader, *program,
                                          fmt::format("{} (variant {}: {:.3f} ms, RMSE {:.4g})", why, results[*best].index,
                                                      results[*best].frameMs, results[*best].rmse),
                                          layouts->attributes);
    if (auto failed = writeFileAtomically((fs::path(o.outputDir) / file).string(), text)) return reporter.fail({*failed, {}, {}});
    out << fmt::format("{}: variant {} ({}) -> {}/{}\n", why, results[*best].index,
                       placementsText(components, results[*best]), o.outputDir, file);
    return kExitSuccess;
  };
  if (int s = writeBest(bestInTime, "best_time_budget.decisions", fmt::format("time budget {:.3f} ms", timeBudget)); s) return s;
  if (int s = writeBest(bestInError, "best_error_budget.decisions", fmt::format("error budget RMSE {:.4g}", errorBudget)); s) return s;

  std::string separators;
  for (size_t i = 0; i < components.size(); ++i) separators += "---|";
  std::string report = fmt::format(
      "# spire-tune report\n\nShader `{}` on `{}` ({}), {} variants of {} components{}; error is RMSE against the "
      "reference over {} camera view(s); time is the median GPU frame time of {} frames after {} unmeasured ones "
      "(the captures of the camera views first).\n\n"
      "![error against time](plot.png)\n\n## Pareto front\n\n| variant | {} | frame ms | RMSE | image |\n|---|{}---|---|---|\n",
      o.shader, o.scenePath, ctx->selectedDevice().name, results.size(), components.size(),
      space->sampled ? " (sampled)" : "", scene->camera.views.size(), o.frames,
      tuner.unmeasuredFrames(), fmt::join(components, " | "),
      separators);
  fs::create_directories(fs::path(o.outputDir) / "front", ec);
  for (size_t i : front) {
    const VariantResult& r = results[i];
    auto capture = tuner.capture(pointAt(space->axes, r.index));
    if (!capture) return reporter.fail(capture.error());
    const std::string thumb = fmt::format("front/{}.png", r.index);
    if (auto written = scene::writePng(fs::path(o.outputDir) / thumb, measure::toRgba8(capture->color)); !written) {
      return reporter.fail({written.error(), {}, {}});
    }
    report += fmt::format("| {} | {} | {:.3f} | {:.4g} | ![]({}) |\n", r.index, fmt::join(r.placements, " | "), r.frameMs,
                          r.rmse, thumb);
  }
  for (const VariantResult& r : results) {
    if (r.nanPixels + r.infPixels > 0 && !r.sameAs) {
      report += fmt::format("\nHazard: variant {} ({}) has {} NaN and {} Inf pixels, first under {}.",
                            r.index, placementsText(components, r), r.nanPixels, r.infPixels, r.hazardInputs);
    }
  }
  report += fmt::format("\n{} variants had NaN or Inf pixels (infinite error, never on the front); {} were infeasible; "
                        "{} had kernels identical to an earlier variant and were measured once.\n\n"
                        "Time: compile {:.1f} s, first-use shader compilation {:.1f} s, render {:.1f} s, error {:.1f} s "
                        "(summed over {} worker(s)).\n",
                        hazards, infeasible, reused, split.compileMs / 1000, split.firstUseMs / 1000,
                        split.renderMs / 1000, split.errorMs / 1000, o.jobs);
  if (!layoutReport.empty()) {
    report += "\n## Data-layout selection\n\nEach baked output of the chosen variants, analysed in a 32-bit float bake; "
              "the error is what the selected format adds to the image against that bake.\n" + layoutReport;
  }
  if (auto failed = writeFileAtomically((fs::path(o.outputDir) / "report.md").string(), report)) {
    return reporter.fail({*failed, {}, {}});
  }
  for (const VariantResult& r : results) {
    if (r.nanPixels + r.infPixels > 0 && !r.sameAs) {
      err << fmt::format("spire-tune: warning: variant {} ({}) produced {} NaN and {} Inf pixels, first under {}\n",
                         r.index, placementsText(components, r), r.nanPixels, r.infPixels, r.hazardInputs);
    }
  }
  out << fmt::format("front: {} variants; {} with NaN/Inf pixels; {} infeasible; {} measured once for identical kernels\n",
                     front.size(), hazards, infeasible, reused);
  out << fmt::format("time split (summed over workers): compile {:.1f} s, first use {:.1f} s, render {:.1f} s, error {:.1f} s\n",
                     split.compileMs / 1000, split.firstUseMs / 1000, split.renderMs / 1000, split.errorMs / 1000);
  out << fmt::format("wrote {0}/variants.csv, pareto.csv, plot.png, report.md, front/\n", o.outputDir);
  out << fmt::format("{} variants in {:.1f} s\n", results.size(), wall.elapsedMs() / 1000.0);
  return engine::reportValidation(*ctx, kExitSuccess, err);
}

}  // namespace spire::tune
