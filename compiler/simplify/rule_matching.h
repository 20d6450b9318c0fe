// How a user rule (user_rules.h) rewrites an expression of a shader: its
// pattern matches the typed syntax tree, never the text.
//   - A metavariable binds any expression; each further use of it must bind
//     an expression of the same tree (same operators, names and literal
//     values; parentheses, layout and comments do not count).
//   - A literal matches a literal of the same kind and value however written:
//     `2.0` matches `2.0`, `2.`, `2e0` and `2.0f`, not `2`; `2` matches `2`
//     and `0x2`, not `2u`.
//   - A name matches the same name, a call a call of the same name with as
//     many arguments, an operator the same operator.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "simplify/user_rules.h"
#include "support/source_manager.h"
#include "syntax/ast.h"

namespace spire::simplify {

struct UserRuleMatch {
  std::string replacement;
  std::vector<const ast::Expr*> holes;  // the expression each `$name` of the replacement bound, in order
};

// What `e` becomes when `rule` matches it: the rule's replacement with each
// metavariable replaced by the source it bound (`sources` holds `e`'s file),
// each of those parenthesized and the whole too, so that precedence around
// and within it stays what the rule's author wrote.
std::optional<UserRuleMatch> applyUserRule(const UserRule& rule, const ast::Expr& e, const SourceManager& sources);

}  // namespace spire::simplify
