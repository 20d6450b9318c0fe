// User-written simplification rules (docs/simplify.md, "User rules"):
// the rule files `spire-simplify --rules FILE` reads, one rule a line,
//
//   # comments run to the end of the line
//   rule pow-square: pow($x, 2.0) -> $x * $x
//
// The pattern and the replacement are Spire expressions in which `$name` is
// a metavariable. Both are read by the compiler's own expression parser (a
// metavariable is parsed as the identifier `_name` in its place, and known
// by that place, so no name a shader uses can be taken for one), so a rule
// means what the same text means in a shader. Every problem is an E8001 (or
// the parser's own E2xxx) at the rule's file:line:col.
#pragma once

#include <iosfwd>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "support/diagnostic.h"
#include "support/source_manager.h"
#include "syntax/ast.h"

namespace spire::simplify {

// One `$name` of a replacement: where it is in the replacement's text.
struct MetavariableUse {
  size_t offset = 0;  // of the `$`
  size_t length = 0;  // `$` and the name
  std::string name;
};

struct UserRule {
  std::string name;   // "pow-square", the Rewrite's rule
  SourceRange range;  // the rule's text in its file
  ast::ExprPtr pattern;
  // The pattern's metavariable nodes (each a NameExpr) and their names.
  std::map<const ast::Expr*, std::string> metavariables;
  std::string replacement;             // as written, `$name`s included
  std::vector<MetavariableUse> holes;  // the replacement's `$name`s, in order
};

// The rules of any number of rule files, with their text for diagnostics.
class UserRules {
 public:
  UserRules() = default;
  UserRules(const UserRules&) = delete;
  UserRules& operator=(const UserRules&) = delete;

  // Reads the rules of `text` (the file `path`); false when it has errors,
  // which are in diagnostics() and leave none of that file's rules behind.
  bool add(const std::string& path, std::string text);
  const std::vector<UserRule>& rules() const { return rules_; }
  const SourceManager& sources() const { return sources_; }
  const DiagnosticList& diagnostics() const { return diags_; }

 private:
  struct Line;
  struct Parsed;
  void addLine(const Line& line);
  bool readRuleName(const Line& line, size_t& pos, UserRule& rule);
  bool readExpression(const Line& line, size_t begin, size_t end, Parsed& out);
  bool findMetavariables(const Line& line, Parsed& out);
  bool bindMetavariables(const Line& line, Parsed& out);

  SourceManager sources_;  // the rule files
  SourceManager scratch_;  // each expression as parsed, `$` as `_`
  ast::Program program_;   // hands out the expressions' ids
  DiagnosticList diags_;
  std::vector<UserRule> rules_;
};

// Reads every rule file of a command line (`--rules FILE`, repeatable) into
// `rules`; false after printing why not to `err`, as `tool` (an unreadable
// file, or the rules' diagnostics).
bool readRuleFiles(const std::vector<std::string>& files, UserRules& rules, std::string_view tool, std::ostream& err);

}  // namespace spire::simplify
