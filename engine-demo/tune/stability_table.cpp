#include "tune/stability_table.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>

namespace spire::tune {
namespace {

// The sample's values as the row shows them.
std::string valueText(const ParameterSample& sample, const SampleLabel& label) {
  if (!label.input.empty()) return fmt::format("{}", fmt::join(sample.at(label.input), ","));
  std::string text;
  for (const auto& [component, values] : sample) {
    text += fmt::format("{}{}={}", text.empty() ? "" : " ", component, fmt::join(values, ","));
  }
  return text;
}

std::string inputName(const SampleLabel& label) {
  if (!label.input.empty()) return label.input;
  return label.kind == "scene" ? "scene" : "all";
}

std::string labelText(const SampleLabel& label, const std::string& value) {
  if (label.kind == "scene") return "at the scene's own values";
  if (label.input.empty()) return fmt::format("under {} ({})", label.kind, value);
  return fmt::format("when {} = {} ({})", label.input, value, label.kind);
}

std::string decisionsText(const std::vector<Axis>& axes, const VariantResult& r) {
  std::string text;
  for (size_t i = 0; i < axes.size() && i < r.placements.size(); ++i) {
    text += fmt::format("{}{}={}", text.empty() ? "" : " ", axes[i].component, r.placements[i]);
  }
  return text;
}

// Whose samples the table diagnoses, in order.
struct Subject {
  std::string variant;
  std::string decisions;
  engine::CompileForDiagnosis compile;
  std::vector<std::pair<size_t, size_t>> pairs;
};

std::vector<Subject> subjects(const Tuner& tuner, const std::vector<Axis>& axes,
                              const std::vector<VariantResult>& results) {
  std::vector<Subject> list;
  const std::vector<SampleLabel>& labels = tuner.sampleLabels();
  if (!tuner.referenceHazards().empty()) {
    list.push_back({"reference", "", tuner.referenceCompile(), samplesToDiagnose(tuner.referenceHazards(), labels)});
  }
  for (const VariantResult& r : results) {
    if (r.sameAs || r.hazardSamples.empty()) continue;
    list.push_back({std::to_string(r.index), decisionsText(axes, r), tuner.variantCompile(pointAt(axes, r.index)),
                    samplesToDiagnose(r.hazardSamples, labels)});
  }
  return list;
}

void addRows(const Subject& subject, const std::vector<engine::Hazard>& hazards, const ParameterSample& sample,
             const SampleLabel& label, StabilityTable& table) {
  for (const engine::Hazard& h : hazards) {
    // What came in with a non-finite input is the origin's doing, listed
    // with the origin.
    if (h.inherited) continue;
    table.rows.push_back({subject.variant, subject.decisions, h.component, h.definition, h.world, inputName(label),
                          label.kind, valueText(sample, label), h.nan, h.count, h.unit, h.operation,
                          h.operationSource});
  }
}

}  // namespace

std::vector<std::pair<size_t, size_t>> samplesToDiagnose(const std::vector<std::pair<size_t, size_t>>& hazardous,
                                                         const std::vector<SampleLabel>& labels) {
  const auto labelOf = [&](size_t sample) { return sample < labels.size() ? labels[sample] : SampleLabel{}; };
  for (const auto& pair : hazardous) {
    if (labelOf(pair.first).kind == "scene") return {pair};
  }
  std::vector<std::pair<size_t, size_t>> corners;
  for (const auto& pair : hazardous) {
    if (!labelOf(pair.first).input.empty()) corners.push_back(pair);
  }
  if (corners.empty() && !hazardous.empty()) corners.push_back(hazardous.front());
  return corners;
}

StabilityTable buildStabilityTable(Tuner& tuner, const std::vector<Axis>& axes,
                                   const std::vector<VariantResult>& results, size_t limit) {
  StabilityTable table;
  table.limit = limit;
  const std::vector<ParameterSample> samples = tuner.samples();
  const std::vector<SampleLabel>& labels = tuner.sampleLabels();
  table.samples = samples.size();
  for (const auto& [sample, view] : tuner.referenceHazards()) {
    table.referenceExcluded.push_back(labelText(labels.at(sample), valueText(samples[sample], labels[sample])));
  }
  for (const Subject& subject : subjects(tuner, axes, results)) {
    for (const auto& [sample, view] : subject.pairs) {
      if (table.diagnosed == limit) {
        ++table.cut;
        continue;
      }
      ++table.diagnosed;
      auto hazards = tuner.diagnoseHazards(subject.compile, sample, view);
      if (!hazards) {
        table.failures.push_back(
            fmt::format("{}, {}: {}", subject.variant, tuner.inputsText(sample, view), hazards.error().message));
        continue;
      }
      addRows(subject, *hazards, samples[sample], labels.at(sample), table);
    }
  }
  return table;
}

std::string stabilityCsv(const StabilityTable& table) {
  std::string csv =
      "variant,decisions,component,definition,world,input,value_kind,value,non_finite,count,unit,operation,"
      "operation_source\n";
  for (const StabilityRow& row : table.rows) {
    csv += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{}\n", quoteCsv(row.variant), quoteCsv(row.decisions),
                       quoteCsv(row.component), quoteCsv(row.definition), quoteCsv(row.world), quoteCsv(row.input),
                       quoteCsv(row.kind), quoteCsv(row.value), row.nan ? "NaN" : "Inf", row.count, quoteCsv(row.unit),
                       quoteCsv(row.operation), quoteCsv(row.operationSource));
  }
  return csv;
}

