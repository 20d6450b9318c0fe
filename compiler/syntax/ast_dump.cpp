// dumpAst and dumpExpr (declared in ast_printer.h).
#include <fmt/format.h>

#include "syntax/ast_printer.h"
#include "syntax/ast_spelling.h"
#include "syntax/lexer.h"

namespace spire {
namespace {

std::string expr(const ast::Expr& e);

std::string exprs(const std::vector<ast::ExprPtr>& items) {
  std::string text;
  for (const auto& item : items) text += " " + expr(*item);
  return text;
}

std::string type(const ast::TypeSyntax& t) { return "(type " + t.name + exprs(t.arraySizes) + ")"; }

// Array sizes of a declarator, or nothing when there are none.
std::string dims(const std::vector<ast::ExprPtr>& sizes) { return sizes.empty() ? "" : " (dims" + exprs(sizes) + ")"; }

// `(binary op lhs rhs)` for every node of a chain, in a loop however long
// the chain is (ast::leftSpine): the heads outermost first, then the first
// operand, then each right operand closing its node.
std::string chain(const ast::BinaryExpr& top) {
  const std::vector<const ast::BinaryExpr*> spine = ast::leftSpine(top);
  std::string text;
  for (auto it = spine.rbegin(); it != spine.rend(); ++it) text += fmt::format("(binary {} ", ast::spelling((*it)->op));
  text += expr(*spine.front()->lhs);
  for (const ast::BinaryExpr* b : spine) text += " " + expr(*b->rhs) + ")";
  return text;
}

std::string expr(const ast::Expr& e) {
  using namespace ast;
  switch (e.kind) {
    case ExprKind::BoolLiteral: return cast<BoolLiteral>(e).value ? "(bool true)" : "(bool false)";
    case ExprKind::IntLiteral: {
      const auto& i = cast<IntLiteral>(e);
      return fmt::format("(int {} {}{})", i.value, quoteString(i.spelling), i.isUnsigned ? " unsigned" : "");
    }
    case ExprKind::FloatLiteral: {
      const auto& f = cast<FloatLiteral>(e);
      return fmt::format("(float {} {})", f.value, quoteString(f.spelling));
    }
    case ExprKind::Name: return "(name " + cast<NameExpr>(e).name + ")";
    case ExprKind::Unary: {
      const auto& u = cast<UnaryExpr>(e);
      const std::string_view fix = u.op == UnaryOp::PreIncrement || u.op == UnaryOp::PreDecrement ? "pre"
                                   : isPostfix(u.op)                                              ? "post"
                                                                                                  : "";
      return fmt::format("(unary {}{} {})", fix, spelling(u.op), expr(*u.operand));
    }
    case ExprKind::Binary: return chain(cast<BinaryExpr>(e));
    case ExprKind::Assign: {
      const auto& a = cast<AssignExpr>(e);
      return fmt::format("(assign {} {} {})", spelling(a.op), expr(*a.target), expr(*a.value));
    }
    case ExprKind::Ternary: {
      const auto& t = cast<TernaryExpr>(e);
      return fmt::format("(ternary {} {} {})", expr(*t.condition), expr(*t.thenValue), expr(*t.elseValue));
    }
    case ExprKind::Call: {
      const auto& c = cast<CallExpr>(e);
      return "(call " + type(c.callee) + exprs(c.args) + ")";
    }
    case ExprKind::Member: {
      const auto& m = cast<MemberExpr>(e);
      return "(member " + expr(*m.object) + " " + m.member + ")";
    }
    case ExprKind::Index: {
      const auto& i = cast<IndexExpr>(e);
      return "(index " + expr(*i.object) + " " + expr(*i.index) + ")";
    }
  }
  return {};
}

std::string attributes(const std::vector<ast::Attribute>& attrs) {
  std::string text;
  for (const auto& a : attrs) text += " (attribute " + a.name + (a.value ? " " + quoteString(*a.value) : "") + ")";
  return text;
}

std::string strategy(const ast::StrategyRef& ref) { return "(strategy " + ref.name + exprs(ref.args) + ")"; }

// Writes nodes that hold declarations or statements one per line, indented
// by nesting; expressions stay on their node's line.
class TreeDumper {
 public:
  std::string run(const ast::Module& module) {
    open("module");
    for (const auto& decl : module.decls) declaration(*decl);
    close();
    out_ += "\n";
    return std::move(out_);
  }

 private:
  void newLine() {
    if (!out_.empty()) out_ += "\n";
    out_.append(2 * depth_, ' ');
  }
  // A node whose children follow on their own lines, up to close().
  void open(std::string_view head) {
    newLine();
    out_ += "(";
    out_ += head;
    ++depth_;
  }
  void close() {
    out_ += ")";
    --depth_;
  }
  // A complete node on one line.
  void leaf(std::string_view text) {
    newLine();
    out_ += text;
  }

