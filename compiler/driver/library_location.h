// Where spirec finds the Spire library that ships with it (stdlib/ and
// pipelines/, for `using "stdlib/lighting.spire";`): relative to the running
// executable, so that an install can be moved. In an install it is
// PREFIX/share/spire beside PREFIX/bin/spirec; in a build tree it is
// build/share/spire, which CMake links to the source tree's folders.
#pragma once

#include <filesystem>
#include <optional>

namespace spire {

// The running program's own file (/proc/self/exe), or nullopt where the
// system does not say.
std::optional<std::filesystem::path> runningExecutable();

// EXE_DIR/../share/spire when that is a directory, else nullopt.
std::optional<std::filesystem::path> bundledLibraryDir(const std::filesystem::path& executable);

}  // namespace spire
