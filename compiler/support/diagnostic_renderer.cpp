#include "support/diagnostic_renderer.h"

#include <fmt/format.h>

#include <algorithm>
#include <nlohmann/json.hpp>

namespace spire {
namespace {

// Number of code points in a byte span, matching SourceManager columns.
uint32_t codePoints(std::string_view text) {
  uint32_t count = 0;
  for (char c : text) {
    if ((static_cast<unsigned char>(c) & 0xC0) != 0x80) ++count;
  }
  return count;
}

std::string location(const SourceManager& sources, const SourceRange& range) {
  if (!range.valid()) return "spirec";
  const LineCol lc = sources.begin(range);
  return fmt::format("{}:{}:{}", sources.file(range.file).path, lc.line, lc.column);
}

// The source line, then a caret under the first character of the range and
// tildes under the rest of it (clipped to the first line).
void appendSnippet(std::string& out, const SourceManager& sources, const SourceRange& range) {
  if (!range.valid()) return;
  const LineCol begin = sources.begin(range);
  const LineCol end = sources.end(range);
  const std::string_view line = sources.lineText(range.file, begin.line);
  const std::string gutter = std::to_string(begin.line);
  const std::string pad(gutter.size(), ' ');
  fmt::format_to(std::back_inserter(out), " {} | {}\n", gutter, line);

  std::string marker;
  uint32_t column = 1;
  // Keep tabs so the caret lines up however the terminal expands them.
  for (size_t i = 0; i < line.size() && column < begin.column; ++i) {
    const auto c = static_cast<unsigned char>(line[i]);
    if ((c & 0xC0) == 0x80) continue;
    marker += c == '\t' ? '\t' : ' ';
    ++column;
  }
  const uint32_t lineWidth = codePoints(line);
  uint32_t width = 1;
  if (end.line == begin.line && end.column > begin.column) width = end.column - begin.column;
  else if (end.line > begin.line && lineWidth >= begin.column) width = lineWidth - begin.column + 1;
  marker += '^';
  marker.append(width - 1, '~');
  fmt::format_to(std::back_inserter(out), " {} | {}\n", pad, marker);
}

}  // namespace

std::string renderDiagnostic(const SourceManager& sources, const Diagnostic& d) {
  std::string out;
  const DiagCodeInfo& info = diagCodeInfo(d.code);
  fmt::format_to(std::back_inserter(out), "{}: {}[{}]: {}\n", location(sources, d.range), severityName(d.severity),
                 info.name, d.message);
  appendSnippet(out, sources, d.range);
  for (const DiagNote& note : d.notes) {
    // A note without a location (a built-in candidate, a list of names)
    // reads as part of the diagnostic above it.
    if (!note.range.valid()) {
      fmt::format_to(std::back_inserter(out), "note: {}\n", note.message);
      continue;
    }
    fmt::format_to(std::back_inserter(out), "{}: note: {}\n", location(sources, note.range), note.message);
    appendSnippet(out, sources, note.range);
  }
  return out;
}

std::string renderDiagnostics(const SourceManager& sources, const DiagnosticList& list, DiagnosticFormat format) {
  if (format == DiagnosticFormat::Text) {
    std::string out;
    for (const Diagnostic& d : list.all()) out += renderDiagnostic(sources, d);
    if (list.errorCount() > 0 || list.warningCount() > 0) {
      auto plural = [](uint32_t n, std::string_view word) {
        return fmt::format("{} {}{}", n, word, n == 1 ? "" : "s");
      };
      if (list.errorCount() > 0 && list.warningCount() > 0) {
        out += plural(list.warningCount(), "warning") + " and " + plural(list.errorCount(), "error") + " generated.\n";
      } else if (list.errorCount() > 0) {
        out += plural(list.errorCount(), "error") + " generated.\n";
      } else {
        out += plural(list.warningCount(), "warning") + " generated.\n";
      }
    }
    return out;
  }

  auto rangeJson = [&](const SourceRange& range) {
    nlohmann::ordered_json j;
    if (!range.valid()) return nlohmann::ordered_json(nullptr);
    const LineCol b = sources.begin(range);
    const LineCol e = sources.end(range);
    j["file"] = sources.file(range.file).path;
    j["line"] = b.line;
    j["column"] = b.column;
    j["endLine"] = e.line;
    j["endColumn"] = e.column;
    return j;
  };
  nlohmann::ordered_json array = nlohmann::ordered_json::array();
  for (const Diagnostic& d : list.all()) {
    nlohmann::ordered_json j;
    j["severity"] = severityName(d.severity);
    j["code"] = diagCodeInfo(d.code).name;
    j["message"] = d.message;
    j["range"] = rangeJson(d.range);
    j["notes"] = nlohmann::ordered_json::array();
    for (const DiagNote& note : d.notes) {
      j["notes"].push_back({{"message", note.message}, {"range", rangeJson(note.range)}});
    }
    array.push_back(std::move(j));
  }
  nlohmann::ordered_json root;
  root["diagnostics"] = std::move(array);
  root["errorCount"] = list.errorCount();
  root["warningCount"] = list.warningCount();
  // Replace invalid UTF-8 from hostile sources rather than throwing.
  return root.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) + "\n";
}

}  // namespace spire