  void declaration(const ast::Decl& decl) {
    using namespace ast;
    switch (decl.kind) {
      case DeclKind::Using: return leaf("(using " + quoteString(cast<UsingDecl>(decl).path) + ")");
      case DeclKind::Struct: {
        const auto& s = cast<StructDecl>(decl);
        open("struct " + s.name);
        for (const auto& f : s.fields) leaf("(field " + type(f.type) + " " + f.name + dims(f.arraySizes) + ")");
        return close();
      }
      case DeclKind::Function: return function(cast<FunctionDecl>(decl));
      case DeclKind::Pipeline: return pipeline(cast<PipelineDecl>(decl));
      case DeclKind::Shader: {
        const auto& s = cast<ShaderDecl>(decl);
        std::string head = "shader " + s.name;
        if (s.pipeline) head += " (pipeline " + s.pipeline->name + ")";
        if (s.base) head += " (base " + s.base->name + ")";
        if (!s.finalizes.empty()) {
          head += " (finalizes";
          for (const auto& world : s.finalizes) head += " " + world.name;
          head += ")";
        }
        open(head);
        for (const auto& c : s.components) component(c);
        return close();
      }
      case DeclKind::Group: {
        const auto& g = cast<GroupDecl>(decl);
        open("group " + g.name);
        for (const auto& entry : g.entries)
          leaf("(entry " + entry.shader.name + (entry.isOptional ? " optional)" : ")"));
        return close();
      }
    }
  }

  void function(const ast::FunctionDecl& f) {
    open("function " + f.name + " " + type(f.returnType) + (f.body ? "" : " prototype"));
    for (const auto& p : f.params) {
      static constexpr std::string_view kDirections[] = {"in", "out", "inout"};
      std::string text = "(param";
      if (p.isConst) text += " const";
      text += " ";
      text += kDirections[static_cast<size_t>(p.direction)];
      if (p.explicitIn) text += " explicit-in";
      text += " " + type(p.type);
      if (!p.name.empty()) text += " " + p.name + dims(p.arraySizes);
      leaf(text + ")");
    }
    if (f.body) statement(*f.body);
    close();
  }

  void pipeline(const ast::PipelineDecl& p) {
    open("pipeline " + p.name);
    for (const auto& w : p.worlds) {
      std::string text = "(world " + w.name + (w.isAbstract ? " abstract" : "") + attributes(w.attributes);
      if (w.language) text += " (language " + quoteString(*w.language) + ")";
      if (w.exportStrategy) text += " (export " + strategy(*w.exportStrategy) + ")";
      leaf(text + ")");
    }
    for (const auto& i : p.imports) {
      leaf("(import " + i.from + " " + i.to + attributes(i.attributes) + " " + strategy(i.strategy) + ")");
    }
    for (const auto& c : p.components) component(c);
    close();
  }

  void component(const ast::ComponentDecl& c) {
    std::string head = "component " + c.name;
    if (!c.variation.empty()) head += " (variation " + c.variation + ")";
    if (c.isAbstract) head += " abstract";
    if (c.isExport) head += " export";
    if (c.world) head += " (world " + *c.world + ")";
    head += attributes(c.attributes) + " " + type(c.type);
    if (c.init) head += " (init " + expr(*c.init) + ")";
    open(head);
    if (c.body) statement(*c.body);
    close();
  }

  // An attributed statement is a node of its own, so that a statement's
  // line looks the same whether or not it carries attributes.
  void statement(const ast::Stmt& s) {
    if (s.attributes.empty()) return unattributedStatement(s);
    open("attributed" + attributes(s.attributes));
    unattributedStatement(s);
    close();
  }

  void unattributedStatement(const ast::Stmt& s) {
    using namespace ast;
    switch (s.kind) {
      case StmtKind::Block:
        open("block");
        for (const auto& child : cast<BlockStmt>(s).statements) statement(*child);
        return close();
      case StmtKind::VarDecl: {
        const auto& v = cast<VarDeclStmt>(s);
        std::string text = std::string("(var") + (v.isConst ? " const " : " ") + type(v.type);
        for (const auto& d : v.declarators) {
          text += " (declarator " + d.name + dims(d.arraySizes) + (d.init ? " (init " + expr(*d.init) + ")" : "") + ")";
        }
        return leaf(text + ")");
      }
      case StmtKind::Expr: return leaf("(expr " + expr(*cast<ExprStmt>(s).expr) + ")");
      case StmtKind::If: {
        const auto& i = cast<IfStmt>(s);
        open("if " + expr(*i.condition));
        statement(*i.thenBranch);
        if (i.elseBranch) {
          open("else");
          statement(*i.elseBranch);
          close();
        }
        return close();
      }
      case StmtKind::For: {
        const auto& f = cast<ForStmt>(s);
        open("for");
        if (f.init) {
          open("init");
          statement(*f.init);
          close();
        }
        if (f.condition) leaf("(condition " + expr(*f.condition) + ")");
        if (f.step) leaf("(step " + expr(*f.step) + ")");
        statement(*f.body);
        return close();
      }
      case StmtKind::While: {
        const auto& w = cast<WhileStmt>(s);
        open("while " + expr(*w.condition));
        statement(*w.body);
        return close();
      }
      case StmtKind::DoWhile: {
        const auto& d = cast<DoWhileStmt>(s);
        open("do-while " + expr(*d.condition));
        statement(*d.body);
        return close();
      }
      case StmtKind::Break: return leaf("(break)");
      case StmtKind::Continue: return leaf("(continue)");
      case StmtKind::Return: {
        const auto& r = cast<ReturnStmt>(s);
        return leaf(r.value ? "(return " + expr(*r.value) + ")" : "(return)");
      }
      case StmtKind::Discard: return leaf("(discard)");
      case StmtKind::Empty: return leaf("(empty)");
    }
  }

  std::string out_;
  size_t depth_ = 0;
};

}  // namespace

std::string dumpAst(const ast::Module& module) { return TreeDumper().run(module); }

std::string dumpExpr(const ast::Expr& e) { return expr(e); }

}  // namespace spire
