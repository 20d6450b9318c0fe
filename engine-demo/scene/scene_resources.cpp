#include "scene/scene_resources.h"

#include "scene/gltf.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <string>

namespace spire::scene {
namespace {

// Generated meshes and textures are bounded so that a mistyped number in a
// scene file gives an error instead of exhausting memory: 2^24 vertices keep
// every index well inside uint32_t, and 16384 texels per side is the largest
// image dimension lavapipe (and most desktop GPUs) accept.
constexpr uint64_t kMaxGeneratedVertices = uint64_t{1} << 24;
constexpr uint32_t kMaxTextureSize = 16384;
// Octave k has 8 * 2^k noise cells across the texture: from octave 12 on they
// are finer than the texels of the largest texture, so more than 16 octaves
// only cost time.
constexpr uint32_t kMaxOctaves = 16;

uint8_t toUnorm8(float value) {
  if (!(value > 0.0F)) return 0;  // also maps NaN to 0
  return static_cast<uint8_t>(std::lround(std::min(value, 1.0F) * 255.0F));
}

Rgba8 toColor8(const glm::vec4& color) {
  return {toUnorm8(color.r), toUnorm8(color.g), toUnorm8(color.b), toUnorm8(color.a)};
}

std::string meshPrefix(const MeshDesc& desc) { return "mesh '" + desc.name + "': "; }

Expected<void> checkGrid(const MeshDesc& desc, uint64_t vertices) {
  if (!std::isfinite(desc.size) || desc.size <= 0.0F) return Failure{"size must be a positive finite number"};
  if (vertices > kMaxGeneratedVertices) {
    return Failure{"resolution " + std::to_string(desc.resolution) + " gives more than " +
                   std::to_string(kMaxGeneratedVertices) + " vertices"};
  }
  return {};
}

// All primitives of the file in one mesh, their indices rebased onto the
// concatenated vertex array; double-sided when any of them is, since one
// draw culls all of its faces or none.
Expected<Mesh> mergeGltf(const MeshDesc& desc) {
  auto parts = loadGltf(desc.file);
  if (!parts) return Error{parts.error()};
  if (parts->empty()) return Error{"glTF '" + desc.file.string() + "' has no triangle meshes in its scene"};
  Mesh merged;
  merged.name = desc.name;
  for (Mesh& part : *parts) {
    size_t base = merged.vertices.size();
    if (part.vertices.size() > std::numeric_limits<uint32_t>::max() - base) {
      return Error{"glTF '" + desc.file.string() + "' has more vertices than 32-bit indices can address"};
    }
    merged.vertices.insert(merged.vertices.end(), part.vertices.begin(), part.vertices.end());
    merged.doubleSided = merged.doubleSided || part.doubleSided;
    for (uint32_t index : part.indices) merged.indices.push_back(index + static_cast<uint32_t>(base));
  }
  return merged;
}

Expected<void> checkProcedural(const TextureDesc& desc) {
  if (desc.size == 0 || desc.size > kMaxTextureSize) {
    return Failure{"size " + std::to_string(desc.size) + " is outside [1, " + std::to_string(kMaxTextureSize) + "]"};
  }
  if (desc.kind == TextureKind::Noise && desc.octaves > kMaxOctaves) {
    return Failure{"octaves " + std::to_string(desc.octaves) + " is more than " + std::to_string(kMaxOctaves)};
  }
  if (desc.kind == TextureKind::NormalMap && !std::isfinite(desc.strength)) {
    return Failure{std::string("strength must be a finite number")};
  }
  return {};
}

Image colorizeNoise(Image noise, const glm::vec4& color, const glm::vec4& color2) {
  for (size_t texel = 0; texel < noise.bytes.size(); texel += 4) {
    float v = static_cast<float>(noise.bytes[texel]) / 255.0F;
    glm::vec4 mixed = color2 + (color - color2) * v;
    Rgba8 out = toColor8(mixed);
    for (size_t c = 0; c < 4; ++c) noise.bytes[texel + c] = out[static_cast<glm::length_t>(c)];
  }
  return noise;
}

}  // namespace

Expected<Mesh> buildMesh(const MeshDesc& desc) {
  Mesh mesh;
  uint64_t gridVertices = (uint64_t{desc.resolution} + 1) * (uint64_t{desc.resolution} + 1);
  switch (desc.kind) {
    case MeshKind::Terrain:
      if (auto grid = checkGrid(desc, gridVertices); !grid) return Error{meshPrefix(desc) + grid.error().message};
      if (!std::isfinite(desc.height)) return Error{meshPrefix(desc) + "height must be a finite number"};
      mesh = makeTerrain(desc.size, desc.resolution, desc.height, desc.seed);
      break;
    case MeshKind::Plane:
      if (auto grid = checkGrid(desc, gridVertices); !grid) return Error{meshPrefix(desc) + grid.error().message};
      mesh = makePlane(desc.size, desc.resolution);
      break;
    case MeshKind::Sphere: {
      if (!std::isfinite(desc.radius) || desc.radius <= 0.0F) {
        return Error{meshPrefix(desc) + "radius must be a positive finite number"};
      }
      uint64_t vertices = (uint64_t{desc.rings} + 1) * (uint64_t{desc.segments} + 1);
      if (vertices > kMaxGeneratedVertices) {
        return Error{meshPrefix(desc) + "rings x segments gives more than " + std::to_string(kMaxGeneratedVertices) +
                     " vertices"};
      }
      mesh = makeSphere(desc.radius, desc.rings, desc.segments);
      break;
    }
    case MeshKind::Gltf: return mergeGltf(desc);
  }
  mesh.name = desc.name;
  return mesh;
}

namespace {

Expected<Image> packChannels(const TextureDesc& desc, const SceneFile& scene) {
  std::map<std::string, Image> sources;
  for (const ChannelSource& channel : desc.channels) {
    if (sources.contains(channel.texture)) continue;
    const TextureDesc* source = scene.findTexture(channel.texture);
    if (source == nullptr || source->kind == TextureKind::Pack) {
      return Error{"texture '" + desc.name + "': '" + channel.texture + "' is not a texture it can take channels of"};
    }
    auto image = buildTexture(*source, scene);
    if (!image) return image;
    sources.emplace(channel.texture, std::move(image).value());
  }
  if (sources.empty()) return Error{"texture '" + desc.name + "': no channels"};
  const Image& first = sources.at(desc.channels.front().texture);
  for (const auto& [name, image] : sources) {
    if (image.width != first.width || image.height != first.height) {
      return Error{fmt::format(
          "texture '{}': its channels come from textures of different sizes ('{}' is {}x{}, '{}' "
          "{}x{})",
          desc.name, desc.channels.front().texture, first.width, first.height, name, image.width, image.height)};
    }
  }
  Image packed{first.width, first.height, std::vector<uint8_t>(first.bytes.size(), 0)};
  for (size_t texel = 3; texel < packed.bytes.size(); texel += 4) packed.bytes[texel] = 255;
  for (size_t c = 0; c < desc.channels.size(); ++c) {
    const ChannelSource& channel = desc.channels[c];
    const std::vector<uint8_t>& from = sources.at(channel.texture).bytes;
    for (size_t texel = 0; texel < packed.bytes.size(); texel += 4) {
      packed.bytes[texel + c] = from[texel + channel.channel];
    }
  }
  return packed;
}

}  // namespace

Expected<Image> buildTexture(const TextureDesc& desc, const SceneFile& scene) {
  if (desc.kind != TextureKind::File && desc.kind != TextureKind::Gltf && desc.kind != TextureKind::Pack) {
    if (auto checked = checkProcedural(desc); !checked) {
      return Error{"texture '" + desc.name + "': " + checked.error().message};
    }
  }
  switch (desc.kind) {
    case TextureKind::File: return loadImage(desc.file);
    case TextureKind::Gltf: return loadGltfImage(desc.file, desc.image);
    case TextureKind::Noise:
      return colorizeNoise(makeNoise(desc.size, desc.seed, desc.octaves), desc.color, desc.color2);
    case TextureKind::Checker: return makeChecker(desc.size, desc.cells, toColor8(desc.color), toColor8(desc.color2));
    case TextureKind::NormalMap: return makeNormalMap(desc.size, desc.seed, desc.strength);
    case TextureKind::Solid: return makeSolid(desc.size, toColor8(desc.color));
    case TextureKind::GgxLut: return makeGgxLut(desc.size);
    case TextureKind::Pack: return packChannels(desc, scene);
  }
  return Error{"texture '" + desc.name + "': unknown kind"};
}

}  // namespace spire::scene
