// `spirec --choices` for the front end alone: every component of every shader
// with the definitions its declarations give, before placement analysis.
#pragma once

#include <string>
#include <string_view>

#include "sema/semantic_model.h"

namespace spire {

// One line per component with definitions: `Shader.component = {...}` where
// each entry is the definition's world (`*` when implicit) and variation.
// Inherited components carry the name of the shader or pipeline that wrote
// them as the prefix. Deterministic: shaders and components in declaration
// order. `shaderFilter` (if non-empty) restricts output to one shader.
std::string listDeclaredDefinitions(const sem::Model& model, std::string_view shaderFilter);

}  // namespace spire
