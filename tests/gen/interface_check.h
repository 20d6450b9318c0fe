// The stage-interface part of the generator's property: what one kernel of
// a variant reads from another must be what that kernel writes. Checked on
// the reflection alone (docs/reflection.md), as an engine would see it.
#pragma once

#include <string>
#include <vector>

#include "codegen/kernel_generator.h"
#include "sema/semantic_model.h"

namespace spire::testgen {

// One line per mismatch, empty when the kernels agree:
//  - an `in` (location) input from a concrete world has the same location
//    and type as that world's `out` for the component;
//  - a texture input names a component the producer writes;
//  - a buffer input from a concrete world reads the producer's record
//    layout (same offset and type, same record stride), except in a world
//    in `lockedWorlds`, whose record holds only what it reads (the engine
//    repacks it), where the producer must write the value with that type;
//  - no two inputs, and no two outputs, of one kernel share a location
//    (matrices and arrays span several).
std::vector<std::string> checkInterfaces(const codegen::GeneratedShader& shader, const sem::Pipeline& pipeline,
                                         const std::vector<sem::WorldId>& lockedWorlds = {});

// How many locations a value of this type takes: `mat3` 3, `vec4[2]` 2,
// scalars and vectors 1.
int locationSpan(const reflection::ValueType& type);

}  // namespace spire::testgen
