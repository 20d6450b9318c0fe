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

// Noise is made at the precision of `format` (8 bits for RGBA8, float else)
// and colored in float: RGBA8 texels are those of colorizing 8-bit noise.
Image coloredNoise(const TextureDesc& desc, PixelFormat format) {
  const PixelFormat grey = format == PixelFormat::RGBA8 ? PixelFormat::RGBA8 : PixelFormat::RGBA32F;
  const Image noise = makeNoise(desc.size, desc.seed, desc.octaves, grey);
  Image colored = makeImage(noise.width, noise.height, format);
  for (uint32_t y = 0; y < noise.height; ++y) {
    for (uint32_t x = 0; x < noise.width; ++x) {
      const float v = noise.texel(x, y).r;
      colored.setTexel(x, y, desc.color2 + (desc.color - desc.color2) * v);
    }
  }
  return colored;
}

Expected<Image> buildProcedural(const TextureDesc& desc) {
  if (auto checked = checkProcedural(desc); !checked) {
    return Error{"texture '" + desc.name + "': " + checked.error().message};
  }
  const PixelFormat format = desc.format.value_or(PixelFormat::RGBA8);
  switch (desc.kind) {
    case TextureKind::Noise: return coloredNoise(desc, format);
    case TextureKind::Checker: return makeChecker(desc.size, desc.cells, desc.color, desc.color2, format);
    case TextureKind::NormalMap: return makeNormalMap(desc.size, desc.seed, desc.strength, format);
    case TextureKind::Solid: return makeSolid(desc.size, desc.color, format);
    case TextureKind::GgxLut: return makeGgxLut(desc.size, format);
    case TextureKind::File:
    case TextureKind::Gltf:
    case TextureKind::Pack: break;
  }
  return Error{"texture '" + desc.name + "': not a procedural kind"};
}

}  // namespace

Expected<Mesh> buildMesh(const MeshDesc& desc) {
  Mesh mesh;
  uint64_t gridVertices = (uint64_t{desc.resolution} + 1) * (uint64_t{desc.resolution} + 1);
  switch (desc.kind) {
    case MeshKind::Terrain:
      if (auto grid = checkGrid(desc, gridVertices); !grid) return Error{meshPrefix(desc) + grid.error().message};
      if (!std::isfinite(desc.height)) return Error{meshPrefix(desc) + "height must be a finite number"};
      mesh = makeTerrain(desc.size, desc.resolution, desc.height, desc.seed, desc.tile);
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
    case MeshKind::Box: mesh = makeBox(desc.size, desc.height); break;
    case MeshKind::Cylinder: mesh = makeCylinder(desc.radius, desc.height, desc.segments); break;
    case MeshKind::Rock: {
      uint64_t vertices = (uint64_t{desc.rings} + 1) * (uint64_t{desc.segments} + 1);
      if (vertices > kMaxGeneratedVertices) return Error{meshPrefix(desc) + "rings x segments gives too many vertices"};
      mesh = makeRock(desc.radius, desc.rings, desc.segments, desc.seed, desc.roughness);
      break;
    }
  }
  mesh.name = desc.name;
  return mesh;
}

namespace {

// The sources of a pack by name, built once each, of one size.
Expected<std::map<std::string, Image>> packSources(const TextureDesc& desc, const SceneFile& scene) {
  std::map<std::string, Image> sources;
  for (const ChannelSource& channel : desc.channels) {
    if (sources.contains(channel.texture)) continue;
    const TextureDesc* source = scene.findTexture(channel.texture);
    if (source == nullptr || source->kind == TextureKind::Pack) {
      return Error{"texture '" + desc.name + "': '" + channel.texture + "' is not a texture it can take channels of"};
    }
    auto image = buildTexture(*source, scene);
    if (!image) return Error{image.error()};
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
  return sources;
}

Expected<Image> packChannels(const TextureDesc& desc, const SceneFile& scene) {
  auto sources = packSources(desc, scene);
  if (!sources) return Error{sources.error()};
  PixelFormat format = sources->begin()->second.format;
  for (const auto& [name, image] : *sources) format = widerFormat(format, image.format);
  std::vector<const Image*> from;
  for (const ChannelSource& channel : desc.channels) from.push_back(&sources->at(channel.texture));
  Image packed = makeImage(from.front()->width, from.front()->height, desc.format.value_or(format));
  for (uint32_t y = 0; y < packed.height; ++y) {
    for (uint32_t x = 0; x < packed.width; ++x) {
      glm::vec4 texel(0.0F, 0.0F, 0.0F, 1.0F);
      for (size_t c = 0; c < from.size(); ++c) {
        const auto channel = static_cast<glm::length_t>(desc.channels[c].channel);
        texel[static_cast<glm::length_t>(c)] = from[c]->texel(x, y)[channel];
      }
      packed.setTexel(x, y, texel);
    }
  }
  return packed;
}

Expected<Image> loadFile(const TextureDesc& desc) {
  auto image = desc.kind == TextureKind::Gltf ? loadGltfImage(desc.file, desc.image) : loadImage(desc.file);
  if (!image) return image;
  const PixelFormat format = desc.format.value_or(image->format);
  return convertImage(std::move(image).value(), format);
}

}  // namespace

Expected<Image> buildTexture(const TextureDesc& desc, const SceneFile& scene) {
  switch (desc.kind) {
    case TextureKind::File:
    case TextureKind::Gltf: return loadFile(desc);
    case TextureKind::Pack: return packChannels(desc, scene);
    case TextureKind::Noise:
    case TextureKind::Checker:
    case TextureKind::NormalMap:
    case TextureKind::Solid:
    case TextureKind::GgxLut: return buildProcedural(desc);
  }
  return Error{"texture '" + desc.name + "': unknown kind"};
}

}  // namespace spire::scene
