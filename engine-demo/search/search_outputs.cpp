#include "search/search_outputs.h"

#include <fmt/format.h>

#include <algorithm>
#include <numeric>

#include "graph/decision_file.h"
#include "scene/texture.h"
#include "tune/error_plot.h"
#include "tune/results_csv.h"

namespace spire::search {

std::string levelFileName(size_t k) { return fmt::format("level{}.decisions", k); }

std::string levelDecisionText(const Chain& chain, size_t k, const ModuleHeader& header) {
  const Level& level = chain.levels[k];
  const std::string what = k == 0 ? "the original" : fmt::format("{} step(s) from the original", k);
  return graph::writeDecisionFile(
      placementDecisions(header.derived, level.placement),
      fmt::format("spire-simplify --search: level {} of {}'s chain, {}.\nMeasured: RMSE {:.6f}, time "
                  "ratio {:.3f} against {}; cost C = {:.1f}.",
                  k, header.base, what, level.error, level.timeRatio, chain.measuredAgainst, level.modelCost));
}

namespace {

std::string chainCsv(const Chain& chain) {
  std::string text = "level,rmse,time_ratio,frame_ms,cost,component,variation,from,rule,before,after\n";
  for (size_t k = 0; k < chain.levels.size(); ++k) {
    const Level& level = chain.levels[k];
    text +=
        fmt::format("{},{:.6f},{:.4f},{:.4f},{:.1f}", k, level.error, level.timeRatio, level.frameMs, level.modelCost);
    if (k == 0) {
      text += ",,,,,,\n";
      continue;
    }
    const Rewriting& r = chain.steps[k - 1];
    text +=
        fmt::format(",{},{},{},{},{},{}\n", tune::quoteCsv(r.component), tune::quoteCsv(r.variation),
                    tune::quoteCsv(r.from), tune::quoteCsv(r.rule), tune::quoteCsv(r.before), tune::quoteCsv(r.after));
  }
  return text;
}

// Markdown table cells: a `|` would end the cell, a backtick the code span.
std::string cell(const std::string& text) {
  std::string escaped;
  for (const char c : text) escaped += c == '|' ? std::string("\\|") : std::string(1, c == '`' ? '\'' : c);
  return escaped;
}

std::string transitionImageName(const Transition& t) { return fmt::format("transition{}_{}.png", t.from, t.to); }

std::string transitionSection(const Chain& chain, const OutputRequest& request) {
  if (!request.policy) return {};
  std::string text =
      "\n## Transitions\n\nHe et al.'s transition shaders: where the policy switches levels, a band over the "
      "last part of the nearer one draws a variant that blends the two by distance (`mix(near, far, fade)` "
      "of each component that differs), so that the switch does not pop.\n\n";
  const ChainTransitions& made = request.transitions;
  if (made.transitions.list.empty()) return text + fmt::format("None: {}.\n", made.note);
  text +=
      "Time is the frame time over the reference's, as for the levels: a transition computes both levels it "
      "blends, so its band costs more than either.\n\n"
      "| from level | to level | blends from | to | time | level A's, B's | decision file | from the first camera "
      "view |\n"
      "|---|---|---|---|---|---|---|---|\n";
  for (size_t i = 0; i < made.transitions.list.size(); ++i) {
    const Transition& t = made.transitions.list[i];
    text += fmt::format(
        "| {0} | {1} | {2:.4g} | {3:.4g} | {4:.3f} | {5:.3f}, {6:.3f} | `{7}` | ![from level {0} to level {1}]({8}) "
        "|\n",
        t.from, t.to, t.nearDistance, t.farDistance, made.drawn.at(i).timeRatio, chain.levels.at(t.from).timeRatio,
        chain.levels.at(t.to).timeRatio, transitionFileName(t), transitionImageName(t));
  }
  return text;
}

std::string report(const Chain& chain, const OutputRequest& request) {
  const SearchOptions& o = *request.options;
  std::string text = fmt::format(
      "# Greedy simplification of {}\n\n"
      "He et al. 2015's search on `{}`: K1 = {}, K2 = {}, K3 = {}, at most {} level(s), error budget {}. "
      "Error is the RMSE against {} over every camera view and parameter sample; time is the frame time "
      "over its, frame for frame ({:.3f} ms). C is He et al.'s cost model of the level's program, "
      "0.3·C_v + 0.7·C_f + 10·N_var; candidates were ranked and the chain ordered by {}.\n\n"
      "Stopped: {}.\n\n![error against time](error_time.png)\n\n"
      "| level | RMSE | time ratio | frame ms | C | rewrite |\n|---|---|---|---|---|---|\n",
      request.header.base, o.scenePath, o.k1, o.k2, o.k3, o.maxLevels, o.errorBudget, chain.measuredAgainst,
      request.referenceMs, o.cost == CostKind::Model ? "C" : "the measured time", chain.stopReason);
  for (size_t k = 0; k < chain.levels.size(); ++k) {
    const Level& level = chain.levels[k];
    std::string rewrite = "the original";
    if (k > 0) {
      const Rewriting& r = chain.steps[k - 1];
      rewrite = isMove(r) ? fmt::format("`{}` moved: `{}` → `{}`", definitionName(r), r.before, r.after)
                          : fmt::format("`{}` = `{}` with {}: `{}` → `{}`", definitionName(r), r.from, r.rule,
                                        cell(r.before), cell(r.after));
    }
    text += fmt::format("| {} | {:.6f} | {:.3f} | {:.3f} | {:.1f} | {} |\n", k, level.error, level.timeRatio,
                        level.frameMs, level.modelCost, rewrite);
  }
  if (!request.levelImages.empty()) {
    text += "\n## Levels\n\nEach level from the scene's first camera view:\n\n";
    for (size_t k = 0; k < request.levelImages.size(); ++k) {
      text += fmt::format("![level {0}: RMSE {1:.4f}, C {2:.1f}](level{0}.png)\n", k, chain.levels[k].error,
                          chain.levels[k].modelCost);
    }
  }
  if (request.policy) {
    text += fmt::format(
        "\n## Level-of-detail policy\n\n`lod_policy.json`: each level's error at each camera distance (the largest "
        "over the scene's materials) and its frame time with every object at it, then He et al.'s choice: the "
        "cheapest level within tolerated_err(d) = ((d - d_near) / (d_far - d_near))^{} x {}, with a penalty of {} "
        "per switch.\n\n{}",
        o.policyChoice.errorExponent, o.policyChoice.maxError, o.policyChoice.switchPenalty, request.policy->table);
  }
  text += transitionSection(chain, request);
  text += "\n## Steps\n\n```\n";
  for (const std::string& line : chain.log) text += line + "\n";
  return text + "```\n";
}

Expected<std::string, Failure> plot(const Chain& chain) {
  std::vector<tune::Measured> points;
  for (const Level& level : chain.levels) points.push_back({level.frameMs, level.error, true, 0.0, 0.0});
  std::vector<size_t> order(points.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return points[a].frameMs < points[b].frameMs; });
  auto png = scene::encodePng(tune::plotErrorAgainstTime(points, order));
  if (!png) return Failure{fmt::format("cannot encode the plot: {}", png.error().message)};
  return std::move(png).value();
}

}  // namespace

