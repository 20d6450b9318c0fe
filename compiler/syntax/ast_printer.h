// Turns syntax trees back into text: Spire source (printModule) and a
// structural dump for tests (dumpAst).
#pragma once

#include <string>

#include "syntax/ast.h"

namespace spire {

// Spire source that parses back to the same tree: same declarations in the
// same order, with parentheses only where precedence needs them. Comments
// and layout are not kept; a pipeline prints its worlds, then its imports,
// then its components.
std::string printModule(const ast::Module& module);
std::string printExpr(const ast::Expr& expr);

// A deterministic S-expression dump of every field except source ranges and
// expression ids, one declaration or statement per line, so that two trees
// are equal exactly when their dumps are.
std::string dumpAst(const ast::Module& module);
// One expression on a single line, e.g. `(binary + (name a) (name b))`.
std::string dumpExpr(const ast::Expr& expr);

}  // namespace spire
