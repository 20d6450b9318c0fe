// Matching a variant's inputs to what the engine and the scene supply:
// MaterialUniform inputs to the instance's material bindings (by component
// name), FrameUniform inputs to per-frame engine values unless the material
// overrides them, MeshVertex inputs to mesh attributes. Every problem is a
// diagnostic at the scene-file value it is about, and all of them are
// reported, not just the first.
#pragma once

#include <functional>
#include <optional>
#include <string>

#include "renderer/kernel_bindings.h"
#include "renderer/variant_program.h"
#include "scene/scene_file.h"
#include "support/diagnostic.h"

namespace spire::engine {

// Returns the texture named `name` (loading it on first use), or null after
// reporting why it cannot be loaded at `range`.
using TextureLookup = std::function<const GpuTexture*(const std::string& name, SourceRange range)>;

// Checks `program` against this engine's world table and resolves the
// instance's material; nullopt after errors. Bindings that match no input
// of the variant are warnings (W7101): a variant may not need every value.
std::optional<MaterialValues> resolveMaterial(const VariantProgram& program, const scene::InstanceDesc& instance,
                                              const TextureLookup& textureFor, DiagnosticList& diags);

}  // namespace spire::engine
