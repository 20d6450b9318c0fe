#include "renderer/world_roles.h"

#include <algorithm>
#include <array>

namespace spire::engine {

namespace {

using codegen::ShaderStage;

constexpr std::array kTable = {
    WorldPass{"MeshVertex", WorldRole::MeshAttributes, std::nullopt, "mesh vertex attributes"},
    WorldPass{"FrameUniform", WorldRole::FrameParameters, std::nullopt, "per-frame engine values"},
    WorldPass{"MaterialUniform", WorldRole::MaterialParameters, std::nullopt, "scene-file material bindings"},
    WorldPass{"PrebakeUniform", WorldRole::UniformBake, ShaderStage::Compute,
              "compute over vertices at load, averaged into a per-mesh uniform"},
    WorldPass{"PrebakeVertex", WorldRole::VertexBake, ShaderStage::Compute,
              "compute per vertex at load into a vertex-data buffer"},
    WorldPass{"PrebakeTex", WorldRole::TextureBake, ShaderStage::Fragment,
              "rasterized in UV space at load into textures"},
    WorldPass{"Vertex", WorldRole::VertexStage, ShaderStage::Vertex, "vertex shader of each frame's draw"},
    WorldPass{"Fragment", WorldRole::FragmentStage, ShaderStage::Fragment, "fragment shader of each frame's draw"},
};

}  // namespace

std::span<const WorldPass> worldPassTable() { return kTable; }

const WorldPass* findWorldPass(std::string_view world) {
  const auto it = std::find_if(kTable.begin(), kTable.end(), [&](const WorldPass& p) { return p.world == world; });
  return it == kTable.end() ? nullptr : &*it;
}

}  // namespace spire::engine
