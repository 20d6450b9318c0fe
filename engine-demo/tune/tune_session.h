// A tuning run after its set-up: the instance whose shader is tuned, the
// points it explores, the tuner over the run's renderer, and what an earlier,
// interrupted run already measured. Also the layout of the output directory,
// which is the run's journal: the merged table, each worker's shard of rows
// and time split, and the work queue.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "scene/scene_file.h"
#include "tool/tool_run.h"
#include "tune/results_csv.h"
#include "tune/tune_options.h"
#include "tune/tune_space.h"
#include "tune/tuner.h"

namespace spire::tune {

struct TuneSession {
  size_t instanceIndex = 0;
  const scene::InstanceDesc* instance = nullptr;
  TuneSpace space;
  std::vector<std::string> components;             // the explored components, in axis order
  std::optional<std::filesystem::path> reference;  // its decision file; nullopt: each instance's own
  std::optional<Tuner> tuner;
  std::map<uint64_t, VariantResult> done;  // by point index
};

// Sets up `session` on `run`: the scene, the instance using the shader, the
// device, the renderer, the space, the tuner and the rows already done.
// nullopt to go on, else the exit status (the problem printed).
std::optional<int> startSession(const TuneOptions& options, engine::ToolRun& run, TuneSession& session,
                                std::ostream& err);

std::filesystem::path shardPath(const TuneOptions& options, int worker);  // the rows worker K measured
std::filesystem::path splitPath(const TuneOptions& options, int worker);  // worker K's TimeSplit
std::filesystem::path queuePath(const TuneOptions& options);

// Rows already measured: the merged table of an earlier run plus any shard a
// worker appended to before an interruption. An error when one is of another
// run or malformed.
Expected<std::map<uint64_t, VariantResult>, Failure> loadDone(const TuneOptions& options,
                                                              const std::vector<std::string>& components);

// Appends `result` to the CSV at `path`, with the header when it is new.
void appendRow(const std::filesystem::path& path, const std::vector<std::string>& components,
               const VariantResult& result);

}  // namespace spire::tune
