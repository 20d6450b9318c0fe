#pragma once

// Builds small glTF files for the scene tests with tinygltf, so tests never
// depend on checked-in assets: a unit quad with optional attributes, and
// images stored in a bufferView, as a data URI or as an external PNG.

#include "scene/texture.h"

#include <gtest/gtest.h>

#include <tiny_gltf.h>

#include <filesystem>
#include <string>
#include <vector>

namespace spire::scene::testing {

struct QuadOptions {
  bool tangents = false;
  bool normals = true;
  int indexType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;  // or -1 for none
  std::vector<double> translation = {};
  std::vector<double> rotation = {};  // quaternion x, y, z, w
  std::vector<double> scale = {};
};

// Appends `size` bytes to buffer 0 as a new bufferView; returns its index.
inline int appendBufferView(tinygltf::Model& model, const unsigned char* bytes, size_t size) {
  tinygltf::Buffer& buffer = model.buffers[0];
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = buffer.data.size();
  view.byteLength = size;
  buffer.data.insert(buffer.data.end(), bytes, bytes + size);
  // Keep every following view 4-byte aligned, as glTF requires for floats.
  buffer.data.resize((buffer.data.size() + 3) / 4 * 4);
  model.bufferViews.push_back(view);
  return static_cast<int>(model.bufferViews.size() - 1);
}

template <typename T>
void appendView(tinygltf::Model& model, const std::vector<T>& values, int componentType, int type, size_t count) {
  tinygltf::Accessor accessor;
  accessor.bufferView =
      appendBufferView(model, reinterpret_cast<const unsigned char*>(values.data()), values.size() * sizeof(T));
  accessor.componentType = componentType;
  accessor.type = type;
  accessor.count = count;
  model.accessors.push_back(accessor);
}

// The unit quad in the XY plane facing +Z with u along +X and v along +Y, so
// computed tangents must be +X with handedness +1.
inline tinygltf::Model makeQuadModel(const QuadOptions& options, const std::string& bufferUri) {
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.buffers.resize(1);
  model.buffers[0].uri = bufferUri;
  tinygltf::Primitive primitive;
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
  auto lastAccessor = [&] { return static_cast<int>(model.accessors.size() - 1); };

  appendView(model, std::vector<float>{0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, TINYGLTF_COMPONENT_TYPE_FLOAT,
             TINYGLTF_TYPE_VEC3, 4);
  model.accessors.back().minValues = {0, 0, 0};  // required for POSITION
  model.accessors.back().maxValues = {1, 1, 0};
  primitive.attributes["POSITION"] = lastAccessor();
  if (options.normals) {
    appendView(model, std::vector<float>{0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, TINYGLTF_COMPONENT_TYPE_FLOAT,
               TINYGLTF_TYPE_VEC3, 4);
    primitive.attributes["NORMAL"] = lastAccessor();
  }
  appendView(model, std::vector<float>{0, 0, 1, 0, 1, 1, 0, 1}, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC2, 4);
  primitive.attributes["TEXCOORD_0"] = lastAccessor();
  if (options.tangents) {
    // Deliberately -1 handedness: proves the file's tangents are used as-is.
    appendView(model, std::vector<float>{1, 0, 0, -1, 1, 0, 0, -1, 1, 0, 0, -1, 1, 0, 0, -1},
               TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC4, 4);
    primitive.attributes["TANGENT"] = lastAccessor();
  }
  switch (options.indexType) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      appendView(model, std::vector<uint8_t>{0, 1, 2, 0, 2, 3}, options.indexType, TINYGLTF_TYPE_SCALAR, 6);
      break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      appendView(model, std::vector<uint16_t>{0, 1, 2, 0, 2, 3}, options.indexType, TINYGLTF_TYPE_SCALAR, 6);
      break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      appendView(model, std::vector<uint32_t>{0, 1, 2, 0, 2, 3}, options.indexType, TINYGLTF_TYPE_SCALAR, 6);
      break;
    default: break;
  }
  if (options.indexType != -1) primitive.indices = lastAccessor();
  model.buffers[0].data.shrink_to_fit();

  tinygltf::Mesh mesh;
  mesh.name = "quad";
  mesh.primitives.push_back(primitive);
  model.meshes.push_back(mesh);
  tinygltf::Node node;
  node.mesh = 0;
  node.translation = options.translation;
  node.rotation = options.rotation;
  node.scale = options.scale;
  model.nodes.push_back(node);
  tinygltf::Scene scene;
  scene.nodes = {0};
  model.scenes.push_back(scene);
  model.defaultScene = 0;
  return model;
}

// `embedImages` writes images given as pixels (addPixelImage) as data URIs;
// otherwise as PNG files beside `path`.
inline std::filesystem::path writeModel(const tinygltf::Model& model, const std::filesystem::path& path, bool binary,
                                        bool embedImages = false) {
  tinygltf::TinyGLTF writer;
  // tinygltf's default image writer gets no filesystem callbacks and silently
  // skips external image files; these are its own defaults.
  tinygltf::FsCallbacks fs{&tinygltf::FileExists, &tinygltf::ExpandFilePath, &tinygltf::ReadWholeFile,
                           &tinygltf::WriteWholeFile, nullptr};
  writer.SetImageWriter(&tinygltf::WriteImageData, &fs);
  EXPECT_TRUE(writer.WriteGltfSceneToFile(&model, path.string(), embedImages, false, true, binary));
  return path;
}

// `image` as PNG bytes, by the library's own encoder.
inline std::vector<unsigned char> pngBytes(const Image& image) {
  const auto encoded = scene::encodePng(image);
  EXPECT_TRUE(encoded) << encoded.error().message;
  if (!encoded) return {};
  return {encoded->begin(), encoded->end()};
}

// Adds `encoded` as an image stored in a bufferView of buffer 0 (the .glb way).
inline int addBufferViewImage(tinygltf::Model& model, const std::vector<unsigned char>& encoded) {
  tinygltf::Image image;
  image.bufferView = appendBufferView(model, encoded.data(), encoded.size());
  image.mimeType = "image/png";
  model.images.push_back(image);
  return static_cast<int>(model.images.size() - 1);
}

// Adds `pixels` as an image that tinygltf's writer encodes as `name`.png,
// either embedded as a data URI or written beside the glTF file.
inline int addPixelImage(tinygltf::Model& model, const std::string& name, const Image& pixels) {
  tinygltf::Image image;
  image.name = name;
  image.mimeType = "image/png";
  image.width = static_cast<int>(pixels.width);
  image.height = static_cast<int>(pixels.height);
  image.component = 4;
  image.bits = 8;
  image.pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
  image.image = pixels.bytes;
  model.images.push_back(image);
  return static_cast<int>(model.images.size() - 1);
}

// A 3x2 image with distinct colors and alphas, so any stride, channel or row
// order mistake changes the decoded bytes.
inline Image makeTestPixels() {
  Image image;
  image.width = 3;
  image.height = 2;
  image.bytes = {255, 0, 0, 255, 0, 255, 0, 200, 0, 0, 255, 100, 10, 20, 30, 40, 50, 60, 70, 80, 90, 100, 110, 120};
  return image;
}

}  // namespace spire::scene::testing
