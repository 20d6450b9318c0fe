// printModule must produce source that parses back to the same tree. This
// runs over a handwritten file with every construct and over every Spire
// file shipped with the project.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "syntax_test_util.h"

namespace spire {
namespace {

namespace fs = std::filesystem;

std::string readFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Parses `source`, prints it, parses the print and compares the dumps; the
// printed form must also be a fixed point of printing.
void expectRoundTrip(const std::string& source, const std::string& name) {
  SCOPED_TRACE(name);
  const auto original = test::parse(source);
  ASSERT_EQ(original->diagnostics(), std::vector<std::string>{}) << "the input itself has syntax errors";
  const std::string printed = printModule(*original->module);
  const auto reparsed = test::parse(printed);
  ASSERT_EQ(reparsed->diagnostics(), std::vector<std::string>{}) << "printed source:\n" << printed;
  EXPECT_EQ(original->dump(), reparsed->dump()) << "printed source:\n" << printed;
  EXPECT_EQ(printModule(*reparsed->module), printed);
}

TEST(RoundTrip, EveryConstruct) {
  const std::string source = readFile(fs::path(SPIRE_TEST_DATA_DIR) / "syntax" / "all_constructs.spire");
  ASSERT_FALSE(source.empty());
  expectRoundTrip(source, "all_constructs.spire");
}

TEST(RoundTrip, PaperListings) {
  const std::string source = readFile(fs::path(SPIRE_TEST_DATA_DIR) / "syntax" / "paper_listings.spire");
  ASSERT_FALSE(source.empty());
  expectRoundTrip(source, "paper_listings.spire");
}

TEST(RoundTrip, ExpressionsNeedingParentheses) {
  expectRoundTrip(R"(void f() {
    x = -(-a) + (-(--b)) - (+(+c)) - (a - b) - (a = b) + (p ? a : b);
    x = (a, b)[(c, d)] + f((a, b), c) + g(a = b) + float[(n, m)](a);
    x = (a ? b : c) = d;
    x = (1).x + (1.5).y + 2.0.z + 1e3.w;
  })",
                  "expressions");
}

// Attributes stay with the statement they precede, wherever it stands, and
// a statement's own node is the same with or without them.
TEST(RoundTrip, StatementAttributes) {
  expectRoundTrip(R"(float f(float x) {
    [Immutable] { x = x * 2.0; }
    [Immutable] [Note: "kept"] float y = x + 1.0;
    for (int i = 0; i < 4; ++i) [Immutable] x += y;
    while (x > 1.0) [Immutable] { x = x * 0.5; }
    if (x > 0.0) [Immutable] return x; else [Immutable] if (x < -1.0) return -x;
    do [Immutable] { x += 1.0; } while (x < 0.0);
    return y;
  })",
                  "statement attributes");
  const auto parsed = test::parse("void f() { [Immutable] { x = 1; } x = 2; }");
  ASSERT_EQ(parsed->diagnostics(), std::vector<std::string>{});
  const std::string dump = parsed->dump();
  EXPECT_NE(dump.find("(attributed (attribute Immutable)\n"), std::string::npos) << dump;
  EXPECT_EQ(printModule(*parsed->module), "void f() {\n  [Immutable] {\n    x = 1;\n  }\n  x = 2;\n}\n");
}

// Chains of binary operators are printed, dumped and copied (a type shared
// by two fields) in a loop: 10000 terms would otherwise recurse 10000 deep.
// Parentheses inside a chain must survive, wherever they stand.
TEST(RoundTrip, LongOperatorChains) {
  std::string sum = "((a - b) - (c - d)) * e";
  std::string size = "1";
  for (int i = 0; i < 10000; ++i) {
    sum += i % 5 == 0 ? " - (a + b) * c" : i % 3 == 0 ? " / d" : " + a";
    size += "+1";
  }
  expectRoundTrip("void f() { x = " + sum + "; y = (" + sum +
                      ", a) << b; }\n"
                      "struct S { float[" +
                      size + "] a, b; };",
                  "long chains");
  EXPECT_EQ(
      test::dumpOf("(a - b) * c - d / (e + f)"),
      "(binary - (binary * (binary - (name a) (name b)) (name c)) (binary / (name d) (binary + (name e) (name f))))");
}

// The examples of docs/language.md must be valid, too.
TEST(RoundTrip, DocumentationExamples) {
  const std::string doc = readFile(fs::path(SPIRE_SOURCE_DIR) / "docs" / "language.md");
  const std::string open = "```spire\n";
  size_t count = 0;
  for (size_t begin = doc.find(open); begin != std::string::npos; begin = doc.find(open, begin)) {
    begin += open.size();
    const size_t end = doc.find("```", begin);
    ASSERT_NE(end, std::string::npos);
    expectRoundTrip(doc.substr(begin, end - begin), fmt::format("example {} of docs/language.md", ++count));
  }
  EXPECT_GE(count, 3u);
}

// The folders hold the project's pipelines, standard library and examples;
// they may still be empty, which is not an error.
TEST(RoundTrip, EveryShippedSpireFile) {
  size_t count = 0;
  for (const char* folder : {"examples", "pipelines", "stdlib"}) {
    const fs::path root = fs::path(SPIRE_SOURCE_DIR) / folder;
    std::error_code error;
    if (!fs::is_directory(root, error)) continue;
    std::vector<fs::path> files;
    for (const auto& entry : fs::recursive_directory_iterator(root, error)) {
      if (entry.is_regular_file() && entry.path().extension() == ".spire") files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end());
    for (const fs::path& file : files) {
      expectRoundTrip(readFile(file), file.string());
      ++count;
    }
  }
  RecordProperty("files", static_cast<int>(count));
}

}  // namespace
}  // namespace spire
