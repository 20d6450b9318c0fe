// The command-line conventions every Spire tool shares (driver/tool_arguments.h).
#include "driver/tool_arguments.h"

#include <gtest/gtest.h>

#include <sstream>

#include "driver/exit_codes.h"

namespace spire {
namespace {

struct Parsed {
  std::optional<int> status;
  std::string out;
  std::string err;
  std::string directory = "unset";
};

Parsed parse(const std::vector<std::string>& args) {
  CLI::App app{"a tool", "some-tool"};
  Parsed parsed;
  addVersionFlag(app);
  addOutputDirectory(app, parsed.directory, "Write to DIR");
  std::ostringstream out, err;
  parsed.status = parseToolArguments(app, args, out, err);
  parsed.out = out.str();
  parsed.err = err.str();
  return parsed;
}

TEST(ToolArguments, HelpAndVersionPrintAndSucceed) {
  const Parsed help = parse({"--help"});
  EXPECT_EQ(help.status, kExitSuccess);
  EXPECT_NE(help.out.find("-o,--output DIR"), std::string::npos) << help.out;
  const Parsed version = parse({"--version"});
  EXPECT_EQ(version.status, kExitSuccess);
  EXPECT_EQ(version.out, std::string("some-tool ") + SPIRE_VERSION + "\n");
  EXPECT_EQ(version.err, "");
}

TEST(ToolArguments, BadUsageIsExitTwoWithAPointerToHelp) {
  const Parsed unknown = parse({"--no-such-flag"});
  EXPECT_EQ(unknown.status, kExitUsageError);
  EXPECT_EQ(unknown.err.rfind("some-tool: error: ", 0), 0U) << unknown.err;
  EXPECT_NE(unknown.err.find("Run 'some-tool --help' for usage.\n"), std::string::npos) << unknown.err;
  EXPECT_EQ(unknown.out, "");
}

TEST(ToolArguments, OutputIsANonEmptyDirectory) {
  const Parsed given = parse({"-o", "out/dir"});
  EXPECT_EQ(given.status, std::nullopt) << given.err;
  EXPECT_EQ(given.directory, "out/dir");
  const Parsed empty = parse({"-o", ""});
  EXPECT_EQ(empty.status, kExitUsageError);
  EXPECT_NE(empty.err.find("the output directory must not be empty"), std::string::npos) << empty.err;
  EXPECT_EQ(parse({"--output="}).status, kExitUsageError);
}

TEST(ToolArguments, UsageErrorNamesTheToolAndHelp) {
  std::ostringstream err;
  EXPECT_EQ(usageError("some-tool", "a scene file is required", err), kExitUsageError);
  EXPECT_EQ(err.str(), "some-tool: error: a scene file is required\nRun 'some-tool --help' for usage.\n");
}

}  // namespace
}  // namespace spire
