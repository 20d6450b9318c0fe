// Every construct of the grammar, checked through the AST dump, plus source
// ranges and expression ids.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>

#include "syntax_test_util.h"

namespace spire {
namespace {

using test::dumpOf;
using test::parseClean;

// The dump without the surrounding `(module ...)`, for one declaration.
std::string dumpDecls(const std::string& source) {
  const std::string dump = parseClean(source)->dump();
  const std::string prefix = "(module\n";
  return dump.substr(prefix.size(), dump.size() - prefix.size() - 2);
}

TEST(Parser, EmptyModule) {
  const auto parsed = parseClean("// nothing here\n");
  EXPECT_TRUE(parsed->module->decls.empty());
  EXPECT_EQ(parsed->module->file, parsed->file);
  EXPECT_EQ(parsed->dump(), "(module)\n");
}

TEST(Parser, UsingDeclaration) {
  const auto parsed = parseClean(R"(using "lib/common.spire";)");
  const auto& decl = ast::cast<ast::UsingDecl>(*parsed->module->decls.at(0));
  EXPECT_EQ(decl.path, "lib/common.spire");
  EXPECT_EQ(parsed->text(decl.pathRange), R"("lib/common.spire")");
  EXPECT_EQ(parsed->text(decl.range), R"(using "lib/common.spire";)");
}

TEST(Parser, StructDeclaration) {
  EXPECT_EQ(dumpDecls("struct Light { vec3 dir; float a, b[2]; float[3] c; };"),
            "  (struct Light\n"
            "    (field (type vec3) dir)\n"
            "    (field (type float) a)\n"
            "    (field (type float) b (dims (int 2 \"2\")))\n"
            "    (field (type float (int 3 \"3\")) c))");
  const auto parsed = parseClean("struct S { float x; };");
  const auto& decl = ast::cast<ast::StructDecl>(*parsed->module->decls.at(0));
  EXPECT_EQ(parsed->text(decl.range), "struct S { float x; };");
  EXPECT_EQ(parsed->text(decl.nameRange), "S");
  EXPECT_EQ(parsed->text(decl.fields.at(0).type.range), "float");
  EXPECT_EQ(parsed->text(decl.fields.at(0).nameRange), "x");
}

TEST(Parser, FunctionsAndParameters) {
  EXPECT_EQ(dumpDecls("float f(void); vec3 g(const in float a, out vec3 b[2], inout S, float) { return b[0]; }"),
            "  (function f (type float) prototype)\n"
            "  (function g (type vec3)\n"
            "    (param const in explicit-in (type float) a)\n"
            "    (param out (type vec3) b (dims (int 2 \"2\")))\n"
            "    (param inout (type S))\n"
            "    (param in (type float))\n"
            "    (block\n"
            "      (return (index (name b) (int 0 \"0\")))))");
  const auto parsed = parseClean("float[2] h(const float x) { }");
  const auto& decl = ast::cast<ast::FunctionDecl>(*parsed->module->decls.at(0));
  EXPECT_EQ(parsed->text(decl.range), "float[2] h(const float x) { }");
  EXPECT_EQ(parsed->text(decl.returnType.range), "float[2]");
  EXPECT_EQ(parsed->text(decl.returnType.nameRange), "float");
  EXPECT_EQ(parsed->text(decl.nameRange), "h");
  EXPECT_EQ(parsed->text(decl.params.at(0).range), "const float x");
  EXPECT_EQ(parsed->text(decl.body->range), "{ }");
}

TEST(Parser, PipelineDeclaration) {
  EXPECT_EQ(
      dumpDecls(R"(pipeline P {
      abstract world U;
      [Doc: "gpu"] world V : "GLSL" export vertexExport(projPos);
      world F : "GLSL";
      world X export bufferExport;
      import U->V using uniformImport;
      [Cached] import V->F using textureImport(uv, 2);
      @U vec3 pos;
      abstract export @F vec4 output;
    })"),
      "  (pipeline P\n"
      "    (world U abstract)\n"
      "    (world V (attribute Doc \"gpu\") (language \"GLSL\") (export (strategy vertexExport (name projPos))))\n"
      "    (world F (language \"GLSL\"))\n"
      "    (world X (export (strategy bufferExport)))\n"
      "    (import U V (strategy uniformImport))\n"
      "    (import V F (attribute Cached) (strategy textureImport (name uv) (int 2 \"2\")))\n"
      "    (component pos (world U) (type vec3))\n"
      "    (component output abstract export (world F) (type vec4)))");
}

TEST(Parser, PipelineRanges) {
  const auto parsed = parseClean("pipeline P {\n  world V : \"GLSL\" export s(a);\n  import A->B using t;\n}");
  const auto& decl = ast::cast<ast::PipelineDecl>(*parsed->module->decls.at(0));
  EXPECT_EQ(parsed->text(decl.range), parsed->sources.file(0).text);
  const ast::WorldDecl& world = decl.worlds.at(0);
  EXPECT_EQ(parsed->text(world.range), "world V : \"GLSL\" export s(a);");
  EXPECT_EQ(parsed->text(world.nameRange), "V");
  EXPECT_EQ(parsed->text(world.languageRange), "\"GLSL\"");
  EXPECT_EQ(parsed->text(world.exportStrategy->range), "s(a)");
  EXPECT_EQ(parsed->text(world.exportStrategy->nameRange), "s");
  const ast::ImportDecl& import = decl.imports.at(0);
  EXPECT_EQ(parsed->text(import.range), "import A->B using t;");
  EXPECT_EQ(parsed->text(import.fromRange), "A");
  EXPECT_EQ(parsed->text(import.toRange), "B");
  EXPECT_EQ(parsed->text(import.strategy.range), "t");
}

TEST(Parser, ShadersAndGroups) {
  EXPECT_EQ(dumpDecls("shader A using P { } shader B : A finalizes Vertex, Fragment { float x; } shader C : G { }; "
                      "group G { shader A; optional shader B; }"),
            "  (shader A (pipeline P))\n"
            "  (shader B (base A) (finalizes Vertex Fragment)\n"
            "    (component x (type float)))\n"
            "  (shader C (base G))\n"
            "  (group G\n"
            "    (entry A)\n"
            "    (entry B optional))");
  const auto parsed = parseClean("shader B : A finalizes V, F { }\ngroup G { optional shader B; }");
  const auto& shader = ast::cast<ast::ShaderDecl>(*parsed->module->decls.at(0));
  EXPECT_EQ(parsed->text(shader.base->range), "A");
  EXPECT_EQ(parsed->text(shader.finalizes.at(1).range), "F");
  const auto& group = ast::cast<ast::GroupDecl>(*parsed->module->decls.at(1));
  EXPECT_EQ(parsed->text(group.entries.at(0).range), "optional shader B;");
  EXPECT_EQ(parsed->text(group.entries.at(0).shader.range), "B");
}

TEST(Parser, ComponentForms) {
  EXPECT_EQ(dumpDecls(R"(shader S using P {
      [Hint][Note: "x"] abstract export @Fragment vec4 a, b;
      float lighting:basic = 1.0, lighting:ggx = 2.0;
      vec4 albedo { return vec4(1.0); }
    })"),
            "  (shader S (pipeline P)\n"
            "    (component a abstract export (world Fragment) (attribute Hint) (attribute Note \"x\") (type vec4))\n"
            "    (component b abstract export (world Fragment) (attribute Hint) (attribute Note \"x\") (type vec4))\n"
            "    (component lighting (variation basic) (type float) (init (float 1 \"1.0\")))\n"
            "    (component lighting (variation ggx) (type float) (init (float 2 \"2.0\")))\n"
            "    (component albedo (type vec4)\n"
            "      (block\n"
            "        (return (call (type vec4) (float 1 \"1.0\"))))))");
}

