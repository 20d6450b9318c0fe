// In-process GLSL -> SPIR-V compilation (glslang) and SPIR-V validation
// (SPIRV-Tools) for the Vulkan GLSL kernels the code generator emits.
//
// The kernels are Vulkan-flavoured GLSL 4.40, with the extensions that give
// the GLSL 4.50 functions Spire offers, compiled for a Vulkan 1.2 client into
// SPIR-V 1.5. They carry `#line N "file.spire"` directives (with
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

// The first lines of every GLSL text given to compileGlslToSpirv. Version
// 4.40, not 4.50: glslang builds the built-in symbol tables of every stage
// that the version has, once per process and version, and 4.50 adds eight
// (ray tracing, mesh and task), which made that start-up twice as long, most
// of a spirec run. The two extensions bring back the 4.50 functions of the
// built-in table: the fine and coarse derivatives, and mix() of integers and
// booleans. Every text uses one version, so a process builds one set.
inline constexpr std::string_view kGlslVersionLines =
    "#version 440\n"
    "#extension GL_ARB_derivative_control : require\n"
    "#extension GL_EXT_shader_integer_mix : require\n";

struct SpirvResult {
  std::vector<uint32_t> words;  // empty on failure
  std::string log;              // glslang's info log (errors and warnings), empty when clean
  bool ok() const { return !words.empty(); }
};

// Compiles Vulkan-flavoured GLSL (kGlslVersionLines; client Vulkan 1.2, target SPIR-V 1.5)
// in-process. `sourceName` names the kernel in the log until a `#line`
// directive names a file. Thread-safe; glslang's process initialisation
// happens once, on first use, and is never torn down.
SpirvResult compileGlslToSpirv(ShaderStage stage, std::string_view glsl, std::string_view sourceName);

// Validates SPIR-V for the Vulkan 1.2 environment with SPIRV-Tools; an error
// with the validator's message when the module is invalid. Thread-safe.
Expected<void, Failure> validateSpirv(const std::vector<uint32_t>& words);

}  // namespace spire::codegen
