#include "renderer/error_report.h"

#include <fmt/format.h>

#include "support/diagnostic_renderer.h"

namespace spire::engine {

void ErrorReporter::flush() {
  for (size_t i = printed_; i < diags_.all().size(); ++i) err_ << renderDiagnostic(sources_, diags_.all()[i]);
  printed_ = diags_.all().size();
}

int ErrorReporter::fail(const Error& error) {
  flush();
  if (error.range.valid()) {
    err_ << renderDiagnostic(sources_, Diagnostic{Severity::Error, DiagCode::E7105, error.range, error.message, {}});
  } else {
    err_ << fmt::format("{}: error: {}\n", tool_, error.message);
  }
  err_ << error.details;
  return 1;
}

}  // namespace spire::engine
