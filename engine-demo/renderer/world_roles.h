// What this engine does with each world of a pipeline (paper section 4.1: the
// engine gives the worlds their meaning). A world says which role it plays
// with a [Role: "..."] attribute on its declaration; a world without one is
// known by its name when that is the role's usual world name (the worlds of
// pipelines/). One table, so that a new pipeline (multi-rate screen-space
// shading, object-space shading) adds rows here and a pass, instead of
// conditions spread across the renderer.
#pragma once

#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "codegen/spirv_compiler.h"
#include "reflection/reflection.h"
#include "support/expected.h"

namespace spire::engine {

enum class WorldRole {
  // Abstract worlds: values the engine supplies.
  MeshAttributes,      // per-vertex attributes of the mesh (vertex buffer, or records for compute)
  FrameParameters,     // per-frame values: matrices, camera, light (FrameValues), or material overrides
  MaterialParameters,  // per-material values from the scene file's bindings
  InstanceParameters,  // per-instance values (model matrix, bake layer, transition fade), one record per instance
  // Concrete worlds: kernels the engine runs.
  UniformBake,    // compute over the mesh's vertices, averaged into a per-mesh uniform, once at load
  VertexBake,     // compute per vertex into a buffer read as vertex data, once at load
  TextureBake,    // rasterized in UV space into textures, once at load
  VertexStage,    // the vertex shader of every frame's draw
  FragmentStage,  // the fragment shader of every frame's draw
  // Per-frame passes that run before an instance's draw and leave textures
  // its Fragment kernel samples (frame_pass.h): the same topology, two
  // meanings (paper section 7.3).
  ScreenPassVertex,    // multi-rate shading: the mesh at a quarter of the pixels
  ScreenPassFragment,  // ... its results in screen-aligned textures
  ObjectPassVertex,    // object-space shading: the mesh in UV space
  ObjectPassFragment,  // ... its results in the object's textures
};

struct WorldPass {
  std::string_view role;        // the [Role] value that names it
  std::string_view usualWorld;  // the world that has this role without saying so
  WorldRole kind;
  // The stage a concrete world's kernel must have; nullopt for abstract worlds.
  std::optional<codegen::ShaderStage> stage;
  std::string_view description;
};

// Rows in the order the engine runs them: bakes before the frame, and
// uniform bakes first because vertex and texture bakes may read them.
std::span<const WorldPass> worldPassTable();
const WorldPass* findRole(std::string_view role);
// The pass of a world without a [Role], by its name; nullptr when none.
const WorldPass* findWorldPass(std::string_view world);
// "mesh (mesh vertex attributes), frame (...), ...": for messages; only the
// roles of worlds with kernels when `kernelsOnly`.
std::string roleList(bool kernelsOnly = false);

// Every world of a pipeline -> its pass, from the worlds' [Role] attributes
// (reflection::Variant::worlds). Worlds without a role or a usual name are
// absent. An error names a world whose role this engine does not implement,
// or two worlds that claim one concrete role.
using WorldPasses = std::map<std::string, const WorldPass*, std::less<>>;
spire::Expected<WorldPasses, Failure> resolveWorldPasses(const std::vector<reflection::World>& worlds);

// Every input of `kernel` (of role `pass`, its inputs' roles `inputPasses`)
// arrives over an edge the engine implements: an input kind (the import
// strategy's reflected kind) from a world of one role into a kernel of
// another, one table in world_roles.cpp. Anything else is refused when the
// variant is loaded, naming the edges the engine does implement, instead of
// being bound to nothing. Inputs from worlds without a role are left to the
// caller, which reports unknown worlds.
spire::Expected<void, Failure> checkEdges(const reflection::Kernel& kernel, const WorldPass& pass,
                                          const std::vector<const WorldPass*>& inputPasses);

}  // namespace spire::engine
