// What a rewrite works on and what it makes, shared by spire-simplify's one
// step from the author's source (simplification.h) and the greedy search,
// which rewrites the definition its previous level wrote (engine-demo/search):
// the components a run may rewrite, and a definition's text with one rewrite
// applied under a new variation name.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "sema/semantic_model.h"
#include "simplify/rewrite_rules.h"
#include "support/expected.h"
#include "support/source_manager.h"
#include "syntax/ast.h"

namespace spire::simplify {

// Whether the component is marked [Immutable] (no rule may touch it).
bool immutable(const sem::Component& component);

// What a module of variations derives from.
struct DerivationBase {
  // The shaders a variation must suit, or the module does not compile: the
  // shader named, or for a shader derived from a group (`Barrel :
  // LodMaterial`) the one it makes from each required member
  // (`Barrel<LodHQ>`; one made from an optional member that a variation does
  // not suit is left out of the derived group, with the compiler's warning).
  // Never empty: a group has a required member.
  std::vector<const sem::Shader*> required;
  // For a shader derived from a group: a shader derived from it is a
  // group's too (`BarrelSimplified : Barrel` makes
  // `BarrelSimplified<LodHQ>`, ...), and only the definitions
  // `Barrel` writes itself are rewritten; the members' own differ from
  // member to member.
  bool fromGroup = false;

  // The shader whose components and definitions are rewritten: the first
  // of `required`.
  const sem::Shader& shader() const { return *required.front(); }
  // The shader that `derived : <the shader named>` makes for shader().
  std::string derivedShader(const std::string& derived) const;
};

// The shader named `name` to derive a module of variations from; or why
// there is none: no such shader, one that a group makes (derive from the
// shader it is made for), or an abstract shader (one derived from it would
// have to define what it leaves abstract).
Expected<DerivationBase, Failure> shaderToDerive(const sem::Model& model, const std::string& name);

struct ComponentSelection {
  std::vector<const sem::Component*> components;
  // Why each component a run would otherwise take was left out: a base
  // finalizes a world it may be computed in (sema/locked_worlds.h), and a
  // shader derived from `shader`, where rewrites go, could not redefine it.
  std::vector<std::string> lockedOut;
};

// The components of `base` to rewrite, in the shader's order: `wanted`, or
// every one when it is empty, never the pipeline's, [Immutable] ones, those
// a derived shader may not redefine, nor, from a group, those the shader
// does not define itself. Naming one of those, or a component the shader
// lacks, is an error.
Expected<ComponentSelection, Failure> selectComponents(const DerivationBase& base,
                                                       const std::vector<std::string>& wanted);

// Whether the module rewrites `definition` of `base`'s shader: from a
// group, only those the shader writes itself.
bool rewritable(const DerivationBase& base, const sem::Definition& definition);

// `decl`'s source with `rewrite` applied, named `variation` (which replaces
// the variation it had, if any).
std::string rewrittenText(const SourceManager& sources, const ast::ComponentDecl& decl, const Rewrite& rewrite,
                          const std::string& variation);

// `decl`'s source named `variation`, with `shift` (Spire source of a
// constant of the definition's type) added to every value it gives: its
// expression, or each returned value, as `((value) + shift)`. Pellacini
// 2005's renormalization of a candidate. nullopt when a `return` lies in an
// [Immutable] statement, which nothing may change.
std::optional<std::string> shiftedText(const SourceManager& sources, const ast::ComponentDecl& decl,
                                       const std::string& shift, const std::string& variation);

// Where rewrittenText puts `rewrite`'s replacement in its result: after the
// name, whose variation part grew or shrank.
size_t replacementOffset(const ast::ComponentDecl& decl, const Rewrite& rewrite, const std::string& variation);

// The definition of `component` named `variation` in a compiled shader (a
// rewrite's, found again in the module it was compiled in); null when the
// shader has none.
const ast::ComponentDecl* definitionNamed(const sem::Shader& shader, const std::string& component,
                                          const std::string& variation);

// Why a rewrite that must keep `type` (Rewrite::type: a user rule's, which
// can compile to another type, `vec3 * float` for `vec3 * vec3`, and mean
// something else) does not, found in `model` where the rewritten definition
// compiled as `decl`, its replacement `replacement` at `replacementAt` of
// its text; nullopt when the type is kept.
std::optional<std::string> replacementTypeError(const sem::Model& model, const ast::ComponentDecl& decl,
                                                size_t replacementAt, const std::string& replacement,
                                                const std::string& type);

}  // namespace spire::simplify
