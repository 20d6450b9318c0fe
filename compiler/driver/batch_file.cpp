#include "driver/batch_file.h"

#include <fmt/format.h>

#include <optional>
#include <string_view>

namespace spire {
namespace {

bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

// Splits one line as documented in docs/integration.md; nullopt after
// reporting E1105. `at` is the line's offset in the file.
class LineSplitter {
 public:
  LineSplitter(std::string_view line, uint32_t at, FileId file, DiagnosticList& diags)
      : line_(line), at_(at), file_(file), diags_(diags) {}

  std::optional<std::vector<std::string>> split() {
    std::vector<std::string> words;
    while (true) {
      while (i_ < line_.size() && isBlank(line_[i_])) ++i_;
      if (i_ == line_.size() || line_[i_] == '#') return words;
      std::string word;
      if (!readWord(word)) return std::nullopt;
      words.push_back(std::move(word));
    }
  }

 private:
  // Reads up to the next blank outside quotes; quoted and unquoted parts of
  // one word join, as in a shell (`-o"out dir"`).
  bool readWord(std::string& word) {
    while (i_ < line_.size() && !isBlank(line_[i_])) {
      const char c = line_[i_];
      if (c == '"' || c == '\'') {
        if (!readQuoted(word, c)) return false;
      } else if (c == '\\') {
        if (i_ + 1 == line_.size()) return fail(i_, "a backslash at the end of a line escapes nothing");
        word += line_[i_ + 1];
        i_ += 2;
      } else {
        word += c;
        ++i_;
      }
    }
    return true;
  }

  // Single quotes keep every character; double quotes let `\"` and `\\`
  // stand for themselves, and keep any other backslash so that Windows-style
  // paths survive quoting.
  bool readQuoted(std::string& word, char quote) {
    const size_t open = i_++;
    while (i_ < line_.size() && line_[i_] != quote) {
      const bool escape =
          quote == '"' && line_[i_] == '\\' && i_ + 1 < line_.size() && (line_[i_ + 1] == '"' || line_[i_ + 1] == '\\');
      if (escape) ++i_;
      word += line_[i_++];
    }
    if (i_ == line_.size()) return fail(open, fmt::format("unterminated {} quote", quote == '"' ? "double" : "single"));
    ++i_;
    return true;
  }

  bool fail(size_t offset, std::string message) {
    const uint32_t begin = at_ + static_cast<uint32_t>(offset);
    diags_.report(DiagCode::E1105, {file_, begin, begin + 1}, std::move(message));
    return false;
  }

  std::string_view line_;
  uint32_t at_;
  FileId file_;
  DiagnosticList& diags_;
  size_t i_ = 0;
};

}  // namespace

std::vector<BatchJob> parseBatchFile(const SourceManager& sources, FileId file, DiagnosticList& diags) {
  const SourceFile& source = sources.file(file);
  std::vector<BatchJob> jobs;
  for (size_t i = 0; i < source.lineStarts.size(); ++i) {
    const uint32_t line = static_cast<uint32_t>(i + 1);
    LineSplitter splitter(sources.lineText(file, line), source.lineStarts[i], file, diags);
    if (auto words = splitter.split(); words && !words->empty()) jobs.push_back({line, std::move(*words)});
  }
  return jobs;
}

}  // namespace spire
