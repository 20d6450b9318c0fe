// Output that is written as a set: a reader sees every old file or every new
// one, never a mix (a kernel beside the reflection of another variant).
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "support/expected.h"

namespace spire {

using FileSet = std::vector<std::pair<std::string, std::string>>;  // file name -> contents

// A directory's new contents, written to a staging directory beside it and
// not yet in its place. Staging is the slow part (creating every file);
// putting it in place is one rename, so a caller that must replace
// directories in some order (spirec --batch) can stage them concurrently and
// commit them in order. An uncommitted stage is removed when destroyed.
class StagedDirectory {
 public:
  // Writes `files` beside `dir` (creating `dir`'s parent folders); on
  // failure nothing is left and the message says why.
  static Expected<StagedDirectory, Failure> stage(const std::string& dir, const FileSet& files);

  StagedDirectory(StagedDirectory&& other) noexcept;
  StagedDirectory& operator=(StagedDirectory&& other) noexcept;
  StagedDirectory(const StagedDirectory&) = delete;
  StagedDirectory& operator=(const StagedDirectory&) = delete;
  ~StagedDirectory();

  // Makes the directory hold exactly the staged files: exchanged with the
  // existing one in one rename (whose old contents are then removed), or
  // renamed into place when there is none. On failure the directory is
  // untouched, the stage is removed and the message says why. Once only.
  Expected<void, Failure> commit();

 private:
  StagedDirectory(std::filesystem::path dir, std::filesystem::path staging);
  void discard();

  std::filesystem::path dir_;
  std::filesystem::path staging_;  // empty once committed or discarded
};

// Makes `dir` a directory holding exactly `files`: staged, then committed.
// On failure `dir` is untouched, nothing is left beside it, and the message
// says why.
Expected<void, Failure> replaceDirectoryAtomically(const std::string& dir, const FileSet& files);

}  // namespace spire
