#include "scene/gltf.h"

#include <tiny_gltf.h>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <system_error>
#include <tuple>
#include <utility>

namespace spire::scene {
namespace {

// Reads one accessor as `width` floats per element, converting integer
// components as the glTF spec allows for TEXCOORD (normalized u8/u16).
// Returns an error message instead of reading outside the buffer.
Expected<std::vector<float>> readFloats(const tinygltf::Model& model, int accessorIndex, int type,
                                        const char* semantic) {
  std::string where = std::string("accessor for ") + semantic;
  if (accessorIndex < 0 || static_cast<size_t>(accessorIndex) >= model.accessors.size()) {
    return Error{where + " is out of range"};
  }
  const tinygltf::Accessor& accessor = model.accessors[static_cast<size_t>(accessorIndex)];
  if (accessor.type != type) return Error{where + " has the wrong element type"};
  if (accessor.sparse.isSparse) return Error{where + " is sparse, which is not supported"};
  if (accessor.bufferView < 0 || static_cast<size_t>(accessor.bufferView) >= model.bufferViews.size()) {
    return Error{where + " has no valid bufferView"};
  }
  const tinygltf::BufferView& view = model.bufferViews[static_cast<size_t>(accessor.bufferView)];
  if (view.buffer < 0 || static_cast<size_t>(view.buffer) >= model.buffers.size()) {
    return Error{where + " refers to a missing buffer"};
  }
  const std::vector<unsigned char>& data = model.buffers[static_cast<size_t>(view.buffer)].data;
  int componentSize = tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(accessor.componentType));
  auto width = static_cast<size_t>(tinygltf::GetNumComponentsInType(static_cast<uint32_t>(type)));
  int stride = accessor.ByteStride(view);
  bool isFloat = accessor.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT;
  bool isUnorm = accessor.normalized && (accessor.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                                         accessor.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
  if (stride <= 0 || componentSize <= 0 || (!isFloat && !isUnorm)) {
    return Error{where + " has an unsupported component type or stride"};
  }
  size_t begin = view.byteOffset + accessor.byteOffset;
  size_t elementBytes = width * static_cast<size_t>(componentSize);
  if (accessor.count > 0) {
    size_t end = begin + (accessor.count - 1) * static_cast<size_t>(stride) + elementBytes;
    if (end > view.byteOffset + view.byteLength || end > data.size()) {
      return Error{where + " reads past the end of its buffer"};
    }
  }
  std::vector<float> out(accessor.count * width);
  for (size_t i = 0; i < accessor.count; ++i) {
    const unsigned char* element = data.data() + begin + i * static_cast<size_t>(stride);
    for (size_t c = 0; c < width; ++c) {
      const unsigned char* src = element + c * static_cast<size_t>(componentSize);
      float value = 0.0f;
      // memcpy: buffer data has no alignment guarantee for the element type.
      if (isFloat) {
        std::memcpy(&value, src, sizeof value);
      } else if (componentSize == 1) {
        value = static_cast<float>(*src) / 255.0f;
      } else {
        uint16_t raw = 0;
        std::memcpy(&raw, src, sizeof raw);
        value = static_cast<float>(raw) / 65535.0f;
      }
      out[i * width + c] = value;
    }
  }
  return out;
}

Expected<std::vector<uint32_t>> readIndices(const tinygltf::Model& model, int accessorIndex, size_t vertexCount) {
  if (static_cast<size_t>(accessorIndex) >= model.accessors.size()) return Error{"index accessor is out of range"};
  const tinygltf::Accessor& accessor = model.accessors[static_cast<size_t>(accessorIndex)];
  if (accessor.type != TINYGLTF_TYPE_SCALAR || accessor.sparse.isSparse || accessor.bufferView < 0 ||
      static_cast<size_t>(accessor.bufferView) >= model.bufferViews.size()) {
    return Error{"index accessor must be a non-sparse scalar with a bufferView"};
  }
  const tinygltf::BufferView& view = model.bufferViews[static_cast<size_t>(accessor.bufferView)];
  if (view.buffer < 0 || static_cast<size_t>(view.buffer) >= model.buffers.size()) {
    return Error{"index accessor refers to a missing buffer"};
  }
  const std::vector<unsigned char>& data = model.buffers[static_cast<size_t>(view.buffer)].data;
  int componentSize = tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(accessor.componentType));
  bool unsignedType = accessor.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                      accessor.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ||
                      accessor.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
  int stride = accessor.ByteStride(view);
  if (!unsignedType || stride <= 0) return Error{"indices must be unsigned 8, 16 or 32 bit integers"};
  size_t begin = view.byteOffset + accessor.byteOffset;
  if (accessor.count > 0) {
    size_t end = begin + (accessor.count - 1) * static_cast<size_t>(stride) + static_cast<size_t>(componentSize);
    if (end > view.byteOffset + view.byteLength || end > data.size()) {
      return Error{"index accessor reads past the end of its buffer"};
    }
  }
  std::vector<uint32_t> out(accessor.count);
  for (size_t i = 0; i < accessor.count; ++i) {
    const unsigned char* src = data.data() + begin + i * static_cast<size_t>(stride);
    uint32_t value = 0;
    if (componentSize == 1) {
      value = *src;
    } else if (componentSize == 2) {
      uint16_t raw = 0;
      std::memcpy(&raw, src, sizeof raw);
      value = raw;
    } else {
      std::memcpy(&value, src, sizeof value);
    }
    if (value >= vertexCount) return Error{"index " + std::to_string(value) + " is out of range"};
    out[i] = value;
  }
  return out;
}

glm::mat4 localTransform(const tinygltf::Node& node) {
  if (node.matrix.size() == 16) {
    glm::mat4 m(1.0f);
    // glTF matrices are column-major, like glm.
    for (int i = 0; i < 16; ++i) m[i / 4][i % 4] = static_cast<float>(node.matrix[static_cast<size_t>(i)]);
    return m;
  }
  glm::mat4 t(1.0f);
  if (node.translation.size() == 3) {
    t[3] = glm::vec4(static_cast<float>(node.translation[0]), static_cast<float>(node.translation[1]),
                     static_cast<float>(node.translation[2]), 1.0f);
  }
  glm::mat4 r(1.0f);
  if (node.rotation.size() == 4) {
    // glTF stores quaternions as (x, y, z, w); glm's constructor takes w first.
    glm::quat q(static_cast<float>(node.rotation[3]), static_cast<float>(node.rotation[0]),
                static_cast<float>(node.rotation[1]), static_cast<float>(node.rotation[2]));
    r = glm::mat4_cast(glm::normalize(q));
  }
  glm::mat4 s(1.0f);
  if (node.scale.size() == 3) {
    s[0][0] = static_cast<float>(node.scale[0]);
    s[1][1] = static_cast<float>(node.scale[1]);
    s[2][2] = static_cast<float>(node.scale[2]);
  }
  return t * r * s;
}

Expected<Mesh> convertPrimitive(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                                const glm::mat4& transform, std::string name) {
  // mode -1 means the attribute was absent: triangles by default.
  if (primitive.mode != TINYGLTF_MODE_TRIANGLES && primitive.mode != -1) {
    return Error{"primitive mode " + std::to_string(primitive.mode) + " is not supported (only triangles)"};
  }
  auto attribute = [&](const char* semantic) -> std::optional<int> {
    auto it = primitive.attributes.find(semantic);
    return it == primitive.attributes.end() ? std::nullopt : std::optional<int>(it->second);
  };
  std::optional<int> positionAccessor = attribute("POSITION");
  if (!positionAccessor) return Error{"primitive has no POSITION attribute"};
  auto positions = readFloats(model, *positionAccessor, TINYGLTF_TYPE_VEC3, "POSITION");
  if (!positions) return Error{positions.error()};
  size_t vertexCount = positions->size() / 3;

  // Optional attributes must match POSITION's element count.
  auto readOptional = [&](const char* semantic, int type, size_t width) -> Expected<std::vector<float>> {
    std::optional<int> index = attribute(semantic);
    if (!index) return std::vector<float>{};
    auto values = readFloats(model, *index, type, semantic);
    if (values && values->size() != vertexCount * width) {
      return Error{std::string(semantic) + " count differs from POSITION count"};
    }
    return values;
  };
  auto normals = readOptional("NORMAL", TINYGLTF_TYPE_VEC3, 3);
  if (!normals) return Error{normals.error()};
  auto uvs = readOptional("TEXCOORD_0", TINYGLTF_TYPE_VEC2, 2);
  if (!uvs) return Error{uvs.error()};
  auto tangents = readOptional("TANGENT", TINYGLTF_TYPE_VEC4, 4);
  if (!tangents) return Error{tangents.error()};

  Mesh mesh;
  mesh.name = std::move(name);
  mesh.doubleSided = primitive.material >= 0 && static_cast<size_t>(primitive.material) < model.materials.size() &&
                     model.materials[static_cast<size_t>(primitive.material)].doubleSided;
  if (primitive.indices >= 0) {
    auto indices = readIndices(model, primitive.indices, vertexCount);
    if (!indices) return Error{indices.error()};
    mesh.indices = std::move(indices).value();
  } else {
    mesh.indices.resize(vertexCount);
    for (size_t i = 0; i < vertexCount; ++i) mesh.indices[i] = static_cast<uint32_t>(i);
  }
  if (mesh.indices.size() % 3 != 0) return Error{"triangle index count is not a multiple of 3"};

  glm::mat3 linear(transform);
  // Normals transform by the inverse transpose so non-uniform scale keeps them
  // perpendicular to the surface; tangents lie in the surface and use `linear`.
  glm::mat3 normalMatrix = glm::transpose(glm::inverse(linear));
  bool mirrored = glm::determinant(linear) < 0.0f;
  mesh.vertices.resize(vertexCount);
  for (size_t i = 0; i < vertexCount; ++i) {
    Vertex& v = mesh.vertices[i];
    const float* p = &(*positions)[i * 3];
    v.position = glm::vec3(transform * glm::vec4(p[0], p[1], p[2], 1.0f));
    if (!normals->empty()) {
      const float* n = &(*normals)[i * 3];
      v.normal = glm::normalize(normalMatrix * glm::vec3(n[0], n[1], n[2]));
    }
    if (!uvs->empty()) v.uv = glm::vec2((*uvs)[i * 2], (*uvs)[i * 2 + 1]);
    if (!tangents->empty()) {
      const float* t = &(*tangents)[i * 4];
      // A mirroring transform flips the bitangent relative to cross(n, t).
      v.tangent = glm::vec4(glm::normalize(linear * glm::vec3(t[0], t[1], t[2])), mirrored ? -t[3] : t[3]);
    }
  }
  // A mirroring transform also reverses the winding; restore counter-clockwise.
  if (mirrored) {
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) std::swap(mesh.indices[t + 1], mesh.indices[t + 2]);
  }
  if (normals->empty()) computeNormals(mesh);
  if (tangents->empty()) computeTangents(mesh);
  return mesh;
}

