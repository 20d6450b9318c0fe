// File output that never leaves a partial file behind.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace spire {

// Writes `contents` to a temporary file next to `path` and renames it over
// `path`. Returns an error message on failure; the target is then untouched.
std::optional<std::string> writeFileAtomically(const std::string& path, std::string_view contents);

}  // namespace spire
