// Diagnostics are plain data: collected in a DiagnosticList by every stage and
// rendered in exactly one place (diagnostic_renderer.h).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "support/source_manager.h"

namespace spire {

enum class Severity : uint8_t { Note, Warning, Error };

enum class DiagCode : uint16_t {
#define SPIRE_DIAG(code, severity, summary) code,
#include "support/diagnostic_codes.def"
#undef SPIRE_DIAG
};

struct DiagCodeInfo {
  std::string_view name;  // "E3001"
  Severity severity;
  std::string_view summary;
};

const DiagCodeInfo& diagCodeInfo(DiagCode code);
std::string_view severityName(Severity severity);
// Every code in catalogue order, for documentation and tests.
const std::vector<DiagCode>& allDiagCodes();

struct DiagNote {
  SourceRange range;  // may be invalid for a note without a location
  std::string message;
};

struct Diagnostic {
  Severity severity = Severity::Error;
  DiagCode code{};
  SourceRange range;
  std::string message;
  std::vector<DiagNote> notes;

  Diagnostic& note(SourceRange where, std::string text) {
    notes.push_back({where, std::move(text)});
    return *this;
  }
};

// Collects diagnostics. After `errorLimit` errors, further errors are dropped
// and one E2005 is recorded so that a pathological input cannot produce
// unbounded output; `limitReached()` lets stages stop early.
class DiagnosticList {
 public:
  explicit DiagnosticList(uint32_t errorLimit = 20) : errorLimit_(errorLimit) {}

  // Severity comes from the catalogue. Returns a diagnostic that may be
  // extended with notes; when the limit is reached it is a discarded scratch.
  Diagnostic& report(DiagCode code, SourceRange range, std::string message);

  // As report(), unless an identical diagnostic (code, range, message) was
  // already reported: checks repeated per derived shader report once.
  Diagnostic& reportOnce(DiagCode code, SourceRange range, std::string message);

  // Reports each of `diagnostics` (collected in another list, by a thread
  // that could not report into this one) as report() would, notes kept.
  void reportAll(std::vector<Diagnostic> diagnostics);

  const std::vector<Diagnostic>& all() const { return diagnostics_; }
  uint32_t errorCount() const { return errorCount_; }
  uint32_t warningCount() const { return warningCount_; }
  bool hasErrors() const { return errorCount_ > 0; }
  bool limitReached() const { return limitReached_; }
  void setErrorLimit(uint32_t limit) { errorLimit_ = limit; }

  // Removes and returns what was reported since `size()` was `mark`, for a
  // speculative step whose failure is reported differently (an optional
  // group member that does not fit becomes one warning).
  std::vector<Diagnostic> takeSince(size_t mark);
  size_t size() const { return diagnostics_.size(); }

  // Turns every warning reported so far into an error noted with `why`, for
  // a run that treats warnings as errors: it fails, and its output says why.
  void promoteWarnings(std::string_view why);

 private:
  std::vector<Diagnostic> diagnostics_;
  Diagnostic scratch_;
  uint32_t errorLimit_;
  uint32_t errorCount_ = 0;
  uint32_t warningCount_ = 0;
  bool limitReached_ = false;
};

}  // namespace spire
