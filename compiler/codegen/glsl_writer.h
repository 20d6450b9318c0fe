// Writes Spire function and component code as GLSL, using the semantic
// model to resolve every name: components become the kernel's globals,
// locals and parameters keep their names unless GLSL reserves them.
#pragma once

#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "codegen/glsl_names.h"
#include "codegen/operation_probe.h"
#include "sema/semantic_model.h"
#include "support/source_manager.h"
#include "syntax/ast.h"
#include "syntax/ast_spelling.h"

namespace spire::codegen {

// Kernel text with `#line` bookkeeping: user code is mapped back to its
// .spire file and line, generated code to the kernel file itself, so
// glslang's messages point at the right place.
class GlslOutput {
 public:
  explicit GlslOutput(std::string kernelFile) : kernelFile_(std::move(kernelFile)) {}

  void line(std::string_view text);
  // The next line comes from `file`:`sourceLine`.
  void mapTo(const std::string& file, uint32_t sourceLine);
  // The next line is generated code.
  void mapToKernel();
  const std::string& text() const { return text_; }

 private:
  std::string kernelFile_;
  std::string text_;
  uint32_t physicalLine_ = 1;  // line number of the next line written
  std::string mappedFile_;     // empty: mapped to the kernel file itself
  uint32_t mappedLine_ = 1;    // what glslang calls the next line
};

struct GlslNameMaps {
  // Component source name -> the kernel global holding it.
  std::function<std::string(std::string_view)> component;
  std::map<const sem::Function*, std::string> functions;
  const std::map<std::string, std::string, std::less<>>* structs = nullptr;
};

class GlslWriter {
 public:
  GlslWriter(const sem::Model& model, const SourceManager& sources, GlslNameMaps names, const NameTable& table)
      : model_(model), sources_(sources), names_(std::move(names)), table_(table) {}

  std::string expr(const ast::Expr& e, ast::Precedence minPrecedence = ast::Precedence::Comma);
  // `e` as the whole expression of a statement about to be written. When it
  // writes nothing (see hasSideEffects), each operator chain longer than
  // kChainSegment operands is computed in temporaries whose declarations are
  // appended to `before`, to be written ahead of the statement: glslang
  // recurses along a chain and overflows the stack on generated shaders with
  // tens of thousands of terms. The evaluation order is kept exactly.
  std::string statementExpr(const ast::Expr& e, std::vector<std::string>& before,
                            ast::Precedence minPrecedence = ast::Precedence::Comma);
  // Why the text written so far may not compile: a chain too long to be
  // written inline where no temporary can take it (a loop condition, or an
  // expression with side effects). Empty when there is nothing to report.
  struct Problem {
    SourceRange range;
    std::string message;
  };
  const std::optional<Problem>& problem() const { return problem_; }
  // Writes what statementExpr hoisted, each line mapped to `range` so that
  // the statement after them keeps its source line.
  void writeHoisted(GlslOutput& out, const std::string& pad, const std::vector<std::string>& before,
                    const SourceRange& range);

  static constexpr size_t kChainSegment = 64;
  static constexpr size_t kMaxInlineChain = 4096;
  // A block's statements at `indent` levels (4 spaces each), with #line.
  void block(GlslOutput& out, const ast::BlockStmt& block, int indent);
  void stmt(GlslOutput& out, const ast::Stmt& s, int indent);
  // A user function's definition.
  void function(GlslOutput& out, const sem::Function& f, const std::string& name);
  std::string typeName(const sem::Type* type) const;
  std::string declare(const sem::Type* type, const std::string& name) const;
  // From now on, every operation isCheckedOperation accepts is written
  // wrapped in `probe`'s check (instrumented kernels only).
  void probeOperations(OperationProbe* probe) { probe_ = probe; }

 private:
  // A loop or branch body: a block's statements, or one statement.
  void body(GlslOutput& out, const ast::Stmt& s, int indent);
  std::string localName(const void* decl, std::string_view source);
  std::string localDeclaration(const ast::VarDeclStmt& d);
  std::string forInit(const ast::Stmt& s);
  void mapLine(GlslOutput& out, const SourceRange& range);
  std::string binary(const ast::BinaryExpr& e, ast::Precedence minPrecedence);
  std::string chainText(const std::vector<const ast::BinaryExpr*>& spine, size_t begin, size_t end,
                        const std::string& head, ast::Precedence context);
  std::string temporaryName();
  // A chain written with every operator parenthesized, so that each checked
  // operation's value is an expression of its own.
  std::string probedChainText(const std::vector<const ast::BinaryExpr*>& spine, size_t begin, size_t end,
                              const std::string& head);
  // `text`, which computes `e`, wrapped in the probe's check when it has one
  // and `e` is an operation it checks.
  std::string probed(const ast::Expr& e, std::string text);
  // `e` where it is evaluated only under a condition (a branch of `?:`, the
  // right of `&&`, `||` or `^^`): never hoisted, since that would evaluate it
  // unconditionally.
  std::string conditionalExpr(const ast::Expr& e, ast::Precedence minPrecedence);
  // Runs `write` with hoisted temporaries going to `target` (nullptr: none
  // may be hoisted), then restores where they went before.
  std::string hoistingInto(std::vector<std::string>* target, const std::function<std::string()>& write);
  std::string declarationStatement(const ast::VarDeclStmt& d, std::vector<std::string>& before);

  const sem::Model& model_;
  const SourceManager& sources_;
  GlslNameMaps names_;
  const NameTable& table_;
  std::map<const void*, std::string> locals_;
  std::vector<std::string>* hoisted_ = nullptr;  // set while a statement may hoist
  std::optional<Problem> problem_;
  size_t nextTemporary_ = 0;
  OperationProbe* probe_ = nullptr;
};

}  // namespace spire::codegen
