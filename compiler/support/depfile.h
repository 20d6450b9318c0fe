// Make-syntax dependency files ("depfiles"), as `gcc -MD` writes them, so that
// a build tool (Make, Ninja, CMake's add_custom_command DEPFILE) reruns a
// command when any file it read changes.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "support/expected.h"

namespace spire {

// `path` escaped for a Make rule: a space or '#' gets a backslash (as do the
// backslashes before a space or '#', and a trailing one), '$' is doubled.
// Make and Ninja (1.10 and later) both read this spelling. A path with a
// newline cannot be written in Make syntax at all: that is a failure.
Expected<std::string, Failure> escapeMakePath(std::string_view path);

// "target: prereq1 \\\n  prereq2\n": one rule, one prerequisite a line, each
// listed once in the order given.
Expected<std::string, Failure> makeDepfile(std::string_view target, const std::vector<std::string>& prerequisites);

}  // namespace spire
