// The exit status of every Spire command line (spirec, spire-demo,
// spire-tune): scripts and CI tell a broken input from a broken command line
// by it, so all tools must agree on the numbers.
#pragma once

namespace spire {

enum ExitCode : int {
  kExitSuccess = 0,
  kExitInputError = 1,  // errors in the inputs (sources, scenes, decisions) or while running
  kExitUsageError = 2,  // a command line the tool cannot run
  kExitNoDevice = 3,    // no usable Vulkan device (only the tools that render)
  // Stopped by SIGINT or SIGTERM after leaving its work resumable (spire-tune);
  // 128 + SIGINT, as a shell reports a command it interrupted.
  kExitInterrupted = 130,
};

}  // namespace spire
