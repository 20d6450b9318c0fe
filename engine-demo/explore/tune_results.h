// A spire-tune output directory as the explorer's Pareto view uses it
// (docs/explorer.md, "Pareto view"): every measured variant that is a point
// of the speed/accuracy trade, with its decisions, and which of them form the
// front. Read through the tuner's own table reader (tune/results_csv.h), so
// the two never disagree on the format.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "support/expected.h"

namespace spire::explore {

class DecisionState;

// One measured variant of the tuned shader.
struct TunedVariant {
  uint64_t index = 0;  // the tuner's variant index (variants.csv's `index`)
  // component -> placement of every explored component: what the tuner
  // compiled, so applying exactly these reproduces the measured variant.
  std::map<std::string, std::string> decisions;
  double frameMs = 0.0;  // variants.csv's frame_ms: the time ratio times the reference's frame
  double rmse = 0.0;
  bool onFront = false;
};

struct TuneResults {
  std::filesystem::path dir;
  std::string shader;
  std::vector<std::string> components;  // the explored ones, in the tuner's axis order
  // The variants on the trade: measured, ok and without NaN/Inf pixels
  // (the ones spire-tune's plot shows), in the tuner's index order.
  std::vector<TunedVariant> variants;
  std::vector<size_t> front;  // indices into `variants`, in pareto.csv's order (fastest first)
};

// Reads `dir`'s variants.csv and pareto.csv. An error when they are missing
// or malformed, or when the run tuned another shader than `shader` (whose
// choices `state` holds): a decision file the tuner wrote names another
// shader, or a tuned component is not one of `shader`'s choices.
Expected<TuneResults, Failure> loadTuneResults(const std::filesystem::path& dir, const std::string& shader,
                                               const DecisionState& state);

// The variant whose decisions are exactly `decisions`, if the run measured it.
std::optional<size_t> matchingVariant(const TuneResults& results, const std::map<std::string, std::string>& decisions);

// "albedo=PrebakeTex lighting=Vertex:basic", for tooltips and logs.
std::string decisionsText(const TunedVariant& variant);

}  // namespace spire::explore
