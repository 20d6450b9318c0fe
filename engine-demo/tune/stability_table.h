// The stability table of an --extremes run (stability.csv and report.md's
// "Stability"): for the reference and each variant, which component the
// instrumented kernels (tool/hazard_diagnosis.h) find going NaN or Inf
// first under which sample, so that a hazard is attributed to the one input
// whose extreme drives it. Diagnosis renders the variant again with
// instrumented kernels, so the table diagnoses a bounded number of
// (variant, sample) pairs, in a fixed order, after the run.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "tune/results_csv.h"
#include "tune/tune_space.h"
#include "tune/tuner.h"

namespace spire::tune {

struct StabilityRow {
  std::string variant;     // "reference" or the variant's index
  std::string decisions;   // "scaled=Fragment:raw"; empty for the reference
  std::string component;   // the first value to go non-finite
  std::string definition;  // "World" or "World:variation"
  std::string world;
  std::string input;  // the one input the sample changes; "all" for every input, "scene" for none
  std::string kind;   // SampleLabel::kind: "min", "max", "texture-min", ...
  std::string value;  // the input's values ("0,0,0,0"); for "all", every input's ("color=0,0 maskMap=0")
  bool nan = false;   // NaN; otherwise Inf
  uint64_t count = 0;
  std::string unit;  // "px", "vertices" or "texels"
  // engine::Hazard's: the first checked operation to fail; empty if none did.
  std::string operation;
  std::string operationSource;
};

struct StabilityTable {
  std::vector<StabilityRow> rows;
  size_t samples = 0;  // the run's parameter samples
  size_t limit = 0;
  size_t diagnosed = 0;                        // (variant, sample) pairs rendered with instrumented kernels
  size_t cut = 0;                              // pairs the limit left undiagnosed
  std::vector<std::string> failures;           // diagnoses that could not run, and why
  std::vector<std::string> referenceExcluded;  // the samples the reference is non-finite under
};

// The (variant, sample) pairs the table diagnoses, the first of 16 in order.
constexpr size_t kStabilityDiagnoses = 16;

// Which of a variant's hazardous samples (with their first hazardous views)
// the table diagnoses: the scene's own values alone when they are hazardous
// (no input is to blame); else every per-input corner that is; else the
// first hazardous sample (a combination of inputs).
std::vector<std::pair<size_t, size_t>> samplesToDiagnose(const std::vector<std::pair<size_t, size_t>>& hazardous,
                                                         const std::vector<SampleLabel>& labels);

// Diagnoses the reference's excluded samples, then each variant's (those
// measured once for identical kernels are their original's), in index
// order, up to `limit` pairs.
StabilityTable buildStabilityTable(Tuner& tuner, const std::vector<Axis>& axes,
                                   const std::vector<VariantResult>& results, size_t limit);

std::string stabilityCsv(const StabilityTable& table);
// "variant 3 (scaled=Fragment:raw): scaled (Fragment:raw) goes Inf when
// maskMap = 0,0,0,0 (min) (289 px)", one per row.
std::vector<std::string> stabilityLines(const StabilityTable& table);
// Notes under the lines: the reference's excluded samples, the limit.
std::vector<std::string> stabilityNotes(const StabilityTable& table);
// report.md's "## Stability" section.
std::string stabilityMarkdown(const StabilityTable& table);

}  // namespace spire::tune
