#include "tune/run_settings.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <map>
#include <sstream>
#include <system_error>

#include "scene/scene_inputs.h"
#include "support/content_hash.h"
#include "support/file_io.h"

namespace spire::tune {

namespace {

namespace fs = std::filesystem;

constexpr const char* kFileName = "settings.txt";
constexpr const char* kHeader =
    "# spire-tune: what this directory's rows were measured with; a rerun resumes them only with the same\n";

// A path as an absolute one, so that a rerun from another working
// directory names the same file the same way.
std::string absolutePath(const std::string& path) {
  if (path.empty()) return path;
  std::error_code ec;
  fs::path absolute = fs::absolute(path, ec);
  if (ec) return path;
  absolute = fs::weakly_canonical(absolute, ec);
  return ec ? path : absolute.string();
}

// One line per value: a line break in an argument is written as `\n`.
std::string oneLine(const std::string& value) {
  std::string line;
  for (const char c : value) line += c == '\n' ? std::string("\\n") : std::string(1, c);
  return line;
}

bool hasEntry(const RunSettings& settings, const std::string& name) {
  return std::any_of(settings.entries.begin(), settings.entries.end(),
                     [&](const auto& entry) { return entry.first == name; });
}

// "source PATH" = the content hash of each file once, in the order given.
void addSourceHashes(RunSettings& settings, const SourceManager& sources) {
  for (size_t id = 0; id < sources.fileCount(); ++id) {
    const SourceFile& file = sources.file(static_cast<FileId>(id));
    std::string name = "source " + oneLine(absolutePath(file.path));
    if (!hasEntry(settings, name)) settings.entries.emplace_back(std::move(name), contentHash(file.text));
  }
}

// "source PATH" = the content hash of a file read from disk, once.
void addFileHash(RunSettings& settings, const std::string& path) {
  std::string name = "source " + oneLine(absolutePath(path));
  if (hasEntry(settings, name)) return;
  const std::optional<std::string> text = readWholeFile(path);
  settings.entries.emplace_back(std::move(name), text ? contentHash(*text) : std::string("(unreadable)"));
}

}  // namespace

RunSettings runSettings(const TuneOptions& options, const engine::ToolRun& run, const std::string& reference,
                        const SourceManager& shaderSources) {
  const scene::SceneFile& scene = run.scene();
  RunSettings settings;
  auto add = [&](const char* name, const std::string& value) { settings.entries.emplace_back(name, oneLine(value)); };
  add("scene", absolutePath(options.scenePath));
  add("shader", options.shader);
  add("components", fmt::format("{}", fmt::join(options.components, ",")));
  add("only", fmt::format("{}", fmt::join(options.only, ",")));
  add("max-variants", std::to_string(options.maxVariants));
  add("seed", std::to_string(options.seed));
  add("resolution", fmt::format("{}x{}", scene.width, scene.height));
  add("frames", std::to_string(options.frames));
  add("max-frames", std::to_string(options.maxFrames));
  add("warmup", std::to_string(options.warmup));
  add("bake-size", std::to_string(options.bakeSize));
  add("reference", reference.empty() ? std::string("(the instances' own decisions)") : absolutePath(reference));
  add("param", fmt::format("{}", fmt::join(options.params, " ")));
  add("param-samples", std::to_string(options.paramSamples));
  add("extremes", options.extremes ? "yes" : "no");
  add("device", run.context().selectedDevice().name);
  addSourceHashes(settings, run.sources());
  addSourceHashes(settings, shaderSources);
  // The meshes, images and policy the scene reads: an edited glTF renders
  // another image as surely as an edited shader.
  std::vector<std::string> files;
  for (const fs::path& file : scene::sceneInputFiles(scene)) files.push_back(file.string());
  if (!reference.empty()) files.push_back(reference);
  for (const std::string& file : files) addFileHash(settings, file);
  return settings;
}

std::string settingsText(const RunSettings& settings) {
  std::string text = kHeader;
  for (const auto& [name, value] : settings.entries) text += fmt::format("{}: {}\n", name, value);
  return text;
}

Expected<RunSettings, Failure> parseSettings(const std::string& text, const fs::path& path) {
  RunSettings settings;
  std::istringstream in(text);
  std::string line;
  for (size_t number = 1; std::getline(in, line); ++number) {
    if (line.empty() || line.front() == '#') continue;
    // An empty value may have lost its space to an editor.
    const size_t colon = line.find(':');
    if (colon == std::string::npos || colon == 0) {
      return Failure{fmt::format("{}:{}: not 'name: value': {}", path.string(), number, line)};
    }
    const size_t value = colon + 1 < line.size() && line[colon + 1] == ' ' ? colon + 2 : colon + 1;
    settings.entries.emplace_back(line.substr(0, colon), line.substr(value));
  }
  return settings;
}

Expected<void, Failure> recordOrCheckSettings(const fs::path& directory, const RunSettings& now, bool hasRows) {
  const fs::path path = directory / kFileName;
  // Without rows there is nothing to resume: a run that stopped before it
  // measured anything (a bad reference) leaves its settings to be replaced.
  if (!hasRows) return writeFileAtomically(path.string(), settingsText(now));
  const std::optional<std::string> text = readWholeFile(path.string());
  if (!text) {
    return Failure{
        fmt::format("'{}' holds measured rows but no {} to say what they were measured with (an older spire-tune's, or "
                    "removed); remove the rows or choose another output directory",
                    directory.string(), kFileName)};
  }
  auto recorded = parseSettings(*text, path);
  if (!recorded) return recorded.error();
  const std::map<std::string, std::string> then(recorded->entries.begin(), recorded->entries.end());
  std::vector<std::string> differences;
  for (const auto& [name, value] : now.entries) {
    const auto it = then.find(name);
    const std::string before = it == then.end() ? std::string("(not recorded)") : it->second;
    if (before != value) differences.push_back(fmt::format("{}: '{}' then, '{}' now", name, before, value));
  }
  if (differences.empty()) return {};
  return Failure{fmt::format(
      "'{}' holds the rows of a run with other settings ({}); rerun with those to resume it, or choose another "
      "output directory",
      directory.string(), fmt::join(differences, "; "))};
}

}  // namespace spire::tune
