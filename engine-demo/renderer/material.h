// Matching a variant's inputs to what the engine and the scene supply:
// MaterialUniform inputs to the instance's material bindings (by component
// name), FrameUniform inputs to per-frame engine values unless the material
// overrides them, MeshVertex inputs to mesh attributes. Every problem is a
// diagnostic at the scene-file value it is about, and all of them are
// reported, not just the first.
#pragma once

#include <functional>
#include <optional>
#include <set>
#include <string>

#include "renderer/kernel_bindings.h"
#include "renderer/variant_program.h"
#include "scene/scene_file.h"
#include "support/diagnostic.h"

namespace spire::engine {

// Returns the texture named `name` (loading it on first use), or null after
// reporting why it cannot be loaded at `range`.
using TextureLookup = std::function<const GpuTexture*(const std::string& name, SourceRange range)>;

struct ResolvedMaterial {
  std::optional<MaterialValues> values;     // nullopt after errors
  std::set<std::string, std::less<>> read;  // the bindings the variant reads
};

// Checks `program` against this engine's world table and resolves the
// instance's material.
ResolvedMaterial resolveMaterial(const VariantProgram& program, const scene::InstanceDesc& instance,
                                 const TextureLookup& textureFor, DiagnosticList& diags);

// W7101 for each binding of `instance` that is not in `read`. A binding one
// variant does not read is expected (a baked variant no longer reads the
// maps it baked), so a tool reports this once, over all its variants.
void reportUnreadBindings(const scene::InstanceDesc& instance, const std::set<std::string, std::less<>>& read,
                          DiagnosticList& diags);

}  // namespace spire::engine