struct Walker {
  const tinygltf::Model& model;
  std::vector<Mesh> meshes;

  Expected<void> visit(int nodeIndex, const glm::mat4& parent, size_t depth) {
    if (nodeIndex < 0 || static_cast<size_t>(nodeIndex) >= model.nodes.size()) {
      return Error{"node " + std::to_string(nodeIndex) + " is out of range"};
    }
    // A valid hierarchy is a forest, so a path longer than the node count
    // means a cycle; stopping here prevents unbounded recursion.
    if (depth > model.nodes.size()) return Error{"node hierarchy contains a cycle"};
    const tinygltf::Node& node = model.nodes[static_cast<size_t>(nodeIndex)];
    glm::mat4 world = parent * localTransform(node);
    if (node.mesh >= 0) {
      if (static_cast<size_t>(node.mesh) >= model.meshes.size()) return Error{"node mesh index is out of range"};
      if (auto added = addMesh(node.mesh, world); !added) return added;
    }
    for (int child : node.children) {
      if (auto visited = visit(child, world, depth + 1); !visited) return visited;
    }
    return {};
  }

  Expected<void> addMesh(int meshIndex, const glm::mat4& transform) {
    const tinygltf::Mesh& source = model.meshes[static_cast<size_t>(meshIndex)];
    std::string baseName = source.name.empty() ? "mesh" + std::to_string(meshIndex) : source.name;
    for (size_t p = 0; p < source.primitives.size(); ++p) {
      std::string name = source.primitives.size() == 1 ? baseName : baseName + "/" + std::to_string(p);
      auto mesh = convertPrimitive(model, source.primitives[p], transform, name);
      if (!mesh) return Error{"mesh '" + name + "': " + mesh.error().message};
      meshes.push_back(std::move(mesh).value());
    }
    return {};
  }
};

