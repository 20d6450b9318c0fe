// Printing problems of a scene run the way the compiler prints its own:
// diagnostics with file:line:col, the line and a caret, then engine errors
// (at their scene-file range when they have one) with their details. Shared
// by spire-demo and spire-tune.
#pragma once

#include <ostream>

#include "driver/exit_codes.h"
#include "renderer/error.h"
#include "support/diagnostic.h"
#include "support/source_manager.h"

namespace spire::vk {
class Context;
}

namespace spire::engine {

// Prints the Vulkan validation messages of a run; any message makes the run
// fail (kExitInputError), whatever `status` it had otherwise.
int reportValidation(const vk::Context& ctx, int status, std::ostream& err);

class ErrorReporter {
 public:
  ErrorReporter(const SourceManager& sources, const DiagnosticList& diags, std::ostream& err, std::string tool)
      : sources_(sources), diags_(diags), err_(err), tool_(std::move(tool)) {}

  // Prints the diagnostics reported since the last flush.
  void flush();
  // Prints `error` after any pending diagnostics; returns exit status 1.
  int fail(const Error& error);

 private:
  const SourceManager& sources_;
  const DiagnosticList& diags_;
  std::ostream& err_;
  std::string tool_;
  size_t printed_ = 0;
};

}  // namespace spire::engine
