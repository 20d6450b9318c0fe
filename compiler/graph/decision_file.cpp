#include "graph/decision_file.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <map>

#include "graph/locked_placement.h"
#include "sema/attribute_catalog.h"
#include "support/spelling.h"
#include "support/utf8.h"

namespace spire::graph {
namespace {

// A cursor over one line of a decision file.
class LineParser {
 public:
  LineParser(const std::string& text, FileId file, uint32_t begin, uint32_t end)
      : text_(text), file_(file), pos_(begin), end_(end) {}

  void skipSpace() {
    while (pos_ < end_ && (text_[pos_] == ' ' || text_[pos_] == '\t' || text_[pos_] == '\r')) ++pos_;
    if (pos_ + 1 < end_ && text_[pos_] == '/' && text_[pos_ + 1] == '/') pos_ = end_;
  }
  bool atEnd() {
    skipSpace();
    return pos_ >= end_;
  }
  bool accept(char c) {
    skipSpace();
    if (pos_ < end_ && text_[pos_] == c) {
      ++pos_;
      return true;
    }
    return false;
  }
  // Identifiers, plus `<`, `>` and `.` so that instance names such as
  // `Terrain<BaseMaterialLQ>.albedo` read as one name.
  std::optional<std::pair<std::string, SourceRange>> name(bool allowPath) {
    skipSpace();
    const uint32_t begin = pos_;
    while (pos_ < end_) {
      const char c = text_[pos_];
      const bool ok =
          std::isalnum(static_cast<unsigned char>(c)) || c == '_' || (allowPath && (c == '<' || c == '>' || c == '.'));
      if (!ok) break;
      ++pos_;
    }
    if (pos_ == begin) return std::nullopt;
    return std::make_pair(text_.substr(begin, pos_ - begin), SourceRange{file_, begin, pos_});
  }
  std::optional<std::string> stringLiteral() {
    skipSpace();
    if (pos_ >= end_ || text_[pos_] != '"') return std::nullopt;
    std::string value;
    for (++pos_; pos_ < end_; ++pos_) {
      if (text_[pos_] == '"') {
        ++pos_;
        return value;
      }
      if (text_[pos_] == '\\' && pos_ + 1 < end_) {
        value += unescaped(text_[++pos_]);
        continue;
      }
      value += text_[pos_];
    }
    return std::nullopt;
  }
  // The character an escape `\c` stands for; quoteDecisionString is its
  // inverse.
  static char unescaped(char c) {
    if (c == 'n') return '\n';
    if (c == 'r') return '\r';
    return c;
  }
  SourceRange here() {
    skipSpace();
    return {file_, pos_, pos_ < end_ ? pos_ + 1 : pos_};
  }
  uint32_t position() const { return pos_; }

