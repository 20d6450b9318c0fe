// Whether a window can open: the tests that need one skip without it, so
// they run under xvfb-run in CI and do not fail on a headless machine.
#pragma once

#include <cstdlib>

namespace spire::testing {

inline bool haveDisplay() {
  for (const char* name : {"DISPLAY", "WAYLAND_DISPLAY"}) {
    const char* value = std::getenv(name);
    if (value != nullptr && value[0] != '\0') return true;
  }
  return false;
}

}  // namespace spire::testing
