// Owns the text of every loaded source file and maps byte offsets to
// line/column positions for diagnostics.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace spire {

using FileId = uint32_t;
inline constexpr FileId kNoFile = ~FileId{0};

// A half-open byte range [begin, end) inside one file. Every token, AST node
// and diagnostic carries one; an empty range marks a point (e.g. end of file).
struct SourceRange {
  FileId file = kNoFile;
  uint32_t begin = 0;
  uint32_t end = 0;

  bool valid() const { return file != kNoFile; }
  // The smallest range covering both; ranges from different files keep `a`.
  static SourceRange cover(const SourceRange& a, const SourceRange& b);
  bool operator==(const SourceRange&) const = default;
};

// 1-based line and column; the column counts Unicode code points, so a caret
// lines up under non-ASCII text.
struct LineCol {
  uint32_t line = 0;
  uint32_t column = 0;
};

struct SourceFile {
  std::string path;  // as given by the user or resolved from an include
  // The name generated code uses for this file (`#line N "name"`): the same
  // whatever the working directory or the spelling of the path, so that
  // kernels and their hashes are too (ModuleLoader decides it; see
  // docs/reflection.md, "#line directives"). Equal to `path` unless set.
  std::string logicalName;
  std::string text;
  std::vector<uint32_t> lineStarts;  // byte offset of each line's first byte
};

// Every byte but a UTF-8 continuation byte starts a column.
inline bool startsColumn(char byte) { return (static_cast<unsigned char>(byte) & 0xC0) != 0x80; }

class SourceManager {
 public:
  // `logicalName` defaults to `path`.
  FileId addFile(std::string path, std::string text, std::string logicalName = {});
  const SourceFile& file(FileId id) const { return *files_[id]; }
  size_t fileCount() const { return files_.size(); }

  LineCol lineCol(FileId id, uint32_t offset) const;
  LineCol begin(const SourceRange& range) const { return lineCol(range.file, range.begin); }
  LineCol end(const SourceRange& range) const { return lineCol(range.file, range.end); }
  // The text of a 1-based line without its line terminator (LF or CRLF).
  std::string_view lineText(FileId id, uint32_t line) const;
  std::string_view text(const SourceRange& range) const;

 private:
  // unique_ptr keeps SourceFile addresses stable while files are added.
  std::vector<std::unique_ptr<SourceFile>> files_;
};

}  // namespace spire
