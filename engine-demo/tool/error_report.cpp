#include "tool/error_report.h"

#include <fmt/format.h>

#include "support/diagnostic_renderer.h"
#include "vk/context.h"

namespace spire::engine {

void ErrorReporter::flush() {
  for (size_t i = printed_; i < diags_.all().size(); ++i) err_ << renderDiagnostic(sources_, diags_.all()[i]);
  printed_ = diags_.all().size();
}

int reportValidation(const vk::Context& ctx, int status, std::ostream& err) {
  const std::vector<std::string> messages = ctx.validationMessages();
  for (const std::string& message : messages) err << "validation: " << message << "\n";
  return messages.empty() ? status : kExitInputError;
}

int ErrorReporter::fail(const Error& error) {
  flush();
  if (error.range.valid()) {
    err_ << renderDiagnostic(sources_, Diagnostic{Severity::Error, DiagCode::E7105, error.range, error.message, {}});
  } else {
    err_ << fmt::format("{}: error: {}\n", tool_, error.message);
  }
  err_ << error.details;
  return kExitInputError;
}

}  // namespace spire::engine
