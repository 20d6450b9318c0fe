// Helpers shared by the syntax tests: parse a snippet, render its
// diagnostics compactly, dump one expression.
#pragma once

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "support/diagnostic.h"
#include "support/source_manager.h"
#include "syntax/ast.h"
#include "syntax/ast_printer.h"
#include "syntax/parser.h"

namespace spire::test {

// `E2001 3:14 expected ';' after expression`, one per diagnostic; notes are
// indented below their diagnostic.
inline std::vector<std::string> describe(const SourceManager& sources, const DiagnosticList& diags) {
  const auto where = [&](const SourceRange& range) {
    if (!range.valid()) return std::string("-");
    const LineCol at = sources.begin(range);
    return fmt::format("{}:{}", at.line, at.column);
  };
  std::vector<std::string> lines;
  for (const Diagnostic& d : diags.all()) {
    lines.push_back(fmt::format("{} {} {}", diagCodeInfo(d.code).name, where(d.range), d.message));
    for (const DiagNote& note : d.notes) lines.push_back(fmt::format("  note {} {}", where(note.range), note.message));
  }
  return lines;
}

struct Parsed {
  SourceManager sources;
  DiagnosticList diags{100};
  ast::Program program;
  std::unique_ptr<ast::Module> module;
  FileId file = kNoFile;

  std::vector<std::string> diagnostics() const { return describe(sources, diags); }
  std::string dump() const { return dumpAst(*module); }
  std::string_view text(const SourceRange& range) const { return sources.text(range); }
};

inline std::unique_ptr<Parsed> parse(std::string source, const ParseLimits& limits = {}) {
  auto parsed = std::make_unique<Parsed>();
  parsed->file = parsed->sources.addFile("test.spire", std::move(source));
  parsed->module = parseModule(parsed->sources, parsed->file, parsed->program, parsed->diags, limits);
  return parsed;
}

// Parses `source` and expects no diagnostics at all.
inline std::unique_ptr<Parsed> parseClean(std::string source) {
  auto parsed = parse(std::move(source));
  EXPECT_EQ(parsed->diagnostics(), std::vector<std::string>{}) << "while parsing:\n" << parsed->sources.file(0).text;
  return parsed;
}

// The single statement of `void f() { <statement> }`.
inline const ast::Stmt& onlyStatement(const Parsed& parsed) {
  const auto& function = ast::cast<ast::FunctionDecl>(*parsed.module->decls.at(0));
  return *function.body->statements.at(0);
}

// The dump of `expression` parsed as an expression statement.
inline std::string dumpOf(std::string_view expression) {
  const auto parsed = parseClean(fmt::format("void f() {{ {}; }}", expression));
  if (parsed->module->decls.empty()) return "<no declaration>";
  const auto* stmt = ast::dyn_cast<ast::ExprStmt>(&onlyStatement(*parsed));
  return stmt ? dumpExpr(*stmt->expr) : "<not an expression statement>";
}

}  // namespace spire::test