TEST(Parser, SplitComponentsGetTheirOwnTypeCopiesAndRanges) {
  const auto parsed = parseClean("shader S using P {\n  [A] @W float[N + 1] a = 1.0, b:v;\n}");
  const auto& shader = ast::cast<ast::ShaderDecl>(*parsed->module->decls.at(0));
  ASSERT_EQ(shader.components.size(), 2u);
  const ast::ComponentDecl& a = shader.components[0];
  const ast::ComponentDecl& b = shader.components[1];
  EXPECT_EQ(parsed->text(a.range), "[A] @W float[N + 1] a = 1.0");
  EXPECT_EQ(parsed->text(b.range), "[A] @W float[N + 1] a = 1.0, b:v;");
  EXPECT_EQ(parsed->text(b.nameRange), "b");
  EXPECT_EQ(parsed->text(b.variationRange), "v");
  EXPECT_EQ(parsed->text(b.worldRange), "W");
  EXPECT_EQ(parsed->text(b.attributes.at(0).range), "[A]");
  EXPECT_EQ(parsed->text(a.type.range), "float[N + 1]");
  EXPECT_EQ(parsed->text(b.type.range), "float[N + 1]");
  ASSERT_EQ(a.type.arraySizes.size(), 1u);
  ASSERT_EQ(b.type.arraySizes.size(), 1u);
  EXPECT_NE(a.type.arraySizes[0].get(), b.type.arraySizes[0].get());
  EXPECT_NE(a.type.arraySizes[0]->id, b.type.arraySizes[0]->id);
  EXPECT_EQ(dumpExpr(*a.type.arraySizes[0]), dumpExpr(*b.type.arraySizes[0]));
  EXPECT_TRUE(a.hasDefinition());
  EXPECT_FALSE(b.hasDefinition());
}

