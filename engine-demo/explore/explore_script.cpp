#include "explore/explore_script.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <array>
#include <charconv>
#include <cstdint>
#include <optional>
#include <string_view>
#include <type_traits>

#include "driver/exit_codes.h"
#include "explore/explorer_model.h"
#include "support/file_io.h"

namespace spire::explore {
namespace {

struct Word {
  std::string_view text;
  uint32_t offset = 0;  // in the file
};

// The line's words, up to a comment.
std::vector<Word> splitWords(std::string_view line, uint32_t lineOffset) {
  std::vector<Word> words;
  size_t i = 0;
  while (i < line.size()) {
    if (line[i] == ' ' || line[i] == '\t' || line[i] == '\r') {
      ++i;
      continue;
    }
    if (line[i] == '#' || line.substr(i, 2) == "//") break;
    const size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
    words.push_back({line.substr(start, i - start), lineOffset + static_cast<uint32_t>(start)});
  }
  return words;
}

struct Verb {
  std::string_view name;
  ActionKind kind;
  size_t arguments;  // words after the verb; `set` is special (NAME = VALUE)
  // The last argument may be left out: `save` and `load` then use the file
  // of the window's Save and Load buttons (--save-to).
  bool lastOptional = false;
};

constexpr std::array<Verb, 26> kVerbs{{{"set", ActionKind::Set, 3},
                                       {"unset", ActionKind::Unset, 1},
                                       {"reset", ActionKind::Reset, 0},
                                       {"load", ActionKind::Load, 1, true},
                                       {"save", ActionKind::Save, 1, true},
                                       {"undo", ActionKind::Undo, 0},
                                       {"walk", ActionKind::Walk, 2},
                                       {"view", ActionKind::View, 1},
                                       {"wait-frames", ActionKind::WaitFrames, 1},
                                       {"wait-reload", ActionKind::WaitReload, 0},
                                       {"screenshot", ActionKind::Screenshot, 1},
                                       {"screenshot-window", ActionKind::WindowShot, 1},
                                       {"load-tune", ActionKind::LoadTune, 1},
                                       {"apply-front", ActionKind::ApplyFront, 1},
                                       {"instance", ActionKind::Instance, 1},
                                       {"quit", ActionKind::Quit, 0},
                                       {"policy until", ActionKind::PolicyUntil, 2},
                                       {"policy member", ActionKind::PolicyMember, 2},
                                       {"policy hysteresis", ActionKind::PolicyHysteresis, 1},
                                       {"policy transition", ActionKind::PolicyTransition, 1},
                                       {"policy add", ActionKind::PolicyAdd, 2},
                                       {"policy remove", ActionKind::PolicyRemove, 1},
                                       {"policy save", ActionKind::PolicySave, 1, true},
                                       {"policy undo", ActionKind::PolicyUndo, 0},
                                       {"policy redo", ActionKind::PolicyRedo, 0},
                                       {"fly-frame", ActionKind::FlyFrame, 1}}};

const char* usageOf(ActionKind kind) {
  switch (kind) {
    case ActionKind::Set: return "set CHOICE = PLACEMENT";
    case ActionKind::Unset: return "unset CHOICE";
    case ActionKind::Load: return "load [FILE]";
    case ActionKind::Save: return "save [FILE]";
    case ActionKind::View: return "view variant|reference|error|hazards|split";
    case ActionKind::WaitFrames: return "wait-frames N";
    case ActionKind::Walk: return "walk N SEED";
    case ActionKind::Screenshot: return "screenshot FILE";
    case ActionKind::WindowShot: return "screenshot-window FILE";
    case ActionKind::LoadTune: return "load-tune DIR";
    case ActionKind::ApplyFront: return "apply-front K";
    case ActionKind::Instance: return "instance N";
    case ActionKind::PolicyUntil: return "policy until LEVEL DIST";
    case ActionKind::PolicyMember: return "policy member LEVEL NAME";
    case ActionKind::PolicyHysteresis: return "policy hysteresis X";
    case ActionKind::PolicyTransition: return "policy transition N";
    case ActionKind::PolicyAdd: return "policy add NAME DIST";
    case ActionKind::PolicyRemove: return "policy remove LEVEL";
    case ActionKind::PolicySave: return "policy save [FILE]";
    case ActionKind::FlyFrame: return "fly-frame N";
    default: return "";
  }
}

template <class T>
bool parseNumber(std::string_view text, std::type_identity_t<T> lowest, std::type_identity_t<T> highest, T& value) {
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  return ec == std::errc{} && end == text.data() + text.size() && value >= lowest && value <= highest;
}

SourceRange rangeOf(FileId file, const Word& word) {
  return {file, word.offset, word.offset + static_cast<uint32_t>(word.text.size())};
}

// The policy's edits are verbs of two words (`policy until`): joined into
// one word, spaces and all, so that their arguments follow the verb as
// other actions' do. Returns the verb's name.
std::string joinPolicyVerb(std::vector<Word>& words) {
  if (words.size() < 2 || words.front().text != "policy") return std::string(words.front().text);
  const Word& second = words[1];
  const std::string name = fmt::format("policy {}", second.text);
  const char* begin = words.front().text.data();
  words.front().text = std::string_view(begin, static_cast<size_t>(second.text.data() + second.text.size() - begin));
  words.erase(words.begin() + 1);
  return name;
}

// The numbers of the level-of-detail actions; false after reporting one
// that is not.
bool parseLodArguments(FileId file, const std::vector<Word>& words, ScriptAction& action, DiagnosticList& diags) {
  const auto count = [&](const Word& word, uint32_t highest, const char* what) {
    if (parseNumber<uint32_t>(word.text, 0, highest, action.count)) return true;
    diags.report(DiagCode::E7201, rangeOf(file, word), fmt::format("expected {} from 0 to {}", what, highest));
    return false;
  };
  const auto number = [&](const Word& word, const char* what) {
    // Finite and within a float: whether it makes a valid policy is the policy reader's to say.
    if (parseNumber<double>(word.text, -1e30, 1e30, action.number)) return true;
    diags.report(DiagCode::E7201, rangeOf(file, word), fmt::format("expected {} (a number)", what));
    return false;
  };
  switch (action.kind) {
    case ActionKind::PolicyUntil: return count(words[1], 254, "a level") && number(words[2], "a distance");
    case ActionKind::PolicyMember: action.value = std::string(words[2].text); return count(words[1], 254, "a level");
    case ActionKind::PolicyHysteresis: return number(words[1], "a hysteresis");
    case ActionKind::PolicyTransition: return count(words[1], 100000, "a frame count");
    case ActionKind::PolicyAdd: action.value = std::string(words[1].text); return number(words[2], "a distance");
    case ActionKind::PolicyRemove: return count(words[1], 254, "a level");
    case ActionKind::FlyFrame: return count(words[1], 100000, "a fly-through frame");
    default: return true;
  }
}

// The action of one line's words, or the error's message and where.
std::optional<ScriptAction> parseLine(FileId file, std::vector<Word> words, SourceRange line, DiagnosticList& diags) {
  const std::string name = joinPolicyVerb(words);
  const Verb* verb = nullptr;
  for (const Verb& v : kVerbs) verb = v.name == name ? &v : verb;
  if (!verb) {
    std::string names;
    for (const Verb& v : kVerbs) names += fmt::format("{}{}", names.empty() ? "" : ", ", v.name);
    diags.report(DiagCode::E7201, rangeOf(file, words.front()),
                 fmt::format("unknown action '{}' (actions: {})", name, names));
    return std::nullopt;
  }
  const bool badSet = verb->kind == ActionKind::Set && words.size() == 4 && words[2].text != "=";
  const bool shortened = verb->lastOptional && words.size() == verb->arguments;
  if ((words.size() != verb->arguments + 1 && !shortened) || badSet) {
    const Word& at = words.size() > verb->arguments + 1 ? words[verb->arguments + 1] : words.back();
    const std::string usage = verb->arguments == 0 ? fmt::format("'{}' takes nothing after it", verb->name)
                                                   : fmt::format("expected '{}'", usageOf(verb->kind));
    diags.report(DiagCode::E7201, badSet ? rangeOf(file, words[2]) : rangeOf(file, at), usage);
    return std::nullopt;
  }
  ScriptAction action{verb->kind, {}, {}, 0, 0.0, 0, line};
  if (words.size() > 1 && !isLodAction(verb->kind)) action.target = std::string(words[1].text);
  if (verb->kind == ActionKind::PolicySave && words.size() > 1) action.target = std::string(words[1].text);
  if (verb->kind == ActionKind::Set) action.value = std::string(words[3].text);
  if (verb->kind == ActionKind::WaitFrames || verb->kind == ActionKind::Walk) {
    const char* what = verb->kind == ActionKind::Walk ? "a change count" : "a frame count";
    if (!parseNumber<uint32_t>(words[1].text, 1, 100000, action.count)) {
      diags.report(DiagCode::E7201, rangeOf(file, words[1]), fmt::format("expected {} from 1 to 100000", what));
      return std::nullopt;
    }
  }
  if (verb->kind == ActionKind::ApplyFront && !parseNumber<uint32_t>(words[1].text, 0, 100000, action.count)) {
    diags.report(DiagCode::E7201, rangeOf(file, words[1]), "expected a front point from 0 (the fastest) to 100000");
    return std::nullopt;
  }
  if (verb->kind == ActionKind::Instance && !parseNumber<uint32_t>(words[1].text, 0, 100000, action.count)) {
    diags.report(DiagCode::E7201, rangeOf(file, words[1]), "expected an instance index from 0 to 100000");
    return std::nullopt;
  }
  if (verb->kind == ActionKind::Walk && !parseNumber<uint64_t>(words[2].text, 0, UINT64_MAX, action.seed)) {
    diags.report(DiagCode::E7201, rangeOf(file, words[2]), "expected a seed (a whole number)");
    return std::nullopt;
  }
  if (isLodAction(verb->kind) && !parseLodArguments(file, words, action, diags)) return std::nullopt;
  if (verb->kind == ActionKind::View) {
    if (!viewModeNamed(action.target)) {
      diags.report(DiagCode::E7201, rangeOf(file, words[1]),
                   fmt::format("unknown view '{}' (views: variant, reference, error, hazards, split)", action.target));
      return std::nullopt;
    }
  }
  return action;
}

}  // namespace

bool isLodAction(ActionKind kind) { return kind >= ActionKind::PolicyUntil; }

std::vector<ScriptAction> parseScript(const SourceManager& sources, FileId file, DiagnosticList& diags) {
  const SourceFile& source = sources.file(file);
  std::vector<ScriptAction> actions;
  bool failed = false;
  for (size_t i = 0; i < source.lineStarts.size(); ++i) {
    const uint32_t start = source.lineStarts[i];
    const std::string_view line = sources.lineText(file, static_cast<uint32_t>(i + 1));
    const std::vector<Word> words = splitWords(line, start);
    if (words.empty()) continue;
    const SourceRange range{file, words.front().offset,
                            words.back().offset + static_cast<uint32_t>(words.back().text.size())};
    std::optional<ScriptAction> action = parseLine(file, words, range, diags);
    failed = failed || !action;
    if (action) actions.push_back(std::move(*action));
  }
  if (failed) actions.clear();
  return actions;
}

std::optional<int> loadScriptFile(engine::ToolRun& run, const std::filesystem::path& path,
                                  std::vector<ScriptAction>& actions) {
  auto text = readFileBytes(path.string());
  if (!text) {
    return run.fail({fmt::format("cannot read script '{}': {}", path.string(), text.error().message()), {}, {}});
  }
  const FileId file = run.sources().addFile(path.string(), std::move(text).value());
  actions = parseScript(run.sources(), file, run.diagnostics());
  if (run.diagnostics().hasErrors()) {
    run.reporter().flush();
    return kExitInputError;
  }
  return std::nullopt;
}

void reportScriptError(engine::ToolRun& run, const ScriptAction& action, const std::string& message) {
  run.diagnostics().report(DiagCode::E7202, action.range, message);
  run.reporter().flush();
}

std::filesystem::path scriptRelative(const std::optional<std::filesystem::path>& script, const std::string& path) {
  const std::filesystem::path p(path);
  if (p.is_absolute() || !script) return p;
  return script->parent_path() / p;
}

std::string describeAction(const SourceManager& sources, const ScriptAction& action) {
  return std::string(sources.text(action.range));
}

Expected<void, Failure> writeSessionLog(const std::filesystem::path& path, const nlohmann::ordered_json& document) {
  return writeFileAtomically(path.string(),
                             document.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) + "\n");
}

}  // namespace spire::explore
