#include "explore/policy_editor.h"

#include <fmt/format.h>

#include <algorithm>
#include <limits>

#include "support/diagnostic_renderer.h"

namespace spire::explore {

namespace {

constexpr float kNoEdge = std::numeric_limits<float>::infinity();

}  // namespace

PolicyEditor::PolicyEditor(lod::LodPolicy start) : edited_(start), valid_(std::move(start)) {}

Expected<void, Failure> PolicyEditor::checkLevel(size_t level) const {
  if (level < edited_.levels.size()) return {};
  return Failure{fmt::format("level {}: the policy has {} level(s), from 0", level, edited_.levels.size())};
}

Expected<void, Failure> PolicyEditor::setMember(size_t level, std::string member) {
  if (auto ok = checkLevel(level); !ok) return ok;
  remember();
  edited_.levels[level].member = std::move(member);
  check();
  return {};
}

Expected<void, Failure> PolicyEditor::setUntil(size_t level, float until) {
  if (auto ok = checkLevel(level); !ok) return ok;
  // Left to the reader: an edge on the last level is its error to report.
  remember();
  edited_.levels[level].until = until;
  check();
  return {};
}

void PolicyEditor::setHysteresis(float hysteresis) {
  remember();
  edited_.hysteresis = hysteresis;
  check();
}

void PolicyEditor::setTransitionFrames(uint32_t frames) {
  remember();
  edited_.transitionFrames = frames;
  check();
}

void PolicyEditor::addLevel(std::string member, float until) {
  remember();
  std::vector<lod::LodLevel>& levels = edited_.levels;
  const auto last = levels.empty() ? levels.end() : levels.end() - 1;
  const auto at = std::find_if(levels.begin(), last, [until](const lod::LodLevel& l) { return l.until > until; });
  levels.insert(at, lod::LodLevel{std::move(member), until, {}, {}});
  check();
}

Expected<void, Failure> PolicyEditor::removeLevel(size_t level) {
  if (auto ok = checkLevel(level); !ok) return ok;
  if (edited_.levels.size() == 1) return Failure{"a policy keeps at least one level"};
  remember();
  edited_.levels.erase(edited_.levels.begin() + static_cast<std::ptrdiff_t>(level));
  edited_.levels.back().until = kNoEdge;
  check();
  return {};
}

void PolicyEditor::replace(lod::LodPolicy policy, bool amend) {
  if (!amend || undo_.empty()) remember();
  edited_ = std::move(policy);
  check();
}

void PolicyEditor::remember() {
  undo_.push_back({edited_, valid_});
  redo_.clear();
}

// Moves the newest snapshot of `from` into the editor, and the editor's
// present onto `to`; the diagnostics are the restored policy's.
bool PolicyEditor::restore(std::vector<Snapshot>& from, std::vector<Snapshot>& to) {
  if (from.empty()) return false;
  to.push_back({std::move(edited_), std::move(valid_)});
  edited_ = std::move(from.back().edited);
  valid_ = std::move(from.back().valid);
  from.pop_back();
  check();
  return true;
}

// A fresh source list per check: edits come every frame while a value is
// dragged, and none of them has to outlive its message.
void PolicyEditor::check() {
  SourceManager sources;
  DiagnosticList diags;
  const std::optional<lod::LodPolicy> read = lod::parseLodPolicy("edited policy", text(), sources, diags);
  diagnostics_.clear();
  for (const Diagnostic& d : diags.all()) diagnostics_ += renderDiagnostic(sources, d);
  isValid_ = read.has_value();
  if (isValid_) valid_ = edited_;
}

}  // namespace spire::explore
