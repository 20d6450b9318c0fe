#include "support/diagnostic_renderer.h"

#include <fmt/format.h>

#include <algorithm>
#include <nlohmann/json.hpp>

namespace spire {
namespace {

std::string location(const SourceManager& sources, const SourceRange& range) {
  if (!range.valid()) return "spirec";
  const LineCol lc = sources.begin(range);
  return fmt::format("{}:{}:{}", sources.file(range.file).path, lc.line, lc.column);
}

// A long line (minified or generated code, a line of megabytes) is quoted
// as a window of this many columns around the caret, with "..." where it is
// cut, so that a diagnostic stays readable and its size bounded.
constexpr uint32_t kSnippetColumns = 120;
constexpr uint32_t kColumnsBeforeCaret = 40;
constexpr std::string_view kCut = "...";

// The byte `columns` columns after `pos` in `line`, or the line's end.
size_t columnsAfter(std::string_view line, size_t pos, uint32_t columns) {
  for (; pos < line.size() && columns > 0; --columns) {
    ++pos;
    while (pos < line.size() && !startsColumn(line[pos])) ++pos;
  }
  return pos;
}

// The first byte of the column `columns` columns before `pos`, or 0.
size_t columnsBefore(std::string_view line, size_t pos, uint32_t columns) {
  while (pos > 0 && columns > 0) {
    if (startsColumn(line[--pos])) --columns;
  }
  return pos;
}

// The bytes [begin, end) of a line that are quoted, cut at column starts so
// that no UTF-8 sequence is split.
struct Window {
  size_t begin = 0;
  size_t end = 0;
};

Window windowAround(std::string_view line, size_t caret) {
  if (columnsAfter(line, 0, kSnippetColumns) == line.size()) return {0, line.size()};
  Window window;
  window.begin = columnsBefore(line, caret, kColumnsBeforeCaret);
  window.end = columnsAfter(line, window.begin, kSnippetColumns);
  // Near the end of the line, show its last columns rather than fewer.
  if (window.end == line.size()) window.begin = columnsBefore(line, line.size(), kSnippetColumns);
  return window;
}

size_t columnsIn(std::string_view text) {
  return static_cast<size_t>(std::count_if(text.begin(), text.end(), startsColumn));
}

// The source line (or its window around the caret), then a caret under the
// first character of the range and tildes under the rest of it, clipped to
// the first line and to the window.
void appendSnippet(std::string& out, const SourceManager& sources, const SourceRange& range) {
  if (!range.valid()) return;
  const LineCol begin = sources.begin(range);
  const std::string_view line = sources.lineText(range.file, begin.line);
  const uint32_t lineStart = sources.file(range.file).lineStarts[begin.line - 1];
  const size_t caret = std::min<size_t>(range.begin - lineStart, line.size());
  // A range that goes on past this line is marked to the line's end.
  const size_t rangeEnd = std::clamp<size_t>(range.end - std::min(range.end, lineStart), caret, line.size());
  const Window window = windowAround(line, caret);
  const std::string_view before = window.begin > 0 ? kCut : "";
  const std::string_view after = window.end < line.size() ? kCut : "";
  const std::string gutter = std::to_string(begin.line);
  fmt::format_to(std::back_inserter(out), " {} | {}{}{}\n", gutter, before,
                 line.substr(window.begin, window.end - window.begin), after);

  std::string marker(before.size(), ' ');
  // Keep tabs so the caret lines up however the terminal expands them.
  for (size_t i = window.begin; i < caret; ++i) {
    if (startsColumn(line[i])) marker += line[i] == '\t' ? '\t' : ' ';
  }
  const size_t marked = columnsIn(line.substr(caret, std::min(rangeEnd, window.end) - caret));
  marker += '^';
  marker.append(std::max<size_t>(marked, 1) - 1, '~');
  fmt::format_to(std::back_inserter(out), " {} | {}\n", std::string(gutter.size(), ' '), marker);
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
