// In-process GLSL -> SPIR-V compilation (glslang) and SPIR-V validation
// (SPIRV-Tools) for the Vulkan GLSL kernels the code generator emits.
//
// The kernels are Vulkan-flavoured GLSL 4.50 compiled for a Vulkan 1.2 client
// into SPIR-V 1.5. They carry `#line N "file.spire"` directives (with
// GL_GOOGLE_cpp_style_line_directive), so glslang's messages name the Spire
// source file and line rather than the generated text.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "reflection/reflection.h"
#include "support/expected.h"

namespace spire::codegen {

// The stage a kernel runs in is part of its reflection.
using ShaderStage = reflection::Stage;
using reflection::stageName;

struct SpirvResult {
  std::vector<uint32_t> words;  // empty on failure
  std::string log;              // glslang's info log (errors and warnings), empty when clean
  bool ok() const { return !words.empty(); }
};

// Compiles Vulkan-flavoured GLSL 4.50 (client Vulkan 1.2, target SPIR-V 1.5)
// in-process. `sourceName` names the kernel in the log until a `#line`
// directive names a file. Thread-safe; glslang's process initialisation
// happens once, on first use, and is never torn down.
SpirvResult compileGlslToSpirv(ShaderStage stage, std::string_view glsl, std::string_view sourceName);

// Validates SPIR-V for the Vulkan 1.2 environment with SPIRV-Tools; an error
// with the validator's message when the module is invalid. Thread-safe.
Expected<void, Failure> validateSpirv(const std::vector<uint32_t>& words);

}  // namespace spire::codegen
