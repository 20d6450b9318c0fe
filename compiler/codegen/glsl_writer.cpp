#include "codegen/glsl_writer.h"

#include <fmt/format.h>

#include <algorithm>
#include <utility>

#include "codegen/expression_effects.h"
#include "codegen/kernel_builder.h"
#include "syntax/ast_spelling.h"

namespace spire::codegen {
namespace {

using ast::Precedence;

// GLSL needs a `.` or an exponent in a float literal (`1f` is not GLSL).
std::string floatLiteral(const std::string& spelling) {
  if (spelling.find_first_of(".eE") != std::string::npos) return spelling;
  std::string digits = spelling;
  while (!digits.empty() && (digits.back() == 'f' || digits.back() == 'F')) digits.pop_back();
  return digits + ".0";
}

std::string indentation(int indent) { return std::string(static_cast<size_t>(indent) * 4, ' '); }

bool isShortCircuit(ast::BinaryOp op) {
  return op == ast::BinaryOp::LogicalAnd || op == ast::BinaryOp::LogicalOr || op == ast::BinaryOp::LogicalXor;
}

}  // namespace

void GlslOutput::line(std::string_view text) {
  text_.append(text);
  text_.push_back('\n');
  ++physicalLine_;
  ++mappedLine_;
}

void GlslOutput::mapTo(const std::string& file, uint32_t sourceLine) {
  if (mappedFile_ == file && mappedLine_ == sourceLine) return;
  line(fmt::format("#line {} \"{}\"", sourceLine, file));
  mappedFile_ = file;
  mappedLine_ = sourceLine;
}

void GlslOutput::mapToKernel() {
  if (mappedFile_.empty()) return;
  // The directive's own line is physicalLine_; the next one is physicalLine_ + 1.
  line(fmt::format("#line {} \"{}\"", physicalLine_ + 1, kernelFile_));
  mappedFile_.clear();
  mappedLine_ = physicalLine_;
}

std::string GlslWriter::typeName(const sem::Type* type) const {
  static const std::map<std::string, std::string, std::less<>> kNone;
  return glslTypeName(type, names_.structs ? *names_.structs : kNone);
}

std::string GlslWriter::declare(const sem::Type* type, const std::string& name) const {
  static const std::map<std::string, std::string, std::less<>> kNone;
  return declareVariable(type, name, names_.structs ? *names_.structs : kNone);
}

std::string GlslWriter::localName(const void* decl, std::string_view source) {
  auto [it, inserted] = locals_.try_emplace(decl);
  if (inserted) it->second = table_.local(source);
  return it->second;
}

// Unique in the kernel: locals never have the generated names' `spire_`
// prefix (NameTable renames them), so only globals need avoiding.
std::string GlslWriter::temporaryName() {
  std::string name;
  do {
    name = fmt::format("spire_chain{}", nextTemporary_++);
  } while (table_.isTaken(name));
  return name;
}

std::string GlslWriter::statementExpr(const ast::Expr& e, std::vector<std::string>& before, Precedence minPrecedence) {
  // `target = value` stores after the value is computed, so its value may
  // hoist as long as computing the target writes nothing either.
  const auto* assign = ast::dyn_cast<ast::AssignExpr>(&e);
  const bool pure = assign ? !hasSideEffects(model_, *assign->target) && !hasSideEffects(model_, *assign->value)
                           : !hasSideEffects(model_, e);
  if (!pure) return expr(e, minPrecedence);
  return hoistingInto(&before, [&] { return expr(e, minPrecedence); });
}

std::string GlslWriter::conditionalExpr(const ast::Expr& e, Precedence minPrecedence) {
  return hoistingInto(nullptr, [&] { return expr(e, minPrecedence); });
}

std::string GlslWriter::hoistingInto(std::vector<std::string>* target, const std::function<std::string()>& write) {
  std::vector<std::string>* const saved = std::exchange(hoisted_, target);
  std::string text = write();
  hoisted_ = saved;
  return text;
}

// The operators spine[begin, end) of a chain whose value before spine[begin]
// is `head`, where the grammar expects `context` or tighter (the
// parenthesization of ast::writeChain). Right operands of `&&`, `||` and
// `^^` are evaluated only under a condition.
std::string GlslWriter::chainText(const std::vector<const ast::BinaryExpr*>& spine, size_t begin, size_t end,
                                  const std::string& head, Precedence context) {
  if (probe_) return probedChainText(spine, begin, end, head);
  std::string opens;
  std::string text;
  for (size_t i = begin; i < end; ++i) {
    const Precedence own = ast::precedenceOf(spine[i]->op);
    const bool parenthesized = own < (i + 1 < end ? ast::precedenceOf(spine[i + 1]->op) : context);
    if (parenthesized) opens += '(';
    text += fmt::format(" {} ", ast::spelling(spine[i]->op));
    const ast::Expr& rhs = *spine[i]->rhs;
    text += isShortCircuit(spine[i]->op) ? conditionalExpr(rhs, ast::tighter(own)) : expr(rhs, ast::tighter(own));
    if (parenthesized) text += ')';
  }
  return opens + head + text;
}

std::string GlslWriter::probedChainText(const std::vector<const ast::BinaryExpr*>& spine, size_t begin, size_t end,
                                        const std::string& head) {
  std::string text = head;
  for (size_t i = begin; i < end; ++i) {
    const Precedence own = ast::precedenceOf(spine[i]->op);
    const ast::Expr& rhs = *spine[i]->rhs;
    const std::string right =
        isShortCircuit(spine[i]->op) ? conditionalExpr(rhs, ast::tighter(own)) : expr(rhs, ast::tighter(own));
    text = probed(*spine[i], fmt::format("({} {} {})", text, ast::spelling(spine[i]->op), right));
  }
  return text;
}

std::string GlslWriter::probed(const ast::Expr& e, std::string text) {
  if (!probe_ || !isCheckedOperation(e, model_.info(e))) return text;
  // One line of source, its whitespace collapsed: enough to recognize the
  // operation in a report without quoting a whole block.
  std::string written;
  for (char c : sources_.text(e.range)) {
    const bool space = c == ' ' || c == '\t' || c == '\n' || c == '\r';
    if (space && (written.empty() || written.back() == ' ')) continue;
    written += space ? ' ' : c;
  }
  while (!written.empty() && written.back() == ' ') written.pop_back();
  constexpr size_t kMaxShown = 60;
  if (written.size() > kMaxShown) written = written.substr(0, kMaxShown - 3) + "...";
  const LineCol at = sources_.begin(e.range);
  return probe_->wrap(
      e, text,
      {std::move(written), fmt::format("{}:{}:{}", sources_.file(e.range.file).logicalName, at.line, at.column)});
}

// In a loop, never recursing along the chain: generated code writes chains
// of thousands of terms.
std::string GlslWriter::binary(const ast::BinaryExpr& e, Precedence minPrecedence) {
  const std::vector<const ast::BinaryExpr*> spine = ast::leftSpine(e);
  std::string head = expr(*spine.front()->lhs, ast::precedenceOf(spine.front()->op));
  if (!hoisted_ || spine.size() <= kChainSegment) {
    if (spine.size() > kMaxInlineChain && !problem_) {
      problem_ = Problem{
          e.range,
          fmt::format(
              "an expression chains {} operators where the kernel cannot compute it in steps (a loop condition or "
              "step, an expression that assigns or calls a function with 'out' parameters, or an operand evaluated "
              "only under a condition), and GLSL compilers fail on chains much longer than {}; compute it in a local "
              "variable first",
              spine.size(), kMaxInlineChain)};
    }
    return chainText(spine, 0, spine.size(), head, minPrecedence);
  }
  for (size_t begin = 0; begin < spine.size(); begin += kChainSegment) {
    const size_t end = std::min(begin + kChainSegment, spine.size());
    std::string text = chainText(spine, begin, end, head, Precedence::Assignment);
    head = temporaryName();
    hoisted_->push_back(declare(model_.info(*spine[end - 1]).type, head) + " = " + text + ";");
  }
  return head;
}

std::string GlslWriter::expr(const ast::Expr& e, Precedence minPrecedence) {
  const sem::ExprInfo& info = model_.info(e);
  auto wrap = [&](Precedence precedence, const std::string& text) {
    return precedence < minPrecedence ? "(" + text + ")" : text;
  };
  switch (e.kind) {
    case ast::ExprKind::BoolLiteral: return ast::cast<ast::BoolLiteral>(e).value ? "true" : "false";
    case ast::ExprKind::IntLiteral: return ast::cast<ast::IntLiteral>(e).spelling;
    case ast::ExprKind::FloatLiteral: return floatLiteral(ast::cast<ast::FloatLiteral>(e).spelling);
    case ast::ExprKind::Name: {
      const auto& n = ast::cast<ast::NameExpr>(e);
      if (info.ref == sem::RefKind::Local) return localName(info.local, n.name);
      if (info.ref == sem::RefKind::Parameter) return localName(info.parameter, n.name);
      return names_.component(n.name);
    }
    case ast::ExprKind::Unary: {
      const auto& u = ast::cast<ast::UnaryExpr>(e);
      if (ast::isPostfix(u.op))
        return wrap(Precedence::Postfix, expr(*u.operand, Precedence::Postfix) + std::string(ast::spelling(u.op)));
      std::string operand = expr(*u.operand, Precedence::Unary);
      const std::string op(ast::spelling(u.op));
      // `- -x` must not become the decrement `--x`.
      const bool separate = !operand.empty() && (operand[0] == '-' || operand[0] == '+');
      return wrap(Precedence::Unary, op + (separate ? " " : "") + operand);
    }
    case ast::ExprKind::Binary: return binary(ast::cast<ast::BinaryExpr>(e), minPrecedence);
    case ast::ExprKind::Assign: {
      const auto& a = ast::cast<ast::AssignExpr>(e);
      const std::string text = fmt::format("{} {} {}", expr(*a.target, Precedence::Unary), ast::spelling(a.op),
                                           expr(*a.value, Precedence::Assignment));
      return probe_ && isCheckedOperation(e, info) ? probed(e, text) : wrap(Precedence::Assignment, text);
    }
    case ast::ExprKind::Ternary: {
      const auto& t = ast::cast<ast::TernaryExpr>(e);
      return wrap(Precedence::Conditional, fmt::format("{} ? {} : {}", expr(*t.condition, Precedence::LogicalOr),
                                                       conditionalExpr(*t.thenValue, Precedence::Assignment),
                                                       conditionalExpr(*t.elseValue, Precedence::Conditional)));
    }
    case ast::ExprKind::Call: {
      const auto& c = ast::cast<ast::CallExpr>(e);
      std::string callee = c.callee.name;
      if (info.ref == sem::RefKind::Function)
        callee = names_.functions.at(info.function);
      else if (info.ref == sem::RefKind::Constructor || info.ref == sem::RefKind::StructConstructor)
        callee = typeName(info.type);
      std::string args;
      for (const ast::ExprPtr& arg : c.args) args += (args.empty() ? "" : ", ") + expr(*arg, Precedence::Assignment);
      return probed(e, fmt::format("{}({})", callee, args));
    }
    case ast::ExprKind::Member: {
      const auto& m = ast::cast<ast::MemberExpr>(e);
      std::string member = m.member;
      if (info.ref == sem::RefKind::Field && isReservedInGlsl(member)) member += '_';
      return wrap(Precedence::Postfix, expr(*m.object, Precedence::Postfix) + "." + member);
    }
    case ast::ExprKind::Index: {
      const auto& i = ast::cast<ast::IndexExpr>(e);
      return wrap(Precedence::Postfix,
                  fmt::format("{}[{}]", expr(*i.object, Precedence::Postfix), expr(*i.index, Precedence::Comma)));
    }
  }
  return "";
}

void GlslWriter::mapLine(GlslOutput& out, const SourceRange& range) {
  if (!range.valid()) return;
  out.mapTo(sources_.file(range.file).logicalName, sources_.begin(range).line);
}

// `[const] T a = x, b[2]`: one declaration, as GLSL wants it in a `for`
// header. Every declarator shares the base type; each keeps its own sizes.
std::string GlslWriter::localDeclaration(const ast::VarDeclStmt& d) {
  std::string text = d.isConst ? "const " : "";
  for (size_t i = 0; i < d.declarators.size(); ++i) {
    const ast::VarDeclarator& v = d.declarators[i];
    const sem::Type* base = model_.localTypes.at(&v);
    std::string dims;
    for (; base->isArray(); base = base->element) dims += fmt::format("[{}]", base->arraySize);
    text += i == 0 ? typeName(base) + " " : std::string(", ");
    text += localName(&v, v.name) + dims;
    if (v.init) text += " = " + expr(*v.init, Precedence::Assignment);
  }
  return text;
}

// A declaration statement of one variable may compute its initializer in
// temporaries; with several, a later initializer may read an earlier
// variable, which does not exist yet where the temporaries go.
std::string GlslWriter::declarationStatement(const ast::VarDeclStmt& d, std::vector<std::string>& before) {
  const bool single = d.declarators.size() == 1 && d.declarators.front().init;
  if (!single || hasSideEffects(model_, *d.declarators.front().init)) return localDeclaration(d);
  return hoistingInto(&before, [&] { return localDeclaration(d); });
}

void GlslWriter::writeHoisted(GlslOutput& out, const std::string& pad, const std::vector<std::string>& before,
                              const SourceRange& range) {
  for (const std::string& declaration : before) {
    out.line(pad + declaration);
    mapLine(out, range);
  }
}

std::string GlslWriter::forInit(const ast::Stmt& s) {
  if (const auto* e = ast::dyn_cast<ast::ExprStmt>(&s)) return expr(*e->expr);
  if (const auto* d = ast::dyn_cast<ast::VarDeclStmt>(&s)) return localDeclaration(*d);
  return "";
}

void GlslWriter::block(GlslOutput& out, const ast::BlockStmt& b, int indent) {
  for (const ast::StmtPtr& s : b.statements) stmt(out, *s, indent);
}

void GlslWriter::body(GlslOutput& out, const ast::Stmt& s, int indent) {
  if (const auto* b = ast::dyn_cast<ast::BlockStmt>(&s))
    block(out, *b, indent);
  else
    stmt(out, s, indent);
}

void GlslWriter::stmt(GlslOutput& out, const ast::Stmt& s, int indent) {
  const std::string pad = indentation(indent);
  mapLine(out, s.range);
  switch (s.kind) {
    case ast::StmtKind::Block:
      out.line(pad + "{");
      block(out, ast::cast<ast::BlockStmt>(s), indent + 1);
      out.line(pad + "}");
      return;
    case ast::StmtKind::VarDecl: {
      std::vector<std::string> before;
      const std::string text = declarationStatement(ast::cast<ast::VarDeclStmt>(s), before);
      writeHoisted(out, pad, before, s.range);
      out.line(pad + text + ";");
      return;
    }
    case ast::StmtKind::Expr: {
      std::vector<std::string> before;
      const std::string text = statementExpr(*ast::cast<ast::ExprStmt>(s).expr, before);
      writeHoisted(out, pad, before, s.range);
      out.line(pad + text + ";");
      return;
    }
    case ast::StmtKind::If: {
      const auto& i = ast::cast<ast::IfStmt>(s);
      std::vector<std::string> before;
      const std::string condition = statementExpr(*i.condition, before);
      writeHoisted(out, pad, before, s.range);
      out.line(pad + "if (" + condition + ") {");
      body(out, *i.thenBranch, indent + 1);
      if (i.elseBranch) {
        out.line(pad + "} else {");
        body(out, *i.elseBranch, indent + 1);
      }
      out.line(pad + "}");
      return;
    }
    case ast::StmtKind::For: {
      const auto& f = ast::cast<ast::ForStmt>(s);
      out.line(fmt::format("{}for ({}; {}; {}) {{", pad, f.init ? forInit(*f.init) : "",
                           f.condition ? expr(*f.condition) : "", f.step ? expr(*f.step) : ""));
      body(out, *f.body, indent + 1);
      out.line(pad + "}");
      return;
    }
    case ast::StmtKind::While: {
      const auto& w = ast::cast<ast::WhileStmt>(s);
      out.line(pad + "while (" + expr(*w.condition) + ") {");
      body(out, *w.body, indent + 1);
      out.line(pad + "}");
      return;
    }
    case ast::StmtKind::DoWhile: {
      const auto& d = ast::cast<ast::DoWhileStmt>(s);
      out.line(pad + "do {");
      body(out, *d.body, indent + 1);
      out.line(pad + "} while (" + expr(*d.condition) + ");");
      return;
    }
    case ast::StmtKind::Break: out.line(pad + "break;"); return;
    case ast::StmtKind::Continue: out.line(pad + "continue;"); return;
    case ast::StmtKind::Return: {
      const auto& r = ast::cast<ast::ReturnStmt>(s);
      std::vector<std::string> before;
      const std::string value = r.value ? statementExpr(*r.value, before) : std::string();
      writeHoisted(out, pad, before, s.range);
      out.line(pad + (r.value ? "return " + value + ";" : std::string("return;")));
      return;
    }
    case ast::StmtKind::Discard: out.line(pad + "discard;"); return;
    case ast::StmtKind::Empty: return;
  }
}

void GlslWriter::function(GlslOutput& out, const sem::Function& f, const std::string& name) {
  std::string params;
  for (size_t i = 0; i < f.params.size(); ++i) {
    const ast::Param& p = f.decl->params[i];
    std::string qualifier = p.isConst ? "const " : "";
    if (p.direction == ast::ParamDirection::Out) qualifier += "out ";
    if (p.direction == ast::ParamDirection::InOut) qualifier += "inout ";
    const std::string paramName = p.name.empty() ? fmt::format("spire_unused{}", i) : localName(&p, p.name);
    params += (params.empty() ? "" : ", ") + qualifier + declare(f.params[i].type, paramName);
  }
  mapLine(out, f.decl->range);
  out.line(fmt::format("{} {}({}) {{", typeName(f.returnType), name, params));
  block(out, *f.decl->body, 1);
  out.line("}");
  out.mapToKernel();
}

}  // namespace spire::codegen
