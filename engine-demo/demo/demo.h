// The `spire-demo` command line, callable in-process so tests see exactly
// what a user sees: renders a scene file's variants headless, measures each
// against the first, and writes PNGs, a comparison image and a report.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

namespace spire::demo {

// Runs spire-demo with `args` (without the program name). The table goes to
// `out`; diagnostics, validation messages and usage errors to `err`. Exit
// status: 0 success, 1 errors in the input or while rendering, 2 bad usage,
// 3 no usable Vulkan device.
int runDemo(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

}  // namespace spire::demo
