#include "measure/report_table.h"

#include <gtest/gtest.h>

#include <limits>
#include <sstream>

namespace spire::measure {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

std::vector<ReportRow> sampleRows() {
  return {
      {"reference", 12.5, 80.25, 0.0, 1.0, 0.0, kInfinity, 0.0, 0},
      {"baked_albedo", 5.1875, 60.0, 3.5, 2.40963855, 0.0312345, 30.1079, 0.25, 0},
      {"broken", 4.0, 50.0, 0.0, 3.125, kInfinity, 0.0, kInfinity, 17},
  };
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

TEST(ReportTableTest, TextTableIsAlignedAndPrintsInf) {
  std::string text = formatTextTable(sampleRows());
  EXPECT_EQ(text,
            "variant       frame ms  first use ms  prebake ms  speedup     rmse  psnr dB  max error  NaN px\n"
            "----------------------------------------------------------------------------------------------\n"
            "reference       12.500        80.250       0.000    1.00x        0      inf          0       0\n"
            "baked_albedo     5.188        60.000       3.500    2.41x  0.03123    30.11       0.25       0\n"
            "broken           4.000        50.000       0.000    3.12x      inf     0.00        inf      17\n");
  for (const std::string& line : lines(text)) EXPECT_EQ(line.size(), lines(text)[0].size()) << line;
}

TEST(ReportTableTest, MarkdownTable) {
  std::vector<ReportRow> rows = sampleRows();
  rows[1].variant = "a|b";
  std::vector<std::string> markdown = lines(formatMarkdownTable(rows));
  ASSERT_EQ(markdown.size(), 5u);
  EXPECT_EQ(markdown[0],
            "| variant | frame ms | first use ms | prebake ms | speedup | rmse | psnr dB | max error | NaN px |");
  EXPECT_EQ(markdown[1], "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |");
  EXPECT_EQ(markdown[2], "| reference | 12.500 | 80.250 | 0.000 | 1.00x | 0 | inf | 0 | 0 |");
  EXPECT_EQ(markdown[3], "| a\\|b | 5.188 | 60.000 | 3.500 | 2.41x | 0.03123 | 30.11 | 0.25 | 0 |");
  EXPECT_EQ(markdown[4], "| broken | 4.000 | 50.000 | 0.000 | 3.12x | inf | 0.00 | inf | 17 |");
}

TEST(ReportTableTest, NonFiniteValuesAreSpelledOut) {
  ReportRow row{"odd",      kInfinity,
                -kInfinity, std::numeric_limits<double>::quiet_NaN(),
                kInfinity,  std::numeric_limits<double>::quiet_NaN(),
                -kInfinity, kInfinity,
                0};
  EXPECT_EQ(lines(formatMarkdownTable({row}))[2], "| odd | inf | -inf | nan | inf | nan | -inf | inf | 0 |");
}

TEST(ReportTableTest, EmptyTableHasOnlyTheHeader) {
  EXPECT_EQ(lines(formatTextTable({})).size(), 2u);
  EXPECT_EQ(lines(formatMarkdownTable({})).size(), 2u);
}

}  // namespace
}  // namespace spire::measure