TEST(Parser, Statements) {
  EXPECT_EQ(
      dumpDecls(R"(void f() {
      const float a = 1.0, b[2];
      x = 1;
      ;
      { }
      if (p) x = 1; else if (q) { } else discard;
      for (int i = 0; i < 3; ++i) continue;
      for (i = 0, j = 1; ; ) break;
      for (;;) { }
      while (p) x++;
      do x--; while (x > 0);
      return;
      return x, y;
    })"),
      "  (function f (type void)\n"
      "    (block\n"
      "      (var const (type float) (declarator a (init (float 1 \"1.0\"))) (declarator b (dims (int 2 \"2\"))))\n"
      "      (expr (assign = (name x) (int 1 \"1\")))\n"
      "      (empty)\n"
      "      (block)\n"
      "      (if (name p)\n"
      "        (expr (assign = (name x) (int 1 \"1\")))\n"
      "        (else\n"
      "          (if (name q)\n"
      "            (block)\n"
      "            (else\n"
      "              (discard)))))\n"
      "      (for\n"
      "        (init\n"
      "          (var (type int) (declarator i (init (int 0 \"0\")))))\n"
      "        (condition (binary < (name i) (int 3 \"3\")))\n"
      "        (step (unary pre++ (name i)))\n"
      "        (continue))\n"
      "      (for\n"
      "        (init\n"
      "          (expr (binary , (assign = (name i) (int 0 \"0\")) (assign = (name j) (int 1 \"1\")))))\n"
      "        (break))\n"
      "      (for\n"
      "        (block))\n"
      "      (while (name p)\n"
      "        (expr (unary post++ (name x))))\n"
      "      (do-while (binary > (name x) (int 0 \"0\"))\n"
      "        (expr (unary post-- (name x))))\n"
      "      (return)\n"
      "      (return (binary , (name x) (name y)))))");
}

TEST(Parser, DanglingElseBindsToTheNearestIf) {
  EXPECT_EQ(dumpDecls("void f() { if (a) if (b) x; else y; }"),
            "  (function f (type void)\n"
            "    (block\n"
            "      (if (name a)\n"
            "        (if (name b)\n"
            "          (expr (name x))\n"
            "          (else\n"
            "            (expr (name y)))))))");
}

TEST(Parser, DeclarationOrExpressionByLookahead) {
  const auto kindOf = [](const std::string& statement) {
    const auto parsed = parseClean("void f() { " + statement + " }");
    return test::onlyStatement(*parsed).kind;
  };
  EXPECT_EQ(kindOf("vec3 v;"), ast::StmtKind::VarDecl);
  EXPECT_EQ(kindOf("Light l = Light(1.0);"), ast::StmtKind::VarDecl);
  EXPECT_EQ(kindOf("float[3] a;"), ast::StmtKind::VarDecl);
  EXPECT_EQ(kindOf("float[N][2] a;"), ast::StmtKind::VarDecl);
  EXPECT_EQ(kindOf("a[b[1]] c;"), ast::StmtKind::VarDecl);
  EXPECT_EQ(kindOf("const int x = 1;"), ast::StmtKind::VarDecl);
  EXPECT_EQ(kindOf("a[2] = b;"), ast::StmtKind::Expr);
  EXPECT_EQ(kindOf("float[3](1.0, 2.0, 3.0);"), ast::StmtKind::Expr);
  EXPECT_EQ(kindOf("v.x = 1.0;"), ast::StmtKind::Expr);
  EXPECT_EQ(kindOf("f(x);"), ast::StmtKind::Expr);
  EXPECT_EQ(kindOf("x++;"), ast::StmtKind::Expr);
}

