#include "syntax/module_loader.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <unordered_set>

#include "support/file_io.h"
#include "support/utf8.h"

namespace spire {
namespace fs = std::filesystem;

namespace {

// Identifies a file however it was reached (`a/../b.spire`, `./b.spire`):
// absolute and lexically normalized, without touching the file system, so
// that in-memory sources behave like files.
std::string fileKey(const std::string& path) {
  std::error_code error;
  fs::path absolute = fs::absolute(path, error);
  if (error) absolute = path;
  return absolute.lexically_normal().generic_string();
}

// `include` relative to `directory`, kept relative when the directory is, so
// that diagnostics show short paths.
std::string joinPath(const fs::path& directory, const std::string& include) {
  return (directory / include).lexically_normal().generic_string();
}

// The key of a directory, without a trailing '/', so that names relative to
// it do not start with "../".
std::string directoryKey(const fs::path& directory) {
  std::string key = fileKey(directory.empty() ? std::string(".") : directory.string());
  while (key.size() > 1 && key.back() == '/') key.pop_back();
  return key;
}

// A file's name in generated code: its key relative to its root directory.
// Both are absolute and normalized, so neither the working directory nor the
// spelling of a path changes it (docs/reflection.md, "#line directives").
std::string logicalName(const std::string& key, const std::string& root) {
  std::string name = fs::path(key).lexically_relative(root).generic_string();
  return name.empty() ? key : name;
}

}  // namespace

struct ModuleLoader::Impl {
  struct OpenFile {
    std::string key;
    std::string displayPath;
    std::string root;  // key of the directory its logical name is relative to
  };

  SourceManager& sources;
  DiagnosticList& diags;
  LoadOptions options;
  std::unordered_set<std::string> loaded;  // keys of files loaded or being loaded
  std::vector<OpenFile> openFiles;         // the chain of includes being loaded
  // Root of the files named by the user: the first one's directory.
  std::optional<std::string> inputRoot;

  // A file named by the user (or given in memory) is named relative to the
  // directory of the first such file. One that declares nothing (empty, or
  // only whitespace and comments) is an error (E1104): it is a wrong or
  // truncated file far more often than intended, and would otherwise
  // compile to nothing without a word. An include may be empty.
  void loadInput(std::string displayPath, std::string key, std::string text, ast::Program& program) {
    if (!inputRoot) inputRoot = fs::path(key).parent_path().generic_string();
    const uint32_t errors = diags.errorCount();
    const ast::Module* module = load(displayPath, std::move(key), *inputRoot, std::move(text), program);
    if (module && module->decls.empty() && diags.errorCount() == errors) {
      diags.report(DiagCode::E1104, {module->file, 0, 0},
                   fmt::format("'{}' declares nothing: it is empty or holds only comments", displayPath));
    }
  }

  // Parses a file, loads what it includes, then appends it to the program.
  // Returns its module, or null when it is not text.
  const ast::Module* load(const std::string& displayPath, std::string key, const std::string& root, std::string text,
                          ast::Program& program) {
    loaded.insert(key);
    const FileId file = sources.addFile(displayPath, std::move(text), logicalName(key, root));
    if (!isText(file)) return nullptr;
    auto module = parseModule(sources, file, program, diags, options.parseLimits);
    openFiles.push_back({std::move(key), displayPath, root});
    for (const auto& decl : module->decls) {
      if (diags.limitReached()) break;
      if (const auto* include = ast::dyn_cast<ast::UsingDecl>(decl.get())) {
        loadInclude(*include, displayPath, root, program);
      }
    }
    openFiles.pop_back();
    program.modules.push_back(std::move(module));
    return program.modules.back().get();
  }

  // Binary files would only produce a flood of stray-character errors.
  bool isText(FileId file) {
    const std::string& text = sources.file(file).text;
    const size_t nul = text.find('\0');
    const size_t invalid = utf8::firstInvalidByte(text);
    const size_t bad = std::min(nul, invalid);
    if (bad == std::string::npos) return true;
    const auto offset = static_cast<uint32_t>(bad);
    diags.report(DiagCode::E1103, {file, offset, offset + 1},
                 bad == nul ? fmt::format("'{}' is not a source file: it contains a NUL byte", sources.file(file).path)
                            : fmt::format("'{}' is not valid UTF-8 text", sources.file(file).path));
    return false;
  }

  // The including file's directory first, then the include directories. A
  // file found next to its includer shares the includer's root; one found
  // through `-I DIR` is named relative to DIR, whoever includes it.
  void loadInclude(const ast::UsingDecl& include, const std::string& includerPath, const std::string& includerRoot,
                   ast::Program& program) {
    struct Candidate {
      std::string path;
      std::string root;
    };
    std::vector<Candidate> candidates = {{joinPath(fs::path(includerPath).parent_path(), include.path), includerRoot}};
    for (const auto& dir : options.includeDirs) candidates.push_back({joinPath(dir, include.path), directoryKey(dir)});

    // A candidate that exists but cannot be read (a directory, no
    // permission) is named with the reason; the others were just not there.
    std::vector<std::string> unreadable;
    for (auto& candidate : candidates) {
      std::string key = fileKey(candidate.path);
      const auto open =
          std::find_if(openFiles.begin(), openFiles.end(), [&](const OpenFile& f) { return f.key == key; });
      if (open != openFiles.end()) return reportCycle(include, open);
      if (loaded.contains(key)) return;
      auto text = readThrough(options.readFile, candidate.path);
      if (text) {
        load(candidate.path, std::move(key), candidate.root, std::move(text).value(), program);
        return;
      }
      if (text.error() != std::errc::no_such_file_or_directory && text.error() != std::errc::not_a_directory) {
        unreadable.push_back(fmt::format("cannot read '{}': {}", candidate.path, text.error().message()));
      }
    }
    std::string searched;
    for (const auto& candidate : candidates) searched += (searched.empty() ? "'" : ", '") + candidate.path + "'";
    Diagnostic& d =
        diags.report(DiagCode::E1101, include.pathRange, fmt::format("cannot open included file '{}'", include.path))
            .note({}, "searched " + searched);
    for (std::string& reason : unreadable) d.note({}, std::move(reason));
  }

  void reportCycle(const ast::UsingDecl& include, std::vector<OpenFile>::const_iterator first) {
    std::string chain;
    for (auto it = first; it != openFiles.end(); ++it) chain += it->displayPath + " -> ";
    chain += first->displayPath;
    diags.report(DiagCode::E1102, include.range, "include cycle: " + chain);
  }
};

ModuleLoader::ModuleLoader(SourceManager& sources, DiagnosticList& diags, LoadOptions options)
    : impl_(std::make_unique<Impl>(Impl{sources, diags, std::move(options), {}, {}, {}})) {}

ModuleLoader::~ModuleLoader() = default;

bool ModuleLoader::loadFile(const std::string& path, ast::Program& program) {
  std::string key = fileKey(path);
  if (impl_->loaded.contains(key)) return true;
  auto text = readThrough(impl_->options.readFile, path);
  if (!text) {
    impl_->diags.report(DiagCode::E1101, {},
                        fmt::format("cannot open source file '{}': {}", path, text.error().message()));
    return false;
  }
  impl_->loadInput(path, std::move(key), std::move(text).value(), program);
  return true;
}

void ModuleLoader::loadSource(std::string displayPath, std::string text, ast::Program& program) {
  std::string key = fileKey(displayPath);
  impl_->loadInput(std::move(displayPath), std::move(key), std::move(text), program);
}

}  // namespace spire
