// Locked worlds (paper section 6.2): a shader derived from a base that
// finalizes a world may neither add definitions there nor redefine what the
// base may compute there. Either would change the locked world's kernel,
// which every shader derived from the base must share. The analyzer
// enforces this; tools that write derived shaders (spire-simplify) ask
// first, so that they never propose what it would refuse.
#pragma once

#include <optional>
#include <string_view>

#include "sema/semantic_model.h"

namespace spire::sem {

// The `finalizes` clause that locks `world` for shaders derived from
// `base`: its own or a base's; null when none does.
const ast::NameRef* finalizingClause(const Shader& base, std::string_view world);

// Whether shaders derived from `base` find `world` locked (finalized by
// `base` or one of its bases).
bool isLocked(const Shader& base, WorldId world);

// A locked world where `base`'s own definitions of `component` may run: an
// explicit one's world, or for an implicit one the first locked world.
std::optional<WorldId> lockedWorldOf(const Shader& base, const Component& component);

// A locked world that a shader derived from `base` would change by defining
// `component` again, in any world: the world the component must be
// computed in when that is locked, else lockedWorldOf. nullopt: a derived
// shader may redefine it.
std::optional<WorldId> lockedAgainstRedefinition(const Shader& base, const Component& component);

}  // namespace spire::sem