TEST(Parser, PrecedenceFollowsGlsl) {
  EXPECT_EQ(dumpOf("a, b = c"), "(binary , (name a) (assign = (name b) (name c)))");
  EXPECT_EQ(dumpOf("a = b ? c : d"), "(assign = (name a) (ternary (name b) (name c) (name d)))");
  EXPECT_EQ(dumpOf("a ? b : c || d"), "(ternary (name a) (name b) (binary || (name c) (name d)))");
  EXPECT_EQ(dumpOf("a || b ^^ c"), "(binary || (name a) (binary ^^ (name b) (name c)))");
  EXPECT_EQ(dumpOf("a ^^ b && c"), "(binary ^^ (name a) (binary && (name b) (name c)))");
  EXPECT_EQ(dumpOf("a && b | c"), "(binary && (name a) (binary | (name b) (name c)))");
  EXPECT_EQ(dumpOf("a | b ^ c"), "(binary | (name a) (binary ^ (name b) (name c)))");
  EXPECT_EQ(dumpOf("a ^ b & c"), "(binary ^ (name a) (binary & (name b) (name c)))");
  EXPECT_EQ(dumpOf("a & b == c"), "(binary & (name a) (binary == (name b) (name c)))");
  EXPECT_EQ(dumpOf("a != b < c"), "(binary != (name a) (binary < (name b) (name c)))");
  EXPECT_EQ(dumpOf("a >= b << c"), "(binary >= (name a) (binary << (name b) (name c)))");
  EXPECT_EQ(dumpOf("a >> b + c"), "(binary >> (name a) (binary + (name b) (name c)))");
  EXPECT_EQ(dumpOf("a - b % c"), "(binary - (name a) (binary % (name b) (name c)))");
  EXPECT_EQ(dumpOf("a * -b"), "(binary * (name a) (unary - (name b)))");
  EXPECT_EQ(dumpOf("-a.b"), "(unary - (member (name a) b))");
  EXPECT_EQ(dumpOf("!a[0]"), "(unary ! (index (name a) (int 0 \"0\")))");
  EXPECT_EQ(dumpOf("++a++"), "(unary pre++ (unary post++ (name a)))");
  EXPECT_EQ(dumpOf("~-+!a"), "(unary ~ (unary - (unary + (unary ! (name a)))))");
  EXPECT_EQ(dumpOf("(a + b) * c"), "(binary * (binary + (name a) (name b)) (name c))");
}

TEST(Parser, Associativity) {
  EXPECT_EQ(dumpOf("a - b - c"), "(binary - (binary - (name a) (name b)) (name c))");
  EXPECT_EQ(dumpOf("a / b * c"), "(binary * (binary / (name a) (name b)) (name c))");
  EXPECT_EQ(dumpOf("a < b < c"), "(binary < (binary < (name a) (name b)) (name c))");
  EXPECT_EQ(dumpOf("a, b, c"), "(binary , (binary , (name a) (name b)) (name c))");
  EXPECT_EQ(dumpOf("a = b += c"), "(assign = (name a) (assign += (name b) (name c)))");
  EXPECT_EQ(dumpOf("a ? b : c ? d : e"), "(ternary (name a) (name b) (ternary (name c) (name d) (name e)))");
  EXPECT_EQ(dumpOf("a ? b, c : d = e"), "(ternary (name a) (binary , (name b) (name c)) (assign = (name d) (name e)))");
  EXPECT_EQ(dumpOf("a.b.c[1][2]"), "(index (index (member (member (name a) b) c) (int 1 \"1\")) (int 2 \"2\"))");
}

