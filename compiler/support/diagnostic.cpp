#include "support/diagnostic.h"

#include <array>

namespace spire {
namespace {

constexpr std::array kCodeInfo = {
#define SPIRE_DIAG(code, severity, summary) DiagCodeInfo{#code, Severity::severity, summary},
#include "support/diagnostic_codes.def"
#undef SPIRE_DIAG
};

}  // namespace

const DiagCodeInfo& diagCodeInfo(DiagCode code) { return kCodeInfo[static_cast<size_t>(code)]; }

std::string_view severityName(Severity severity) {
  switch (severity) {
    case Severity::Note: return "note";
    case Severity::Warning: return "warning";
    case Severity::Error: return "error";
  }
  return "error";
}

const std::vector<DiagCode>& allDiagCodes() {
  static const std::vector<DiagCode> codes = [] {
    std::vector<DiagCode> result;
    for (size_t i = 0; i < kCodeInfo.size(); ++i) result.push_back(static_cast<DiagCode>(i));
    return result;
  }();
  return codes;
}

Diagnostic& DiagnosticList::report(DiagCode code, SourceRange range, std::string message) {
  const Severity severity = diagCodeInfo(code).severity;
  if (limitReached_) {
    scratch_ = {};
    return scratch_;
  }
  if (severity == Severity::Error && errorCount_ >= errorLimit_) {
    limitReached_ = true;
    diagnostics_.push_back({Severity::Error,
                            DiagCode::E2005,
                            {},
                            "too many errors emitted (limit " + std::to_string(errorLimit_) + "), stopping now",
                            {}});
    ++errorCount_;
    scratch_ = {};
    return scratch_;
  }
  if (severity == Severity::Error) ++errorCount_;
  if (severity == Severity::Warning) ++warningCount_;
  diagnostics_.push_back({severity, code, range, std::move(message), {}});
  return diagnostics_.back();
}

Diagnostic& DiagnosticList::reportOnce(DiagCode code, SourceRange range, std::string message) {
  for (const Diagnostic& d : diagnostics_) {
    if (d.code == code && d.range == range && d.message == message) {
      scratch_ = {};
      return scratch_;
    }
  }
  return report(code, range, std::move(message));
}

void DiagnosticList::reportAll(std::vector<Diagnostic> diagnostics) {
  for (Diagnostic& d : diagnostics) {
    if (d.code == DiagCode::E2005) continue;  // this list counts toward its own limit
    report(d.code, d.range, std::move(d.message)).notes = std::move(d.notes);
  }
}

std::vector<Diagnostic> DiagnosticList::takeSince(size_t mark) {
  std::vector<Diagnostic> taken(diagnostics_.begin() + static_cast<std::ptrdiff_t>(mark), diagnostics_.end());
  diagnostics_.resize(mark);
  for (const Diagnostic& d : taken) {
    if (d.code == DiagCode::E2005) limitReached_ = false;
    if (d.severity == Severity::Error) --errorCount_;
    if (d.severity == Severity::Warning) --warningCount_;
  }
  return taken;
}

void DiagnosticList::promoteWarnings(std::string_view why) {
  for (Diagnostic& d : diagnostics_) {
    if (d.severity != Severity::Warning) continue;
    d.severity = Severity::Error;
    d.notes.push_back({{}, std::string(why)});
  }
  errorCount_ += warningCount_;
  warningCount_ = 0;
}

}  // namespace spire
