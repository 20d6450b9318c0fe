#include "support/diagnostic.h"

#include <gtest/gtest.h>

#include "support/diagnostic_renderer.h"

namespace spire {
namespace {

TEST(Diagnostics, RendersLocationSourceLineAndCaret) {
  SourceManager sm;
  const FileId f = sm.addFile("t.spire", "float x = mixFactr;\n");
  DiagnosticList list;
  list.report(DiagCode::E3001, {f, 10, 18}, "undeclared identifier 'mixFactr'")
      .note({f, 6, 7}, "declared here");
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

TEST(Diagnostics, ErrorLimitStopsCollection) {
  DiagnosticList list(2);
  for (int i = 0; i < 10; ++i) list.report(DiagCode::E1001, {}, "x");
  EXPECT_TRUE(list.limitReached());
  ASSERT_EQ(list.all().size(), 3u);
  EXPECT_EQ(list.all().back().code, DiagCode::E2005);
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
