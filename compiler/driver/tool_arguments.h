// The command-line conventions of every Spire tool (spirec, spire-demo,
// spire-tune), in one place so that they cannot drift apart: --help and
// --version print to stdout and succeed, anything CLI11 rejects is a usage
// error (exit 2) with a pointer to --help, and -o,--output names an output
// directory.
#pragma once

#include <CLI/CLI.hpp>

#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

namespace spire {

// Adds --version, printing "<tool> <version>" (the app's name and the
// project version).
void addVersionFlag(CLI::App& app);

// Adds -o,--output DIR. An empty DIR is a usage error: it would otherwise
// mean the current directory or "no output" depending on the tool.
CLI::Option* addOutputDirectory(CLI::App& app, std::string& directory, const std::string& description);

// Parses `args` (without the program name) with the app's name as the tool's
// name in messages. nullopt means go on; otherwise the exit status to return.
std::optional<int> parseToolArguments(CLI::App& app, const std::vector<std::string>& args, std::ostream& out,
                                      std::ostream& err);

// Prints "<tool>: error: <message>" and the pointer to --help; returns
// kExitUsageError.
int usageError(std::string_view tool, std::string_view message, std::ostream& err);

}  // namespace spire
