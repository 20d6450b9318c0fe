#include "scene/gltf.h"

#include "temp_dir.h"

#include <gtest/gtest.h>

#include <tiny_gltf.h>

#include <glm/geometric.hpp>

#include <cstring>
#include <fstream>

namespace spire::scene {
namespace {

using testing::TempDir;

constexpr float kEps = 1e-5f;

struct QuadOptions {
  bool tangents = false;
  bool normals = true;
  int indexType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;  // or -1 for none
  std::vector<double> translation = {};
  std::vector<double> rotation = {};  // quaternion x, y, z, w
  std::vector<double> scale = {};
};

template <typename T>
void appendView(tinygltf::Model& model, const std::vector<T>& values, int componentType, int type,
                size_t count) {
  tinygltf::Buffer& buffer = model.buffers[0];
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = buffer.data.size();
  view.byteLength = values.size() * sizeof(T);
  const auto* bytes = reinterpret_cast<const unsigned char*>(values.data());
  buffer.data.insert(buffer.data.end(), bytes, bytes + view.byteLength);
  // Keep every following view 4-byte aligned, as glTF requires for floats.
  buffer.data.resize((buffer.data.size() + 3) / 4 * 4);
  model.bufferViews.push_back(view);
  tinygltf::Accessor accessor;
  accessor.bufferView = static_cast<int>(model.bufferViews.size() - 1);
  accessor.componentType = componentType;
  accessor.type = type;
  accessor.count = count;
  model.accessors.push_back(accessor);
}

// The unit quad in the XY plane facing +Z with u along +X and v along +Y, so
// computed tangents must be +X with handedness +1.
tinygltf::Model makeQuadModel(const QuadOptions& options, const std::string& bufferUri) {
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
    default:
      break;
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

std::filesystem::path writeModel(const tinygltf::Model& model, const std::filesystem::path& path, bool binary) {
  tinygltf::TinyGLTF writer;
  EXPECT_TRUE(writer.WriteGltfSceneToFile(&model, path.string(), false, false, true, binary));
  return path;
}

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
  ASSERT_TRUE(meshes) << meshes.error();
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
  ASSERT_TRUE(meshes) << meshes.error();
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
  ASSERT_TRUE(meshes) << meshes.error();
  expectQuad(meshes->front());
  EXPECT_NEAR(meshes->front().vertices[2].tangent.x, 1.0f, kEps);
}

TEST(GltfTest, ByteAndIntIndices) {
  TempDir dir;
  for (int type : {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT}) {
    auto path = writeModel(makeQuadModel({.indexType = type}, ""), dir.path() / "quad.glb", true);
    auto meshes = loadGltf(path);
    ASSERT_TRUE(meshes) << meshes.error();
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
  ASSERT_TRUE(meshes) << meshes.error();
  EXPECT_EQ(meshes->front().vertices.size(), 3u);
  EXPECT_EQ(meshes->front().indices, (std::vector<uint32_t>{0, 1, 2}));
}

TEST(GltfTest, MissingNormalsComeFromFaces) {
  TempDir dir;
  auto path = writeModel(makeQuadModel({.normals = false}, ""), dir.path() / "quad.glb", true);
  auto meshes = loadGltf(path);
  ASSERT_TRUE(meshes) << meshes.error();
  expectQuad(meshes->front());
}

TEST(GltfTest, NodeTransformIsApplied) {
  TempDir dir;
  // 90 degrees about +Y maps +X to -Z and +Z to +X.
  double half = std::sqrt(0.5);
  QuadOptions options{.tangents = true, .translation = {1, 2, 3}, .rotation = {0, half, 0, half}};
  auto path = writeModel(makeQuadModel(options, ""), dir.path() / "quad.glb", true);
  auto meshes = loadGltf(path);
  ASSERT_TRUE(meshes) << meshes.error();
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
  ASSERT_TRUE(meshes) << meshes.error();
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

TEST(GltfTest, MissingFileErrorNamesPath) {
  TempDir dir;
  auto path = dir.path() / "missing.gltf";
  auto meshes = loadGltf(path);
  ASSERT_FALSE(meshes);
  EXPECT_NE(meshes.error().find(path.string()), std::string::npos) << meshes.error();
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
    EXPECT_NE(meshes.error().find(path.string()), std::string::npos) << meshes.error();
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
  EXPECT_NE(meshes.error().find("out of range"), std::string::npos) << meshes.error();
}

}  // namespace
}  // namespace spire::scene
