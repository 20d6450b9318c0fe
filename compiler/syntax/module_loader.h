// Loads source files and everything they include with `using "file";`.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "support/diagnostic.h"
#include "support/file_io.h"
#include "support/source_manager.h"
#include "syntax/ast.h"
#include "syntax/parser.h"

namespace spire {

struct LoadOptions {
  std::vector<std::string> includeDirs;  // searched after the including file's directory
  ParseLimits parseLimits;
  // Reads a whole file; unset, the file system (whose errors are reported
  // with their reason). Tests and the fuzzer substitute an in-memory map.
  FileReader readFile;
};

// Each file is loaded once (by normalized path) however often it is included;
// an include cycle is an error (E1102) at the `using` that closes it. Modules
// are appended to the program in post-order: a file's includes come before it.
// Each file also gets its logical name (SourceFile::logicalName): its path
// relative to a root directory, which is the first input file's directory
// for inputs and what is found next to them, and the include directory for a
// file found through one (and what is found next to that file).
class ModuleLoader {
 public:
  ModuleLoader(SourceManager& sources, DiagnosticList& diags, LoadOptions options);
  ~ModuleLoader();

  // A file named on the command line. Returns false if it could not be read.
  bool loadFile(const std::string& path, ast::Program& program);
  // In-memory source, e.g. from a test; includes resolve relative to
  // `displayPath`'s directory.
  void loadSource(std::string displayPath, std::string text, ast::Program& program);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace spire
