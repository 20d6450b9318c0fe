// A search step's candidates (He et al. 2015, propose_xforms): each rule's
// first K1 rewrites of every selected component's current definition, the
// one the current level places, read from the compiled module of that level.
// So level k's candidates rewrite level k-1's definitions, and rewrites
// accumulate. The rules are spire-simplify's (compiler/simplify), which order
// their rewrites by the source they remove, most first.
#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "driver/shader_library.h"
#include "search/chain.h"
#include "simplify/average_sites.h"
#include "simplify/user_rules.h"
#include "support/expected.h"

namespace spire::search {

// How the search compiles its modules: as the renderer compiles the
// instance's source (the scene's include folders, its pipeline).
struct ModuleCompile {
  FrontEndOptions frontEnd;
  std::optional<std::string> pipelineSource;
};

// The definition of `component` that `placement` ("Fragment:level2")
// computes: its variation, in its world when the component has a definition
// for that world, else the general one; null when there is none.
const ast::ComponentDecl* currentDecl(const sem::Shader& shader, const sem::Component& component,
                                      const std::string& placement);

// `text`, as if read from `path`, compiled with its sources; the compiler's
// first error when it or the derived shader does not compile.
Expected<std::unique_ptr<ShaderLibrary>, Failure> compileModule(const ModuleCompile& compile, const std::string& path,
                                                                const std::string& text, const std::string& derived);

struct Candidate {
  Rewriting rewriting;  // as measured: variation `candidateJ`
  // A user rule's rewrite must keep this type (simplify::Rewrite::type),
  // checked on the compiled step module; empty for the built-in rules.
  std::string type;
  size_t replacementAt = 0;  // where the replacement starts in rewriting.text
  Rewriting level;           // the same rewrite named as the level it would make
  std::string key;           // the rewrite's identity across steps, for the error cache: the definition it makes
};

struct StepRequest {
  const ShaderLibrary* current = nullptr;  // the compiled module of the current level
  std::string derived;
  Placement placement;  // the current level's
  Placement original;   // level 0's: the variation names grow from its
  std::vector<std::string> components;
  size_t k1 = 1;
  size_t level = 1;                                            // the level the candidates would make
  const std::vector<simplify::UserRule>* userRules = nullptr;  // beside the built-in rules
};

// Every candidate of the step, component by component in `components`
// order, each rule's first K1 per component.
Expected<std::vector<Candidate>, Failure> proposeCandidates(const StepRequest& request);

// The moves of the step (He et al.'s move to vertex and to parameter stage,
// in any pipeline): each selected component's current definition put in
// another world that the level's choice file offers it in, the K1 of least
// cost C per component among those that cost less than the level. A move
// that makes no variant of the level (C cannot be computed) is none.
std::vector<Candidate> proposeMoves(const StepRequest& request);

// A subtree of a component's current definition (simplify/average_sites.h)
// that Pellacini 2005's average rule or He et al. 2015's approximate common
// subexpression elimination replaces: measured by rendering its probe, then
// a candidate (siteCandidate).
struct AverageProbe {
  std::string component;
  std::string placement;  // the component's in the current level: "Fragment", "Fragment:level2"
  simplify::AverageSite site;
};

// Every selected component's first K1 sites of the average rule.
Expected<std::vector<AverageProbe>, Failure> proposeAverageProbes(const StepRequest& request);

// The candidate of rule `rule` that replaces `probe`'s subtree by
// `replacement` (Spire source, parenthesized here), numbered `number` among
// the step's candidates.
Expected<Candidate, Failure> siteCandidate(const StepRequest& request, const AverageProbe& probe,
                                           const std::string& rule, const std::string& replacement, size_t number);

// The variation name of a search's definition: `kind` and `number` after the
// author's variation, if the original placement had one (`ggx_level2`).
std::string searchVariation(const std::string& originalVariation, const std::string& kind, size_t number);

}  // namespace spire::search