// The meshes of the default scene (or of every scene when none is the
// default); a file without scenes contributes all its meshes untransformed.
Expected<void> walkScenes(Walker& walker) {
  const tinygltf::Model& model = walker.model;
  const glm::mat4 identity(1.0f);
  if (model.scenes.empty()) {
    for (size_t m = 0; m < model.meshes.size(); ++m) {
      if (auto added = walker.addMesh(static_cast<int>(m), identity); !added) return added;
    }
    return {};
  }
  size_t first = 0;
  size_t last = model.scenes.size();
  if (model.defaultScene >= 0 && static_cast<size_t>(model.defaultScene) < model.scenes.size()) {
    first = static_cast<size_t>(model.defaultScene);
    last = first + 1;
  }
  for (size_t s = first; s < last; ++s) {
    for (int root : model.scenes[s].nodes) {
      if (auto visited = walker.visit(root, identity, 0); !visited) return visited;
    }
  }
  return {};
}

// tinygltf's image callback. Decoding is deferred to loadGltfImage so that
// loading meshes decodes no images at all, and because tinygltf hands over a
// bufferView image without checking the view against its buffer: those bytes
// are only read later, after that check. Data URIs and external files arrive
// in correctly sized vectors, so their encoded bytes are kept as they are.
bool keepEncodedImage(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                      const unsigned char* bytes, int size, void*) {
  if (image->bufferView < 0 && size > 0) image->image.assign(bytes, bytes + size);
  return true;
}

