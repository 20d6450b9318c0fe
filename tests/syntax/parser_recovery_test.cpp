// Syntax errors: codes, messages and positions, recovery that reports
// several independent errors in one run, and robustness against hostile input.
#include <gtest/gtest.h>

#include <chrono>
#include <random>

#include "syntax_test_util.h"

namespace spire {
namespace {

using Lines = std::vector<std::string>;

Lines errorsOf(const std::string& source) { return test::parse(source)->diagnostics(); }

TEST(ParserRecovery, ExpectedExpression) {
  EXPECT_EQ(errorsOf("shader S using P {\n  float x = 1.0 + ;\n}"), Lines{"E2002 2:19 expected an expression"});
}

TEST(ParserRecovery, MissingSemicolonAtLineEndPointsAfterThePreviousToken) {
  const auto parsed = test::parse("shader S using P {\n  float x = 1.0\n  float y = 2.0;\n}");
  EXPECT_EQ(parsed->diagnostics(), Lines{"E2001 2:16 expected ';' after component declaration"});
  // The ';' is assumed, so the next line is not lost.
  EXPECT_EQ(ast::cast<ast::ShaderDecl>(*parsed->module->decls.at(0)).components.size(), 2u);
}

TEST(ParserRecovery, UnexpectedTokenOnTheSameLineIsPointedAt) {
  EXPECT_EQ(errorsOf("void f() { x = 1 y = 2; z = 3 }"),
            (Lines{"E2001 1:18 expected ';' after expression", "E2001 1:31 expected ';' after expression"}));
}

// Attributes need a statement; the block still closes where it did, so the
// next statement of the function is not lost.
TEST(ParserRecovery, AttributesWithoutAStatement) {
  EXPECT_EQ(errorsOf("void f() {\n  if (a) { [Immutable]\n  }\n  x = 1 y;\n}"),
            (Lines{"E2001 2:23 expected a statement after the attributes", "E2001 4:9 expected ';' after expression"}));
  EXPECT_EQ(errorsOf("void f() { [Immutable: ] x = 1; }"),
            Lines{"E2001 1:24 expected string literal after ':' in attribute"});
}

TEST(ParserRecovery, ClosingBracketsNoteTheOpeningOne) {
  EXPECT_EQ(errorsOf("void f() {\n  x = g(a, (b + c];\n}"),
            (Lines{"E2001 2:18 expected ')' after expression", "  note 2:12 to match this '('"}));
  EXPECT_EQ(errorsOf("void f() {\n  x = g(a, b;\n}"),
            (Lines{"E2001 2:13 expected ')' after arguments", "  note 2:8 to match this '('"}));
}

TEST(ParserRecovery, SeveralIndependentErrorsInOneRun) {
  const auto parsed = test::parse(R"(pipeline P {
  world V : "GLSL" export ;
  import A->B uniformImport;
  vec4 ok = vec4(1.0);
}
shader S using P {
  float x = 1.0 + ;
  float y = 2.0 * 3.0;
  vec3 n { return n * ; }
}
void f() {
  if (x == ) { y = 1; }
  for (int i = 0 i < 3; i++) { z = 1; }
  return;
}
struct T { float a; float b };
)");
  EXPECT_EQ(parsed->diagnostics(), (Lines{
                                       "E2001 2:27 expected a strategy name after 'export'",
                                       "E2001 3:15 expected 'using' after the target world of an import",
                                       "E2002 7:19 expected an expression",
                                       "E2002 9:23 expected an expression",
                                       "E2002 12:12 expected an expression",
                                       "E2001 13:18 expected ';' after declaration",
                                       "E2001 16:29 expected ';' after struct field",
                                   }));
  const auto& pipeline = ast::cast<ast::PipelineDecl>(*parsed->module->decls.at(0));
  EXPECT_EQ(pipeline.components.size(), 1u);
  // `x` is dropped; `n` keeps its body without the broken statement.
  const auto& shader = ast::cast<ast::ShaderDecl>(*parsed->module->decls.at(1));
  ASSERT_EQ(shader.components.size(), 2u);
  EXPECT_EQ(shader.components[0].name, "y");
  EXPECT_TRUE(shader.components[1].body->statements.empty());
  EXPECT_EQ(ast::cast<ast::StructDecl>(*parsed->module->decls.at(3)).fields.size(), 2u);
}

TEST(ParserRecovery, UnterminatedExpressionAtEndOfFileIsOneError) {
  EXPECT_EQ(errorsOf("shader S using P {\n  float x = (1.0 + 2.0\n"),
            (Lines{"E2001 2:23 expected ')' after expression", "  note 2:13 to match this '('"}));
}

TEST(ParserRecovery, MissingClosingBraceIsOneError) {
  EXPECT_EQ(errorsOf("shader S using P {\n  vec4 c {\n    if (a) {\n      return x;\n"),
            (Lines{"E2001 4:16 expected '}' at end of block", "  note 3:12 to match this '{'"}));
  EXPECT_EQ(errorsOf("pipeline P {\n  world W;\n"),
            (Lines{"E2001 2:11 expected '}' at end of pipeline 'P'", "  note 1:12 to match this '{'"}));
}

TEST(ParserRecovery, ANewDeclarationEndsAnUnclosedBody) {
  const auto parsed = test::parse("shader A using P {\n  float x = 1.0;\n\nshader B using P { }\n");
  EXPECT_EQ(parsed->diagnostics(),
            (Lines{"E2001 2:17 expected '}' at end of shader 'A'", "  note 1:18 to match this '{'"}));
  EXPECT_EQ(parsed->module->decls.size(), 2u);
}

TEST(ParserRecovery, AFunctionHeaderEndsAnUnclosedBlock) {
  const auto parsed = test::parse("void f() {\n  int x;\n\nfloat g(float x) {\n  return x;\n}\n");
  EXPECT_EQ(parsed->diagnostics(), (Lines{"E2001 2:9 expected '}' at end of block", "  note 1:10 to match this '{'"}));
  EXPECT_EQ(parsed->module->decls.size(), 2u);
}

TEST(ParserRecovery, AStrayKeywordIsNotTakenForADeclaration) {
  const auto parsed = test::parse("void f() {\n  shader a += b;\n  x = 1;\n}\ngroup G { shader A; }");
  EXPECT_EQ(parsed->diagnostics(), Lines{"E2002 2:3 expected an expression"});
  EXPECT_EQ(ast::cast<ast::FunctionDecl>(*parsed->module->decls.at(0)).body->statements.size(), 1u);
  EXPECT_EQ(ast::cast<ast::GroupDecl>(*parsed->module->decls.at(1)).entries.size(), 1u);
}

TEST(ParserRecovery, StatementsSpilledToTheTopLevelAreOneError) {
  const auto parsed = test::parse(
      "void f() {\n  for (;;) break; }\n  total += 1;\n  int x = 2;\n  if (x) { x = 3; }\n}\n"
      "float g() { return 1.0; }\n");
  EXPECT_EQ(parsed->diagnostics(), Lines{"E2003 3:3 expected a declaration"});
  ASSERT_EQ(parsed->module->decls.size(), 2u);
  EXPECT_EQ(ast::cast<ast::FunctionDecl>(*parsed->module->decls[1]).name, "g");
}

TEST(ParserRecovery, ExpectedADeclaration) {
  EXPECT_EQ(errorsOf("} shader S using P { }"), Lines{"E2003 1:1 expected a declaration"});
  EXPECT_EQ(errorsOf("float g = 1.0;"),
            Lines{"E2003 1:7 file-scope variables are not supported; declare a component in a pipeline or shader "
                  "instead"});
  EXPECT_EQ(errorsOf("pipeline P { 42; world W; }"),
            Lines{"E2003 1:14 expected a world, import or component declaration"});
  EXPECT_EQ(errorsOf("shader S using P { world W; }"),
            Lines{"E2003 1:20 worlds and imports can only be declared in a pipeline"});
  EXPECT_EQ(errorsOf("group G { S; }"),
            Lines{"E2003 1:11 expected a group entry ('shader Name;' or 'optional shader Name;')"});
  EXPECT_EQ(errorsOf("shader S P { }"), Lines{"E2001 1:10 expected 'using' or ':' after shader name"});
}

TEST(ParserRecovery, InvalidComponentDeclarations) {
  EXPECT_EQ(errorsOf("shader S using P {\n  float a, b { return 1.0; }\n  float ok;\n}"),
            Lines{"E2006 2:14 a component with a body block must be declared on its own"});
  EXPECT_EQ(errorsOf("shader S using P {\n  float a { return 1.0; }, b;\n}"),
            Lines{"E2006 2:26 a component with a body block must be declared on its own"});
  EXPECT_EQ(errorsOf("shader S using P { float w[4]; }"),
            Lines{"E2006 1:27 array dimensions of a component belong to its type, as in 'float[4] weights'"});
}

TEST(ParserRecovery, ExpectedAType) {
  EXPECT_EQ(errorsOf("void f(const 3 x) { }"), Lines{"E2007 1:14 expected a type"});
  EXPECT_EQ(errorsOf("shader S using P { @W 3 x; }"), Lines{"E2007 1:23 expected a type"});
  EXPECT_EQ(errorsOf("struct S { 3 x; };"), Lines{"E2007 1:12 expected a type"});
}

TEST(ParserRecovery, LexicalErrorsDoNotCascade) {
  const auto parsed = test::parse("using \"common.spire;\nshader S using P { float x = 1.5lf; }\n");
  EXPECT_EQ(parsed->diagnostics(), (Lines{"E1003 1:7 unterminated string literal",
                                          "E1004 2:30 double-precision literals are not supported; drop the 'lf' "
                                          "suffix"}));
  EXPECT_EQ(parsed->module->decls.size(), 2u);
  EXPECT_EQ(errorsOf("shader S using P {\n  float x = 1.0; /* unterminated\n}\n"),
            Lines{"E1002 2:18 unterminated block comment"});
}

TEST(ParserRecovery, ErrorLimitStopsTheParser) {
  SourceManager sources;
  std::string source;
  for (int i = 0; i < 1000; ++i) source += "shader S using P { float x = ; }\n";
  const FileId file = sources.addFile("many.spire", source);
  DiagnosticList diags(5);
  ast::Program program;
  parseModule(sources, file, program, diags);
  EXPECT_TRUE(diags.limitReached());
  EXPECT_EQ(diags.all().size(), 6u);
  EXPECT_EQ(diags.all().back().code, DiagCode::E2005);
}

double secondsToParse(const std::string& source, Lines& diagnostics) {
  const auto start = std::chrono::steady_clock::now();
  diagnostics = errorsOf(source);
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

TEST(ParserRecovery, DeepNestingIsReportedNotRecursedInto) {
  Lines diagnostics;
  EXPECT_LT(secondsToParse("void f() { x = " + std::string(100000, '(') + "1;\n}", diagnostics), 5.0);
  EXPECT_EQ(diagnostics, Lines{"E2004 1:213 nesting too deep (the limit is 200)"});
  EXPECT_LT(secondsToParse("void f() " + std::string(100000, '{'), diagnostics), 5.0);
  EXPECT_EQ(diagnostics, Lines{"E2004 1:210 nesting too deep (the limit is 200)"});
  EXPECT_LT(secondsToParse("void f() { x = " + std::string(100000, '!') + "1;\n}", diagnostics), 5.0);
  EXPECT_EQ(diagnostics, Lines{"E2004 1:213 nesting too deep (the limit is 200)"});
}

// A chain of binary operators is a loop, not nesting: generated shaders
// write sums of thousands of terms.
TEST(ParserRecovery, LongOperatorChainsAreNotNesting) {
  std::string chain = "void f() { x = a";
  for (int i = 0; i < 50000; ++i) chain += i % 7 == 3 ? "*a" : "+a";
  Lines diagnostics;
  EXPECT_LT(secondsToParse(chain + "; }", diagnostics), 5.0);
  EXPECT_EQ(diagnostics, Lines{});
}

TEST(ParserRecovery, NestingLimitIsConfigurable) {
  const std::string source = "void f() { x = ((((a)))); }";
  EXPECT_TRUE(test::parse(source, ParseLimits{10})->diagnostics().empty());
  EXPECT_EQ(test::parse(source, ParseLimits{4})->diagnostics(), Lines{"E2004 1:17 nesting too deep (the limit is 4)"});
}

// Whatever the parser recovers must be a complete tree: printable, and
// printing it again gives source without syntax errors.
TEST(ParserRecovery, RandomTokenSoupTerminatesWithAPrintableTree) {
  const std::vector<std::string> vocabulary = {
      "shader",    "pipeline", "group", "struct", "world", "import", "abstract", "export", "using",   "optional",
      "finalizes", "if",       "else",  "for",    "while", "do",     "return",   "break",  "discard", "const",
      "in",        "out",      "float", "vec4",   "x",     "y",      "S",        "P",      "W",       "1",
      "2.0",       "\"s\"",    "(",     ")",      "[",     "]",      "{",        "}",      ";",       ",",
      ".",         ":",        "?",     "@",      "->",    "+",      "-",        "*",      "=",       "+=",
      "++",        "<",        "&&",    "!",      "$"};
  std::mt19937 random(20160724);
  for (int round = 0; round < 300; ++round) {
    std::string source;
    const size_t length = random() % 200;
    for (size_t i = 0; i < length; ++i) source += vocabulary[random() % vocabulary.size()] + " ";
    const auto parsed = test::parse(source);
    const std::string printed = printModule(*parsed->module);
    const auto reparsed = test::parse(printed);
    ASSERT_EQ(reparsed->diagnostics(), Lines{}) << "input:\n" << source << "\nprinted:\n" << printed;
    EXPECT_EQ(reparsed->dump(), parsed->dump());
  }
}

}  // namespace
}  // namespace spire
