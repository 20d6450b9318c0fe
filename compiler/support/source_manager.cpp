#include "support/source_manager.h"

#include <algorithm>

namespace spire {

SourceRange SourceRange::cover(const SourceRange& a, const SourceRange& b) {
  if (!a.valid()) return b;
  if (!b.valid() || a.file != b.file) return a;
  return {a.file, std::min(a.begin, b.begin), std::max(a.end, b.end)};
}

FileId SourceManager::addFile(std::string path, std::string text, std::string logicalName) {
  auto file = std::make_unique<SourceFile>();
  file->logicalName = logicalName.empty() ? path : std::move(logicalName);
  file->path = std::move(path);
  file->text = std::move(text);
  file->lineStarts.push_back(0);
  for (uint32_t i = 0; i < file->text.size(); ++i) {
    if (file->text[i] == '\n') file->lineStarts.push_back(i + 1);
  }
  files_.push_back(std::move(file));
  return static_cast<FileId>(files_.size() - 1);
}

LineCol SourceManager::lineCol(FileId id, uint32_t offset) const {
  const SourceFile& f = file(id);
  offset = std::min<uint32_t>(offset, static_cast<uint32_t>(f.text.size()));
  auto it = std::upper_bound(f.lineStarts.begin(), f.lineStarts.end(), offset);
  const auto line = static_cast<uint32_t>(it - f.lineStarts.begin());
  const uint32_t lineStart = f.lineStarts[line - 1];
  uint32_t column = 1;
  for (uint32_t i = lineStart; i < offset; ++i) column += startsColumn(f.text[i]) ? 1 : 0;
  return {line, column};
}

std::string_view SourceManager::lineText(FileId id, uint32_t line) const {
  const SourceFile& f = file(id);
  if (line == 0 || line > f.lineStarts.size()) return {};
  const uint32_t begin = f.lineStarts[line - 1];
  uint32_t end = line < f.lineStarts.size() ? f.lineStarts[line] : static_cast<uint32_t>(f.text.size());
  while (end > begin && (f.text[end - 1] == '\n' || f.text[end - 1] == '\r')) --end;
  return std::string_view(f.text).substr(begin, end - begin);
}

std::string_view SourceManager::text(const SourceRange& range) const {
  if (!range.valid()) return {};
  const std::string& t = file(range.file).text;
  const uint32_t begin = std::min<uint32_t>(range.begin, static_cast<uint32_t>(t.size()));
  const uint32_t end = std::clamp<uint32_t>(range.end, begin, static_cast<uint32_t>(t.size()));
  return std::string_view(t).substr(begin, end - begin);
}

}  // namespace spire