// Parses the file; `prefix` starts every error message.
Expected<tinygltf::Model> parseModel(const std::filesystem::path& path, const std::string& prefix) {
  // The GLB magic decides the parser, so a binary file with a .gltf
  // extension (or the reverse) still loads.
  char magic[4] = {};
  {
    errno = 0;
    std::ifstream file(path, std::ios::binary);
    if (!file) return Error{prefix + (errno != 0 ? std::strerror(errno) : "file cannot be opened")};
    file.read(magic, sizeof magic);
  }
  bool binary = std::memcmp(magic, "glTF", 4) == 0;

  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(keepEncodedImage, nullptr);
  tinygltf::Model model;
  std::string error;
  std::string warning;
  bool ok = false;
  // tinygltf reports most problems through `error`, but some inputs reach
  // throwing standard-library calls inside it (vector::at, allocation).
  try {
    ok = binary ? loader.LoadBinaryFromFile(&model, &error, &warning, path.string())
                : loader.LoadASCIIFromFile(&model, &error, &warning, path.string());
  } catch (const std::exception& exception) {
    return Error{prefix + exception.what()};
  }
  // tinygltf explains some failures (an unreadable external image) only as a warning.
  if (!ok) return Error{prefix + (!error.empty() ? error : !warning.empty() ? warning : "parse failed")};
  return model;
}

// The encoded bytes of a bufferView image, or an error when the view does not
// lie inside its buffer.
Expected<std::pair<const unsigned char*, size_t>> bufferViewBytes(const tinygltf::Model& model, int viewIndex) {
  if (viewIndex < 0 || static_cast<size_t>(viewIndex) >= model.bufferViews.size()) {
    return Error{"bufferView " + std::to_string(viewIndex) + " is out of range"};
  }
  const tinygltf::BufferView& view = model.bufferViews[static_cast<size_t>(viewIndex)];
  if (view.buffer < 0 || static_cast<size_t>(view.buffer) >= model.buffers.size()) {
    return Error{"bufferView " + std::to_string(viewIndex) + " refers to a missing buffer"};
  }
  const std::vector<unsigned char>& data = model.buffers[static_cast<size_t>(view.buffer)].data;
  // Written so that a huge offset or length cannot wrap around.
  if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset) {
    return Error{"bufferView " + std::to_string(viewIndex) + " reads past the end of its buffer"};
  }
  return std::pair{data.data() + view.byteOffset, static_cast<size_t>(view.byteLength)};
}

}  // namespace

Expected<std::vector<Mesh>> loadGltf(const std::filesystem::path& path) {
  std::string prefix = "cannot load glTF '" + path.string() + "': ";
  auto parsed = parseModel(path, prefix);
  if (!parsed) return Error{parsed.error()};
  const tinygltf::Model& model = *parsed;

  Walker walker{model, {}};
  if (auto walked = walkScenes(walker); !walked) return Error{prefix + walked.error().message};
  return std::move(walker.meshes);
}

Expected<Image> loadGltfImage(const std::filesystem::path& path, uint32_t index) {
  std::string prefix = "cannot load image " + std::to_string(index) + " of glTF '" + path.string() + "': ";
  auto parsed = parseModel(path, prefix);
  if (!parsed) return Error{parsed.error()};
  const tinygltf::Model& model = *parsed;
  if (index >= model.images.size()) {
    return Error{prefix + "the file has " + std::to_string(model.images.size()) + " image(s)"};
  }
  const tinygltf::Image& source = model.images[index];
  const unsigned char* bytes = source.image.data();
  size_t size = source.image.size();
  if (source.bufferView >= 0) {
    auto view = bufferViewBytes(model, source.bufferView);
    if (!view) return Error{prefix + view.error().message};
    std::tie(bytes, size) = *view;
  } else if (source.image.empty()) {
    // tinygltf keeps only the URI of an external image it could not read.
    std::filesystem::path external = path.parent_path() / source.uri;
    std::error_code ec;
    std::string reason = std::filesystem::exists(external, ec)
                             ? "cannot be read"
                             : std::make_error_code(std::errc::no_such_file_or_directory).message();
    return Error{prefix + "external image '" + external.string() + "': " + reason};
  }
  auto image = decodeImage(std::span(bytes, size));
  if (!image) return Error{prefix + "cannot decode: " + image.error().message};
  return image;
}

}  // namespace spire::scene
