// A shader's simplified variations as Spire source: every rewrite that
// rewrite_rules.h proposes for a component's definition becomes a variation
// of that component (`albedo:simplified1`) in a shader derived from the
// original (`TerrainSimplified : Terrain`), so spirec's choices, spire-tune
// and spire-explore offer them like any variation a person wrote, and a
// person can read and edit them. Components marked [Immutable] are left as
// they are. User rules (user_rules.h) add their rewrites to the built-in
// ones; what they write must keep the type it replaces. Every variation
// written compiles: the module is compiled with its
// sources before it is returned, and a candidate that does not compile is
// dropped with the reason.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "driver/shader_library.h"
#include "simplify/user_rules.h"
#include "support/expected.h"

namespace spire::simplify {

struct SimplifyOptions {
  std::string shader;
  // Components to simplify; empty: every component the shader and its bases
  // define (not the pipeline's, not inputs, not [Immutable] ones).
  std::vector<std::string> components;
  // The rewrites of all of a component's definitions are ranked together
  // (rankRewrites: the largest saving first) and the first N kept.
  size_t maxPerComponent = 4;
  // Where the module will be written: its `using` names the shader's source
  // relative to this file's folder.
  std::string outputPath;
  std::string derivedName;   // default: the shader's name + "Simplified"
  FrontEndOptions frontEnd;  // for compiling the module (its -I folders)
  // Rules read from rule files (user_rules.h), proposing rewrites beside
  // the built-in ones; null: the built-in ones only.
  const UserRules* userRules = nullptr;
};

struct Variation {
  std::string component;  // "albedo"
  std::string name;       // "albedo:simplified1"
  std::string rule;       // "constant-operand", ..., or a user rule's name
  std::string site;       // "terrain.spire:44:16", the rewritten source
  std::string before;     // the source the rewrite replaced
  std::string after;
  // Scalar operations the variation saves against the definition it
  // rewrites (cost_model.h), costed on the compiled module; negative when it
  // adds some.
  int64_t saving = 0;
};

struct Simplified {
  std::string module;  // the Spire source to write
  std::vector<Variation> variations;
  std::vector<std::string> dropped;  // candidates that did not compile, with why
  // Components left out because a derived shader may not redefine them
  // (rewrite_target.h's ComponentSelection), with why.
  std::vector<std::string> lockedOut;
  // From a group: the compiler's word on each optional member the derived
  // shader lost, because a variation redefines what the member locks.
  std::vector<std::string> membersLeftOut;
};

// `library` must have compiled without errors.
Expected<Simplified, Failure> simplifyShader(const ShaderLibrary& library, const SimplifyOptions& options);

}  // namespace spire::simplify
