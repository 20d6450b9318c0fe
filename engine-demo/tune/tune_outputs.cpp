#include "tune/tune_outputs.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>

#include "driver/exit_codes.h"
#include "graph/decision_file.h"
#include "measure/image_metrics.h"
#include "scene/texture.h"
#include "support/file_io.h"
#include "tune/error_plot.h"
#include "tune/format_selection.h"
#include "tune/pareto.h"
#include "tune/report_html.h"
#include "tune/stability_table.h"

namespace spire::tune {
namespace {

namespace fs = std::filesystem;

// The results seen as points of the trade, their front, and the counts the
// report gives.
struct FrontSummary {
  std::vector<Measured> measured;  // per result; hazards have infinite error
  std::vector<size_t> front;       // indices into the results, fastest first
  size_t hazards = 0;
  size_t infeasible = 0;
  size_t reused = 0;
  std::vector<size_t> offTrade;  // failed, infeasible and degenerate variants, in index order
};

// How many variants of each class off the trade the console names before
// pointing to the report, which names them all.
constexpr size_t kConsoleListed = 10;

// Why a result is not a point of the trade, for people.
std::string offTradeReason(const VariantResult& r) {
  if (r.status == "infeasible") {
    return "infeasible: its decisions cannot hold together (one component's world rules out another's)";
  }
  return r.status;
}

// The best variant within each budget (indices into the results).
struct BudgetChoice {
  double timeBudgetMs = 0.0;
  double errorBudget = 0.0;
  std::optional<size_t> bestInTime;   // most accurate within the time budget
  std::optional<size_t> bestInError;  // fastest within the error budget
};

FrontSummary summarize(const std::vector<VariantResult>& results) {
  FrontSummary summary;
  for (const VariantResult& r : results) {
    const bool hazard = r.nanPixels + r.infPixels > 0;
    summary.hazards += hazard ? 1 : 0;
    summary.infeasible += r.status == "infeasible" ? 1 : 0;
    summary.reused += r.sameAs ? 1 : 0;
    if (!r.ok()) summary.offTrade.push_back(summary.measured.size());
    // The interval of the paired ratio, in milliseconds as frameMs is.
    const double ms = r.time.median > 0.0 ? r.frameMs / r.time.median : 0.0;
    summary.measured.push_back({r.frameMs, hazard ? std::numeric_limits<double>::infinity() : r.rmse, r.ok(),
                                r.time.interval.low * ms, r.time.interval.high * ms});
  }
  summary.front = paretoFront(summary.measured);
  return summary;
}

std::optional<int> writeFront(const TuneOptions& options, engine::ToolRun& run, const TuneSession& session,
                              const std::vector<VariantResult>& results, const FrontSummary& summary) {
  std::string frontCsv = csvHeader(session.components);
  for (size_t i : summary.front) frontCsv += csvRow(results[i]);
  if (auto written = writeFileAtomically((fs::path(options.outputDir) / "pareto.csv").string(), frontCsv); !written) {
    return run.fail(written.error().message);
  }
  const scene::Image plot = plotErrorAgainstTime(summary.measured, summary.front);
  if (auto written = scene::writePng(fs::path(options.outputDir) / "plot.png", plot); !written) {
    return run.fail(written.error());
  }
  return std::nullopt;
}

// Budgets: by default, half the reference's frame time and an RMSE of 0.01.
BudgetChoice chooseBest(const TuneOptions& options, const std::vector<VariantResult>& results,
                        const FrontSummary& summary) {
  double referenceMs = 0.0;
  for (size_t i : summary.front) referenceMs = std::max(referenceMs, results[i].frameMs);
  BudgetChoice choice;
  choice.timeBudgetMs = options.timeBudgetMs.value_or(referenceMs / 2.0);
  choice.errorBudget = options.errorBudget.value_or(0.01);
  for (size_t i : summary.front) {
    const VariantResult& r = results[i];
    if (r.frameMs <= choice.timeBudgetMs && (!choice.bestInTime || r.rmse < results[*choice.bestInTime].rmse)) {
      choice.bestInTime = i;
    }
    if (summary.measured[i].error <= choice.errorBudget &&
        (!choice.bestInError || r.frameMs < results[*choice.bestInError].frameMs)) {
      choice.bestInError = i;
    }
  }
  return choice;
}

std::string placementsText(const std::vector<std::string>& components, const VariantResult& r) {
  std::string text;
  for (size_t i = 0; i < components.size(); ++i) {
    text += fmt::format("{}{}={}", text.empty() ? "" : " ", components[i], r.placements[i]);
  }
  return text;
}

std::string decisionFile(const std::string& shader, const engine::VariantProgram& program, const std::string& why,
                         const ShaderLibrary::Attributes& attributes) {
  std::string comment = "spire-tune: " + why;
  if (!attributes.empty()) {
    comment += "\nFormats of the baked textures chosen from their values (data-layout selection).";
  }
  graph::DecisionFile decisions;
  for (const auto& [component, placement] : program.placement) {
    const auto found = attributes.find(component);
    const auto none = decltype(found->second){};
    decisions.lines.push_back(
        graph::makeDecision(shader, component, placement, found == attributes.end() ? none : found->second));
  }
  return graph::writeDecisionFile(decisions, comment);
}

// Writes result `best` as decision file `file` with the formats data-layout
// selection chooses for its bakes (their table goes to `layoutReport`).
std::optional<int> writeBest(const TuneOptions& options, engine::ToolRun& run, TuneSession& session,
                             const VariantResult& best, const std::string& file, const std::string& why,
                             std::string& layoutReport, std::ostream& out) {
  const TunePoint point = pointAt(session.space.axes, best.index);
  auto program = session.tuner->program(point);
  if (!program) return run.fail(program.error());
  auto layouts = selectLayouts(run.renderer(), session.instanceIndex, point, options.bakeSize);
  if (!layouts) return run.fail(layouts.error());
  if (!layouts->layouts.empty()) {
    layoutReport += fmt::format("\n### Data layout of `{}`\n\n{}", file, layoutTable(*layouts));
  }
  const std::string text =
      decisionFile(options.shader, *program,
                   fmt::format("{} (variant {}: {:.3f} ms, RMSE {:.4g})", why, best.index, best.frameMs, best.rmse),
                   layouts->attributes);
  if (auto written = writeFileAtomically((fs::path(options.outputDir) / file).string(), text); !written)
    return run.fail(written.error().message);
  out << fmt::format("{}: variant {} ({}) -> {}/{}\n", why, best.index, placementsText(session.components, best),
                     options.outputDir, file);
  return std::nullopt;
}

std::optional<int> writeBudgetVariants(const TuneOptions& options, engine::ToolRun& run, TuneSession& session,
                                       const std::vector<VariantResult>& results, const BudgetChoice& choice,
                                       std::string& layoutReport, std::ostream& out) {
  const auto write = [&](std::optional<size_t> best, const std::string& file, const std::string& why) {
    if (best) return writeBest(options, run, session, results[*best], file, why, layoutReport, out);
    out << fmt::format("no variant meets the {}; {} not written\n", why, file);
    return std::optional<int>();
  };
  if (const auto status = write(choice.bestInTime, "best_time_budget.decisions",
                                fmt::format("time budget {:.3f} ms", choice.timeBudgetMs))) {
    return status;
  }
  return write(choice.bestInError, "best_error_budget.decisions",
               fmt::format("error budget RMSE {:.4g}", choice.errorBudget));
}

// The report's first lines and the head of the front's table.
std::string reportHeader(const TuneOptions& options, const engine::ToolRun& run, const TuneSession& session,
                         size_t variants) {
  std::string separators;
  for (size_t i = 0; i < session.components.size(); ++i) separators += "---|";
  return fmt::format(
      "# spire-tune report\n\nShader `{}` on `{}` ({}) at {}x{}, {} variants of {} components{}; error is RMSE against "
      "the "
      "reference over {} camera view(s) and every parameter sample together; worst RMSE the largest under one "
      "sample. Time: the variant's and the reference's frames are rendered in turn, "
      "after {} unmeasured ones (the captures of the camera views first), and a variant's time is the median of "
      "its per-pair ratios: {} pairs, and for the candidates for the front a new measurement that adds pairs "
      "until the ratio's 95% interval is within 6% or it has {}; in milliseconds, times the reference's median "
      "frame, {:.3f} ms. A front point whose interval "
      "overlaps the previous one's is marked *within noise*: their order is not known.\n\n"
      "![error against time](plot.png)\n\n## Pareto front\n\n"
      "| variant | {} | frame ms | 95% interval (ms) | pairs | RMSE | worst RMSE | image "
      "|\n|---|{}---|---|---|---|---|---|"
      "\n",
      options.shader, options.scenePath, run.context().selectedDevice().name, run.scene().width, run.scene().height,
      variants, session.components.size(), session.space.sampled ? " (sampled)" : "", run.scene().camera.views.size(),
      session.tuner->unmeasuredFrames(), options.frames, options.maxFrames, session.tuner->referenceMs(),
      fmt::join(session.components, " | "), separators);
}

// A row per variant of the front, with its image from camera view 0 as
// front/<index>.png.
std::optional<int> appendFrontTable(const TuneOptions& options, engine::ToolRun& run, TuneSession& session,
                                    const std::vector<VariantResult>& results, const FrontSummary& summary,
                                    std::string& report) {
  std::error_code ec;
  fs::create_directories(fs::path(options.outputDir) / "front", ec);
  for (size_t k = 0; k < summary.front.size(); ++k) {
    const VariantResult& r = results[summary.front[k]];
    auto capture = session.tuner->capture(pointAt(session.space.axes, r.index));
    if (!capture) return run.fail(capture.error());
    const std::string thumb = fmt::format("front/{}.png", r.index);
    if (auto written = scene::writePng(fs::path(options.outputDir) / thumb, measure::toRgba8(capture->color));
        !written) {
      return run.fail(written.error());
    }
    const double ms = session.tuner->referenceMs();
    const bool tied = k > 0 && withinNoise(results[summary.front[k - 1]].time, r.time);
    report +=
        fmt::format("| {} | {} | {:.3f}{} | {:.3f}-{:.3f} | {} | {:.4g} | {:.4g} | ![]({}) |\n", r.index,
                    fmt::join(r.placements, " | "), r.frameMs, tied ? " *within noise*" : "", r.time.interval.low * ms,
                    r.time.interval.high * ms, r.time.pairs, r.rmse, r.worstRmse, thumb);
  }
  return std::nullopt;
}

// Hazards, counts and where the time went.
std::string reportFindings(const TuneOptions& options, const TuneSession& session,
                           const std::vector<VariantResult>& results, const FrontSummary& summary,
                           const TimeSplit& split) {
  std::string text;
  for (const VariantResult& r : results) {
    if (r.nanPixels + r.infPixels > 0 && !r.sameAs) {
      text += fmt::format("\nHazard: variant {} ({}) has {} NaN and {} Inf pixels, first under {}.", r.index,
                          placementsText(session.components, r), r.nanPixels, r.infPixels, r.hazardInputs);
      for (const std::string& cause : r.hazardCauses) text += fmt::format("\n  - {}", cause);
    }
  }
  if (!summary.offTrade.empty()) {
    text +=
        "\n\n## Variants off the trade\n\nFailed, infeasible and degenerate variants (images covering far fewer "
        "pixels than the reference's): none is on the front.\n\n| variant | decisions | why |\n|---|---|---|\n";
    for (size_t i : summary.offTrade) {
      const VariantResult& r = results[i];
      text += fmt::format("| {} | {} | {} |\n", r.index, placementsText(session.components, r), offTradeReason(r));
    }
  }
  text += fmt::format(
      "\n{} variants had NaN or Inf pixels (infinite error, never on the front); {} were infeasible; "
      "{} had kernels identical to an earlier variant and were measured once.\n\n"
      "Time: compile {:.1f} s, first-use shader compilation {:.1f} s, render {:.1f} s, error {:.1f} s "
      "(summed over {} worker(s)).\n",
      summary.hazards, summary.infeasible, summary.reused, split.compileMs / 1000, split.firstUseMs / 1000,
      split.renderMs / 1000, split.errorMs / 1000, options.jobs);
  return text;
}

// Why a variant with NaN or Inf pixels is off the trade, for the page.
std::string hazardReason(const VariantResult& r) {
  std::string reason = fmt::format("{} NaN and {} Inf pixels (infinite error), first under {}", r.nanPixels,
                                   r.infPixels, r.hazardInputs);
  for (const std::string& cause : r.hazardCauses) reason += "; " + cause;
  return reason;
}

// What report.html shows: the results as report.md has them, the front's
// images and the decision files written for the budgets.
ReportPage reportPage(const TuneOptions& options, const engine::ToolRun& run, const TuneSession& session,
                      const std::vector<VariantResult>& results, const FrontSummary& summary,
                      const BudgetChoice& choice, const StabilityTable* stability) {
  ReportPage page;
  if (stability) {
    page.stability = stabilityLines(*stability);
    page.stabilityNotes = stabilityNotes(*stability);
    page.showStability = true;
  }
  page.title = fmt::format("spire-tune report: {} on {}", options.shader, options.scenePath);
  page.summary = fmt::format(
      "Shader {} on {} ({}), {} variants of {} components{}. Error: RMSE against the reference over {} camera "
      "view(s) and every parameter sample. Time: the median of the variant's per-pair frame time ratios to the "
      "reference, times the reference's median frame ({:.3f} ms).",
      options.shader, options.scenePath, run.context().selectedDevice().name, results.size(), session.components.size(),
      session.space.sampled ? " (sampled)" : "", run.scene().camera.views.size(), session.tuner->referenceMs());
  page.components = session.components;
  page.results = results;
  page.front = summary.front;
  page.referenceMs = session.tuner->referenceMs();
  for (size_t i : summary.front) page.images[i] = fmt::format("front/{}.png", results[i].index);
  if (choice.bestInTime) page.decisionFiles[*choice.bestInTime].push_back("best_time_budget.decisions");
  if (choice.bestInError) page.decisionFiles[*choice.bestInError].push_back("best_error_budget.decisions");
  for (size_t i : summary.offTrade) page.offTrade.push_back({i, offTradeReason(results[i])});
  for (size_t i = 0; i < results.size(); ++i) {
    if (results[i].ok() && !std::isfinite(summary.measured[i].error)) {
      page.offTrade.push_back({i, hazardReason(results[i])});
    }
  }
  return page;
}

// The report's sections besides the front and the findings.
struct ReportExtras {
  std::string layoutReport;                   // data-layout selection of the decision files
  const StabilityTable* stability = nullptr;  // --extremes only
};

std::optional<int> writeReport(const TuneOptions& options, engine::ToolRun& run, TuneSession& session,
                               const std::vector<VariantResult>& results, const FrontSummary& summary,
                               const TimeSplit& split, const BudgetChoice& choice, const ReportExtras& extras) {
  const std::string& layoutReport = extras.layoutReport;
  std::string report = reportHeader(options, run, session, results.size());
  if (const auto status = appendFrontTable(options, run, session, results, summary, report)) return status;
  report += reportFindings(options, session, results, summary, split);
  if (extras.stability) report += stabilityMarkdown(*extras.stability);
  if (!layoutReport.empty()) {
    report +=
        "\n## Data-layout selection\n\nEach baked output of the chosen variants, analysed in a 32-bit float "
        "bake; the error is what the selected format adds to the image against that bake.\n" +
        layoutReport;
  }
  if (auto written = writeFileAtomically((fs::path(options.outputDir) / "report.md").string(), report); !written) {
    return run.fail(written.error().message);
  }
  const std::string page =
      renderReportHtml(reportPage(options, run, session, results, summary, choice, extras.stability));
  if (auto written = writeFileAtomically((fs::path(options.outputDir) / "report.html").string(), page); !written) {
    return run.fail(written.error().message);
  }
  return std::nullopt;
}

void printSummary(const TuneOptions& options, const TuneSession& session, const std::vector<VariantResult>& results,
                  const FrontSummary& summary, const TimeSplit& split, const vk::HostTimer& wall, std::ostream& out,
                  std::ostream& err) {
  for (const VariantResult& r : results) {
    if (r.nanPixels + r.infPixels > 0 && !r.sameAs) {
      err << fmt::format("spire-tune: warning: variant {} ({}) produced {} NaN and {} Inf pixels, first under {}\n",
                         r.index, placementsText(session.components, r), r.nanPixels, r.infPixels, r.hazardInputs);
      for (const std::string& cause : r.hazardCauses) err << fmt::format("spire-tune:   {}\n", cause);
    }
  }
  for (size_t k = 0; k < summary.offTrade.size() && k < kConsoleListed; ++k) {
    const VariantResult& r = results[summary.offTrade[k]];
    err << fmt::format("spire-tune: warning: variant {} ({}) is off the trade: {}\n", r.index,
                       placementsText(session.components, r), offTradeReason(r));
  }
  if (summary.offTrade.size() > kConsoleListed) {
    err << fmt::format("spire-tune: warning: and {} more variants off the trade; {}/report.md lists them all\n",
                       summary.offTrade.size() - kConsoleListed, options.outputDir);
  }
  out << fmt::format(
      "front: {} variants; {} with NaN/Inf pixels; {} off the trade ({} infeasible, {} failed or degenerate); {} "
      "measured once for identical kernels\n",
      summary.front.size(), summary.hazards, summary.offTrade.size(), summary.infeasible,
      summary.offTrade.size() - summary.infeasible, summary.reused);
  out << fmt::format(
      "time split (summed over workers): compile {:.1f} s, first use {:.1f} s, render {:.1f} s, error {:.1f} s\n",
      split.compileMs / 1000, split.firstUseMs / 1000, split.renderMs / 1000, split.errorMs / 1000);
  out << fmt::format("wrote {0}/variants.csv, pareto.csv, plot.png, report.md, report.html, {1}front/\n",
                     options.outputDir, options.extremes ? "stability.csv, " : "");
  out << fmt::format("{} variants in {:.1f} s\n", results.size(), wall.elapsedMs() / 1000.0);
}

}  // namespace

int writeTuneOutputs(const TuneOptions& options, engine::ToolRun& run, TuneSession& session,
                     const std::vector<VariantResult>& results, const TimeSplit& split, const vk::HostTimer& wall,
                     std::ostream& out, std::ostream& err) {
  const FrontSummary summary = summarize(results);
  if (const auto status = writeFront(options, run, session, results, summary)) return *status;
  ReportExtras extras;
  const BudgetChoice choice = chooseBest(options, results, summary);
  if (const auto status = writeBudgetVariants(options, run, session, results, choice, extras.layoutReport, out)) {
    return *status;
  }
  std::optional<StabilityTable> stability;
  if (options.extremes) {
    stability = buildStabilityTable(*session.tuner, session.space.axes, results, kStabilityDiagnoses);
    const std::string path = (fs::path(options.outputDir) / "stability.csv").string();
    if (auto written = writeFileAtomically(path, stabilityCsv(*stability)); !written) {
      return run.fail(written.error().message);
    }
    extras.stability = &*stability;
    for (const std::string& note : stabilityNotes(*stability)) err << "spire-tune: warning: " << note << "\n";
  }
  if (const auto status = writeReport(options, run, session, results, summary, split, choice, extras)) {
    return *status;
  }
  printSummary(options, session, results, summary, split, wall, out, err);
  return run.finish(kExitSuccess);
}

}  // namespace spire::tune
