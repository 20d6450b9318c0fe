#include "lod/lod_policy.h"

#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "scene/json_value_checker.h"
#include "support/file_io.h"

namespace spire::lod {

namespace {

using scene::JsonKind;
using scene::JsonMember;
using scene::JsonValue;

const scene::KeyList kPolicyKeys = {"levels", "hysteresis", "transitionFrames"};
const scene::KeyList kLevelKeys = {"member", "until"};

class PolicyReader {
 public:
  PolicyReader(const SourceManager& sources, DiagnosticList& diags) : check_(sources, diags), diags_(diags) {}

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
    if (!value.find("member")) check_.missing(value, "a level has no 'member' (the group member it draws with)");
    if (!last && !value.find("until")) check_.missing(value, "a level before the last has no 'until'");
    return level;
  }

  scene::JsonValueChecker check_;
  DiagnosticList& diags_;
};

}  // namespace

std::optional<LodPolicy> parseLodPolicy(std::string displayPath, std::string text, SourceManager& sources,
                                        DiagnosticList& diags) {
  const uint32_t errorsBefore = diags.errorCount();
  const FileId file = sources.addFile(std::move(displayPath), std::move(text));
  const std::optional<JsonValue> root = scene::parseJson(sources, file, diags);
  if (!root) return std::nullopt;
  LodPolicy policy;
  PolicyReader(sources, diags).read(*root, policy);
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

std::string formatLodPolicy(const LodPolicy& policy) {
  std::string text = "{\n  \"levels\": [\n";
  for (size_t i = 0; i < policy.levels.size(); ++i) {
    const LodLevel& level = policy.levels[i];
    text += fmt::format("    {{\"member\": \"{}\"", level.member);
    if (std::isfinite(level.until)) text += fmt::format(", \"until\": {}", level.until);
    text += i + 1 < policy.levels.size() ? "},\n" : "}\n";
  }
  text += fmt::format("  ],\n  \"hysteresis\": {},\n  \"transitionFrames\": {}\n}}\n", policy.hysteresis,
                      policy.transitionFrames);
  return text;
}

}  // namespace spire::lod
