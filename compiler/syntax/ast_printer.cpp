#include "syntax/ast_printer.h"

#include <fmt/format.h>

#include "syntax/ast_spelling.h"
#include "syntax/lexer.h"

namespace spire {
namespace {

using Prec = ast::Precedence;

Prec precedence(const ast::Expr& expr) {
  switch (expr.kind) {
    case ast::ExprKind::Binary: return ast::precedenceOf(ast::cast<ast::BinaryExpr>(expr).op);
    case ast::ExprKind::Assign: return Prec::Assignment;
    case ast::ExprKind::Ternary: return Prec::Conditional;
    case ast::ExprKind::Unary: return isPostfix(ast::cast<ast::UnaryExpr>(expr).op) ? Prec::Postfix : Prec::Unary;
    case ast::ExprKind::Call:
    case ast::ExprKind::Member:
    case ast::ExprKind::Index: return Prec::Postfix;
    default: return Prec::Primary;
  }
}

std::string expr(const ast::Expr& e, Prec context);

std::string type(const ast::TypeSyntax& t, Prec sizeContext = Prec::Conditional) {
  std::string text = t.name;
  for (const auto& size : t.arraySizes) text += "[" + expr(*size, sizeContext) + "]";
  return text;
}

std::string dims(const std::vector<ast::ExprPtr>& sizes) {
  std::string text;
  for (const auto& size : sizes) text += "[" + expr(*size, Prec::Conditional) + "]";
  return text;
}

std::string list(const std::vector<ast::ExprPtr>& items) {
  std::string text;
  for (const auto& item : items) text += (text.empty() ? "" : ", ") + expr(*item, Prec::Assignment);
  return text;
}

// A chain of binary operators, in a loop however long it is.
std::string chain(const ast::BinaryExpr& top, Prec context) {
  return ast::writeChain(top, context, expr, [](ast::BinaryOp op) {
    return op == ast::BinaryOp::Comma ? std::string(", ") : fmt::format(" {} ", ast::spelling(op));
  });
}

std::string unparenthesized(const ast::Expr& e) {
  using namespace ast;
  switch (e.kind) {
    case ExprKind::BoolLiteral: return cast<BoolLiteral>(e).value ? "true" : "false";
    case ExprKind::IntLiteral: return cast<IntLiteral>(e).spelling;
    case ExprKind::FloatLiteral: return cast<FloatLiteral>(e).spelling;
    case ExprKind::Name: return cast<NameExpr>(e).name;
    case ExprKind::Unary: {
      const auto& u = cast<UnaryExpr>(e);
      if (isPostfix(u.op)) return expr(*u.operand, Prec::Postfix) + std::string(spelling(u.op));
      const std::string op(spelling(u.op));
      const std::string operand = expr(*u.operand, Prec::Unary);
      // `- -x` must not become the decrement `--x`.
      const bool glue = operand.front() == op.back() && (op.back() == '+' || op.back() == '-');
      return op + (glue ? " " : "") + operand;
    }
    case ExprKind::Binary: return chain(cast<BinaryExpr>(e), Prec::Comma);
    case ExprKind::Assign: {
      // The target is parsed as a conditional-expr, which a bare ternary would
      // swallow the assignment into.
      const auto& a = cast<AssignExpr>(e);
      return fmt::format("{} {} {}", expr(*a.target, Prec::LogicalOr), spelling(a.op),
                         expr(*a.value, Prec::Assignment));
    }
    case ExprKind::Ternary: {
      const auto& t = cast<TernaryExpr>(e);
      return fmt::format("{} ? {} : {}", expr(*t.condition, Prec::LogicalOr), expr(*t.thenValue, Prec::Comma),
                         expr(*t.elseValue, Prec::Assignment));
    }
    case ExprKind::Call: {
      const auto& c = cast<CallExpr>(e);
      return type(c.callee, Prec::Comma) + "(" + list(c.args) + ")";
    }
    case ExprKind::Member: {
      // `1.x` would lex as the float `1.` followed by `x`.
      const auto& m = cast<MemberExpr>(e);
      const std::string object = m.object->kind == ExprKind::IntLiteral ? "(" + unparenthesized(*m.object) + ")"
                                                                        : expr(*m.object, Prec::Postfix);
      return object + "." + m.member;
    }
    case ExprKind::Index: {
      const auto& i = cast<IndexExpr>(e);
      return expr(*i.object, Prec::Postfix) + "[" + expr(*i.index, Prec::Comma) + "]";
    }
  }
  return {};
}

// `e` as it must be written where the grammar expects `context` or tighter.
std::string expr(const ast::Expr& e, Prec context) {
  if (const auto* b = ast::dyn_cast<ast::BinaryExpr>(&e)) return chain(*b, context);
  std::string text = unparenthesized(e);
  return precedence(e) < context ? "(" + text + ")" : text;
}

std::string attributes(const std::vector<ast::Attribute>& attrs) {
  std::string text;
  for (const auto& a : attrs) text += "[" + a.name + (a.value ? ": " + quoteString(*a.value) : "") + "] ";
  return text;
}

std::string strategy(const ast::StrategyRef& ref) {
  return ref.args.empty() ? ref.name : ref.name + "(" + list(ref.args) + ")";
}

class SourcePrinter {
 public:
  std::string run(const ast::Module& module) {
    for (const auto& decl : module.decls) {
      if (!out_.empty()) out_ += "\n";
      declaration(*decl);
    }
    return std::move(out_);
  }

