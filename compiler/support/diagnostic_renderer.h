// The one place where diagnostics become text, either for people
// (`file:line:col: error[E3001]: ...` with the source line and a caret) or for
// tools (JSON with the same content).
#pragma once

#include <string>

#include "support/diagnostic.h"
#include "support/source_manager.h"

namespace spire {

enum class DiagnosticFormat { Text, Json };

std::string renderDiagnostic(const SourceManager& sources, const Diagnostic& diagnostic);
std::string renderDiagnostics(const SourceManager& sources, const DiagnosticList& list, DiagnosticFormat format);

}  // namespace spire
