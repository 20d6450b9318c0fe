#include "scene/json_document.h"

#include <gtest/gtest.h>

#include <string>

#include "support/diagnostic_renderer.h"

namespace spire::scene {
namespace {

// One parse of `text` as "doc.json": the document and the rendered diagnostics.
struct Parsed {
  SourceManager sources;
  DiagnosticList diags;
  std::optional<JsonValue> value;
  std::string rendered;
};

std::unique_ptr<Parsed> parse(std::string text) {
  auto parsed = std::make_unique<Parsed>();
  const FileId file = parsed->sources.addFile("doc.json", std::move(text));
  parsed->value = parseJson(parsed->sources, file, parsed->diags);
  for (const Diagnostic& d : parsed->diags.all()) parsed->rendered += renderDiagnostic(parsed->sources, d);
  return parsed;
}

// The first line of the only diagnostic: "doc.json:L:C: error[E7001]: message".
std::string firstLineOfError(const std::string& text) {
  const auto parsed = parse(text);
  EXPECT_FALSE(parsed->value.has_value()) << text;
  EXPECT_EQ(parsed->diags.all().size(), 1u) << parsed->rendered;
  return parsed->rendered.substr(0, parsed->rendered.find('\n'));
}

std::string parseString(const std::string& literal) {
  const auto parsed = parse(literal);
  EXPECT_TRUE(parsed->value.has_value()) << parsed->rendered;
  if (!parsed->value) return {};
  EXPECT_EQ(parsed->value->kind, JsonKind::String);
  return parsed->value->string;
}

double parseNumber(const std::string& literal) {
  const auto parsed = parse(literal);
  EXPECT_TRUE(parsed->value.has_value()) << literal << ": " << parsed->rendered;
  if (!parsed->value) return -12345.0;
  EXPECT_EQ(parsed->value->kind, JsonKind::Number);
  return parsed->value->number;
}

TEST(JsonDocument, Literals) {
  auto parsed = parse(" [null, true, false] ");
  ASSERT_TRUE(parsed->value);
  const JsonValue& array = *parsed->value;
  ASSERT_EQ(array.kind, JsonKind::Array);
  ASSERT_EQ(array.elements.size(), 3u);
  EXPECT_EQ(array.elements[0].kind, JsonKind::Null);
  EXPECT_EQ(array.elements[1].kind, JsonKind::Bool);
  EXPECT_TRUE(array.elements[1].boolean);
  EXPECT_FALSE(array.elements[2].boolean);
  EXPECT_EQ(parsed->sources.text(array.range), "[null, true, false]");
  EXPECT_EQ(parsed->sources.text(array.elements[2].range), "false");
}

TEST(JsonDocument, Numbers) {
  EXPECT_EQ(parseNumber("0"), 0.0);
  EXPECT_EQ(parseNumber("-0"), 0.0);
  EXPECT_EQ(parseNumber("42"), 42.0);
  EXPECT_EQ(parseNumber("-3.25"), -3.25);
  EXPECT_EQ(parseNumber("1e3"), 1000.0);
  EXPECT_EQ(parseNumber("1E+3"), 1000.0);
  EXPECT_EQ(parseNumber("2.5e-3"), 0.0025);
  EXPECT_EQ(parseNumber("-1.5E2"), -150.0);
  EXPECT_EQ(parseNumber("0.000001"), 1e-6);
  EXPECT_EQ(parseNumber("1.7976931348623157e308"), 1.7976931348623157e308);
  EXPECT_EQ(parseNumber("4e-320"), 4e-320);  // subnormal
  // Below the smallest subnormal: rounds to zero, like any IEEE parser.
  EXPECT_EQ(parseNumber("1e-400"), 0.0);
  EXPECT_EQ(
      parseNumber("0.0000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000"
                  "000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000"
                  "000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000"
                  "000000000000000000000000000000000000000000000000000000000000000000000000000000000000000001"),
      0.0);
  EXPECT_EQ(parseNumber("0e999999999999999999"), 0.0);
}

TEST(JsonDocument, MalformedNumbers) {
  EXPECT_EQ(firstLineOfError("01"), "doc.json:1:1: error[E7001]: leading zeros are not allowed in a JSON number");
  EXPECT_EQ(firstLineOfError("[-]"), "doc.json:1:3: error[E7001]: expected a digit after '-', found ']'");
  EXPECT_EQ(firstLineOfError("1."),
            "doc.json:1:3: error[E7001]: expected a digit after the decimal point, found the "
            "end of the file");
  EXPECT_EQ(firstLineOfError("[1e+]"), "doc.json:1:5: error[E7001]: expected a digit in the exponent, found ']'");
  EXPECT_EQ(firstLineOfError("+1"), "doc.json:1:1: error[E7001]: expected a JSON value, found '+'");
  EXPECT_EQ(firstLineOfError(".5"), "doc.json:1:1: error[E7001]: expected a JSON value, found '.'");
  EXPECT_EQ(firstLineOfError("1e400"), "doc.json:1:1: error[E7001]: number 1e400 is too large for a double");
  EXPECT_EQ(firstLineOfError("-Infinity"), "doc.json:1:2: error[E7001]: expected a digit after '-', found 'Infinity'");
  EXPECT_EQ(firstLineOfError("NaN"), "doc.json:1:1: error[E7001]: expected a JSON value, found 'NaN'");
  EXPECT_EQ(firstLineOfError("0x10"),
            "doc.json:1:2: error[E7001]: expected the end of the file after the top-level "
            "value, found 'x10'");
}

TEST(JsonDocument, EveryEscape) {
  EXPECT_EQ(parseString(R"("\" \\ \/ \b \f \n \r \t")"), "\" \\ / \b \f \n \r \t");
  EXPECT_EQ(parseString(R"("\u0041\u00e9\u20AC")"), "A\xC3\xA9\xE2\x82\xAC");
  EXPECT_EQ(parseString(R"("\uD83D\uDE00")"), "\xF0\x9F\x98\x80");  // U+1F600 from a surrogate pair
  EXPECT_EQ(parseString(R"("\uDBFF\uDFFF")"), "\xF4\x8F\xBF\xBF");  // U+10FFFF
  EXPECT_EQ(parseString(R"("a\u0000b")"), std::string("a\0b", 3));
  EXPECT_EQ(parseString("\"gr\xC3\xBC\xC3\x9F \xE2\x9C\x93\""), "gr\xC3\xBC\xC3\x9F \xE2\x9C\x93");
  EXPECT_EQ(parseString(R"("")"), "");
}

TEST(JsonDocument, MalformedStrings) {
  EXPECT_EQ(firstLineOfError(R"("\x")"), R"(doc.json:1:2: error[E7001]: invalid escape sequence '\x')");
  EXPECT_EQ(firstLineOfError(R"("\u12G4")"),
            R"(doc.json:1:2: error[E7001]: expected four hexadecimal digits after '\u')");
  EXPECT_EQ(firstLineOfError(R"("\u12")"),
            R"(doc.json:1:2: error[E7001]: expected four hexadecimal digits after '\u')");
  EXPECT_EQ(
      firstLineOfError(R"(["ok", "\uD83D"])"),
      R"(doc.json:1:9: error[E7001]: unpaired UTF-16 high surrogate '\uD83D' (a low surrogate '\uDC00'-'\uDFFF' must follow))");
  EXPECT_EQ(
      firstLineOfError(R"("\uD83D\u0041")"),
      R"(doc.json:1:2: error[E7001]: unpaired UTF-16 high surrogate '\uD83D' (a low surrogate '\uDC00'-'\uDFFF' must follow))");
  EXPECT_EQ(firstLineOfError(R"("\uDE00")"),
            R"(doc.json:1:2: error[E7001]: unpaired UTF-16 low surrogate '\uDE00' (it must follow a high surrogate))");
  EXPECT_EQ(firstLineOfError("\"tab\there\""),
            "doc.json:1:5: error[E7001]: control character U+0009 must be escaped in a string");
  EXPECT_EQ(
      firstLineOfError("{\"a\": \"open\n}"),
      R"(doc.json:1:7: error[E7001]: unterminated string: a string cannot span lines (write '\n' for a line break))");
  EXPECT_EQ(firstLineOfError("\"open"), "doc.json:1:1: error[E7001]: unterminated string: the file ends inside it");
  EXPECT_EQ(firstLineOfError("\"ends with \\"),
            "doc.json:1:12: error[E7001]: unterminated string: the file ends "
            "inside it");
}

TEST(JsonDocument, ObjectMembersKeepFileOrderAndRanges) {
  auto parsed = parse("{\n  \"zeta\": 1,\n  \"alpha\": {\"inner\": [1, 2]},\n  \"mid\": \"x\"\n}\n");
  ASSERT_TRUE(parsed->value) << parsed->rendered;
  const JsonValue& object = *parsed->value;
  ASSERT_EQ(object.members.size(), 3u);
  EXPECT_EQ(object.members[0].key, "zeta");
  EXPECT_EQ(object.members[1].key, "alpha");
  EXPECT_EQ(object.members[2].key, "mid");
  EXPECT_EQ(parsed->sources.text(object.members[1].keyRange), "\"alpha\"");
  EXPECT_EQ(parsed->sources.text(object.members[1].value.range), "{\"inner\": [1, 2]}");
  const LineCol mid = parsed->sources.begin(object.members[2].value.range);
  EXPECT_EQ(mid.line, 4u);
  EXPECT_EQ(mid.column, 10u);
  ASSERT_NE(object.find("alpha"), nullptr);
  EXPECT_EQ(object.find("alpha")->value.find("inner")->value.elements[1].number, 2.0);
  EXPECT_EQ(object.find("missing"), nullptr);
  EXPECT_EQ(parsed->sources.text(object.openingRange()), "{");
}

TEST(JsonDocument, SyntaxErrorsAtExactPositions) {
  EXPECT_EQ(firstLineOfError("{\n  \"a\": 1\n  \"b\": 2\n}"),
            "doc.json:3:3: error[E7001]: expected ',' or '}' after an object member, found '\"'");
  EXPECT_EQ(firstLineOfError("[1 2]"),
            "doc.json:1:4: error[E7001]: expected ',' or ']' after an array element, found '2'");
  EXPECT_EQ(firstLineOfError("{\"a\" 1}"), "doc.json:1:6: error[E7001]: expected ':' after an object key, found '1'");
  EXPECT_EQ(firstLineOfError("{a: 1}"),
            "doc.json:1:2: error[E7001]: expected a string key in double quotes, found 'a'");
  EXPECT_EQ(firstLineOfError("{'a': 1}"),
            "doc.json:1:2: error[E7001]: expected a string key in double quotes, found "
            "''' (JSON strings use double quotes)");
  EXPECT_EQ(firstLineOfError("{\"a\": 1,\n}"),
            "doc.json:1:8: error[E7001]: trailing comma before '}' is not allowed in JSON");
  EXPECT_EQ(firstLineOfError("[1, 2, ]"),
            "doc.json:1:6: error[E7001]: trailing comma before ']' is not allowed in JSON");
  EXPECT_EQ(firstLineOfError("[1,,2]"), "doc.json:1:4: error[E7001]: expected a JSON value, found ','");
  EXPECT_EQ(firstLineOfError("{\"a\": 1 // one\n}"),
            "doc.json:1:9: error[E7001]: expected ',' or '}' after an object "
            "member, found '/' (JSON does not allow comments)");
  EXPECT_EQ(firstLineOfError("[1, /* two */ 2]"),
            "doc.json:1:5: error[E7001]: expected a JSON value, found '/' (JSON "
            "does not allow comments)");
  EXPECT_EQ(firstLineOfError("{\"a\": [1, 2}"),
            "doc.json:1:12: error[E7001]: expected ',' or ']' after an array "
            "element, found '}'");
  EXPECT_EQ(firstLineOfError("{\"a\": 1"),
            "doc.json:1:8: error[E7001]: expected ',' or '}' after an object member, "
            "found the end of the file");
  EXPECT_EQ(firstLineOfError("[True]"), "doc.json:1:2: error[E7001]: expected a JSON value, found 'True'");
  EXPECT_EQ(firstLineOfError("{} {}"),
            "doc.json:1:4: error[E7001]: expected the end of the file after the top-level "
            "value, found '{'");
}

TEST(JsonDocument, GarbageAndEncoding) {
  EXPECT_EQ(firstLineOfError(""), "doc.json:1:1: error[E7001]: expected a JSON value, found the end of the file");
  EXPECT_EQ(firstLineOfError("  \n\t "),
            "doc.json:2:3: error[E7001]: expected a JSON value, found the end of the file");
  EXPECT_EQ(firstLineOfError("\xEF\xBB\xBF{}"),
            "doc.json:1:1: error[E7001]: the file starts with a byte order mark, "
            "which JSON does not allow; save it as UTF-8 without a BOM");
  EXPECT_EQ(firstLineOfError("[\"a\xFF\"]"), "doc.json:1:4: error[E7001]: the file is not valid UTF-8 text");
  EXPECT_EQ(firstLineOfError("[1, \x01]"),
            "doc.json:1:5: error[E7001]: expected a JSON value, found control character "
            "U+0001");
  EXPECT_EQ(firstLineOfError(std::string("[1,\0 2]", 7)),
            "doc.json:1:4: error[E7001]: expected a JSON value, found "
            "control character U+0000");
  EXPECT_EQ(firstLineOfError("[\xC2\xA0 1]"),
            "doc.json:1:2: error[E7001]: expected a JSON value, found U+00A0 '\xC2\xA0'");
  EXPECT_EQ(firstLineOfError("\x7F"
                             "ELF\x02\x01"),
            "doc.json:1:1: error[E7001]: expected a JSON value, found control "
            "character U+007F");
}

TEST(JsonDocument, NestingIsCapped) {
  const auto nested = [](uint32_t depth) { return std::string(depth, '[') + std::string(depth, ']'); };
  EXPECT_TRUE(parse(nested(kMaxJsonDepth))->value.has_value());
  EXPECT_EQ(firstLineOfError(nested(kMaxJsonDepth + 1)),
            "doc.json:1:129: error[E7001]: arrays and objects are nested more than 128 levels deep");
  // Hostile input far beyond the cap is rejected, not a stack overflow.
  EXPECT_FALSE(parse(std::string(1'000'000, '['))->value.has_value());
  std::string objects;
  for (int i = 0; i < 100'000; ++i) objects += "{\"a\":";
  EXPECT_FALSE(parse(objects)->value.has_value());
}

TEST(JsonDocument, DuplicateKeysAreReportedAndTheFirstIsKept) {
  auto parsed = parse("{\"a\": 1, \"b\": 2,\n \"a\": 3}");
  ASSERT_TRUE(parsed->value.has_value());
  EXPECT_EQ(parsed->value->members.size(), 2u);
  EXPECT_EQ(parsed->value->find("a")->value.number, 1.0);
  EXPECT_EQ(parsed->rendered,
            "doc.json:2:2: error[E7007]: duplicate key 'a'\n"
            " 2 |  \"a\": 3}\n"
            "   |  ^~~\n"
            "doc.json:1:2: note: first defined here\n"
            " 1 | {\"a\": 1, \"b\": 2,\n"
            "   |  ^~~\n");
}

TEST(JsonDocument, WhitespaceBetweenTokens) {
  auto parsed = parse("\r\n\t{ \"a\" :\t[ 1 ,\r\n 2 ] }\n\n");
  ASSERT_TRUE(parsed->value.has_value()) << parsed->rendered;
  EXPECT_EQ(parsed->value->find("a")->value.elements.size(), 2u);
}

TEST(JsonDocument, QuotedForMessageEscapesControlCharacters) {
  EXPECT_EQ(quotedForMessage("plain"), "'plain'");
  EXPECT_EQ(quotedForMessage("two\nlines"), "'two\\u000Alines'");
}

}  // namespace
}  // namespace spire::scene