TEST(Parser, EveryAssignmentOperator) {
  for (const char* op : {"=", "*=", "/=", "%=", "+=", "-=", "<<=", ">>=", "&=", "^=", "|="}) {
    EXPECT_EQ(dumpOf(fmt::format("a {} b", op)), fmt::format("(assign {} (name a) (name b))", op));
  }
}

TEST(Parser, CallsAndConstructors) {
  EXPECT_EQ(dumpOf("f()"), "(call (type f))");
  EXPECT_EQ(dumpOf("vec4(a, b = c)"), "(call (type vec4) (name a) (assign = (name b) (name c)))");
  EXPECT_EQ(dumpOf("float[3](1.0, 2.0, 3.0)"),
            "(call (type float (int 3 \"3\")) (float 1 \"1.0\") (float 2 \"2.0\") (float 3 \"3.0\"))");
  EXPECT_EQ(dumpOf("f(a, (b, c))"), "(call (type f) (name a) (binary , (name b) (name c)))");
  EXPECT_EQ(dumpOf("texture(map, uv).xyz"), "(member (call (type texture) (name map) (name uv)) xyz)");
  EXPECT_EQ(dumpOf("f(1)[2]"), "(index (call (type f) (int 1 \"1\")) (int 2 \"2\"))");
  EXPECT_EQ(dumpOf("a[1][2]"), "(index (index (name a) (int 1 \"1\")) (int 2 \"2\"))");
}

TEST(Parser, Literals) {
  EXPECT_EQ(dumpOf("0x1Fu + 017 + 2"),
            "(binary + (binary + (int 31 \"0x1Fu\" unsigned) (int 15 \"017\")) (int 2 \"2\"))");
  EXPECT_EQ(dumpOf(".5 + 2.f + 1e-3"),
            "(binary + (binary + (float 0.5 \".5\") (float 2 \"2.f\")) (float 0.001 \"1e-3\"))");
  EXPECT_EQ(dumpOf("true != false"), "(binary != (bool true) (bool false))");
}

TEST(Parser, ExpressionRanges) {
  const auto parsed = parseClean("void f() { x = (a + b) * c.yz[i++] + g(1, -d); }");
  const auto& assign = ast::cast<ast::AssignExpr>(*ast::cast<ast::ExprStmt>(test::onlyStatement(*parsed)).expr);
  EXPECT_EQ(parsed->text(assign.range), "x = (a + b) * c.yz[i++] + g(1, -d)");
  EXPECT_EQ(parsed->text(assign.opRange), "=");
  const auto& sum = ast::cast<ast::BinaryExpr>(*assign.value);
  EXPECT_EQ(parsed->text(sum.range), "(a + b) * c.yz[i++] + g(1, -d)");
  EXPECT_EQ(parsed->text(sum.opRange), "+");
  const auto& product = ast::cast<ast::BinaryExpr>(*sum.lhs);
  EXPECT_EQ(parsed->text(product.range), "(a + b) * c.yz[i++]");
  EXPECT_EQ(parsed->text(product.lhs->range), "a + b");
  const auto& index = ast::cast<ast::IndexExpr>(*product.rhs);
  EXPECT_EQ(parsed->text(index.range), "c.yz[i++]");
  EXPECT_EQ(parsed->text(index.index->range), "i++");
  EXPECT_EQ(parsed->text(ast::cast<ast::UnaryExpr>(*index.index).opRange), "++");
  const auto& member = ast::cast<ast::MemberExpr>(*index.object);
  EXPECT_EQ(parsed->text(member.range), "c.yz");
  EXPECT_EQ(parsed->text(member.memberRange), "yz");
  const auto& call = ast::cast<ast::CallExpr>(*sum.rhs);
  EXPECT_EQ(parsed->text(call.range), "g(1, -d)");
  EXPECT_EQ(parsed->text(call.callee.range), "g");
  EXPECT_EQ(parsed->text(call.args.at(1)->range), "-d");
}

