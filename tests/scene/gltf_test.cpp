#include "scene/gltf.h"

#include "gltf_test_model.h"
#include "temp_dir.h"

#include <gtest/gtest.h>

#include <tiny_gltf.h>

#include <glm/geometric.hpp>

#include <cstring>
#include <fstream>
#include <iterator>
#include <string>

namespace spire::scene {
namespace {

using testing::addBufferViewImage;
using testing::addPixelImage;
using testing::makeQuadModel;
using testing::makeTestPixels;
using testing::pngBytes;
using testing::QuadOptions;
using testing::TempDir;
using testing::writeModel;

constexpr float kEps = 1e-5f;

void expectQuad(const Mesh& mesh, glm::vec3 offset = glm::vec3(0.0f)) {
  ASSERT_EQ(mesh.vertices.size(), 4u);
  EXPECT_EQ(mesh.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
  const glm::vec3 positions[] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const glm::vec2 uvs[] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (size_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(glm::distance(mesh.vertices[i].position, positions[i] + offset), 0.0f, kEps) << i;
    EXPECT_EQ(mesh.vertices[i].uv, uvs[i]) << i;
    EXPECT_NEAR(glm::distance(mesh.vertices[i].normal, glm::vec3(0, 0, 1)), 0.0f, kEps) << i;
  }
}

TEST(GltfTest, BinaryWithTangentsKeepsFileTangents) {
  TempDir dir;
  auto path = writeModel(makeQuadModel({.tangents = true}, ""), dir.path() / "quad.glb", true);
  auto meshes = loadGltf(path);
  ASSERT_TRUE(meshes) << meshes.error().message;
  ASSERT_EQ(meshes->size(), 1u);
  const Mesh& mesh = meshes->front();
  EXPECT_EQ(mesh.name, "quad");
  expectQuad(mesh);
  for (const Vertex& v : mesh.vertices) EXPECT_EQ(v.tangent, glm::vec4(1, 0, 0, -1));
}

TEST(GltfTest, TextWithSeparateBinComputesTangents) {
  TempDir dir;
  auto path = writeModel(makeQuadModel({}, "quad.bin"), dir.path() / "quad.gltf", false);
  ASSERT_TRUE(std::filesystem::exists(dir.path() / "quad.bin"));
  auto meshes = loadGltf(path);
  ASSERT_TRUE(meshes) << meshes.error().message;
  ASSERT_EQ(meshes->size(), 1u);
  expectQuad(meshes->front());
  for (const Vertex& v : meshes->front().vertices) {
    EXPECT_NEAR(glm::distance(glm::vec3(v.tangent), glm::vec3(1, 0, 0)), 0.0f, kEps);
    EXPECT_EQ(v.tangent.w, 1.0f);
  }
}

TEST(GltfTest, BinaryWithoutTangentsComputesTangents) {
  TempDir dir;
  auto path = writeModel(makeQuadModel({}, ""), dir.path() / "quad.glb", true);
  auto meshes = loadGltf(path);
  ASSERT_TRUE(meshes) << meshes.error().message;
  expectQuad(meshes->front());
  EXPECT_NEAR(meshes->front().vertices[2].tangent.x, 1.0f, kEps);
}

TEST(GltfTest, ByteAndIntIndices) {
  TempDir dir;
  for (int type : {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT}) {
    auto path = writeModel(makeQuadModel({.indexType = type}, ""), dir.path() / "quad.glb", true);
    auto meshes = loadGltf(path);
    ASSERT_TRUE(meshes) << meshes.error().message;
    expectQuad(meshes->front());
  }
}

TEST(GltfTest, NonIndexedGetsSequentialIndices) {
  TempDir dir;
  tinygltf::Model model = makeQuadModel({.indexType = -1}, "");
  // Only the first triangle: every attribute accessor reads 3 of the 4 vertices.
  for (tinygltf::Accessor& accessor : model.accessors) accessor.count = 3;
  model.accessors[0].maxValues = {1, 1, 0};
  auto path = writeModel(model, dir.path() / "triangle.glb", true);
  auto meshes = loadGltf(path);
  ASSERT_TRUE(meshes) << meshes.error().message;
  EXPECT_EQ(meshes->front().vertices.size(), 3u);
  EXPECT_EQ(meshes->front().indices, (std::vector<uint32_t>{0, 1, 2}));
}

TEST(GltfTest, MissingNormalsComeFromFaces) {
  TempDir dir;
  auto path = writeModel(makeQuadModel({.normals = false}, ""), dir.path() / "quad.glb", true);
  auto meshes = loadGltf(path);
  ASSERT_TRUE(meshes) << meshes.error().message;
  expectQuad(meshes->front());
}

TEST(GltfTest, NodeTransformIsApplied) {
  TempDir dir;
  // 90 degrees about +Y maps +X to -Z and +Z to +X.
  double half = std::sqrt(0.5);
  QuadOptions options{.tangents = true, .translation = {1, 2, 3}, .rotation = {0, half, 0, half}};
  auto path = writeModel(makeQuadModel(options, ""), dir.path() / "quad.glb", true);
  auto meshes = loadGltf(path);
  ASSERT_TRUE(meshes) << meshes.error().message;
  const Mesh& mesh = meshes->front();
  EXPECT_NEAR(glm::distance(mesh.vertices[1].position, glm::vec3(1, 2, 2)), 0.0f, kEps);
  EXPECT_NEAR(glm::distance(mesh.vertices[2].position, glm::vec3(1, 3, 2)), 0.0f, kEps);
  for (const Vertex& v : mesh.vertices) {
    EXPECT_NEAR(glm::distance(v.normal, glm::vec3(1, 0, 0)), 0.0f, kEps);
    EXPECT_NEAR(glm::distance(glm::vec3(v.tangent), glm::vec3(0, 0, -1)), 0.0f, kEps);
  }
}

TEST(GltfTest, MirroringTransformKeepsFrontFacesAndHandedness) {
  TempDir dir;
  QuadOptions options{.tangents = true, .scale = {-1, 1, 1}};
  auto path = writeModel(makeQuadModel(options, ""), dir.path() / "quad.glb", true);
  auto meshes = loadGltf(path);
  ASSERT_TRUE(meshes) << meshes.error().message;
  const Mesh& mesh = meshes->front();
  EXPECT_EQ(mesh.indices, (std::vector<uint32_t>{0, 2, 1, 0, 3, 2}));
  const glm::vec3& a = mesh.vertices[mesh.indices[0]].position;
  glm::vec3 face = glm::cross(mesh.vertices[mesh.indices[1]].position - a, mesh.vertices[mesh.indices[2]].position - a);
  for (const Vertex& v : mesh.vertices) {
    EXPECT_GT(glm::dot(face, v.normal), 0.0f);
    EXPECT_NEAR(glm::distance(glm::vec3(v.tangent), glm::vec3(-1, 0, 0)), 0.0f, kEps);
    EXPECT_EQ(v.tangent.w, 1.0f);  // the file's -1, flipped by the mirror
  }
}

// glTF culls back faces unless the primitive's material is double-sided; a
// primitive without a material gets the default material, single-sided.
TEST(GltfTest, DoubleSidedComesFromThePrimitivesMaterial) {
  TempDir dir;
  tinygltf::Model model = makeQuadModel({}, "");
  auto meshes = loadGltf(writeModel(model, dir.path() / "default.glb", true));
  ASSERT_TRUE(meshes) << meshes.error().message;
  EXPECT_FALSE(meshes->front().doubleSided);

  tinygltf::Material material;
  material.doubleSided = true;
  model.materials.push_back(material);
  model.meshes[0].primitives[0].material = 0;
  meshes = loadGltf(writeModel(model, dir.path() / "double_sided.glb", true));
  ASSERT_TRUE(meshes) << meshes.error().message;
  EXPECT_TRUE(meshes->front().doubleSided);

  model.materials[0].doubleSided = false;
  meshes = loadGltf(writeModel(model, dir.path() / "single_sided.glb", true));
  ASSERT_TRUE(meshes) << meshes.error().message;
  EXPECT_FALSE(meshes->front().doubleSided);
}

TEST(GltfTest, MissingFileErrorNamesPath) {
  TempDir dir;
  auto path = dir.path() / "missing.gltf";
  auto meshes = loadGltf(path);
  ASSERT_FALSE(meshes);
  EXPECT_NE(meshes.error().message.find(path.string()), std::string::npos) << meshes.error().message;
}

TEST(GltfTest, CorruptFilesErrorNamesPath) {
  TempDir dir;
  auto text = dir.path() / "corrupt.gltf";
  std::ofstream(text) << "{ \"asset\": { \"version\": ";
  auto binary = dir.path() / "corrupt.glb";
  std::ofstream(binary, std::ios::binary) << "glTF\x02\x00\x00\x00 truncated";
  for (const auto& path : {text, binary}) {
    auto meshes = loadGltf(path);
    ASSERT_FALSE(meshes) << path;
    EXPECT_NE(meshes.error().message.find(path.string()), std::string::npos) << meshes.error().message;
  }
}

TEST(GltfTest, OutOfRangeIndexIsAnError) {
  TempDir dir;
  tinygltf::Model model = makeQuadModel({.indexType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT}, "");
  // Patch index 5 of the last bufferView (the indices) to point past the quad.
  const tinygltf::BufferView& view = model.bufferViews.back();
  uint32_t bad = 9;
  std::memcpy(model.buffers[0].data.data() + view.byteOffset + 5 * sizeof(uint32_t), &bad, sizeof bad);
  auto path = writeModel(model, dir.path() / "bad.glb", true);
  auto meshes = loadGltf(path);
  ASSERT_FALSE(meshes);
  EXPECT_NE(meshes.error().message.find("out of range"), std::string::npos) << meshes.error().message;
}

void expectContains(const std::string& text, const std::string& part) {
  EXPECT_NE(text.find(part), std::string::npos) << "'" << part << "' not in: " << text;
}

std::string readText(const std::filesystem::path& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(GltfImageTest, BufferViewImagesInGlbByIndex) {
  TempDir dir;
  tinygltf::Model model = makeQuadModel({}, "");
  Image second = makeChecker(4, 2, Rgba8(1, 2, 3, 4), Rgba8(250, 251, 252, 253));
  addBufferViewImage(model, pngBytes(makeTestPixels()));
  addBufferViewImage(model, pngBytes(second));
  auto path = writeModel(model, dir.path() / "textured.glb", true);
  auto first = loadGltfImage(path, 0);
  ASSERT_TRUE(first) << first.error().message;
  EXPECT_EQ(first->width, 3u);
  EXPECT_EQ(first->height, 2u);
  EXPECT_EQ(first->bytes, makeTestPixels().bytes);
  auto other = loadGltfImage(path, 1);
  ASSERT_TRUE(other) << other.error().message;
  EXPECT_EQ(other->bytes, second.bytes);
  // Images do not get in the way of the meshes.
  auto meshes = loadGltf(path);
  ASSERT_TRUE(meshes) << meshes.error().message;
  expectQuad(meshes->front());
}

TEST(GltfImageTest, DataUriImage) {
  TempDir dir;
  tinygltf::Model model = makeQuadModel({}, "quad.bin");
  addPixelImage(model, "pixels", makeTestPixels());
  auto path = writeModel(model, dir.path() / "quad.gltf", false, true);
  ASSERT_FALSE(std::filesystem::exists(dir.path() / "pixels.png"));
  expectContains(readText(path), "data:image/png;base64,");
  auto image = loadGltfImage(path, 0);
  ASSERT_TRUE(image) << image.error().message;
  EXPECT_EQ(image->width, 3u);
  EXPECT_EQ(image->bytes, makeTestPixels().bytes);
}

TEST(GltfImageTest, ExternalImage) {
  TempDir dir;
  tinygltf::Model model = makeQuadModel({}, "quad.bin");
  addPixelImage(model, "pixels", makeTestPixels());
  auto path = writeModel(model, dir.path() / "quad.gltf", false, false);
  ASSERT_TRUE(std::filesystem::exists(dir.path() / "pixels.png"));
  auto image = loadGltfImage(path, 0);
  ASSERT_TRUE(image) << image.error().message;
  EXPECT_EQ(image->bytes, makeTestPixels().bytes);
}

TEST(GltfImageTest, MissingExternalImageNamesItsPath) {
  TempDir dir;
  tinygltf::Model model = makeQuadModel({}, "quad.bin");
  addPixelImage(model, "pixels", makeTestPixels());
  auto path = writeModel(model, dir.path() / "quad.gltf", false, false);
  std::filesystem::remove(dir.path() / "pixels.png");
  auto image = loadGltfImage(path, 0);
  ASSERT_FALSE(image);
  expectContains(image.error().message, (dir.path() / "pixels.png").string());
  expectContains(image.error().message, "No such file or directory");
  // The meshes of the same file still load.
  EXPECT_TRUE(loadGltf(path));
}

TEST(GltfImageTest, MissingFileNamesPathAndReason) {
  TempDir dir;
  auto path = dir.path() / "missing.glb";
  auto image = loadGltfImage(path, 0);
  ASSERT_FALSE(image);
  expectContains(image.error().message, path.string());
  expectContains(image.error().message, "No such file or directory");
}

TEST(GltfImageTest, IndexPastTheImagesIsAnError) {
  TempDir dir;
  tinygltf::Model model = makeQuadModel({}, "");
  addBufferViewImage(model, pngBytes(makeTestPixels()));
  auto path = writeModel(model, dir.path() / "textured.glb", true);
  auto image = loadGltfImage(path, 1);
  ASSERT_FALSE(image);
  expectContains(image.error().message, path.string());
  expectContains(image.error().message, "has 1 image");
}

TEST(GltfImageTest, CorruptImageDataIsAnErrorButMeshesLoad) {
  TempDir dir;
  tinygltf::Model model = makeQuadModel({}, "");
  addBufferViewImage(model, {0x89, 'P', 'N', 'G', 1, 2, 3, 4, 5});
  auto path = writeModel(model, dir.path() / "textured.glb", true);
  auto image = loadGltfImage(path, 0);
  ASSERT_FALSE(image);
  expectContains(image.error().message, path.string());
  expectContains(image.error().message, "cannot decode");
  EXPECT_TRUE(loadGltf(path));
}

TEST(GltfImageTest, BufferViewPastItsBufferIsAnError) {
  TempDir dir;
  auto path = dir.path() / "short.gltf";
  std::ofstream(path) << R"({"asset": {"version": "2.0"},
    "buffers": [{"byteLength": 4, "uri": "data:application/octet-stream;base64,AAAAAA=="}],
    "bufferViews": [{"buffer": 0, "byteLength": 1000000}],
    "images": [{"bufferView": 0, "mimeType": "image/png"}]})";
  auto image = loadGltfImage(path, 0);
  ASSERT_FALSE(image);
  expectContains(image.error().message, "reads past the end");
}

TEST(GltfImageTest, CorruptFileNamesPath) {
  TempDir dir;
  auto path = dir.path() / "corrupt.gltf";
  std::ofstream(path) << "{ \"images\": [";
  auto image = loadGltfImage(path, 0);
  ASSERT_FALSE(image);
  expectContains(image.error().message, path.string());
}

}  // namespace
}  // namespace spire::scene