 private:
  void indent() { out_.append(2 * depth_, ' '); }
  void line(std::string_view text) {
    indent();
    out_ += text;
    out_ += "\n";
  }

  void declaration(const ast::Decl& decl) {
    using namespace ast;
    switch (decl.kind) {
      case DeclKind::Using: return line("using " + quoteString(cast<UsingDecl>(decl).path) + ";");
      case DeclKind::Struct: return structDecl(cast<StructDecl>(decl));
      case DeclKind::Function: return function(cast<FunctionDecl>(decl));
      case DeclKind::Pipeline: return pipeline(cast<PipelineDecl>(decl));
      case DeclKind::Shader: return shader(cast<ShaderDecl>(decl));
      case DeclKind::Group: return group(cast<GroupDecl>(decl));
    }
  }

  void structDecl(const ast::StructDecl& decl) {
    line("struct " + decl.name + " {");
    ++depth_;
    for (const auto& field : decl.fields) line(type(field.type) + " " + field.name + dims(field.arraySizes) + ";");
    --depth_;
    line("};");
  }

  void function(const ast::FunctionDecl& decl) {
    std::string params;
    for (const auto& p : decl.params) {
      if (!params.empty()) params += ", ";
      if (p.isConst) params += "const ";
      if (p.direction == ast::ParamDirection::Out) params += "out ";
      if (p.direction == ast::ParamDirection::InOut) params += "inout ";
      if (p.direction == ast::ParamDirection::In && p.explicitIn) params += "in ";
      params += type(p.type);
      if (!p.name.empty()) params += " " + p.name + dims(p.arraySizes);
    }
    indent();
    out_ += type(decl.returnType) + " " + decl.name + "(" + params + ")";
    if (decl.body) {
      out_ += " ";
      block(*decl.body);
      out_ += "\n";
    } else {
      out_ += ";\n";
    }
  }

  void pipeline(const ast::PipelineDecl& decl) {
    line("pipeline " + decl.name + " {");
    ++depth_;
    for (const auto& w : decl.worlds) {
      std::string text = attributes(w.attributes) + (w.isAbstract ? "abstract world " : "world ") + w.name;
      if (w.language) text += " : " + quoteString(*w.language);
      if (w.exportStrategy) text += " export " + strategy(*w.exportStrategy);
      line(text + ";");
    }
    for (const auto& i : decl.imports) {
      line(attributes(i.attributes) + "import " + i.from + "->" + i.to + " using " + strategy(i.strategy) + ";");
    }
    for (const auto& c : decl.components) component(c);
    --depth_;
    line("}");
  }

  void shader(const ast::ShaderDecl& decl) {
    std::string header = "shader " + decl.name;
    if (decl.pipeline) header += " using " + decl.pipeline->name;
    if (decl.base) header += " : " + decl.base->name;
    for (size_t i = 0; i < decl.finalizes.size(); ++i) {
      header += (i == 0 ? " finalizes " : ", ") + decl.finalizes[i].name;
    }
    line(header + " {");
    ++depth_;
    for (const auto& c : decl.components) component(c);
    --depth_;
    line("}");
  }

  void group(const ast::GroupDecl& decl) {
    line("group " + decl.name + " {");
    ++depth_;
    for (const auto& entry : decl.entries)
      line((entry.isOptional ? "optional shader " : "shader ") + entry.shader.name + ";");
    --depth_;
    line("}");
  }

  void component(const ast::ComponentDecl& c) {
    indent();
    out_ += attributes(c.attributes);
    if (c.isAbstract) out_ += "abstract ";
    if (c.isExport) out_ += "export ";
    if (c.world) out_ += "@" + *c.world + " ";
    out_ += type(c.type) + " " + c.name;
    if (!c.variation.empty()) out_ += ":" + c.variation;
    if (c.body) {
      out_ += " ";
      block(*c.body);
      out_ += "\n";
    } else {
      out_ += c.init ? " = " + expr(*c.init, Prec::Assignment) + ";\n" : ";\n";
    }
  }

