// What the explorer knows and shows, as plain data: shared by the loop that
// changes it (explorer.cpp) and the panels that draw it (explorer_panels.cpp).
#pragma once

#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "explore/decision_state.h"
#include "explore/tune_results.h"
#include "measure/image_metrics.h"

namespace spire::explore {

enum class ViewMode { Variant, Reference, Error, Hazards, Split };

// "variant", "reference", "error", "hazards", "split" (the script's names).
const char* viewModeName(ViewMode mode);
std::optional<ViewMode> viewModeNamed(std::string_view name);

// One change of decisions, from the moment it was made to the first frame of
// its variant on screen: where the time went.
struct ChangeRecord {
  std::string action;  // "set Terrain.albedo = PrebakeTex", "undo", "reload FILE", ...
  uint64_t request = 0;
  size_t instance = 0;     // the scene's instance whose decisions changed
  bool reload = false;     // the sources were read again (a file was saved)
  double startMs = 0.0;    // when the change was made (explorer clock)
  double compileMs = 0.0;  // compiler library: code generation, glslang, validation (worker thread)
  double prepareMs = 0.0;  // pipelines, descriptor sets and bakes (worker thread, after the compile)
  double bakeMs = 0.0;     // of prepareMs, bakes run (not reused)
  // Of prepareMs: graphics pipelines built, and those shared with the
  // variant on screen because their kernels did not change (lavapipe
  // compiles only the built ones at the first frame).
  size_t pipelinesCreated = 0;
  size_t pipelinesReused = 0;
  // Presented with the previous variant while the worker compiled and
  // prepared the new one.
  uint32_t framesWhileCompiling = 0;
  double firstFrameMs = 0.0;  // the first frame's host time: lavapipe compiles shaders at first draw
  double totalMs = 0.0;       // decision to the first presented frame of the new variant
  bool ok = false;
  std::string error;                 // compile or prepare failure, rendered
  std::vector<std::string> skipped;  // decisions the compiler did not apply
};

// Live metrics of the variant on screen.
struct Metrics {
  std::deque<double> gpuMs;                  // the last frames' GPU times
  std::optional<measure::ImageError> error;  // against the reference, at the fixed camera view
  uint64_t nonFinitePixels = 0;
  double referenceGpuMs = 0.0;  // median of the reference's last measured frames

  // Median of the sliding window; 0 without frames.
  double medianGpuMs() const;
  void addFrame(double ms);
};

// What the user asked for through the panels during one frame.
struct PanelRequests {
  std::optional<size_t> instance;                          // explore another of the scene's instances
  std::optional<std::pair<std::string, std::string>> set;  // choice key, placement
  std::optional<std::string> unset;
  bool undo = false;
  bool reset = false;
  bool save = false;
  bool load = false;
  std::optional<ViewMode> view;
  // A tuned variant clicked in the Pareto view (an index into
  // TuneResults::variants): its decisions replace the session's at once.
  std::optional<size_t> applyTunePoint;
};

struct PanelState {
  std::string shader;
  size_t instance = 0;                 // the explored one, an index into `instances`
  std::vector<std::string> instances;  // the scene's: "1: Couch (cushion)"
  std::vector<ChoiceRow> rows;
  ViewMode view = ViewMode::Variant;
  const Metrics* metrics = nullptr;
  std::optional<ChangeRecord> lastChange;
  bool compiling = false;
  std::string diagnostics;             // the last failure, rendered with file:line:col
  std::string decisionsPath;           // where Save writes and Load reads
  const TuneResults* tune = nullptr;   // --tune-dir or load-tune; the Pareto view shows it
  std::optional<size_t> tunedCurrent;  // the tuned variant with the session's decisions
};

}  // namespace spire::explore
