// Recursive-descent parser for one Spire source file.
#pragma once

#include <memory>

#include "support/diagnostic.h"
#include "support/source_manager.h"
#include "syntax/ast.h"

namespace spire {

struct ParseLimits {
  // Deeper nesting of expressions, statements or blocks is reported (E2004)
  // instead of exhausting the stack.
  uint32_t maxNesting = 200;
};

// Parses `file` into a module. Never fails: syntax errors are reported to
// `diags` and the parser recovers at `;` and `}`, so the module holds every
// declaration it could make sense of. Expression ids come from `program`.
std::unique_ptr<ast::Module> parseModule(const SourceManager& sources, FileId file, ast::Program& program,
                                         DiagnosticList& diags, const ParseLimits& limits = {});

// Parses the whole of `file` as one expression, for tools whose inputs hold
// Spire expressions (spire-simplify's rule files) and must read them as the
// compiler does. Null after an error was reported, also when tokens follow
// the expression.
ast::ExprPtr parseStandaloneExpression(const SourceManager& sources, FileId file, ast::Program& program,
                                       DiagnosticList& diags, const ParseLimits& limits = {});

}  // namespace spire