TEST(Parser, StatementRanges) {
  const auto parsed = parseClean("void f() {\n  if (a) { b; } else c;\n  for (;;) d;\n  int x = 1, y;\n}");
  const auto& body = *ast::cast<ast::FunctionDecl>(*parsed->module->decls.at(0)).body;
  EXPECT_EQ(parsed->text(body.statements.at(0)->range), "if (a) { b; } else c;");
  EXPECT_EQ(parsed->text(body.statements.at(1)->range), "for (;;) d;");
  const auto& decl = ast::cast<ast::VarDeclStmt>(*body.statements.at(2));
  EXPECT_EQ(parsed->text(decl.range), "int x = 1, y;");
  EXPECT_EQ(parsed->text(decl.declarators.at(1).nameRange), "y");
}

void collectIds(const ast::Expr& e, std::vector<uint32_t>& ids);

void collectIds(const std::vector<ast::ExprPtr>& exprs, std::vector<uint32_t>& ids) {
  for (const auto& e : exprs) collectIds(*e, ids);
}

void collectIds(const ast::Expr& e, std::vector<uint32_t>& ids) {
  using namespace ast;
  ids.push_back(e.id);
  if (const auto* u = dyn_cast<UnaryExpr>(&e)) collectIds(*u->operand, ids);
  if (const auto* b = dyn_cast<BinaryExpr>(&e)) {
    collectIds(*b->lhs, ids);
    collectIds(*b->rhs, ids);
  }
  if (const auto* a = dyn_cast<AssignExpr>(&e)) {
    collectIds(*a->target, ids);
    collectIds(*a->value, ids);
  }
  if (const auto* t = dyn_cast<TernaryExpr>(&e)) {
    collectIds(*t->condition, ids);
    collectIds(*t->thenValue, ids);
    collectIds(*t->elseValue, ids);
  }
  if (const auto* c = dyn_cast<CallExpr>(&e)) {
    collectIds(c->callee.arraySizes, ids);
    collectIds(c->args, ids);
  }
  if (const auto* m = dyn_cast<MemberExpr>(&e)) collectIds(*m->object, ids);
  if (const auto* i = dyn_cast<IndexExpr>(&e)) {
    collectIds(*i->object, ids);
    collectIds(*i->index, ids);
  }
}

TEST(Parser, ExpressionIdsAreUniqueAndDense) {
  const auto parsed = parseClean(
      "shader S using P { float[2] a = float[2](1.0, b[1]), c = x ? y : -z; }\n"
      "void f() { a[i] = b.c + g(1, 2); }");
  std::vector<uint32_t> ids;
  for (const auto& c : ast::cast<ast::ShaderDecl>(*parsed->module->decls.at(0)).components) {
    collectIds(c.type.arraySizes, ids);
    if (c.init) collectIds(*c.init, ids);
  }
  const auto& function = ast::cast<ast::FunctionDecl>(*parsed->module->decls.at(1));
  collectIds(*ast::cast<ast::ExprStmt>(*function.body->statements.at(0)).expr, ids);
  const std::set<uint32_t> unique(ids.begin(), ids.end());
  EXPECT_EQ(unique.size(), ids.size());
  EXPECT_EQ(ids.size(), parsed->program.exprCount);
  EXPECT_EQ(*unique.rbegin(), parsed->program.exprCount - 1);
}

TEST(Parser, PaperListingsParseCleanly) {
  std::ifstream in(std::filesystem::path(SPIRE_TEST_DATA_DIR) / "syntax" / "paper_listings.spire");
  const auto parsed = parseClean({std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()});
  const auto& decls = parsed->module->decls;
  ASSERT_EQ(decls.size(), 7u);
  const auto& pipeline = ast::cast<ast::PipelineDecl>(*decls[0]);
  EXPECT_EQ(pipeline.worlds.size(), 6u);
  EXPECT_EQ(pipeline.imports.size(), 9u);
  EXPECT_EQ(pipeline.components.size(), 5u);
  const auto& terrain = ast::cast<ast::ShaderDecl>(*decls[1]);
  EXPECT_EQ(terrain.components.size(), 15u);
  const auto& lq = ast::cast<ast::ShaderDecl>(*decls[4]);
  ASSERT_EQ(lq.finalizes.size(), 2u);
  EXPECT_EQ(lq.finalizes[1].name, "Fragment");
  EXPECT_EQ(ast::cast<ast::GroupDecl>(*decls[5]).entries.size(), 2u);
}

}  // namespace
}  // namespace spire