  // `{ ... }` from the current position; the line stays open after the '}'.
  void block(const ast::BlockStmt& b) {
    out_ += "{\n";
    ++depth_;
    for (const auto& s : b.statements) {
      indent();
      statement(*s);
    }
    --depth_;
    indent();
    out_ += "}";
  }

  // The body of `if`, `for`, `while` or `do` after its header. Returns true
  // when it was a block, whose '}' leaves the line open.
  bool body(const ast::Stmt& s) {
    if (s.kind == ast::StmtKind::Block) {
      out_ += " " + attributes(s.attributes);
      block(ast::cast<ast::BlockStmt>(s));
      return true;
    }
    out_ += "\n";
    ++depth_;
    indent();
    statement(s);
    --depth_;
    return false;
  }

  // `T a = 1, b[2]` or an expression, without the ';'.
  static std::string simpleStatement(const ast::Stmt& s) {
    if (s.kind == ast::StmtKind::Expr) return expr(*ast::cast<ast::ExprStmt>(s).expr, Prec::Comma);
    const auto& v = ast::cast<ast::VarDeclStmt>(s);
    std::string text = (v.isConst ? "const " : "") + type(v.type) + " ";
    for (size_t i = 0; i < v.declarators.size(); ++i) {
      const auto& d = v.declarators[i];
      text += (i == 0 ? "" : ", ") + d.name + dims(d.arraySizes);
      if (d.init) text += " = " + expr(*d.init, Prec::Assignment);
    }
    return text;
  }

  // One statement from the current position (indentation already written),
  // ending with a newline.
  void statement(const ast::Stmt& s) {
    using namespace ast;
    out_ += attributes(s.attributes);
    switch (s.kind) {
      case StmtKind::Block:
        block(cast<BlockStmt>(s));
        out_ += "\n";
        return;
      case StmtKind::VarDecl:
      case StmtKind::Expr: out_ += simpleStatement(s) + ";\n"; return;
      case StmtKind::If: {
        const auto& i = cast<IfStmt>(s);
        out_ += "if (" + expr(*i.condition, Prec::Comma) + ")";
        const bool open = body(*i.thenBranch);
        if (!i.elseBranch) {
          if (open) out_ += "\n";
          return;
        }
        if (open) {
          out_ += " else";
        } else {
          indent();
          out_ += "else";
        }
        if (i.elseBranch->kind == StmtKind::If) {
          out_ += " ";
          statement(*i.elseBranch);
        } else if (body(*i.elseBranch)) {
          out_ += "\n";
        }
        return;
      }
      case StmtKind::For: {
        const auto& f = cast<ForStmt>(s);
        out_ += "for (" + (f.init ? simpleStatement(*f.init) : "") + ";";
        if (f.condition) out_ += " " + expr(*f.condition, Prec::Comma);
        out_ += ";";
        if (f.step) out_ += " " + expr(*f.step, Prec::Comma);
        out_ += ")";
        if (body(*f.body)) out_ += "\n";
        return;
      }
      case StmtKind::While: {
        const auto& w = cast<WhileStmt>(s);
        out_ += "while (" + expr(*w.condition, Prec::Comma) + ")";
        if (body(*w.body)) out_ += "\n";
        return;
      }
      case StmtKind::DoWhile: {
        const auto& d = cast<DoWhileStmt>(s);
        out_ += "do";
        if (body(*d.body)) {
          out_ += " ";
        } else {
          indent();
        }
        out_ += "while (" + expr(*d.condition, Prec::Comma) + ");\n";
        return;
      }
      case StmtKind::Break: out_ += "break;\n"; return;
      case StmtKind::Continue: out_ += "continue;\n"; return;
      case StmtKind::Return: {
        const auto& r = cast<ReturnStmt>(s);
        out_ += r.value ? "return " + expr(*r.value, Prec::Comma) + ";\n" : "return;\n";
        return;
      }
      case StmtKind::Discard: out_ += "discard;\n"; return;
      case StmtKind::Empty: out_ += ";\n"; return;
    }
  }

  std::string out_;
  size_t depth_ = 0;
};

}  // namespace

std::string printModule(const ast::Module& module) { return SourcePrinter().run(module); }

std::string printExpr(const ast::Expr& e) { return expr(e, Prec::Comma); }

}  // namespace spire
