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
    WorldPass{"instance", "InstanceUniform", WorldRole::InstanceParameters, std::nullopt,
              "per-instance engine values, one record per instance"},
    WorldPass{"prebakeUniform", "PrebakeUniform", WorldRole::UniformBake, ShaderStage::Compute,
              "compute over the surface at load, averaged into a per-mesh uniform"},
    WorldPass{"prebakeVertex", "PrebakeVertex", WorldRole::VertexBake, ShaderStage::Compute,
              "compute per vertex at load into a vertex-data buffer"},
    WorldPass{"prebakeTexture", "PrebakeTex", WorldRole::TextureBake, ShaderStage::Fragment,
              "rasterized in UV space at load into textures"},
    WorldPass{"vertex", "Vertex", WorldRole::VertexStage, ShaderStage::Vertex, "vertex shader of each frame's draw"},
    WorldPass{"fragment", "Fragment", WorldRole::FragmentStage, ShaderStage::Fragment,
              "fragment shader of each frame's draw"},
    WorldPass{"lowResVertex", "LowResVertex", WorldRole::ScreenPassVertex, ShaderStage::Vertex,
              "vertex shader of each frame's low-resolution pass, at half width and height"},
    WorldPass{"lowResFragment", "LowResFragment", WorldRole::ScreenPassFragment, ShaderStage::Fragment,
              "fragment shader of the low-resolution pass, into screen-aligned textures"},
    WorldPass{"objectSpaceVertex", "ObjSpaceVertex", WorldRole::ObjectPassVertex, ShaderStage::Vertex,
              "vertex shader of each frame's object-space pass, in UV space"},
    WorldPass{"objectSpaceFragment", "ObjSpaceFrag", WorldRole::ObjectPassFragment, ShaderStage::Fragment,
              "fragment shader of the object-space pass, into the object's textures"},
};

using reflection::InputKind;

// Inputs of `kind` from a world of role `from` into kernels of the roles in `into`.
struct WorldEdge {
  InputKind kind;
  WorldRole from;
  uint32_t into;             // one bit per WorldRole (roleBit)
  std::string_view how;      // how the engine binds it, for readers of the table
  bool perInstance = false;  // buffer records read at gl_InstanceIndex, not per vertex or invocation
};

constexpr std::string_view kInstanceIndex = "gl_InstanceIndex";

constexpr uint32_t roleBit(WorldRole role) { return 1U << static_cast<uint32_t>(role); }

constexpr uint32_t kBakes =
    roleBit(WorldRole::UniformBake) | roleBit(WorldRole::VertexBake) | roleBit(WorldRole::TextureBake);
constexpr uint32_t kPassVertices = roleBit(WorldRole::ScreenPassVertex) | roleBit(WorldRole::ObjectPassVertex);
constexpr uint32_t kPassFragments = roleBit(WorldRole::ScreenPassFragment) | roleBit(WorldRole::ObjectPassFragment);
// Every kernel that runs each frame: the draw and the passes before it.
constexpr uint32_t kDraw =
    roleBit(WorldRole::VertexStage) | roleBit(WorldRole::FragmentStage) | kPassVertices | kPassFragments;
constexpr uint32_t kRasterized = roleBit(WorldRole::TextureBake) | roleBit(WorldRole::VertexStage) | kPassVertices;

