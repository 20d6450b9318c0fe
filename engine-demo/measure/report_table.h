#pragma once

// The demo's results table: one row per shader variant with its timings and
// its image error against the reference variant. The same rows render as
// aligned plain text (printed) and as Markdown (report.md).

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace spire::measure {

struct ReportRow {
  std::string variant;
  double frameMs = 0.0;     // mean GPU time of a measured frame
  double firstUseMs = 0.0;  // the first (warm-up) frame, shader compilation included
  double prebakeMs = 0.0;   // offline worlds computed before rendering
  double speedup = 1.0;     // reference frameMs / frameMs
  double rmse = 0.0;
  double psnr = std::numeric_limits<double>::infinity();
  double maxError = 0.0;
  uint64_t nanPixels = 0;
  // The image covers far fewer pixels than the reference's: no speedup is
  // shown, since drawing almost nothing is not a trade.
  bool degenerate = false;
};

// Columns separated by two spaces, the variant left-aligned and numbers
// right-aligned, a header and a dashed rule; every line ends with '\n'.
// Infinite values print as "inf" (or "-inf"), NaN as "nan".
std::string formatTextTable(const std::vector<ReportRow>& rows);

// A GitHub-flavoured Markdown table with right-aligned number columns; '|'
// in a variant name is escaped.
std::string formatMarkdownTable(const std::vector<ReportRow>& rows);

}  // namespace spire::measure
