#include "explore/tune_results.h"

#include <fmt/format.h>

#include <cmath>

#include "explore/decision_state.h"
#include "graph/decision_file.h"
#include "support/diagnostic.h"
#include "support/file_io.h"
#include "support/source_manager.h"
#include "tune/results_csv.h"

namespace spire::explore {
namespace fs = std::filesystem;
namespace {

// The shader the run tuned, as its decision files name it; nullopt when it
// wrote none (no variant met either budget). The tables themselves only
// name components, which two shaders can share.
Expected<std::optional<std::string>, Failure> tunedShader(const fs::path& dir) {
  for (const char* name : {"best_error_budget.decisions", "best_time_budget.decisions"}) {
    const fs::path path = dir / name;
    if (!fs::exists(path)) continue;
    auto text = readFileBytes(path.string());
    if (!text) return Failure{fmt::format("cannot read '{}': {}", path.string(), text.error().message())};
    SourceManager sources;
    DiagnosticList diags;
    const FileId file = sources.addFile(path.string(), std::move(text).value());
    const graph::DecisionFile decisions = graph::parseDecisionFile(sources, file, diags);
    if (diags.hasErrors()) return Failure{fmt::format("'{}' is not a decision file", path.string())};
    if (!decisions.lines.empty()) return std::optional<std::string>(decisions.lines.front().prefix);
  }
  return std::optional<std::string>();
}

Expected<void, Failure> checkShader(const fs::path& dir, const std::string& shader,
                                    const std::vector<std::string>& components, const DecisionState& state) {
  auto tuned = tunedShader(dir);
  if (!tuned) return tuned.error();
  if (*tuned && **tuned != shader) {
    return Failure{
        fmt::format("'{}' is spire-tune's output for shader '{}', but the explored instance's shader is '{}'",
                    dir.string(), **tuned, shader)};
  }
  for (const std::string& component : components) {
    if (!state.isChoice(component)) {
      return Failure{fmt::format("'{}' tuned the component '{}', which is not a choice of the explored shader '{}'",
                                 dir.string(), component, shader)};
    }
  }
  return {};
}

bool onTrade(const tune::VariantResult& r) {
  return r.ok() && r.nanPixels + r.infPixels == 0 && std::isfinite(r.rmse) && std::isfinite(r.frameMs);
}

}  // namespace

Expected<TuneResults, Failure> loadTuneResults(const fs::path& dir, const std::string& shader,
                                               const DecisionState& state) {
  const fs::path table = dir / "variants.csv";
  auto components = tune::readComponents(table);
  if (!components) return components.error();
  if (auto ok = checkShader(dir, shader, *components, state); !ok) return ok.error();
  auto rows = tune::readResults(table, *components);
  if (!rows) return rows.error();
  // readResults takes a missing table for an empty journal; a missing front
  // is a run that did not finish.
  if (!fs::exists(dir / "pareto.csv")) {
    return Failure{fmt::format("'{}' has no pareto.csv: the tuning run did not finish", dir.string())};
  }
  auto front = tune::readResults(dir / "pareto.csv", *components);
  if (!front) return front.error();
  TuneResults results{dir, shader, *components, {}, {}};
  std::map<uint64_t, size_t> byIndex;
  for (const tune::VariantResult& r : *rows) {
    if (!onTrade(r)) continue;
    TunedVariant variant{r.index, {}, r.frameMs, r.rmse, false};
    for (size_t i = 0; i < components->size(); ++i) variant.decisions[(*components)[i]] = r.placements[i];
    byIndex[r.index] = results.variants.size();
    results.variants.push_back(std::move(variant));
  }
  for (const tune::VariantResult& r : *front) {
    const auto found = byIndex.find(r.index);
    if (found == byIndex.end()) {
      return Failure{fmt::format("{}: front variant {} is not a measured variant of variants.csv",
                                 (dir / "pareto.csv").string(), r.index)};
    }
    results.variants[found->second].onFront = true;
    results.front.push_back(found->second);
  }
  return results;
}

std::optional<size_t> matchingVariant(const TuneResults& results, const std::map<std::string, std::string>& decisions) {
  for (size_t i = 0; i < results.variants.size(); ++i) {
    if (results.variants[i].decisions == decisions) return i;
  }
  return std::nullopt;
}

std::string decisionsText(const TunedVariant& variant) {
  std::string text;
  for (const auto& [component, placement] : variant.decisions) {
    text += fmt::format("{}{}={}", text.empty() ? "" : " ", component, placement);
  }
  return text;
}

}  // namespace spire::explore
