// report.html: the tuning run's report as one self-contained page beside
// report.md. An SVG scatter plot of every measured variant, frame time (x)
// against RMSE (y), with the Pareto front joined and highlighted; front
// points whose order against a neighbour is within the noise (their 95% time
// intervals overlap) drawn apart, every front point with its interval as an
// error bar. Hovering a point shows its decisions and, on the front, its
// image; a point with a decision file links to it. Tables of the front and
// of the variants off the trade (failed, infeasible, degenerate, NaN or Inf
// pixels) with their reasons follow, then, for an --extremes run, the
// stability table's lines. The page has no script and no external
// reference: images and decision files are links relative to the page, in
// the run's output directory.
#pragma once

#include <cstddef>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "tune/results_csv.h"

namespace spire::tune {

// A variant the plot leaves out, and why.
struct OffTradeVariant {
  size_t result = 0;   // index into ReportPage::results
  std::string reason;  // plain text: "infeasible: ...", "failed: ...", "12 NaN and 0 Inf pixels ..."
};

// What the page shows; every text is plain and escaped by the page.
struct ReportPage {
  std::string title;                       // the page's heading
  std::string summary;                     // a paragraph under it
  std::vector<std::string> components;     // the explored components, in axis order
  std::span<const VariantResult> results;  // every variant of the run
  std::vector<size_t> front;               // indices into results, fastest first
  double referenceMs = 0.0;                // a time ratio times this is a frame time in ms
  // Paths relative to the page, by index into results: the variant's image
  // (the front's front/INDEX.png) and the decision files written for it.
  std::map<size_t, std::string> images;
  std::map<size_t, std::vector<std::string>> decisionFiles;
  std::vector<OffTradeVariant> offTrade;  // in the order the table lists them
  // --extremes: the stability table's lines and notes (tune/stability_table.h).
  bool showStability = false;
  std::vector<std::string> stability;
  std::vector<std::string> stabilityNotes;
};

std::string renderReportHtml(const ReportPage& page);

// `text` with & < > " and ' written as character references, for element
// content and quoted attribute values alike.
std::string escapeHtml(std::string_view text);

}  // namespace spire::tune
