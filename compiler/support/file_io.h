// File output that never leaves a partial file behind.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace spire {

// The whole file as bytes; nullopt if it cannot be read or is a directory.
std::optional<std::string> readWholeFile(const std::string& path);

// Writes `contents` to a temporary file next to `path` and renames it over
// `path`. Returns an error message on failure; the target is then untouched.
std::optional<std::string> writeFileAtomically(const std::string& path, std::string_view contents);

}  // namespace spire
