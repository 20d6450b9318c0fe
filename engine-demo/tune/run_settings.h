// The settings that give a tuning run's rows their meaning, kept beside them
// in the output directory (DIR/settings.txt). A rerun resumes a journal only
// when it would have measured the same rows itself: the same scene, shader
// and space, the same image size, frames and bakes, the same reference,
// parameter samples and device. Rows measured at another resolution or
// against another reference would otherwise be merged with the new ones
// into one front without a word.
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "support/expected.h"
#include "support/source_manager.h"
#include "tool/tool_run.h"
#include "tune/tune_options.h"

namespace spire::tune {

// Named settings in a fixed order, each value on one line.
struct RunSettings {
  std::vector<std::pair<std::string, std::string>> entries;
};

// This run's settings: `reference` is the decision file the tuner measures
// against (empty: the instances' own decisions); `shaderSources` the files
// the tuned shader was compiled from. Besides the options, a hash of each
// file the rows depend on (the scene's, the shader's, the reference's), so
// that an edit between two runs is a difference too.
RunSettings runSettings(const TuneOptions& options, const engine::ToolRun& run, const std::string& reference,
                        const SourceManager& shaderSources);

// The file's text, and back; reading fails on a line that is not
// `name: value`.
std::string settingsText(const RunSettings& settings);
Expected<RunSettings, Failure> parseSettings(const std::string& text, const std::filesystem::path& path);

// Before a run measures into `directory`: records `now` when the directory
// holds no rows yet (`hasRows` false), else checks them against the recorded
// ones and fails, naming each setting that differs, when they are not the
// same. Rows without recorded settings are refused too, since nothing says
// what they were measured with.
Expected<void, Failure> recordOrCheckSettings(const std::filesystem::path& directory, const RunSettings& now,
                                              bool hasRows);

}  // namespace spire::tune