std::vector<std::string> stabilityLines(const StabilityTable& table) {
  std::vector<std::string> lines;
  for (const StabilityRow& row : table.rows) {
    const std::string who =
        row.variant == "reference" ? "reference" : fmt::format("variant {} ({})", row.variant, row.decisions);
    const SampleLabel label{row.input == "all" || row.input == "scene" ? "" : row.input, row.kind};
    const std::string at =
        row.operation.empty() ? "" : fmt::format(" at `{}` ({})", row.operation, row.operationSource);
    lines.push_back(fmt::format("{}: {} ({}) goes {}{} {} ({} {})", who, row.component, row.definition,
                                row.nan ? "NaN" : "Inf", at, labelText(label, row.value), row.count, row.unit));
  }
  return lines;
}

std::vector<std::string> stabilityNotes(const StabilityTable& table) {
  std::vector<std::string> notes;
  if (!table.referenceExcluded.empty()) {
    notes.push_back(fmt::format(
        "The reference is NaN or Inf under {} of the {} samples, which every variant's error leaves out (there is "
        "nothing to compare against): {}.",
        table.referenceExcluded.size(), table.samples, fmt::join(table.referenceExcluded, "; ")));
  }
  if (table.cut > 0) {
    notes.push_back(
        fmt::format("The limit of {} diagnosed (variant, sample) pairs cut {} more short: the table is "
                    "incomplete.",
                    table.limit, table.cut));
  }
  for (const std::string& failure : table.failures) notes.push_back("No diagnosis for " + failure + ".");
  return notes;
}

std::string stabilityMarkdown(const StabilityTable& table) {
  std::string text = fmt::format(
      "\n## Stability\n\nUnder --extremes' {} samples, the component that instrumented kernels find going NaN or "
      "Inf first, for the reference and each variant, under each per-input corner that has NaN or Inf pixels "
      "(each input alone at an extreme, the others at the scene's values), or under the scene's own values or "
      "the first hazardous combination when no corner has them; also in stability.csv.\n\n",
      table.samples);
  const std::vector<std::string> lines = stabilityLines(table);
  if (lines.empty()) text += "No component goes NaN or Inf.\n";
  for (const std::string& line : lines) text += fmt::format("- {}\n", line);
  for (const std::string& note : stabilityNotes(table)) text += fmt::format("\n{}\n", note);
  return text;
}

}  // namespace spire::tune
