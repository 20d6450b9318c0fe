#include "renderer/world_roles.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>

namespace spire::engine {

namespace {

using codegen::ShaderStage;

constexpr std::array kTable = {
    WorldPass{"mesh", "MeshVertex", WorldRole::MeshAttributes, std::nullopt, "mesh vertex attributes"},
    WorldPass{"frame", "FrameUniform", WorldRole::FrameParameters, std::nullopt, "per-frame engine values"},
    WorldPass{"material", "MaterialUniform", WorldRole::MaterialParameters, std::nullopt,
              "scene-file material bindings"},
    WorldPass{"prebakeUniform", "PrebakeUniform", WorldRole::UniformBake, ShaderStage::Compute,
              "compute over vertices at load, averaged into a per-mesh uniform"},
    WorldPass{"prebakeVertex", "PrebakeVertex", WorldRole::VertexBake, ShaderStage::Compute,
              "compute per vertex at load into a vertex-data buffer"},
    WorldPass{"prebakeTexture", "PrebakeTex", WorldRole::TextureBake, ShaderStage::Fragment,
              "rasterized in UV space at load into textures"},
    WorldPass{"vertex", "Vertex", WorldRole::VertexStage, ShaderStage::Vertex, "vertex shader of each frame's draw"},
    WorldPass{"fragment", "Fragment", WorldRole::FragmentStage, ShaderStage::Fragment,
              "fragment shader of each frame's draw"},
};

}  // namespace

std::span<const WorldPass> worldPassTable() { return kTable; }

const WorldPass* findRole(std::string_view role) {
  const auto it = std::find_if(kTable.begin(), kTable.end(), [&](const WorldPass& p) { return p.role == role; });
  return it == kTable.end() ? nullptr : &*it;
}

const WorldPass* findWorldPass(std::string_view world) {
  const auto it = std::find_if(kTable.begin(), kTable.end(), [&](const WorldPass& p) { return p.usualWorld == world; });
  return it == kTable.end() ? nullptr : &*it;
}

std::string roleList(bool kernelsOnly) {
  std::string text;
  for (const WorldPass& p : kTable) {
    if (kernelsOnly && !p.stage) continue;
    text += fmt::format("{}{} ({})", text.empty() ? "" : ", ", p.role, p.description);
  }
  return text;
}

spire::Expected<WorldPasses, Failure> resolveWorldPasses(const std::vector<reflection::World>& worlds) {
  WorldPasses passes;
  std::map<const WorldPass*, std::string> claimed;  // concrete pass -> the world that has it
  for (const reflection::World& world : worlds) {
    const WorldPass* pass = world.role.empty() ? findWorldPass(world.name) : findRole(world.role);
    if (!pass && !world.role.empty()) {
      return Failure{
          fmt::format("world '{}' has [Role: \"{}\"], which this engine does not implement; its roles are: {}",
                      world.name, world.role, roleList())};
    }
    if (!pass) continue;
    if (pass->stage) {
      const auto [it, fresh] = claimed.emplace(pass, world.name);
      if (!fresh) {
        return Failure{fmt::format("worlds '{}' and '{}' both have the role '{}'; the engine runs one world per role",
                                   it->second, world.name, pass->role)};
      }
    }
    passes.emplace(world.name, pass);
  }
  return passes;
}

}  // namespace spire::engine
