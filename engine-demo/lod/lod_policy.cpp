#include "lod/lod_policy.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <limits>
#include <set>
#include <vector>

#include "scene/json_value_checker.h"
#include "support/file_io.h"

namespace spire::lod {

namespace {

using scene::JsonKind;
using scene::JsonMember;
using scene::JsonValue;

const scene::KeyList kPolicyKeys = {"levels", "hysteresis", "transitionFrames"};
const scene::KeyList kLevelKeys = {"member", "decisions", "until", "blend"};

class PolicyReader {
 public:
  // `folder`: where the policy file is, which its decision files' paths are
  // relative to.
  PolicyReader(const SourceManager& sources, DiagnosticList& diags, std::filesystem::path folder)
      : check_(sources, diags), diags_(diags), folder_(std::move(folder)) {}

  void read(const JsonValue& root, LodPolicy& policy) {
    policy.range = root.openingRange();
    if (!check_.expectKind(root, JsonKind::Object, "the policy")) return;
    for (const JsonMember& member : root.members) {
      if (member.key == "levels") {
        readLevels(member.value, policy);
      } else if (member.key == "hysteresis") {
        if (auto h = check_.real(member.value, "'hysteresis'", scene::Bounds{0.0, 1.0, false, true})) {
          policy.hysteresis = *h;
        }
      } else if (member.key == "transitionFrames") {
        if (auto frames = check_.integer(member.value, "'transitionFrames'", 0, 1000))
          policy.transitionFrames = *frames;
      } else {
        check_.unknownKey(member, kPolicyKeys, "the policy");
      }
    }
    if (!root.find("levels")) check_.missing(root, "the policy has no 'levels'");
  }

 private:
  void readLevels(const JsonValue& value, LodPolicy& policy) {
    if (!check_.expectArray(value, "'levels'", 1, 255, "an array of 1 to 255 levels")) return;
    for (size_t i = 0; i < value.elements.size(); ++i) {
      const bool last = i + 1 == value.elements.size();
      LodLevel level = readLevel(value.elements[i], last);
      if (level.blend && (i == 0 || last)) {
        diags_.report(DiagCode::E7004, level.range,
                      "a 'blend' band blends the bands on either side of it: it cannot be the first or the last");
      }
      if (!last && !policy.levels.empty() && level.until <= policy.levels.back().until) {
        diags_.report(DiagCode::E7004, level.range,
                      fmt::format("level {} ends at {}, not beyond level {} ({}): bands go from near to far", i,
                                  level.until, i - 1, policy.levels.back().until));
      }
      policy.levels.push_back(std::move(level));
    }
  }

  LodLevel readLevel(const JsonValue& value, bool last) {
    LodLevel level;
    level.range = value.openingRange();
    level.until = std::numeric_limits<float>::infinity();
    if (!check_.expectKind(value, JsonKind::Object, "a level")) return level;
    for (const JsonMember& member : value.members) {
      if (member.key == "member") {
        if (auto name = check_.text(member.value, "'member'")) level.member = *name;
      } else if (member.key == "decisions") {
        readDecisions(member.value, level);
      } else if (member.key == "blend") {
        if (auto blend = check_.flag(member.value, "'blend'")) level.blend = *blend;
      } else if (member.key == "until") {
        if (last) {
          diags_.report(DiagCode::E7002, member.keyRange,
                        "the last level has no 'until': it draws everything beyond the others");
        } else if (auto until = check_.real(member.value, "'until'", scene::greaterThan(0.0))) {
          level.until = *until;
        }
      } else {
        check_.unknownKey(member, kLevelKeys, "a level");
      }
    }
    if (!value.find("member") && !value.find("decisions")) {
      check_.missing(value, "a level has neither a 'member' (the group member it draws with) nor 'decisions'");
    }
    if (!last && !value.find("until")) check_.missing(value, "a level before the last has no 'until'");
    return level;
  }

  // {"Shader": "file.decisions", ...}: each file must be there now, so that
  // a missing one is reported here and not when a level is first drawn.
  void readDecisions(const JsonValue& value, LodLevel& level) {
    if (!check_.expectKind(value, JsonKind::Object, "'decisions'")) return;
    if (value.members.empty()) check_.missing(value, "'decisions' names no shader");
    for (const JsonMember& member : value.members) {
      auto file = check_.text(member.value, fmt::format("the decisions of '{}'", member.key));
      if (!file) continue;
      const std::filesystem::path path = folder_ / *file;
      std::error_code ec;
      if (!std::filesystem::is_regular_file(path, ec)) {
        diags_.report(DiagCode::E1101, member.value.range,
                      fmt::format("cannot open decision file '{}'", path.generic_string()));
        continue;
      }
      level.decisions.emplace(member.key, path);
    }
  }

