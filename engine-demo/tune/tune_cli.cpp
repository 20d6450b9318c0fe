#include "tune/tune_cli.h"

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <ostream>

#include "driver/exit_codes.h"
#include "driver/tool_arguments.h"
#include "support/file_io.h"
#include "tool/tool_run.h"
#include "tune/lod_policy_tune.h"
#include "tune/output_lock.h"
#include "tune/progress.h"
#include "tune/racing.h"
#include "tune/run_environment.h"
#include "tune/shader_cache.h"
#include "tune/stop_request.h"
#include "tune/tune_options.h"
#include "tune/tune_outputs.h"
#include "tune/tune_session.h"
#include "tune/work_queue.h"
#include "tune/worker_processes.h"
#include "vk/timer.h"

namespace spire::tune {

namespace {

namespace fs = std::filesystem;

constexpr const char* kTool = "spire-tune";

// The points that differ only in the last component form a chunk (see
// WorkQueue).
size_t chunkSize(const TuneSpace& space) { return space.axes.empty() ? 1 : space.axes.back().placements.size(); }

// Points of this run's space an earlier run measured (the journal may hold
// rows of a sample this run does not take).
size_t doneInSpace(const TuneSession& session) {
  size_t done = 0;
  for (const TunePoint& point : session.space.points) done += session.done.contains(point.index) ? 1 : 0;
  return done;
}

// Measures the points in [begin, end) not done yet, appending each row to
// the worker's shard as it finishes (the journal a rerun resumes from).
void measureRange(const TuneOptions& options, TuneSession& session, int worker, size_t begin, size_t end,
                  Progress* progress, size_t& finished) {
  const std::vector<TunePoint>& points = session.space.points;
  for (size_t i = begin; i < std::min(end, points.size()); ++i) {
    if (StopRequest::requested()) return;
    if (session.done.contains(points[i].index)) continue;
    appendRow(shardPath(options, std::max(worker, 0)), session.components, session.tuner->measure(points[i]));
    if (progress) progress->update(++finished);
  }
}

// All the points in a serial run (worker < 0); a worker's chunks from the
// queue otherwise.
std::optional<int> measurePoints(const TuneOptions& options, engine::ToolRun& run, TuneSession& session, int worker,
                                 Progress* progress) {
  if (auto ok = session.tuner->renderReference(session.reference); !ok) return run.fail(ok.error());
  size_t finished = doneInSpace(session);
  const size_t count = session.space.points.size();
  if (worker < 0) {
    measureRange(options, session, worker, 0, count, progress, finished);
    return std::nullopt;
  }
  const size_t chunk = chunkSize(session.space);
  const size_t chunks = (count + chunk - 1) / chunk;
  WorkQueue queue(queuePath(options));
  while (true) {
    if (StopRequest::requested()) return std::nullopt;
    const auto next = queue.next(chunks);
    if (!next) return run.fail(next.error().message);
    if (!next->has_value()) return std::nullopt;
    const uint64_t taken = **next;
    measureRange(options, session, worker, taken * chunk, (taken + 1) * chunk, progress, finished);
  }
}

// A worker's time split as measureShard writes it; zero when there is none.
TimeSplit readTimeSplit(const fs::path& path) {
  TimeSplit split;
  std::ifstream in(path);
  if (!(in >> split.compileMs >> split.firstUseMs >> split.renderMs >> split.errorMs)) split = TimeSplit{};
  return split;
}

// Measures a shard (see measurePoints) and records where its time went.
int measureShard(const TuneOptions& options, engine::ToolRun& run, TuneSession& session, int worker,
                 Progress* progress) {
  if (const auto status = measurePoints(options, run, session, worker, progress)) return *status;
  if (StopRequest::requested()) return kExitInterrupted;
  // Added to what a worker before it in this directory spent (one that
  // fresh workers replaced after a crash, or one of an earlier run that
  // failed), so the split covers every row of the run.
  const fs::path splitFile = splitPath(options, std::max(worker, 0));
  TimeSplit s = readTimeSplit(splitFile);
  s += session.tuner->timeSplit();
  const std::string text = fmt::format("{} {} {} {}\n", s.compileMs, s.firstUseMs, s.renderMs, s.errorMs);
  if (auto written = writeFileAtomically(splitFile.string(), text); !written) {
    return run.fail(written.error().message);
  }
  // Exploring variants leaves some material values unused by design, so
  // only errors are worth printing here.
  if (run.diagnostics().hasErrors()) run.reporter().flush();
  return run.finish(kExitSuccess);
}

// How many of this run's points the journal holds now (workers add to it).
Expected<size_t, Failure> measuredInSpace(const TuneOptions& options, const TuneSession& session) {
  const auto done = loadDone(options, session.components);
  if (!done) return done.error();
  size_t measured = 0;
  for (const TunePoint& point : session.space.points) measured += done->contains(point.index) ? 1 : 0;
  return measured;
}

// After a stop request: what the journal keeps, and how to go on.
int reportInterrupted(const TuneOptions& options, const TuneSession& session, std::ostream& err) {
  const auto measured = measuredInSpace(options, session);
  const size_t kept = measured ? *measured : 0;
  err << fmt::format(
      "spire-tune: interrupted: {} of {} variants are measured and kept in '{}'; run the same command again to "
      "resume\n",
      kept, session.space.points.size(), options.outputDir);
  return kExitInterrupted;
}

// Whether worker processes measure the variants (else this process does).
bool workersMeasure(const TuneOptions& options, const std::string& workerProgram) {
  return options.jobs > 1 && !workerProgram.empty();
}

// The points left, measured by worker processes. A worker that a signal
// ended (lavapipe has crashed in one, rarely and not again on the same
// variant) costs one retry with fresh workers, which take up the points
// left from the journal; a second crash, or a worker that failed with a
// message, ends the run.
std::optional<int> measureWithWorkers(const TuneOptions& options, engine::ToolRun& run, TuneSession& session,
                                      const std::vector<std::string>& args, const std::string& workerProgram,
                                      std::ostream& err) {
  WorkerPlan plan{workerProgram, args, {}};
  for (uint32_t k = 0; k < options.jobs; ++k) plan.shards.push_back(shardPath(options, static_cast<int>(k)));
  const size_t total = session.space.points.size();
  for (int attempt = 0; attempt < 2; ++attempt) {
    if (const auto created = WorkQueue::create(queuePath(options)); !created) return run.fail(created.error().message);
    const auto already = measuredInSpace(options, session);
    if (!already) return run.fail(already.error().message);
    const WorkersEnd end = runWorkers(plan, *already, total, err);
    if (end == WorkersEnd::Finished) return std::nullopt;
    if (end == WorkersEnd::Interrupted) return reportInterrupted(options, session, err);
    if (end == WorkersEnd::Failed) break;
    if (attempt == 0) err << "spire-tune: measuring the variants left with fresh workers\n";
  }
  err << "spire-tune: error: a worker failed (above: its own messages, then how it ended); rerun to resume\n";
  return kExitInputError;
}

// The coordinator: measures what is not done yet, in this process or in
// worker processes.
std::optional<int> measureAll(const TuneOptions& options, engine::ToolRun& run, TuneSession& session,
                              const std::vector<std::string>& args, const std::string& workerProgram, std::ostream& out,
                              std::ostream& err) {
  const TuneSpace& space = session.space;
  const size_t total = space.points.size();
  out << fmt::format(
      "tuning {} of '{}': {} components, {} variants{}{}\n", options.shader, options.scenePath,
      session.components.size(), space.productSize,
      space.sampled ? fmt::format(" (too many: measuring a sample of {})", total) : std::string(),
      session.done.empty() ? std::string() : fmt::format(", resuming with {} measured", session.done.size()));
  const size_t already = doneInSpace(session);
  if (already == total) return std::nullopt;
  if (!workersMeasure(options, workerProgram)) {
    Progress progress(err, total, already);
    const int status = measureShard(options, run, session, -1, &progress);
    // Workers prepare variants in other processes, so only an in-process
    // run knows which bindings no variant read.
    run.renderer().reportUnreadBindings();
    run.reporter().flush();
    if (status == kExitInterrupted) return reportInterrupted(options, session, err);
    return status == kExitSuccess ? std::nullopt : std::optional<int>(status);
  }
  return measureWithWorkers(options, run, session, args, workerProgram, err);
}

// One row per point of this run, in index order, each time ratio turned
// into milliseconds with this process's reference time, so rows that workers
// or an earlier run measured share one scale.
std::optional<int> mergeResults(const TuneOptions& options, engine::ToolRun& run, const TuneSession& session,
                                std::vector<VariantResult>& results) {
  const auto done = loadDone(options, session.components);
  if (!done) return run.fail(done.error().message);
  for (const TunePoint& point : session.space.points) {
    if (const auto it = done->find(point.index); it != done->end()) results.push_back(it->second);
  }
  for (VariantResult& r : results) r.frameMs = r.time.median * session.tuner->referenceMs();
  return std::nullopt;
}

// Racing (tune/racing.h): the candidates for the front are measured again
// in this process (with the workers' single lavapipe thread when there were
// workers, so that ratios compare), with pairs added until the interval is
// tight or up to --max-frames, round after round until no candidate is left
// to measure.
void race(const TuneOptions& options, TuneSession& session, RaceState state, std::vector<VariantResult>& results,
          std::ostream& err) {
  // A re-measured time stops no sooner than it is a 95% interval.
  const uint32_t minPairs = std::max(options.frames, kPairsFor95);
  const StoppingRule rule{minPairs, std::max(minPairs, options.maxFrames), StoppingRule{}.relativeWidth};
  for (std::vector<size_t> next; !(next = nextToRace(results, state, rule.relativeWidth)).empty();) {
    err << fmt::format("racing: {} candidates for the front measured again, up to {} pairs each\n", next.size(),
                       rule.maxPairs);
    for (size_t i : next) {
      if (StopRequest::requested()) return;
      const uint64_t index = results[i].index;
      state.raced.insert(index);
      auto time = session.tuner->remeasureTime(pointAt(session.space.axes, index), rule);
      if (!time) continue;  // the earlier measurement stands
      for (VariantResult& r : results) {
        if (r.index != index && r.sameAs != index) continue;
        r.time = *time;
        r.frameMs = time->median * session.tuner->referenceMs();
      }
    }
  }
}

// The rows this process measures itself: none when workers do, else every
// row not resumed from an earlier run.
RaceState raceState(const TuneOptions& options, const TuneSession& session, const std::string& workerProgram) {
  RaceState state;
  if (workersMeasure(options, workerProgram)) return state;
  for (const TunePoint& point : session.space.points) {
    if (!session.done.contains(point.index)) state.measuredHere.insert(point.index);
  }
  return state;
}

std::optional<int> writeResultsTable(const TuneOptions& options, engine::ToolRun& run, const TuneSession& session,
                                     const std::vector<VariantResult>& results) {
  std::string table = csvHeader(session.components);
  for (const VariantResult& r : results) table += csvRow(r);
  if (auto written = writeFileAtomically((fs::path(options.outputDir) / "variants.csv").string(), table); !written) {
    return run.fail(written.error().message);
  }
  return std::nullopt;
}

// The coordinator's hold on the output directory and, when workers measure,
// the workers' single lavapipe thread for its own timings (racing).
std::optional<int> prepareCoordinator(const TuneOptions& options, const std::string& workerProgram,
                                      std::optional<OutputLock>& lock, RunEnvironment& environment, std::ostream& err) {
  auto acquired = OutputLock::acquire(options.outputDir);
  if (!acquired) {
    err << fmt::format("spire-tune: error: {}\n", acquired.error().message);
    return kExitInputError;
  }
  lock.emplace(std::move(acquired).value());
  if (workersMeasure(options, workerProgram)) environment.set("LP_NUM_THREADS", "1");
  return std::nullopt;
}

// The workers' time splits summed; their shards, splits and the queue are
// removed, now that variants.csv holds every row. Every shard in the
// directory, not only this run's --jobs: a run resumed with fewer workers
// than the one before it read theirs too.
TimeSplit collectTimeSplits(const TuneOptions& options) {
  TimeSplit split;
  std::error_code ec;
  std::vector<fs::path> leftovers;
  for (const auto& entry : fs::directory_iterator(options.outputDir, ec)) {
    const std::string name = entry.path().filename().string();
    const std::string extension = entry.path().extension().string();
    if (!name.starts_with("shard-") || (extension != ".csv" && extension != ".time")) continue;
    if (extension == ".time") split += readTimeSplit(entry.path());
    leftovers.push_back(entry.path());
  }
  for (const fs::path& path : leftovers) fs::remove(path, ec);
  fs::remove(queuePath(options), ec);
  return split;
}

}  // namespace

int runTune(const std::vector<std::string>& args, std::ostream& out, std::ostream& err,
            const std::string& workerProgram) {
  CLI::App app{"spire-tune: explores a shader's optimization choices on a scene and measures the speed/accuracy trade",
               kTool};
  TuneOptions options;
  defineTuneOptions(app, options);
  if (const auto status = parseToolArguments(app, args, out, err)) return *status;
  if (!options.lodPolicyPath.empty()) return runLodPolicyTune(options, out, err);
  if (options.shader.empty()) return usageError(kTool, "--shader is required (or --lod-policy PATH)", err);
  const vk::HostTimer wall;
  // Workers inherit the coordinator's setting. Declared before the run, so
  // the cache outlives the device that uses it.
  ShaderCacheSetting shaderCache;
  if (options.worker < 0) {
    if (const auto applied = shaderCache.apply(options.shaderCache); !applied) {
      err << fmt::format("spire-tune: error: {}\n", applied.error().message);
      return kExitInputError;
    }
  }
  const StopRequest stop;
  std::optional<OutputLock> lock;
  RunEnvironment environment;  // before the run: Mesa reads it when the device is made
  if (options.worker >= 0) {
    followCoordinator();
  } else if (const auto status = prepareCoordinator(options, workerProgram, lock, environment, err)) {
    return *status;
  }
  engine::ToolRun run(kTool, err);
  TuneSession session;
  if (const auto status = startSession(options, run, session, err)) return *status;
  if (options.worker >= 0) return measureShard(options, run, session, options.worker, nullptr);
  // Before any worker starts: a broken reference stops the run here, once.
  if (auto ok = session.tuner->renderReference(session.reference); !ok) return run.fail(ok.error());
  const RaceState raceStart = raceState(options, session, workerProgram);
  if (const auto status = measureAll(options, run, session, args, workerProgram, out, err)) return *status;
  std::vector<VariantResult> results;
  if (const auto status = mergeResults(options, run, session, results)) return *status;
  race(options, session, raceStart, results, err);
  if (StopRequest::requested()) return reportInterrupted(options, session, err);
  if (const auto status = writeResultsTable(options, run, session, results)) return *status;
  const TimeSplit split = collectTimeSplits(options);
  return writeTuneOutputs(options, run, session, results, split, wall, out, err);
}

}  // namespace spire::tune