std::string moduleFileName(const ModuleHeader& header) { return header.derived + ".spire"; }

Expected<FileSet, Failure> searchOutputs(const Chain& chain, const OutputRequest& request) {
  FileSet files;
  const ChainTransitions& made = request.transitions;
  for (size_t i = 0; i < made.transitions.list.size(); ++i) {
    const Transition& t = made.transitions.list[i];
    files.emplace_back(transitionFileName(t), transitionDecisionText(t, request.header));
    files.emplace_back(transitionImageName(t), made.drawn.at(i).image);
  }
  files.emplace_back(moduleFileName(request.header),
                     chainModuleText(request.header, chain, transitionDefinitions(made.transitions)));
  for (size_t k = 0; k < chain.levels.size(); ++k) {
    files.emplace_back(levelFileName(k), levelDecisionText(chain, k, request.header));
  }
  for (size_t k = 0; k < request.levelImages.size(); ++k) {
    files.emplace_back(fmt::format("level{}.png", k), request.levelImages[k]);
  }
  files.emplace_back("chain.csv", chainCsv(chain));
  if (request.policy) {
    const lod::LodPolicy policy = withTransitions(request.policy->policy, made.transitions.list, request.header.derived,
                                                  request.options->outputDir);
    files.emplace_back("lod_policy.json", lod::formatLodPolicy(policy, request.options->outputDir));
  }
  files.emplace_back("report.md", report(chain, request));
  auto png = plot(chain);
  if (!png) return png.error();
  files.emplace_back("error_time.png", std::move(png).value());
  return files;
}

}  // namespace spire::search
