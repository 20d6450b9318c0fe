#include "syntax/lexer.h"

#include <gtest/gtest.h>

#include "syntax_test_util.h"

namespace spire {
namespace {

struct Lexed {
  SourceManager sources;
  DiagnosticList diags{100};
  std::vector<Token> tokens;

  std::vector<std::string> diagnostics() const { return test::describe(sources, diags); }
  std::vector<TokenKind> kinds() const {
    std::vector<TokenKind> result;
    for (const Token& t : tokens) result.push_back(t.kind);
    return result;
  }
  std::vector<std::string> texts() const {
    std::vector<std::string> result;
    for (const Token& t : tokens) result.emplace_back(t.text);
    return result;
  }
};

std::unique_ptr<Lexed> lex(std::string source) {
  auto lexed = std::make_unique<Lexed>();
  const FileId file = lexed->sources.addFile("lex.spire", std::move(source));
  lexed->tokens = lexFile(lexed->sources, file, lexed->diags);
  return lexed;
}

using K = TokenKind;

TEST(Lexer, EmptyInputIsJustEndOfFile) {
  const auto lexed = lex("");
  EXPECT_EQ(lexed->kinds(), std::vector<K>{K::EndOfFile});
  EXPECT_EQ(lexed->tokens[0].range, (SourceRange{0, 0, 0}));
}

TEST(Lexer, IdentifiersKeywordsAndTypeNames) {
  const auto lexed =
      lex("pipeline world import export abstract shader group optional finalizes using "
          "struct if else for while do break continue return discard true false in out inout const "
          "float vec3 mat4 sampler2D _x a1 output worlds");
  const std::vector<K> expected = {
      K::KwPipeline, K::KwWorld,     K::KwImport,   K::KwExport,   K::KwAbstract, K::KwShader,   K::KwGroup,
      K::KwOptional, K::KwFinalizes, K::KwUsing,    K::KwStruct,   K::KwIf,       K::KwElse,     K::KwFor,
      K::KwWhile,    K::KwDo,        K::KwBreak,    K::KwContinue, K::KwReturn,   K::KwDiscard,  K::KwTrue,
      K::KwFalse,    K::KwIn,        K::KwOut,      K::KwInout,    K::KwConst,    K::Identifier, K::Identifier,
      K::Identifier, K::Identifier,  K::Identifier, K::Identifier, K::Identifier, K::Identifier, K::EndOfFile};
  EXPECT_EQ(lexed->kinds(), expected);
  EXPECT_TRUE(lexed->diags.all().empty());
}

TEST(Lexer, EveryOperatorAndPunctuator) {
  const auto lexed =
      lex("( ) [ ] { } ; , . : ? @ -> + - * / % ++ -- << >> < > <= >= == != & ^ | && ^^ || ! ~ "
          "= *= /= %= += -= <<= >>= &= ^= |=");
  std::vector<K> expected;
  for (auto k = static_cast<int>(K::LParen); k <= static_cast<int>(K::PipeAssign); ++k) {
    expected.push_back(static_cast<K>(k));
  }
  expected.push_back(K::EndOfFile);
  EXPECT_EQ(lexed->kinds(), expected);
  for (size_t i = 0; i + 1 < lexed->tokens.size(); ++i) {
    EXPECT_EQ(lexed->tokens[i].text, tokenSpelling(lexed->tokens[i].kind));
  }
}

TEST(Lexer, LongestMatchWins) {
  EXPECT_EQ(lex("a<<=b>>=c")->kinds(),
            (std::vector<K>{K::Identifier, K::ShlAssign, K::Identifier, K::ShrAssign, K::Identifier, K::EndOfFile}));
  EXPECT_EQ(lex("x+++y")->kinds(), (std::vector<K>{K::Identifier, K::PlusPlus, K::Plus, K::Identifier, K::EndOfFile}));
  EXPECT_EQ(lex("A->B")->kinds(), (std::vector<K>{K::Identifier, K::Arrow, K::Identifier, K::EndOfFile}));
  EXPECT_EQ(lex("a^^b^c")->kinds(),
            (std::vector<K>{K::Identifier, K::CaretCaret, K::Identifier, K::Caret, K::Identifier, K::EndOfFile}));
  EXPECT_EQ(lex("a--->b")->kinds(),
            (std::vector<K>{K::Identifier, K::MinusMinus, K::Arrow, K::Identifier, K::EndOfFile}));
}

TEST(Lexer, IntegerLiterals) {
  const auto lexed = lex("0 42 0x1F 0XffU 017 10u 4294967295 0xFFFFFFFF");
  EXPECT_TRUE(lexed->diags.all().empty());
  const std::vector<std::pair<uint64_t, bool>> expected = {{0, false},           {42, false},         {31, false},
                                                           {255, true},          {15, false},         {10, true},
                                                           {4294967295u, false}, {0xFFFFFFFFu, false}};
  ASSERT_EQ(lexed->tokens.size(), expected.size() + 1);
  for (size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(lexed->tokens[i].kind, K::IntLiteral);
    const IntLiteralValue value = intLiteralValue(lexed->tokens[i]);
    EXPECT_EQ(value.value, expected[i].first) << lexed->tokens[i].text;
    EXPECT_EQ(value.isUnsigned, expected[i].second) << lexed->tokens[i].text;
  }
}

TEST(Lexer, FloatLiterals) {
  const auto lexed = lex("1.0 .5 1e-3 2.f 1.5F 3E+2 2. 0.25e1f 09.5");
  EXPECT_TRUE(lexed->diags.all().empty()) << ::testing::PrintToString(lexed->diagnostics());
  const std::vector<double> expected = {1.0, 0.5, 1e-3, 2.0, 1.5, 300.0, 2.0, 2.5, 9.5};
  ASSERT_EQ(lexed->tokens.size(), expected.size() + 1);
  for (size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(lexed->tokens[i].kind, K::FloatLiteral) << lexed->tokens[i].text;
    EXPECT_DOUBLE_EQ(floatLiteralValue(lexed->tokens[i]), expected[i]) << lexed->tokens[i].text;
  }
}

TEST(Lexer, MalformedNumbersAreOneErrorEach) {
  const auto lexed = lex("1.0lf 1e 0x 09 1abc 2f 1.5u 3.0LF x");
  EXPECT_EQ(lexed->diagnostics(), (std::vector<std::string>{
                                      "E1004 1:1 double-precision literals are not supported; drop the 'lf' suffix",
                                      "E1004 1:7 exponent has no digits",
                                      "E1004 1:10 hexadecimal literal has no digits",
                                      "E1004 1:13 invalid digit '9' in octal literal",
                                      "E1004 1:16 invalid suffix 'abc' on integer literal",
                                      "E1004 1:21 invalid suffix 'f' on integer literal",
                                      "E1004 1:24 invalid suffix 'u' on floating-point literal",
                                      "E1004 1:29 double-precision literals are not supported; drop the 'lf' suffix",
                                  }));
  ASSERT_EQ(lexed->tokens.size(), 10u);
  for (size_t i = 0; i < 8; ++i) EXPECT_TRUE(lexed->tokens[i].malformed) << lexed->tokens[i].text;
  EXPECT_EQ(lexed->tokens[8].kind, K::Identifier);
  EXPECT_EQ(intLiteralValue(lexed->tokens[4]).value, 0u);
}

TEST(Lexer, OutOfRangeLiterals) {
  const auto lexed = lex("4294967296 0x100000000 99999999999999999999999 1e39 1e400 3.4e38");
  EXPECT_EQ(lexed->diagnostics(), (std::vector<std::string>{
                                      "E1005 1:1 integer literal '4294967296' does not fit in 32 bits",
                                      "E1005 1:12 integer literal '0x100000000' does not fit in 32 bits",
                                      "E1005 1:24 integer literal '99999999999999999999999' does not fit in 32 bits",
                                      "E1005 1:48 floating-point literal '1e39' is out of range for 'float'",
                                      "E1005 1:53 floating-point literal '1e400' is out of range for 'float'",
                                  }));
  EXPECT_FALSE(lexed->tokens[5].malformed);
}

TEST(Lexer, StringLiteralsAndEscapes) {
  const auto lexed = lex(R"("GLSL" "a \"quoted\" \\ path" "")");
  EXPECT_TRUE(lexed->diags.all().empty());
  ASSERT_EQ(lexed->tokens.size(), 4u);
  EXPECT_EQ(stringLiteralValue(lexed->tokens[0]), "GLSL");
  EXPECT_EQ(stringLiteralValue(lexed->tokens[1]), R"(a "quoted" \ path)");
  EXPECT_EQ(stringLiteralValue(lexed->tokens[2]), "");
  EXPECT_EQ(quoteString(R"(a "quoted" \ path)"), R"("a \"quoted\" \\ path")");
}

TEST(Lexer, UnterminatedStringStopsAtTheLineEnd) {
  const auto lexed = lex("using \"common.spire;\nshader");
  EXPECT_EQ(lexed->diagnostics(), std::vector<std::string>{"E1003 1:7 unterminated string literal"});
  EXPECT_EQ(lexed->kinds(), (std::vector<K>{K::KwUsing, K::StringLiteral, K::KwShader, K::EndOfFile}));
  EXPECT_TRUE(lexed->tokens[1].malformed);
  EXPECT_EQ(stringLiteralValue(lexed->tokens[1]), "common.spire;");

  const auto atEnd = lex("\"abc\\");
  EXPECT_EQ(atEnd->diagnostics(), std::vector<std::string>{"E1003 1:1 unterminated string literal"});
}

TEST(Lexer, UnknownEscapeIsReported) {
  const auto lexed = lex(R"("dir\file")");
  EXPECT_EQ(lexed->diagnostics(),
            std::vector<std::string>{
                R"(E1001 1:5 unknown escape sequence '\f' in string literal (only '\"' and '\\' are allowed))"});
  EXPECT_EQ(lexed->kinds(), (std::vector<K>{K::StringLiteral, K::EndOfFile}));
}

TEST(Lexer, CommentsAreSkipped) {
  const auto lexed = lex("a // line comment with $ and \"\n b /* block\n comment $ */ c /* / * */ d//end");
  EXPECT_TRUE(lexed->diags.all().empty());
  EXPECT_EQ(lexed->texts(), (std::vector<std::string>{"a", "b", "c", "d", ""}));
}

TEST(Lexer, UnterminatedBlockComment) {
  const auto lexed = lex("a /* never closed\n b c");
  EXPECT_EQ(lexed->diagnostics(), std::vector<std::string>{"E1002 1:3 unterminated block comment"});
  EXPECT_EQ(lexed->kinds(), (std::vector<K>{K::Identifier, K::EndOfFile}));
  EXPECT_TRUE(lexed->tokens.back().malformed);
}

TEST(Lexer, CrlfLineEndingsGiveTheSameTokensAndPositions) {
  const auto lf = lex("float x;\n// comment\n  y = 1;\n");
  const auto crlf = lex("float x;\r\n// comment\r\n  y = 1;\r\n");
  EXPECT_EQ(lf->texts(), crlf->texts());
  EXPECT_TRUE(crlf->diags.all().empty());
  const Token& y = crlf->tokens[3];
  ASSERT_EQ(y.text, "y");
  EXPECT_EQ(crlf->sources.begin(y.range).line, 3u);
  EXPECT_EQ(crlf->sources.begin(y.range).column, 3u);
}

TEST(Lexer, StrayCharactersAreReportedAndSkipped) {
  const auto lexed = lex("a $ b # c ` d \xC3\xA9 e \x01 f \xFF g \\ h");
  EXPECT_EQ(lexed->diagnostics(), (std::vector<std::string>{
                                      "E1001 1:3 stray character '$' in program",
                                      "E1001 1:7 stray character '#' in program",
                                      "E1001 1:11 stray character '`' in program",
                                      "E1001 1:15 stray character '\xC3\xA9' in program",
                                      "E1001 1:19 stray character '\\x01' in program",
                                      "E1001 1:23 stray character '\\xFF' in program",
                                      "E1001 1:27 stray character '\\' in program",
                                  }));
  EXPECT_EQ(lexed->texts(), (std::vector<std::string>{"a", "b", "c", "d", "e", "f", "g", "h", ""}));
}

TEST(Lexer, ByteOrderMarkIsIgnored) {
  const auto lexed = lex("\xEF\xBB\xBFshader");
  EXPECT_TRUE(lexed->diags.all().empty());
  EXPECT_EQ(lexed->kinds(), (std::vector<K>{K::KwShader, K::EndOfFile}));
}

TEST(Lexer, TokenRangesAreExact) {
  const auto lexed = lex("  vec4 albedo=1.5f;");
  ASSERT_EQ(lexed->tokens.size(), 6u);
  EXPECT_EQ(lexed->tokens[0].range, (SourceRange{0, 2, 6}));
  EXPECT_EQ(lexed->tokens[1].range, (SourceRange{0, 7, 13}));
  EXPECT_EQ(lexed->tokens[2].range, (SourceRange{0, 13, 14}));
  EXPECT_EQ(lexed->tokens[3].range, (SourceRange{0, 14, 18}));
  EXPECT_EQ(lexed->tokens[4].range, (SourceRange{0, 18, 19}));
  EXPECT_EQ(lexed->tokens[5].range, (SourceRange{0, 19, 19}));
}

TEST(Lexer, DescribesTokensForDiagnostics) {
  EXPECT_EQ(describeToken(K::Semicolon), "';'");
  EXPECT_EQ(describeToken(K::KwWorld), "'world'");
  EXPECT_EQ(describeToken(K::Identifier), "identifier");
  EXPECT_EQ(describeToken(K::EndOfFile), "end of file");
}

}  // namespace
}  // namespace spire
