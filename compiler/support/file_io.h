// Reading whole files with the reason when it fails, and file output that
// never leaves a partial file behind.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>

#include "support/expected.h"

namespace spire {

// The whole file as bytes, or the error that stopped reading it: the
// system's (no such file, permission denied, ...), is_a_directory, or
// file_too_large beyond the 4 GiB that source offsets can address.
Expected<std::string, std::error_code> readFileBytes(const std::string& path);

// As readFileBytes, for callers that have no use for the reason.
std::optional<std::string> readWholeFile(const std::string& path);

// Reads a file in place of the file system (tests and the fuzzer read from
// memory); nullopt when it has no such file.
using FileReader = std::function<std::optional<std::string>(const std::string& path)>;

// Reads through `reader` when it is set, else from the file system. What
// `reader` does not have is no_such_file_or_directory.
Expected<std::string, std::error_code> readThrough(const FileReader& reader, const std::string& path);

// Writes `contents` to a temporary file next to `path` and renames it over
// `path`. On failure the target is untouched and the message says why.
Expected<void, Failure> writeFileAtomically(const std::string& path, std::string_view contents);

// Creates `path` holding `contents`, failing if it exists. Not atomic: only
// for a file in a directory that no reader sees yet (a staging directory,
// replaced into place as a whole).
Expected<void, Failure> writeNewFile(const std::string& path, std::string_view contents);

}  // namespace spire