  scene::JsonValueChecker check_;
  DiagnosticList& diags_;
  std::filesystem::path folder_;
};

// A member name or decision-file path is any bytes a user gave (a script's
// word, a file name): bytes that are not UTF-8, which JSON cannot hold, are
// written as U+FFFD instead of throwing.
std::string jsonString(const std::string& text) {
  return nlohmann::json(text).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace

std::optional<LodPolicy> parseLodPolicy(std::string displayPath, std::string text, SourceManager& sources,
                                        DiagnosticList& diags) {
  const uint32_t errorsBefore = diags.errorCount();
  const FileId file = sources.addFile(std::move(displayPath), std::move(text));
  const std::optional<JsonValue> root = scene::parseJson(sources, file, diags);
  if (!root) return std::nullopt;
  LodPolicy policy;
  const std::filesystem::path folder = std::filesystem::path(sources.file(file).path).parent_path();
  PolicyReader(sources, diags, folder).read(*root, policy);
  if (diags.errorCount() > errorsBefore || diags.limitReached()) return std::nullopt;
  return policy;
}

std::optional<LodPolicy> loadLodPolicy(const std::filesystem::path& path, SourceManager& sources, DiagnosticList& diags,
                                       SourceRange namedAt) {
  std::optional<std::string> text = readWholeFile(path.string());
  if (!text) {
    diags.report(DiagCode::E1101, namedAt, fmt::format("cannot open level-of-detail policy '{}'", path.string()));
    return std::nullopt;
  }
  return parseLodPolicy(path.string(), std::move(*text), sources, diags);
}

scene::InstanceDesc levelInstance(const scene::InstanceDesc& instance, const LodLevel& level) {
  scene::InstanceDesc drawn = instance;
  if (const auto it = level.decisions.find(instance.shader); it != level.decisions.end()) drawn.decisions = it->second;
  if (!level.member.empty()) drawn.shader = fmt::format("{}<{}>", instance.shader, level.member);
  return drawn;
}

std::string levelName(const LodLevel& level) {
  std::vector<std::string> parts;
  if (!level.member.empty()) parts.push_back(level.member);
  // Each file once, however many shaders draw with it.
  std::set<std::string> stems;
  for (const auto& [shader, path] : level.decisions) {
    if (stems.insert(path.stem().string()).second) parts.push_back(path.stem().string());
  }
  return fmt::format("{}", fmt::join(parts, " "));
}

std::string formatLodPolicy(const LodPolicy& policy, const std::filesystem::path& folder) {
  std::string text = "{\n  \"levels\": [\n";
  for (size_t i = 0; i < policy.levels.size(); ++i) {
    const LodLevel& level = policy.levels[i];
    std::vector<std::string> fields;
    if (!level.member.empty()) fields.push_back(fmt::format("\"member\": {}", jsonString(level.member)));
    if (!level.decisions.empty()) {
      std::vector<std::string> files;
      for (const auto& [shader, path] : level.decisions) {
        const std::filesystem::path written =
            folder.empty() ? path
                           : std::filesystem::absolute(path).lexically_normal().lexically_relative(
                                 std::filesystem::absolute(folder).lexically_normal());
        files.push_back(fmt::format("{}: {}", jsonString(shader), jsonString(written.generic_string())));
      }
      fields.push_back(fmt::format("\"decisions\": {{{}}}", fmt::join(files, ", ")));
    }
    text += fmt::format("    {{{}", fmt::join(fields, ", "));
    if (level.blend) text += ", \"blend\": true";
    if (std::isfinite(level.until)) text += fmt::format(", \"until\": {}", level.until);
    text += i + 1 < policy.levels.size() ? "},\n" : "}\n";
  }
  text += fmt::format("  ],\n  \"hysteresis\": {},\n  \"transitionFrames\": {}\n}}\n", policy.hysteresis,
                      policy.transitionFrames);
  return text;
}

}  // namespace spire::lod
