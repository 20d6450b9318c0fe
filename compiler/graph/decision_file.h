// Decision files (docs/choices-and-decisions.md): one `Shader.component = World[:variation]`
// per line, with `//` comments and optional attributes before a decision,
// such as `[Format: "RGB10_A2"] Terrain.albedo = PrebakeTex`.
#pragma once

#include <functional>

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "graph/variant.h"
#include "sema/semantic_model.h"
#include "support/diagnostic.h"
#include "support/source_manager.h"

namespace spire::graph {

struct DecisionLine {
  SourceRange range;
  std::string prefix;  // a shader, one of its bases, or a group-derived shader
  SourceRange prefixRange;
  std::string component;
  SourceRange componentRange;
  std::string world;
  SourceRange worldRange;
  std::string variation;  // empty when none
  SourceRange variationRange;
  std::vector<std::pair<std::string, std::string>> attributes;
};

struct DecisionFile {
  std::vector<DecisionLine> lines;
};

// Syntax errors are E5001 errors; the malformed line is skipped. In an
// attribute value, `\n` is a line feed, `\r` a carriage return and a
// backslash before any other character is that character (`\"`, `\\`).
DecisionFile parseDecisionFile(const SourceManager& sources, FileId file, DiagnosticList& diags);

// The one writer of decision text: parseDecisionFile reads back what these
// write (the same prefixes, components, placements and attribute values,
// whatever bytes the values hold). Names are written as they are; attribute
// names must be identifiers.
//
// A decision for `prefix.component` at `placement` as choice files spell it
// ("World" or "World:variation").
DecisionLine makeDecision(std::string prefix, std::string component, std::string_view placement,
                          std::vector<std::pair<std::string, std::string>> attributes = {});
// `value` quoted, with quotes, backslashes and line breaks escaped.
std::string quoteDecisionString(std::string_view value);
// One line: its attributes, then `prefix.component = world[:variation]`.
std::string writeDecisionLine(const DecisionLine& line);
// `comment` as `//` lines (one per line of it), then every decision line.
std::string writeDecisionFile(const DecisionFile& decisions, std::string_view comment = {});

// Warns (W5001) about lines whose prefix names no shader or group at all.
// `knownElsewhere` accepts the prefixes that another library reading the
// same file knows (a scene's variant file is read once per instance's
// source, and each source reads only its own lines).
void checkDecisionPrefixes(const DecisionFile& decisions, const sem::Model& model, DiagnosticList& diags,
                           const std::function<bool(std::string_view)>& knownElsewhere = {});

// Builds the variant of the space's shader from the lines that apply to it,
// warning about unknown components, worlds and variations (W5001),
// decisions outside the choice space (W5003), duplicates (W5004) and
// conflicts (W5002, naming the earlier decision). Every such line is skipped.
std::optional<Variant> applyDecisions(const DecisionFile& decisions, const ChoiceSpace& space, DiagnosticList& diags);

// E5002 when the file has decisions but none of them takes effect in any of
// the shaders it is applied to (`spaces`): a decision file written for
// another shader, or for an older version of this one, would otherwise give
// the default variant with warnings only. A file without decisions asks for
// the default variant and passes.
void checkSomeDecisionApplies(const DecisionFile& decisions, const std::vector<const ChoiceSpace*>& spaces,
                              DiagnosticList& diags);

}  // namespace spire::graph
