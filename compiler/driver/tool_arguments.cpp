#include "driver/tool_arguments.h"

#include <fmt/format.h>

#include "driver/exit_codes.h"

namespace spire {

void addVersionFlag(CLI::App& app) { app.set_version_flag("--version", app.get_name() + " " + SPIRE_VERSION); }

CLI::Option* addOutputDirectory(CLI::App& app, std::string& directory, const std::string& description) {
  const CLI::Validator nonEmpty(
      [](const std::string& value) {
        return value.empty() ? std::string("the output directory must not be empty") : std::string();
      },
      "DIR", "non-empty");
  return app.add_option("-o,--output", directory, description)->check(nonEmpty)->type_name("DIR");
}

std::optional<int> parseToolArguments(CLI::App& app, const std::vector<std::string>& args, std::ostream& out,
                                      std::ostream& err) {
  // CLI11 consumes a vector from its back.
  std::vector<std::string> reversed(args.rbegin(), args.rend());
  try {
    app.parse(reversed);
  } catch (const CLI::CallForVersion& version) {
    out << version.what() << "\n";
    return kExitSuccess;
  } catch (const CLI::Success&) {
    out << app.help();
    return kExitSuccess;
  } catch (const CLI::ParseError& e) {
    return usageError(app.get_name(), e.what(), err);
  }
  return std::nullopt;
}

int usageError(std::string_view tool, std::string_view message, std::ostream& err) {
  err << fmt::format("{0}: error: {1}\nRun '{0} --help' for usage.\n", tool, message);
  return kExitUsageError;
}

}  // namespace spire
