// What this engine does with each world of a pipeline (paper section 4.1: the
// engine gives the worlds their meaning). One table, so that a new pipeline
// (multi-rate screen-space shading, object-space shading) adds rows here and
// a pass, instead of conditions spread across the renderer.
#pragma once

#include <optional>
#include <span>
#include <string_view>

#include "codegen/spirv_compiler.h"

namespace spire::engine {

enum class WorldRole {
  // Abstract worlds: values the engine supplies.
  MeshAttributes,      // per-vertex attributes of the mesh (vertex buffer, or records for compute)
  FrameParameters,     // per-frame values: matrices, camera, light (FrameValues), or material overrides
  MaterialParameters,  // per-material values from the scene file's bindings
  // Concrete worlds: kernels the engine runs.
  UniformBake,    // compute over the mesh's vertices, averaged into a per-mesh uniform, once at load
  VertexBake,     // compute per vertex into a buffer read as vertex data, once at load
  TextureBake,    // rasterized in UV space into textures, once at load
  VertexStage,    // the vertex shader of every frame's draw
  FragmentStage,  // the fragment shader of every frame's draw
};

struct WorldPass {
  std::string_view world;
  WorldRole role;
  // The stage a concrete world's kernel must have; nullopt for abstract worlds.
  std::optional<codegen::ShaderStage> stage;
  std::string_view description;
};

// Rows in the order the engine runs them: bakes before the frame, and
// uniform bakes first because vertex and texture bakes may read them.
std::span<const WorldPass> worldPassTable();
const WorldPass* findWorldPass(std::string_view world);

}  // namespace spire::engine