constexpr std::array kEdges = {
    WorldEdge{InputKind::Varying, WorldRole::MeshAttributes, kRasterized, "the mesh's vertex buffer"},
    WorldEdge{InputKind::Varying, WorldRole::VertexBake, kRasterized,
              "the vertex bake's records as a second vertex buffer"},
    WorldEdge{InputKind::Varying, WorldRole::VertexStage, roleBit(WorldRole::FragmentStage),
              "the rasterizer's interpolated outputs"},
    WorldEdge{InputKind::Varying, WorldRole::ScreenPassVertex, roleBit(WorldRole::ScreenPassFragment),
              "the rasterizer's interpolated outputs"},
    WorldEdge{InputKind::Varying, WorldRole::ObjectPassVertex, roleBit(WorldRole::ObjectPassFragment),
              "the rasterizer's interpolated outputs"},
    WorldEdge{InputKind::UniformMember, WorldRole::MaterialParameters, kBakes | kDraw,
              "material bindings, written once"},
    // Frame values change every frame; bakes run once, at load.
    WorldEdge{InputKind::UniformMember, WorldRole::FrameParameters, kDraw, "engine values, written every frame"},
    WorldEdge{InputKind::UniformMember, WorldRole::UniformBake,
              roleBit(WorldRole::VertexBake) | roleBit(WorldRole::TextureBake) | kDraw,
              "the uniform bake's averages, written once"},
    WorldEdge{InputKind::BufferMember, WorldRole::MeshAttributes,
              roleBit(WorldRole::UniformBake) | roleBit(WorldRole::VertexBake),
              "std430 records of the mesh's vertices"},
    WorldEdge{InputKind::BufferMember, WorldRole::VertexBake, roleBit(WorldRole::VertexStage) | kPassVertices,
              "the vertex bake's records, read at gl_VertexIndex"},
    // Instanced drawing: one record per instance, read at gl_InstanceIndex,
    // so that objects with different values share one draw.
    WorldEdge{InputKind::BufferMember, WorldRole::InstanceParameters, roleBit(WorldRole::VertexStage),
              "per-instance engine values, one record per instance", true},
    WorldEdge{InputKind::BufferMember, WorldRole::UniformBake, roleBit(WorldRole::VertexStage),
              "the uniform bake's averages of each instance's object, one record per instance", true},
    WorldEdge{InputKind::Texture, WorldRole::TextureBake, kDraw, "the bake's render targets as sampled images"},
    WorldEdge{InputKind::Texture, WorldRole::ScreenPassFragment, roleBit(WorldRole::FragmentStage),
              "the low-resolution pass's targets, rendered earlier in the frame"},
    WorldEdge{InputKind::Texture, WorldRole::ObjectPassFragment, roleBit(WorldRole::FragmentStage),
              "the object-space pass's targets, rendered earlier in the frame"},
    WorldEdge{InputKind::Sampler, WorldRole::MaterialParameters, kBakes | kDraw, "the bound scene texture"},
};

const WorldEdge* findEdge(const reflection::KernelInput& input, WorldRole from, WorldRole into) {
  const bool perInstance = input.kind == InputKind::BufferMember && input.index == kInstanceIndex;
  const auto it = std::find_if(kEdges.begin(), kEdges.end(), [&](const WorldEdge& e) {
    return e.kind == input.kind && e.from == from && (e.into & roleBit(into)) != 0 && e.perInstance == perInstance;
  });
  return it == kEdges.end() ? nullptr : &*it;
}

// "varying into vertex and prebakeTexture; uniform into ...": the edges out of `from`.
std::string edgesFrom(WorldRole from) {
  std::string text;
  for (const WorldEdge& edge : kEdges) {
    if (edge.from != from) continue;
    std::string into;
    for (const WorldPass& p : kTable) {
      if (edge.into & roleBit(p.kind)) into += fmt::format("{}{}", into.empty() ? "" : ", ", p.role);
    }
    text += fmt::format("{}{}{} into {}", text.empty() ? "" : "; ", reflection::inputKindName(edge.kind),
                        edge.perInstance ? " (per instance)" : "", into);
  }
  return text.empty() ? "nothing" : text;
}

}  // namespace

spire::Expected<void, Failure> checkEdges(const reflection::Kernel& kernel, const WorldPass& pass,
                                          const std::vector<const WorldPass*>& inputPasses) {
  for (size_t i = 0; i < kernel.inputs.size() && i < inputPasses.size(); ++i) {
    const reflection::KernelInput& input = kernel.inputs[i];
    const WorldPass* from = inputPasses[i];
    if (!from || findEdge(input, from->kind, pass.kind)) continue;
    const bool perInstance = input.kind == InputKind::BufferMember && input.index == kInstanceIndex;
    return Failure{fmt::format(
        "the {} kernel ({}) reads '{}' from world '{}' ({}) as a {}{} input ({}), an edge this engine does not "
        "implement; out of {} it implements: {}",
        kernel.world, pass.role, input.component, input.from, from->role, reflection::inputKindName(input.kind),
        perInstance ? " (per instance)" : "", input.strategy, from->role, edgesFrom(from->kind))};
  }
  return {};
}

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