 private:
  const std::string& text_;
  FileId file_;
  uint32_t pos_;
  uint32_t end_;
};

std::optional<DecisionLine> parseLine(LineParser& p, FileId file, DiagnosticList& diags) {
  DecisionLine line;
  const uint32_t begin = p.here().begin;
  auto fail = [&](std::string message) -> std::optional<DecisionLine> {
    diags.report(DiagCode::E5001, p.here(), std::move(message));
    return std::nullopt;
  };
  while (p.accept('[')) {
    auto attr = p.name(false);
    if (!attr) return fail("expected an attribute name after '['");
    std::optional<std::string> value;
    SourceRange valueRange = attr->second;
    if (p.accept(':')) {
      const SourceRange literal = p.here();
      value = p.stringLiteral();
      if (!value) return fail("expected a quoted attribute value, as in [Format: \"RGBA8\"]");
      // The value reaches reflection.json, and JSON holds only UTF-8 text.
      if (utf8::firstInvalidByte(*value) != std::string::npos) {
        diags.report(DiagCode::E5001, literal, "the attribute value is not valid UTF-8 text");
        return std::nullopt;
      }
      valueRange = {file, literal.begin, p.position()};
    }
    if (!p.accept(']')) return fail("expected ']' to close the attribute");
    if (auto problem = sem::checkAttribute(sem::AttributeSite::Decision, attr->first, value)) {
      diags.report(problem->isError ? DiagCode::E5010 : DiagCode::W5011, problem->atValue ? valueRange : attr->second,
                   std::move(problem->message));
    }
    line.attributes.emplace_back(attr->first, value.value_or(""));
  }
  auto path = p.name(true);
  if (!path) return fail("expected 'Shader.component = World' in the decision file");
  const size_t dot = path->first.rfind('.');
  if (dot == std::string::npos || dot == 0 || dot + 1 == path->first.size()) {
    diags.report(DiagCode::E5001, path->second,
                 fmt::format("expected 'Shader.component', not '{}': a decision names its shader", path->first));
    return std::nullopt;
  }
  line.prefix = path->first.substr(0, dot);
  line.prefixRange = {file, path->second.begin, path->second.begin + static_cast<uint32_t>(dot)};
  line.component = path->first.substr(dot + 1);
  line.componentRange = {file, line.prefixRange.end + 1, path->second.end};
  if (!p.accept('=')) return fail("expected '=' after the component name");
  auto world = p.name(false);
  if (!world) return fail("expected a world name after '='");
  line.world = world->first;
  line.worldRange = world->second;
  if (p.accept(':')) {
    auto variation = p.name(false);
    if (!variation) return fail("expected a variation name after ':'");
    line.variation = variation->first;
    line.variationRange = variation->second;
  }
  p.accept(';');
  if (!p.atEnd()) return fail("unexpected text after the decision");
  line.range = {file, begin, p.position()};
  return line;
}

std::string skipped(const std::optional<std::string>& suggestion) {
  return suggestion ? fmt::format("did you mean '{}'? The decision is skipped", *suggestion)
                    : std::string("the decision is skipped");
}

std::string spell(const DecisionLine& line) {
  return fmt::format("{}.{} = {}{}", line.prefix, line.component, line.world,
                     line.variation.empty() ? "" : ":" + line.variation);
}

// Names a decision line may use for `shader`: its own, its bases', and that
// of the group-derived declaration it instantiates.
bool appliesTo(const std::string& prefix, const sem::Shader& shader) {
  for (const sem::Shader* s = &shader; s; s = s->base) {
    if (s->name == prefix) return true;
  }
  return shader.derivedFrom && shader.decl->name == prefix;
}

// The lines of a decision file that apply to one shader, as requests for
// buildVariant, each with the line it comes from.
struct Requests {
  std::vector<DecisionRequest> requests;
  std::vector<const DecisionLine*> origins;
};

// The unknown names (W5001), placements outside the space (W5003) and
// duplicates (W5004) among the lines for the space's shader are reported
// and skipped; lines for other shaders are left out silently.
Requests collectRequests(const DecisionFile& decisions, const ChoiceSpace& space, DiagnosticList& diags) {
  const ShaderGraph& graph = space.graph();
  const sem::Shader& shader = graph.shader();
  const sem::Pipeline& pipeline = graph.pipeline();
  Requests result;
  std::map<sem::ComponentId, const DecisionLine*> decided;

  for (const DecisionLine& line : decisions.lines) {
    if (!appliesTo(line.prefix, shader)) continue;
    const sem::Shader* named = nullptr;
    for (const sem::Shader* s = &shader; s && !named; s = s->base) {
      if (s->name == line.prefix) named = s;
    }
    const sem::ComponentSet& scope = named ? static_cast<const sem::ComponentSet&>(*named) : shader;
    const auto componentIt = scope.componentByName.find(line.component);
    if (componentIt == scope.componentByName.end()) {
      std::vector<std::string_view> names;
      for (const sem::Component& c : scope.components) names.push_back(c.name);
      const auto suggestion = closestSpelling(line.component, names);
      diags.report(DiagCode::W5001, line.componentRange,
                   fmt::format("'{}' has no component '{}'; {}", line.prefix, line.component, skipped(suggestion)));
      continue;
    }
    const sem::ComponentId id = shader.componentByName.at(line.component);
    const ComponentNode& node = graph.node(id);
    if (!pipeline.findWorld(line.world)) {
      std::vector<std::string_view> names;
      for (const sem::World& w : pipeline.worlds) names.push_back(w.name);
      const auto suggestion = closestSpelling(line.world, names);
      diags.report(
          DiagCode::W5001, line.worldRange,
          fmt::format("unknown world '{}' in pipeline '{}'; {}", line.world, pipeline.name, skipped(suggestion)));
      continue;
    }
    if (std::find(node.variations.begin(), node.variations.end(), line.variation) == node.variations.end()) {
      std::string known;
      for (const std::string& v : node.variations) {
        known += fmt::format("{}'{}'", known.empty() ? "" : ", ", v.empty() ? "(none)" : v);
      }
      diags.report(DiagCode::W5001, line.variation.empty() ? line.worldRange : line.variationRange,
                   line.variation.empty()
                       ? fmt::format("'{}.{}' needs a variation name (it has {}); the decision is skipped", line.prefix,
                                     line.component, known)
                       : fmt::format("component '{}' has no variation '{}' (it has {}); the decision is skipped",
                                     line.component, line.variation, known));
      continue;
    }
    const auto alt = graph.findAlternative(node, line.world, line.variation);
    if (!alt || !space.alive(id, *alt)) {
      std::string choices;
      for (AltId a : space.aliveAlternatives(id)) {
        choices += fmt::format("{}{}", choices.empty() ? "" : ", ", graph.altName(node, a));
      }
      diags.report(DiagCode::W5003, SourceRange::cover(line.worldRange, line.variationRange),
                   fmt::format("'{}' is not a possible placement of '{}.{}' (possible: {}); the decision is skipped",
                               line.variation.empty() ? line.world : line.world + ":" + line.variation, line.prefix,
                               line.component, choices.empty() ? "none" : choices));
      continue;
    }
    if (auto previous = decided.find(id); previous != decided.end()) {
      const DecisionLine& earlier = *previous->second;
      if (earlier.world == line.world && earlier.variation == line.variation) {
        diags.report(DiagCode::W5004, line.range, fmt::format("duplicate decision '{}'", spell(line)))
            .note(earlier.range, "the same decision is made here");
        continue;
      }
    } else {
      decided[id] = &line;
    }
    result.requests.push_back({id, *alt, line.attributes, lockDepth(shader, named ? named->name : shader.name)});
    result.origins.push_back(&line);
  }
  return result;
}

// A decision skipped because the shader that makes it is below a finalizer,
// where the same decision by the finalizer applies: what the finalized
// worlds see is the base's to decide (locked_placement.h). The finalizer
// can make it when the alternative is one of its own definitions.
bool reportBelowFinalizer(const ChoiceSpace& space, const std::vector<DecisionRequest>& requests, size_t i,
                          const DecisionLine& line, DiagnosticList& diags) {
  const DecisionRequest& request = requests[i];
  if (request.lockDepth == 0) return false;
  std::vector<DecisionRequest> asBase = requests;
  asBase[i].lockDepth = request.lockDepth - 1;
  if (buildVariant(space, asBase).outcomes[i].status != DecisionStatus::Applied) return false;
  const sem::Shader& shader = space.graph().shader();
  const sem::Shader& finalizer = *lockLevels(shader)[asBase[i].lockDepth].finalizer;
  const Alternative& alt = space.graph().node(request.component).alternatives[request.alternative];
  const bool finalizersOwn = lockDepth(shader, alt.definition->origin) <= asBase[i].lockDepth;
  diags.report(DiagCode::W5002, line.range,
               fmt::format("decision '{}' is skipped: it would change, for '{}' alone, kernels that every shader "
                           "derived from '{}' shares{}",
                           spell(line), line.prefix, finalizer.name,
                           finalizersOwn ? fmt::format("; decide '{}.{}' to place it for all of them", finalizer.name,
                                                       line.component)
                                         : ""));
  return true;
}

}  // namespace

DecisionFile parseDecisionFile(const SourceManager& sources, FileId file, DiagnosticList& diags) {
  DecisionFile result;
  const SourceFile& f = sources.file(file);
  for (size_t i = 0; i < f.lineStarts.size(); ++i) {
    const uint32_t begin = f.lineStarts[i];
    const uint32_t end = i + 1 < f.lineStarts.size() ? f.lineStarts[i + 1] - 1 : static_cast<uint32_t>(f.text.size());
    if (begin > end) continue;
    LineParser parser(f.text, file, begin, end);
    if (parser.atEnd()) continue;
    if (auto line = parseLine(parser, file, diags)) result.lines.push_back(std::move(*line));
    if (diags.limitReached()) break;
  }
  return result;
}

DecisionLine makeDecision(std::string prefix, std::string component, std::string_view placement,
                          std::vector<std::pair<std::string, std::string>> attributes) {
  DecisionLine line;
  line.prefix = std::move(prefix);
  line.component = std::move(component);
  const size_t colon = placement.find(':');
  line.world = placement.substr(0, colon);
  if (colon != std::string_view::npos) line.variation = placement.substr(colon + 1);
  line.attributes = std::move(attributes);
  return line;
}

std::string quoteDecisionString(std::string_view value) {
  std::string quoted = "\"";
  for (const char c : value) {
    if (c == '\n')
      quoted += "\\n";
    else if (c == '\r')
      quoted += "\\r";
    else if (c == '"' || c == '\\')
      quoted += {'\\', c};
    else
      quoted += c;
  }
  return quoted + '"';
}

std::string writeDecisionLine(const DecisionLine& line) {
  std::string text;
  for (const auto& [name, value] : line.attributes) text += fmt::format("[{}: {}] ", name, quoteDecisionString(value));
  return text + spell(line) + "\n";
}

std::string writeDecisionFile(const DecisionFile& decisions, std::string_view comment) {
  std::string text;
  for (size_t begin = 0; begin < comment.size();) {
    const size_t end = std::min(comment.find('\n', begin), comment.size());
    text += fmt::format("// {}\n", comment.substr(begin, end - begin));
    begin = end + 1;
  }
  for (const DecisionLine& line : decisions.lines) text += writeDecisionLine(line);
  return text;
}

void checkDecisionPrefixes(const DecisionFile& decisions, const sem::Model& model, DiagnosticList& diags,
                           const std::function<bool(std::string_view)>& knownElsewhere) {
  std::vector<std::string_view> names;
  for (const auto& s : model.shaders) names.push_back(s->name);
  for (const auto& g : model.groups) names.push_back(g->name);
  for (const DecisionLine& line : decisions.lines) {
    if (model.findShader(line.prefix) || model.findGroup(line.prefix)) continue;
    if (knownElsewhere && knownElsewhere(line.prefix)) continue;
    const auto suggestion = closestSpelling(line.prefix, names);
    diags.report(DiagCode::W5001, line.prefixRange,
                 fmt::format("unknown shader '{}'; {}", line.prefix, skipped(suggestion)));
  }
}

std::optional<Variant> applyDecisions(const DecisionFile& decisions, const ChoiceSpace& space, DiagnosticList& diags) {
  const sem::Shader& shader = space.graph().shader();
  const auto [requests, origins] = collectRequests(decisions, space, diags);
  VariantResult result = buildVariant(space, requests);
  for (size_t i = 0; i < requests.size(); ++i) {
    const DecisionOutcome& outcome = result.outcomes[i];
    if (outcome.status != DecisionStatus::Conflict) continue;
    if (reportBelowFinalizer(space, requests, i, *origins[i], diags)) continue;
    const DecisionLine& earlier = *origins[outcome.conflictsWith];
    Diagnostic& d =
        diags.report(DiagCode::W5002, origins[i]->range,
                     outcome.conflictsWith == i
                         ? fmt::format("decision '{}' leaves no valid variant and is skipped", spell(*origins[i]))
                         : fmt::format("decision '{}' conflicts with the earlier decision '{}' and is skipped",
                                       spell(*origins[i]), spell(earlier)));
    if (outcome.conflictsWith != i) d.note(earlier.range, "the earlier decision is here");
  }
  if (!result.variant && !reportLockedMove(space, diags)) {
    diags.report(DiagCode::E4017, shader.decl->nameRange, fmt::format("shader '{}' has no valid variant", shader.name));
  }
  return std::move(result.variant);
}

void checkSomeDecisionApplies(const DecisionFile& decisions, const std::vector<const ChoiceSpace*>& spaces,
                              DiagnosticList& diags) {
  if (decisions.lines.empty() || spaces.empty()) return;
  bool named = false;
  for (const ChoiceSpace* space : spaces) {
    // Quietly: applyDecisions has already said why lines are skipped.
    DiagnosticList quiet(UINT32_MAX);
    const Requests requests = collectRequests(decisions, *space, quiet);
    const VariantResult result = buildVariant(*space, requests.requests);
    const auto applied = [](const DecisionOutcome& o) { return o.status == DecisionStatus::Applied; };
    if (std::any_of(result.outcomes.begin(), result.outcomes.end(), applied)) return;
    named = named || std::any_of(decisions.lines.begin(), decisions.lines.end(), [&](const DecisionLine& line) {
              return appliesTo(line.prefix, space->graph().shader());
            });
  }
  const auto quoted = [](const std::vector<std::string_view>& names) {
    std::string text;
    for (std::string_view name : names) text += fmt::format("{}'{}'", text.empty() ? "" : ", ", name);
    return text;
  };
  std::vector<std::string_view> shaders;
  for (const ChoiceSpace* space : spaces) shaders.push_back(space->graph().shader().name);
  std::vector<std::string_view> prefixes;
  for (const DecisionLine& line : decisions.lines) {
    if (std::find(prefixes.begin(), prefixes.end(), line.prefix) == prefixes.end()) prefixes.push_back(line.prefix);
  }
  diags.report(DiagCode::E5002, decisions.lines.front().prefixRange,
               fmt::format("no decision in this file applies to {} {}: {}", shaders.size() == 1 ? "shader" : "shaders",
                           quoted(shaders),
                           named ? fmt::format("every decision for {} is skipped", shaders.size() == 1 ? "it" : "them")
                                 : "its decisions are for " + quoted(prefixes)));
}

}  // namespace spire::graph
