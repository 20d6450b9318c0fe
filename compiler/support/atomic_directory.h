// Output that is written as a set: a reader sees every old file or every new
// one, never a mix (a kernel beside the reflection of another variant).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "support/expected.h"

namespace spire {

using FileSet = std::vector<std::pair<std::string, std::string>>;  // file name -> contents

// Makes `dir` a directory holding exactly `files`. They are written to a
// staging directory beside `dir`, which is then exchanged with `dir` in one
// rename, and the old contents are removed. On failure `dir` is untouched,
// nothing is left beside it, and the message says why.
Expected<void, Failure> replaceDirectoryAtomically(const std::string& dir, const FileSet& files);

}  // namespace spire
