#include "measure/report_table.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace spire::measure {
namespace {

constexpr size_t kColumns = 9;
using Cells = std::array<std::string, kColumns>;

const Cells kHeader = {"variant", "frame ms", "first use ms", "prebake ms", "speedup",
                       "rmse",    "psnr dB",  "max error",    "NaN px"};

// fmt would print non-finite values too, but spelling them out keeps the
// table's contract independent of the format specs below.
std::string nonFinite(double value) {
  if (std::isnan(value)) return "nan";
  return value > 0 ? "inf" : "-inf";
}

std::string fixed(double value, int decimals) {
  return std::isfinite(value) ? fmt::format("{:.{}f}", value, decimals) : nonFinite(value);
}

// Errors span orders of magnitude (1e-6 for a reordering, 0.1 for a wrong
// texture), so they keep four significant digits rather than fixed decimals.
std::string significant(double value) { return std::isfinite(value) ? fmt::format("{:.4g}", value) : nonFinite(value); }

Cells cells(const ReportRow& row) {
  return {row.variant,
          fixed(row.frameMs, 3),
          fixed(row.firstUseMs, 3),
          fixed(row.prebakeMs, 3),
          row.degenerate               ? std::string("degenerate")
          : std::isfinite(row.speedup) ? fmt::format("{:.2f}x", row.speedup)
                                       : nonFinite(row.speedup),
          significant(row.rmse),
          fixed(row.psnr, 2),
          significant(row.maxError),
          fmt::format("{}", row.nanPixels)};
}

std::string escapeMarkdown(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '|') out += '\\';
    out += c;
  }
  return out;
}

}  // namespace

std::string formatTextTable(const std::vector<ReportRow>& rows) {
  std::vector<Cells> table{kHeader};
  for (const ReportRow& row : rows) table.push_back(cells(row));
  std::array<size_t, kColumns> widths{};
  for (const Cells& line : table) {
    for (size_t c = 0; c < kColumns; ++c) widths[c] = std::max(widths[c], line[c].size());
  }
  std::string out;
  auto appendLine = [&](const Cells& line) {
    std::string text = fmt::format("{:<{}}", line[0], widths[0]);
    for (size_t c = 1; c < kColumns; ++c) text += fmt::format("  {:>{}}", line[c], widths[c]);
    out += text + '\n';
  };
  appendLine(table[0]);
  size_t ruleWidth = widths[0];
  for (size_t c = 1; c < kColumns; ++c) ruleWidth += 2 + widths[c];
  out += std::string(ruleWidth, '-') + '\n';
  for (size_t r = 1; r < table.size(); ++r) appendLine(table[r]);
  return out;
}

std::string formatMarkdownTable(const std::vector<ReportRow>& rows) {
  auto appendLine = [](std::string& out, const Cells& line) {
    out += "|";
    for (const std::string& cell : line) out += " " + cell + " |";
    out += '\n';
  };
  std::string out;
  appendLine(out, kHeader);
  out += "| --- |";
  for (size_t c = 1; c < kColumns; ++c) out += " ---: |";
  out += '\n';
  for (const ReportRow& row : rows) {
    Cells line = cells(row);
    line[0] = escapeMarkdown(line[0]);
    appendLine(out, line);
  }
  return out;
}

}  // namespace spire::measure
