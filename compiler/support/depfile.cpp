#include "support/depfile.h"

#include <fmt/format.h>

#include <unordered_set>

namespace spire {

Expected<std::string, Failure> escapeMakePath(std::string_view path) {
  if (path.find_first_of("\n\r") != std::string_view::npos) {
    return Failure{
        fmt::format("cannot list '{}' in a depfile: Make syntax has no way to write a newline in a path", path)};
  }
  std::string escaped;
  size_t backslashes = 0;  // the run of backslashes just copied
  for (const char c : path) {
    if (c == ' ' || c == '#') {
      escaped.append(backslashes + 1, '\\');  // each backslash before it, and the character itself
    }
    if (c == '$') escaped += '$';
    escaped += c;
    backslashes = c == '\\' ? backslashes + 1 : 0;
  }
  escaped.append(backslashes, '\\');  // a trailing backslash would join the next line
  return escaped;
}

Expected<std::string, Failure> makeDepfile(std::string_view target, const std::vector<std::string>& prerequisites) {
  auto rule = escapeMakePath(target);
  if (!rule) return rule.error();
  std::string text = std::move(rule).value() + ":";
  std::unordered_set<std::string> listed;
  for (const std::string& prerequisite : prerequisites) {
    if (!listed.insert(prerequisite).second) continue;
    auto escaped = escapeMakePath(prerequisite);
    if (!escaped) return escaped.error();
    text += " \\\n  " + escaped.value();
  }
  return text + "\n";
}

}  // namespace spire
