// Command-line parsing shared by the engine's tools (spire-demo, spire-tune):
// --help prints usage and succeeds, anything CLI11 rejects is a usage error
// with a pointer to --help.
#pragma once

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "renderer/error_report.h"

namespace spire::engine {

// Parses `args` (without the program name). nullopt means go on; otherwise
// the exit status to return.
inline std::optional<int> parseToolArguments(CLI::App& app, const std::vector<std::string>& args, std::string_view tool,
                                             std::ostream& out, std::ostream& err) {
  // CLI11 consumes a vector from its back.
  std::vector<std::string> reversed(args.rbegin(), args.rend());
  try {
    app.parse(reversed);
  } catch (const CLI::Success&) {
    out << app.help();
    return kToolSuccess;
  } catch (const CLI::ParseError& e) {
    err << fmt::format("{0}: error: {1}\nRun '{0} --help' for usage.\n", tool, e.what());
    return kToolUsageError;
  }
  return std::nullopt;
}

}  // namespace spire::engine
