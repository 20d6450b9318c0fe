#include "simplify/user_rules.h"

#include <fmt/format.h>

#include <algorithm>
#include <functional>
#include <ostream>
#include <set>

#include "support/diagnostic_renderer.h"
#include "support/file_io.h"
#include "syntax/parser.h"

namespace spire::simplify {
namespace {

bool isNameStart(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; }
bool isNameChar(char c) { return isNameStart(c) || (c >= '0' && c <= '9'); }
bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r'; }

size_t skipSpace(std::string_view text, size_t pos, size_t end) {
  while (pos < end && isSpace(text[pos])) ++pos;
  return pos;
}

size_t trimEnd(std::string_view text, size_t begin, size_t end) {
  while (end > begin && isSpace(text[end - 1])) --end;
  return end;
}

// Calls `f` on `e` and every expression below it. Patterns and replacements
// are a line long, so plain recursion is enough here.
void forEachExpr(const ast::Expr& e, const std::function<void(const ast::Expr&)>& f) {
  f(e);
  const auto each = [&](const ast::ExprPtr& child) {
    if (child) forEachExpr(*child, f);
  };
  switch (e.kind) {
    case ast::ExprKind::Unary: each(ast::cast<ast::UnaryExpr>(e).operand); break;
    case ast::ExprKind::Binary:
      each(ast::cast<ast::BinaryExpr>(e).lhs);
      each(ast::cast<ast::BinaryExpr>(e).rhs);
      break;
    case ast::ExprKind::Assign:
      each(ast::cast<ast::AssignExpr>(e).target);
      each(ast::cast<ast::AssignExpr>(e).value);
      break;
    case ast::ExprKind::Ternary:
      each(ast::cast<ast::TernaryExpr>(e).condition);
      each(ast::cast<ast::TernaryExpr>(e).thenValue);
      each(ast::cast<ast::TernaryExpr>(e).elseValue);
      break;
    case ast::ExprKind::Call:
      for (const ast::ExprPtr& arg : ast::cast<ast::CallExpr>(e).args) each(arg);
      break;
    case ast::ExprKind::Member: each(ast::cast<ast::MemberExpr>(e).object); break;
    case ast::ExprKind::Index:
      each(ast::cast<ast::IndexExpr>(e).object);
      each(ast::cast<ast::IndexExpr>(e).index);
      break;
    default: break;
  }
}

}  // namespace

// One line of a rule file: [begin, end) is its text before any comment.
struct UserRules::Line {
  FileId file;
  std::string_view text;  // the whole file
  size_t begin;
  size_t end;
};

bool UserRules::add(const std::string& path, std::string text) {
  const FileId file = sources_.addFile(path, std::move(text));
  const std::string_view all = sources_.file(file).text;
  const size_t rulesBefore = rules_.size();
  const uint32_t errorsBefore = diags_.errorCount();
  for (size_t begin = 0; begin < all.size() && !diags_.limitReached();) {
    const size_t newline = std::min(all.find('\n', begin), all.size());
    // `#` is no Spire operator, so wherever it is it starts a comment.
    const size_t end = std::min(all.find('#', begin), newline);
    addLine({file, all, begin, end});
    begin = newline + 1;
  }
  if (diags_.errorCount() == errorsBefore) return true;
  rules_.erase(rules_.begin() + static_cast<std::ptrdiff_t>(rulesBefore), rules_.end());
  return false;
}

// An expression of a rule: [begin, end) in the rule file, trimmed.
struct UserRules::Parsed {
  size_t begin = 0;
  size_t end = 0;
  ast::ExprPtr expr;
  std::vector<MetavariableUse> uses;                      // file offsets
  std::map<const ast::Expr*, std::string> metavariables;  // the uses' nodes
};

// rule-line = "rule" name ":" pattern "->" replacement ;
void UserRules::addLine(const Line& line) {
  size_t pos = skipSpace(line.text, line.begin, line.end);
  if (pos == line.end) return;
  UserRule rule;
  rule.range = {line.file, static_cast<uint32_t>(pos), static_cast<uint32_t>(trimEnd(line.text, pos, line.end))};
  if (!readRuleName(line, pos, rule)) return;
  const size_t arrow = line.text.substr(0, line.end).find("->", pos);
  if (arrow == std::string_view::npos) {
    diags_.report(DiagCode::E8001, {line.file, rule.range.end, rule.range.end},
                  "expected '->' between the pattern and its replacement");
    return;
  }
  Parsed pattern;
  Parsed replacement;
  if (!readExpression(line, pos, arrow, pattern)) return;
  if (pattern.metavariables.count(pattern.expr.get()) > 0) {
    diags_.report(DiagCode::E8001,
                  {line.file, static_cast<uint32_t>(pattern.begin), static_cast<uint32_t>(pattern.end)},
                  "a pattern that is only a metavariable would match every expression");
    return;
  }
  if (!readExpression(line, arrow + 2, line.end, replacement)) return;
  for (MetavariableUse& hole : replacement.uses) {
    const bool bound = std::any_of(pattern.uses.begin(), pattern.uses.end(),
                                   [&](const MetavariableUse& use) { return use.name == hole.name; });
    if (!bound) {
      const auto at = static_cast<uint32_t>(hole.offset);
      diags_.report(DiagCode::E8001, {line.file, at, static_cast<uint32_t>(at + hole.length)},
                    fmt::format("'${}' is not a metavariable of the pattern", hole.name));
      return;
    }
    hole.offset -= replacement.begin;
  }
  rule.pattern = std::move(pattern.expr);
  rule.metavariables = std::move(pattern.metavariables);
  rule.replacement = std::string(line.text.substr(replacement.begin, replacement.end - replacement.begin));
  rule.holes = std::move(replacement.uses);
  rules_.push_back(std::move(rule));
}

// "rule" name ":", where a name is letters, digits, '_' and '-'.
bool UserRules::readRuleName(const Line& line, size_t& pos, UserRule& rule) {
  const std::string_view text = line.text;
  const auto here = [&](size_t at) {
    return SourceRange{line.file, static_cast<uint32_t>(at), static_cast<uint32_t>(at)};
  };
  if (text.substr(pos, 4) != "rule" || (pos + 4 < line.end && !isSpace(text[pos + 4]))) {
    diags_.report(DiagCode::E8001, here(pos), "expected 'rule NAME: PATTERN -> REPLACEMENT'");
    return false;
  }
  pos = skipSpace(text, pos + 4, line.end);
  const size_t nameBegin = pos;
  while (pos < line.end && (isNameChar(text[pos]) || text[pos] == '-')) ++pos;
  if (pos == nameBegin || !isNameStart(text[nameBegin])) {
    diags_.report(DiagCode::E8001, here(nameBegin),
                  "expected a rule name (a letter or '_', then letters, digits, '_' and '-')");
    return false;
  }
  rule.name = std::string(text.substr(nameBegin, pos - nameBegin));
  const SourceRange nameRange{line.file, static_cast<uint32_t>(nameBegin), static_cast<uint32_t>(pos)};
  for (const UserRule& other : rules_) {
    if (other.name != rule.name) continue;
    diags_.report(DiagCode::E8001, nameRange, fmt::format("a rule named '{}' is already defined", rule.name))
        .note(other.range, "previous definition is here");
    return false;
  }
  pos = skipSpace(text, pos, line.end);
  if (pos >= line.end || text[pos] != ':') {
    diags_.report(DiagCode::E8001, here(pos), "expected ':' after the rule name");
    return false;
  }
  pos = pos + 1;
  return true;
}

// Parses [begin, end) with the compiler's parser. Its diagnostics, made on
// a copy of the text, land at the same offsets of the rule file.
bool UserRules::readExpression(const Line& line, size_t begin, size_t end, Parsed& out) {
  out.begin = skipSpace(line.text, begin, end);
  out.end = trimEnd(line.text, out.begin, end);
  if (!findMetavariables(line, out)) return false;
  std::string text(line.text.substr(out.begin, out.end - out.begin));
  for (const MetavariableUse& use : out.uses) text[use.offset - out.begin] = '_';
  const FileId copy = scratch_.addFile(sources_.file(line.file).path, std::move(text));
  DiagnosticList diags;
  out.expr = parseStandaloneExpression(scratch_, copy, program_, diags);
  const auto moved = [&](SourceRange r) {
    return r.valid() ? SourceRange{line.file, static_cast<uint32_t>(r.begin + out.begin),
                                   static_cast<uint32_t>(r.end + out.begin)}
                     : r;
  };
  for (const Diagnostic& d : diags.all()) {
    Diagnostic& reported = diags_.report(d.code, moved(d.range), d.message);
    for (const DiagNote& note : d.notes) reported.note(moved(note.range), note.message);
  }
  return out.expr && !diags.hasErrors() && bindMetavariables(line, out);
}

// Every `$name` of [out.begin, out.end): a '$' that starts a name.
bool UserRules::findMetavariables(const Line& line, Parsed& out) {
  const std::string_view text = line.text;
  for (size_t pos = out.begin; pos < out.end; ++pos) {
    if (text[pos] != '$') continue;
    size_t nameEnd = pos + 1;
    while (nameEnd < out.end && isNameChar(text[nameEnd])) ++nameEnd;
    const bool glued = pos > out.begin && isNameChar(text[pos - 1]);
    if (nameEnd == pos + 1 || !isNameStart(text[pos + 1]) || glued) {
      diags_.report(DiagCode::E8001, {line.file, static_cast<uint32_t>(pos), static_cast<uint32_t>(nameEnd)},
                    glued ? "a metavariable cannot continue a name: write a space or an operator before '$'"
                          : "expected a metavariable name after '$' (a letter or '_', then letters, digits and '_')");
      return false;
    }
    out.uses.push_back({pos, nameEnd - pos, std::string(text.substr(pos + 1, nameEnd - pos - 1))});
  }
  return true;
}

// The names the parser made of the uses; a use that became anything else
// (a callee, a member, a type) is not an expression and cannot be bound.
bool UserRules::bindMetavariables(const Line& line, Parsed& out) {
  std::set<size_t> seen;
  forEachExpr(*out.expr, [&](const ast::Expr& e) {
    if (e.kind != ast::ExprKind::Name) return;
    const size_t at = e.range.begin + out.begin;
    for (const MetavariableUse& use : out.uses) {
      if (use.offset != at || use.length != e.range.end - e.range.begin) continue;
      out.metavariables.emplace(&e, use.name);
      seen.insert(at);
    }
  });
  for (const MetavariableUse& use : out.uses) {
    if (seen.count(use.offset) > 0) continue;
    diags_.report(
        DiagCode::E8001, {line.file, static_cast<uint32_t>(use.offset), static_cast<uint32_t>(use.offset + use.length)},
        fmt::format("'${}' must stand for an expression here, not for a function, type or member name", use.name));
    return false;
  }
  return true;
}

bool readRuleFiles(const std::vector<std::string>& files, UserRules& rules, std::string_view tool, std::ostream& err) {
  for (const std::string& file : files) {
    auto text = readFileBytes(file);
    if (!text) {
      err << fmt::format("{}: error: cannot read rule file '{}': {}\n", tool, file, text.error().message());
      return false;
    }
    rules.add(file, std::move(*text));
  }
  if (!rules.diagnostics().hasErrors()) return true;
  err << renderDiagnostics(rules.sources(), rules.diagnostics(), DiagnosticFormat::Text);
  return false;
}

}  // namespace spire::simplify
