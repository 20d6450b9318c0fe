#include "support/diagnostic.h"

#include <gtest/gtest.h>

#include "support/diagnostic_renderer.h"

namespace spire {
namespace {

TEST(Diagnostics, RendersLocationSourceLineAndCaret) {
  SourceManager sm;
  const FileId f = sm.addFile("t.spire", "float x = mixFactr;\n");
  DiagnosticList list;
  list.report(DiagCode::E3001, {f, 10, 18}, "undeclared identifier 'mixFactr'").note({f, 6, 7}, "declared here");
  EXPECT_EQ(renderDiagnostics(sm, list, DiagnosticFormat::Text),
            "t.spire:1:11: error[E3001]: undeclared identifier 'mixFactr'\n"
            " 1 | float x = mixFactr;\n"
            "   |           ^~~~~~~~\n"
            "t.spire:1:7: note: declared here\n"
            " 1 | float x = mixFactr;\n"
            "   |       ^\n"
            "1 error generated.\n");
}

TEST(Diagnostics, CaretKeepsTabs) {
  SourceManager sm;
  const FileId f = sm.addFile("t.spire", "\tx;\n");
  DiagnosticList list;
  list.report(DiagCode::E1001, {f, 1, 2}, "stray");
  EXPECT_NE(renderDiagnostics(sm, list, DiagnosticFormat::Text).find("   | \t^\n"), std::string::npos);
}

// The text and caret lines of the one diagnostic at byte `begin` of `line`,
// marking `length` bytes.
std::string snippetOf(const std::string& line, uint32_t begin, uint32_t length) {
  SourceManager sm;
  const FileId f = sm.addFile("t.spire", "first\n" + line + "\nlast\n");
  DiagnosticList list;
  list.report(DiagCode::E1001, {f, 6 + begin, 6 + begin + length}, "here");
  const std::string text = renderDiagnostic(sm, list.all().at(0));
  return text.substr(text.find('\n') + 1);
}

// A long line is quoted as a window of 120 columns around the caret, cut at
// character boundaries, with "..." where it is cut; the caret stays under
// its character and the marking ends with the window.
TEST(Diagnostics, LongLinesAreQuotedAroundTheCaret) {
  std::string line;
  for (int i = 0; i < 1000; ++i) line += static_cast<char>('a' + i % 26);
  EXPECT_EQ(snippetOf(line, 500, 3), " 2 | ..." + line.substr(460, 120) +
                                         "...\n"
                                         "   |    " +
                                         std::string(40, ' ') + "^~~\n");
  EXPECT_EQ(snippetOf(line, 2, 1), " 2 | " + line.substr(0, 120) +
                                       "...\n"
                                       "   |   ^\n");
  EXPECT_EQ(snippetOf(line, 995, 500), " 2 | ..." + line.substr(880) +
                                           "\n"
                                           "   |    " +
                                           std::string(115, ' ') + "^~~~~\n");
  EXPECT_EQ(snippetOf(line, 100, 900), " 2 | ..." + line.substr(60, 120) +
                                           "...\n"
                                           "   |    " +
                                           std::string(40, ' ') + "^" + std::string(79, '~') + "\n");
  // Up to 120 columns the whole line is quoted, whatever its size in bytes.
  std::string wide;
  for (int i = 0; i < 120; ++i) wide += "\xC3\xA9";  // é
  EXPECT_EQ(snippetOf(wide, 20, 2), " 2 | " + wide + "\n   |           ^\n");
  // Cutting never splits a character; tabs before the caret are kept.
  const std::string mixed = wide + "\t" + wide + "x";
  EXPECT_EQ(snippetOf(mixed, 2 * 120 + 1 + 2 * 20, 2), " 2 | ..." + wide.substr(0, 2 * 19) + "\t" +
                                                           wide.substr(0, 2 * 100) +
                                                           "...\n"
                                                           "   |    " +
                                                           std::string(19, ' ') + "\t" + std::string(20, ' ') + "^\n");
}

TEST(Diagnostics, ErrorLimitStopsCollection) {
  DiagnosticList list(2);
  for (int i = 0; i < 10; ++i) list.report(DiagCode::E1001, {}, "x");
  EXPECT_TRUE(list.limitReached());
  ASSERT_EQ(list.all().size(), 3u);
  EXPECT_EQ(list.all().back().code, DiagCode::E2005);
}

// What a worker thread collected in a list of its own joins the main list
// as if reported there: counted, with its notes, under that list's limit.
TEST(Diagnostics, ReportAllAddsAnotherListsDiagnosticsUnderThisListsLimit) {
  DiagnosticList worker(1);
  worker.report(DiagCode::E7102, {}, "first").note({}, "why");
  worker.report(DiagCode::E7102, {}, "second");  // over the worker's limit: E2005
  DiagnosticList main;
  main.report(DiagCode::E7102, {}, "earlier");
  main.reportAll(worker.all());
  ASSERT_EQ(main.all().size(), 2U) << "the worker's E2005 is the worker's limit, not this list's";
  EXPECT_EQ(main.all()[1].message, "first");
  ASSERT_EQ(main.all()[1].notes.size(), 1U);
  EXPECT_EQ(main.all()[1].notes[0].message, "why");
  EXPECT_EQ(main.errorCount(), 2U);

  DiagnosticList small(1);
  small.reportAll(main.all());
  EXPECT_TRUE(small.limitReached());
  EXPECT_EQ(small.errorCount(), 2U) << "one error and E2005";
}

TEST(Diagnostics, JsonCarriesTheSameContent) {
  SourceManager sm;
  const FileId f = sm.addFile("t.spire", "abc\n");
  DiagnosticList list;
  list.report(DiagCode::E1001, {f, 1, 2}, "stray character 'b'");
  const std::string json = renderDiagnostics(sm, list, DiagnosticFormat::Json);
  EXPECT_NE(json.find("\"code\": \"E1001\""), std::string::npos);
  EXPECT_NE(json.find("\"column\": 2"), std::string::npos);
}

TEST(Diagnostics, CatalogueCodesAreUniqueAndOrdered) {
  std::string previous;
  for (DiagCode code : allDiagCodes()) {
    const std::string name(diagCodeInfo(code).name);
    EXPECT_EQ(name.size(), 5u);
    EXPECT_NE(name, previous);
    previous = name;
  }
}

}  // namespace
}  // namespace spire
