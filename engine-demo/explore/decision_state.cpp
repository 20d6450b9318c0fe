#include "explore/decision_state.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>

#include "graph/decision_file.h"

namespace spire::explore {
namespace {

// "Terrain.albedo" -> "albedo".
std::string componentOf(const std::string& key) {
  const size_t dot = key.rfind('.');
  return dot == std::string::npos ? key : key.substr(dot + 1);
}

std::optional<size_t> indexOf(const graph::Choice& choice, const std::string& placement) {
  const auto it = std::find(choice.names.begin(), choice.names.end(), placement);
  if (it == choice.names.end()) return std::nullopt;
  return static_cast<size_t>(it - choice.names.begin());
}

}  // namespace

DecisionState::DecisionState(const graph::ChoiceSpace& space)
    : space_(&space), choices_(graph::enumerateChoices(space)) {}

const graph::Choice* DecisionState::findChoice(const std::string& name) const {
  const std::string component = componentOf(name);
  for (const graph::Choice& choice : choices_) {
    // A qualified name must match the choice's own prefix as well.
    if (componentOf(choice.key) == component && (name == component || name == choice.key)) return &choice;
  }
  return nullptr;
}

std::optional<graph::ChoiceSpace> DecisionState::propagated(const std::map<std::string, std::string>& decisions) const {
  graph::ChoiceSpace space = *space_;
  for (const auto& [component, placement] : decisions) {
    const graph::Choice* choice = findChoice(component);
    if (!choice) continue;
    const std::optional<size_t> index = indexOf(*choice, placement);
    if (!index) continue;
    if (!space.alive(choice->component, choice->alternatives[*index]) ||
        !space.restrict(choice->component, choice->alternatives[*index])) {
      return std::nullopt;
    }
  }
  return space;
}

std::vector<ChoiceRow> DecisionState::rows() const {
  if (rows_) return *rows_;
  std::vector<ChoiceRow> rows;
  for (const graph::Choice& choice : choices_) {
    ChoiceRow row{choice.key, componentOf(choice.key), {}, std::nullopt};
    std::map<std::string, std::string> others = current_.placement;
    if (const auto it = others.find(row.component); it != others.end()) row.decided = it->second;
    // Exactly what set() would accept: propagation keeps alternatives that
    // no single rule rules out, but deciding one of them can still empty
    // another component, so each is tried with the other decisions.
    const std::optional<graph::ChoiceSpace> space = propagated([&] {
      auto without = others;
      without.erase(row.component);
      return without;
    }());
    for (size_t i = 0; i < choice.names.size(); ++i) {
      bool possible = space && space->alive(choice.component, choice.alternatives[i]);
      if (possible) {
        others[row.component] = choice.names[i];
        possible = propagated(others).has_value();
      }
      row.alternatives.push_back({choice.names[i], possible});
    }
    rows.push_back(std::move(row));
  }
  rows_ = rows;
  return rows;
}

Expected<void, Failure> DecisionState::commit(Decided next) {
  if (!propagated(next.placement)) {
    return Failure{"these decisions contradict each other: no variant satisfies them all"};
  }
  undo_.push_back(std::move(current_));
  current_ = std::move(next);
  rows_.reset();
  return {};
}

Expected<void, Failure> DecisionState::set(const std::string& name, const std::string& placement) {
  const graph::Choice* choice = findChoice(name);
  if (!choice) return Failure{fmt::format("'{}' is not a choice of this shader", name)};
  if (!indexOf(*choice, placement)) {
    return Failure{fmt::format("'{}' is not an alternative of '{}' (its alternatives: {})", placement, choice->key,
                               fmt::join(choice->names, ", "))};
  }
  Decided next = current_;
  const std::string component = componentOf(choice->key);
  next.placement[component] = placement;
  // Attributes belong to the decision they came with.
  next.attributes.erase(component);
  if (!propagated(next.placement)) {
    return Failure{fmt::format("'{} = {}' is impossible with the other decisions{}", choice->key, placement,
                               blockers(next.placement, component))};
  }
  return commit(std::move(next));
}

std::string DecisionState::blockers(const std::map<std::string, std::string>& decisions,
                                    const std::string& changed) const {
  std::vector<std::string> names;
  for (const auto& [component, placement] : decisions) {
    if (component == changed) continue;
    std::map<std::string, std::string> without = decisions;
    without.erase(component);
    if (propagated(without)) names.push_back(fmt::format("{} (now {})", component, placement));
  }
  if (names.empty()) return "";
  return fmt::format("; change or unset {}", fmt::join(names, " or "));
}

Expected<void, Failure> DecisionState::unset(const std::string& name) {
  const graph::Choice* choice = findChoice(name);
  if (!choice) return Failure{fmt::format("'{}' is not a choice of this shader", name)};
  Decided next = current_;
  if (next.placement.erase(componentOf(choice->key)) == 0) {
    return Failure{fmt::format("'{}' has no decision", choice->key)};
  }
  next.attributes.erase(componentOf(choice->key));
  return commit(std::move(next));
}

Expected<void, Failure> DecisionState::replace(const std::map<std::string, std::string>& decisions,
                                               const ShaderLibrary::Attributes& attributes) {
  Decided next;
  for (const auto& [name, placement] : decisions) {
    const graph::Choice* choice = findChoice(name);
    if (!choice) return Failure{fmt::format("'{}' is not a choice of this shader", name)};
    if (!indexOf(*choice, placement)) {
      return Failure{fmt::format("'{}' is not an alternative of '{}'", placement, choice->key)};
    }
    const std::string component = componentOf(choice->key);
    next.placement[component] = placement;
    if (const auto it = attributes.find(name); it != attributes.end()) next.attributes[component] = it->second;
  }
  return commit(std::move(next));
}

bool DecisionState::undo() {
  if (undo_.empty()) return false;
  current_ = std::move(undo_.back());
  rows_.reset();
  undo_.pop_back();
  return true;
}

std::string DecisionState::decisionFileText(std::string_view comment) const {
  graph::DecisionFile file;
  for (const graph::Choice& choice : choices_) {
    const auto it = current_.placement.find(componentOf(choice.key));
    if (it == current_.placement.end()) continue;
    const size_t dot = choice.key.rfind('.');
    const auto attributes = current_.attributes.find(it->first);
    file.lines.push_back(graph::makeDecision(choice.key.substr(0, dot), it->first, it->second,
                                             attributes == current_.attributes.end()
                                                 ? std::vector<std::pair<std::string, std::string>>{}
                                                 : attributes->second));
  }
  return graph::writeDecisionFile(file, comment);
}

}  // namespace spire::explore
