#include "scene/scene_resources.h"

#include "gltf_test_model.h"
#include "temp_dir.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <stb/stb_image_write.h>

#include <cmath>
#include <string>

namespace spire::scene {
namespace {

using testing::addBufferViewImage;
using testing::makeQuadModel;
using testing::makeTestPixels;
using testing::pngBytes;
using testing::TempDir;
using testing::writeModel;

void expectContains(const std::string& text, const std::string& part) {
  EXPECT_NE(text.find(part), std::string::npos) << "'" << part << "' not in: " << text;
}

void expectSameMesh(const Mesh& a, const Mesh& b) {
  ASSERT_EQ(a.vertices.size(), b.vertices.size());
  EXPECT_EQ(a.indices, b.indices);
  for (size_t i = 0; i < a.vertices.size(); ++i) {
    EXPECT_EQ(a.vertices[i].position, b.vertices[i].position) << i;
    EXPECT_EQ(a.vertices[i].normal, b.vertices[i].normal) << i;
    EXPECT_EQ(a.vertices[i].uv, b.vertices[i].uv) << i;
    EXPECT_EQ(a.vertices[i].tangent, b.vertices[i].tangent) << i;
  }
}

MeshDesc meshDesc(MeshKind kind) {
  MeshDesc desc;
  desc.name = "ground";
  desc.kind = kind;
  desc.size = 4.0F;
  desc.resolution = 8;
  desc.height = 0.5F;
  desc.seed = 7;
  desc.radius = 2.0F;
  desc.rings = 6;
  desc.segments = 9;
  return desc;
}

TextureDesc textureDesc(TextureKind kind) {
  TextureDesc desc;
  desc.name = "albedo";
  desc.kind = kind;
  desc.size = 16;
  desc.seed = 3;
  desc.octaves = 4;
  desc.cells = 4;
  desc.strength = 1.5F;
  desc.color = glm::vec4(1.0F, 0.0F, 0.5F, 1.0F);
  desc.color2 = glm::vec4(0.0F, 1.0F, 0.0F, 0.5F);
  return desc;
}

Image build(const TextureDesc& desc) {
  auto image = buildTexture(desc, SceneFile{});
  EXPECT_TRUE(image) << image.error().message;
  return image ? std::move(image).value() : Image{};
}

// A pack's R, G, B, A are the named channels of other textures; missing
// colors are 0 and a missing alpha 1; the sources must share one size.
TEST(SceneResourcesTest, PackCopiesTheNamedChannels) {
  SceneFile scene;
  scene.textures.push_back(textureDesc(TextureKind::Noise));
  scene.textures.back().name = "noise";
  scene.textures.push_back(textureDesc(TextureKind::Checker));
  scene.textures.back().name = "checker";
  TextureDesc pack;
  pack.name = "masks";
  pack.kind = TextureKind::Pack;
  pack.channels = {{"checker", 2, {}}, {"noise", 0, {}}};
  auto packed = buildTexture(pack, scene);
  ASSERT_TRUE(packed) << packed.error().message;
  const Image noise = build(scene.textures[0]);
  const Image checker = build(scene.textures[1]);
  ASSERT_EQ(packed->width, noise.width);
  ASSERT_EQ(packed->bytes.size(), noise.bytes.size());
  for (size_t texel = 0; texel < packed->bytes.size(); texel += 4) {
    ASSERT_EQ(packed->bytes[texel], checker.bytes[texel + 2]) << texel;
    ASSERT_EQ(packed->bytes[texel + 1], noise.bytes[texel]) << texel;
    ASSERT_EQ(packed->bytes[texel + 2], 0) << texel;
    ASSERT_EQ(packed->bytes[texel + 3], 255) << texel;
  }

  scene.textures[1].size = 8;
  auto mismatched = buildTexture(pack, scene);
  ASSERT_FALSE(mismatched);
  EXPECT_EQ(mismatched.error().message,
            "texture 'masks': its channels come from textures of different sizes ('checker' is 8x8, 'noise' 16x16)");
}

// A pack of 8-bit sources stays RGBA8; a float source makes it RGBA32F, so
// that every value of every source survives; "format" overrides both.
TEST(SceneResourcesTest, PackTakesTheWiderFormatOfItsSources) {
  SceneFile scene;
  scene.textures.push_back(textureDesc(TextureKind::Noise));
  scene.textures.back().name = "noise";
  scene.textures.push_back(textureDesc(TextureKind::Solid));
  scene.textures.back().name = "fine";
  scene.textures.back().color = glm::vec4(0.123456F, 0.25F, 1.0F / 3.0F, 1.0F);
  scene.textures.back().format = PixelFormat::RGBA32F;
  TextureDesc pack;
  pack.name = "masks";
  pack.kind = TextureKind::Pack;
  pack.channels = {{"noise", 0, {}}, {"fine", 0, {}}, {"fine", 2, {}}};
  auto packed = buildTexture(pack, scene);
  ASSERT_TRUE(packed) << packed.error().message;
  EXPECT_EQ(packed->format, PixelFormat::RGBA32F);
  const Image noise = build(scene.textures[0]);
  EXPECT_EQ(packed->texel(5, 7), glm::vec4(noise.pixel(5, 7).r / 255.0F, 0.123456F, 1.0F / 3.0F, 1.0F));

  scene.textures.back().format = PixelFormat::RGBA16;
  packed = buildTexture(pack, scene);
  ASSERT_TRUE(packed) << packed.error().message;
  EXPECT_EQ(packed->format, PixelFormat::RGBA16);
  EXPECT_EQ(std::lround(packed->texel(5, 7).r * 65535.0F), noise.pixel(5, 7).r * 257);
  EXPECT_EQ(std::lround(packed->texel(5, 7).g * 65535.0F), std::lround(0.123456F * 65535.0F));

  pack.format = PixelFormat::R32F;
  packed = buildTexture(pack, scene);
  ASSERT_TRUE(packed) << packed.error().message;
  EXPECT_EQ(packed->format, PixelFormat::R32F);
  EXPECT_EQ(packed->texel(5, 7), glm::vec4(noise.pixel(5, 7).r / 255.0F, 0.0F, 0.0F, 1.0F));
}

// Procedural textures in a format other than RGBA8 are computed in float, so
// that colors keep more than 8 bits; "RGBA8" asked for is the default.
TEST(SceneResourcesTest, ProceduralTexturesAreMadeInTheirFormat) {
  const glm::vec4 fine(0.123456F, 0.25F, 1.0F / 3.0F, 0.75F);
  for (TextureKind kind :
       {TextureKind::Noise, TextureKind::Checker, TextureKind::NormalMap, TextureKind::Solid, TextureKind::GgxLut}) {
    TextureDesc desc = textureDesc(kind);
    const Image eightBit = build(desc);
    desc.format = PixelFormat::RGBA8;
    EXPECT_EQ(build(desc).bytes, eightBit.bytes);
    for (PixelFormat format : {PixelFormat::RGBA16, PixelFormat::RGBA16F, PixelFormat::RGBA32F, PixelFormat::R32F}) {
      desc.format = format;
      const Image image = build(desc);
      EXPECT_EQ(image.format, format);
      EXPECT_TRUE(image.consistent());
      EXPECT_EQ(image.width, 16U);
    }
  }
  TextureDesc solid = textureDesc(TextureKind::Solid);
  solid.color = fine;
  solid.format = PixelFormat::RGBA32F;
  EXPECT_EQ(build(solid).texel(3, 3), fine);
  TextureDesc noise = textureDesc(TextureKind::Noise);
  noise.format = PixelFormat::RGBA32F;
  const Image grey = makeNoise(16, 3, 4, PixelFormat::RGBA32F);
  const float v = grey.texel(9, 2).r;
  const glm::vec4 mixed = noise.color2 + (noise.color - noise.color2) * v;
  EXPECT_EQ(build(noise).texel(9, 2), mixed);
}

TEST(SceneResourcesTest, FileTexturesConvertIntoTheirFormat) {
  TempDir dir;
  TextureDesc file = textureDesc(TextureKind::File);
  file.file = dir.path() / "pixels.png";
  const Image pixels = makeTestPixels();
  ASSERT_TRUE(writePng(file.file, pixels));
  file.format = PixelFormat::RGBA16F;
  const Image half = build(file);
  EXPECT_EQ(half.format, PixelFormat::RGBA16F);
  EXPECT_EQ(convertImage(half, PixelFormat::RGBA8).bytes, pixels.bytes);

  // .hdr is RGBA32F by default and clamps into RGBA8.
  file.file = dir.path() / "bright.hdr";
  const float rgb[] = {4.0F, 0.5F, 0.25F};
  ASSERT_NE(stbi_write_hdr(file.file.c_str(), 1, 1, 3, rgb), 0);
  file.format.reset();
  const Image bright = build(file);
  EXPECT_EQ(bright.format, PixelFormat::RGBA32F);
  EXPECT_EQ(bright.texel(0, 0), glm::vec4(4.0F, 0.5F, 0.25F, 1.0F));
  file.format = PixelFormat::RGBA8;
  EXPECT_EQ(build(file).pixel(0, 0), Rgba8(255, 128, 64, 255));
}

TEST(SceneResourcesTest, ProceduralMeshesComeFromTheGenerators) {
  auto terrain = buildMesh(meshDesc(MeshKind::Terrain));
  ASSERT_TRUE(terrain) << terrain.error().message;
  EXPECT_EQ(terrain->name, "ground");
  expectSameMesh(*terrain, makeTerrain(4.0F, 8, 0.5F, 7));

  auto plane = buildMesh(meshDesc(MeshKind::Plane));
  ASSERT_TRUE(plane) << plane.error().message;
  expectSameMesh(*plane, makePlane(4.0F, 8));

  auto sphere = buildMesh(meshDesc(MeshKind::Sphere));
  ASSERT_TRUE(sphere) << sphere.error().message;
  expectSameMesh(*sphere, makeSphere(2.0F, 6, 9));
}

TEST(SceneResourcesTest, TerrainIsDeterministicPerSeed) {
  MeshDesc desc = meshDesc(MeshKind::Terrain);
  auto first = buildMesh(desc);
  auto second = buildMesh(desc);
  ASSERT_TRUE(first && second);
  expectSameMesh(*first, *second);
  desc.seed = 8;
  auto reseeded = buildMesh(desc);
  ASSERT_TRUE(reseeded);
  EXPECT_NE(reseeded->vertices[10].position, first->vertices[10].position);
}

TEST(SceneResourcesTest, GltfPrimitivesAreMergedIntoOneMesh) {
  TempDir dir;
  tinygltf::Model model = makeQuadModel({}, "");
  // A second instance of the quad, moved along +Z.
  tinygltf::Node moved;
  moved.mesh = 0;
  moved.translation = {0, 0, 2};
  model.nodes.push_back(moved);
  model.scenes[0].nodes.push_back(1);
  MeshDesc desc = meshDesc(MeshKind::Gltf);
  desc.file = writeModel(model, dir.path() / "quads.glb", true);

  auto mesh = buildMesh(desc);
  ASSERT_TRUE(mesh) << mesh.error().message;
  EXPECT_EQ(mesh->name, "ground");
  ASSERT_EQ(mesh->vertices.size(), 8u);
  EXPECT_EQ(mesh->indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7}));
  EXPECT_EQ(mesh->vertices[6].position, glm::vec3(1, 1, 2));
  for (const Vertex& v : mesh->vertices) {
    // Tangents computed by loadGltf: the quad's u runs along +X.
    EXPECT_NEAR(glm::distance(glm::vec3(v.tangent), glm::vec3(1, 0, 0)), 0.0F, 1e-5F);
  }
}

TEST(SceneResourcesTest, MeshErrors) {
  TempDir dir;
  MeshDesc gltf = meshDesc(MeshKind::Gltf);
  gltf.file = dir.path() / "missing.glb";
  auto missing = buildMesh(gltf);
  ASSERT_FALSE(missing);
  expectContains(missing.error().message, gltf.file.string());
  expectContains(missing.error().message, "No such file or directory");

  tinygltf::Model empty;
  empty.asset.version = "2.0";
  gltf.file = writeModel(empty, dir.path() / "empty.gltf", false);
  auto noMeshes = buildMesh(gltf);
  ASSERT_FALSE(noMeshes);
  expectContains(noMeshes.error().message, "no triangle meshes");

  MeshDesc huge = meshDesc(MeshKind::Terrain);
  huge.resolution = 100000;
  auto tooBig = buildMesh(huge);
  ASSERT_FALSE(tooBig);
  expectContains(tooBig.error().message, "mesh 'ground': resolution 100000");

  MeshDesc sphere = meshDesc(MeshKind::Sphere);
  sphere.radius = -1.0F;
  auto negative = buildMesh(sphere);
  ASSERT_FALSE(negative);
  expectContains(negative.error().message, "radius");

  MeshDesc plane = meshDesc(MeshKind::Plane);
  plane.size = std::nanf("");
  EXPECT_FALSE(buildMesh(plane));
}

TEST(SceneResourcesTest, SolidCheckerNormalMapAndGgxLutUseTheirGenerators) {
  TextureDesc solid = textureDesc(TextureKind::Solid);
  // 0.5 * 255 = 127.5 rounds up; out-of-range components clamp.
  solid.color = glm::vec4(0.5F, 0.25F, 2.0F, -1.0F);
  EXPECT_EQ(build(solid).bytes, makeSolid(16, Rgba8(128, 64, 255, 0)).bytes);

  EXPECT_EQ(build(textureDesc(TextureKind::Checker)).bytes,
            makeChecker(16, 4, Rgba8(255, 0, 128, 255), Rgba8(0, 255, 0, 128)).bytes);
  EXPECT_EQ(build(textureDesc(TextureKind::NormalMap)).bytes, makeNormalMap(16, 3, 1.5F).bytes);
  EXPECT_EQ(build(textureDesc(TextureKind::GgxLut)).bytes, makeGgxLut(16).bytes);
}

TEST(SceneResourcesTest, NoiseMixesTheTwoColors) {
  TextureDesc desc = textureDesc(TextureKind::Noise);
  Image colored = build(desc);
  Image grey = makeNoise(16, 3, 4);
  ASSERT_EQ(colored.bytes.size(), grey.bytes.size());
  for (size_t texel = 0; texel < grey.bytes.size(); texel += 4) {
    int v = grey.bytes[texel];
    // mix(color2, color, v): red follows v, green its complement; blue runs
    // from 0 to 0.5 and alpha from 0.5 to 1, rounded to the nearest step (ties
    // either way, as float arithmetic lands them).
    EXPECT_EQ(colored.bytes[texel], v);
    EXPECT_EQ(colored.bytes[texel + 1], 255 - v);
    EXPECT_LE(std::abs(colored.bytes[texel + 2] - v * 0.5), 0.5);
    EXPECT_LE(std::abs(colored.bytes[texel + 3] - (127.5 + v * 0.5)), 0.5);
  }
  // The default colors (white over opaque black) leave the grey noise as it is.
  TextureDesc plain = desc;
  plain.color = TextureDesc{}.color;
  plain.color2 = TextureDesc{}.color2;
  EXPECT_EQ(build(plain).bytes, grey.bytes);
}

TEST(SceneResourcesTest, ProceduralTexturesAreDeterministic) {
  for (TextureKind kind :
       {TextureKind::Noise, TextureKind::Checker, TextureKind::NormalMap, TextureKind::Solid, TextureKind::GgxLut}) {
    TextureDesc desc = textureDesc(kind);
    Image first = build(desc);
    EXPECT_EQ(first.width, 16u);
    EXPECT_EQ(first.height, 16u);
    EXPECT_EQ(build(desc).bytes, first.bytes);
  }
  TextureDesc reseeded = textureDesc(TextureKind::Noise);
  reseeded.seed = 4;
  EXPECT_NE(build(reseeded).bytes, build(textureDesc(TextureKind::Noise)).bytes);
}

TEST(SceneResourcesTest, FileAndGltfTextures) {
  TempDir dir;
  TextureDesc file = textureDesc(TextureKind::File);
  file.file = dir.path() / "pixels.png";
  ASSERT_TRUE(writePng(file.file, makeTestPixels()));
  EXPECT_EQ(build(file).bytes, makeTestPixels().bytes);

  tinygltf::Model model = makeQuadModel({}, "");
  addBufferViewImage(model, pngBytes(makeSolid(2, Rgba8(9, 8, 7, 6))));
  addBufferViewImage(model, pngBytes(makeTestPixels()));
  TextureDesc gltf = textureDesc(TextureKind::Gltf);
  gltf.file = writeModel(model, dir.path() / "textured.glb", true);
  gltf.image = 1;
  Image image = build(gltf);
  EXPECT_EQ(image.width, 3u);
  EXPECT_EQ(image.bytes, makeTestPixels().bytes);
}

TEST(SceneResourcesTest, TextureErrors) {
  TempDir dir;
  TextureDesc file = textureDesc(TextureKind::File);
  file.file = dir.path() / "missing.png";
  auto missing = buildTexture(file, SceneFile{});
  ASSERT_FALSE(missing);
  expectContains(missing.error().message, file.file.string());

  TextureDesc gltf = textureDesc(TextureKind::Gltf);
  gltf.file = dir.path() / "missing.gltf";
  auto noFile = buildTexture(gltf, SceneFile{});
  ASSERT_FALSE(noFile);
  expectContains(noFile.error().message, gltf.file.string());

  gltf.file = writeModel(makeQuadModel({}, ""), dir.path() / "untextured.glb", true);
  auto noImage = buildTexture(gltf, SceneFile{});
  ASSERT_FALSE(noImage);
  expectContains(noImage.error().message, "has 0 image");

  TextureDesc empty = textureDesc(TextureKind::Checker);
  empty.size = 0;
  auto zero = buildTexture(empty, SceneFile{});
  ASSERT_FALSE(zero);
  expectContains(zero.error().message, "texture 'albedo': size 0");

  TextureDesc octaves = textureDesc(TextureKind::Noise);
  octaves.octaves = 1000;
  EXPECT_FALSE(buildTexture(octaves, SceneFile{}));

  TextureDesc strength = textureDesc(TextureKind::NormalMap);
  strength.strength = INFINITY;
  EXPECT_FALSE(buildTexture(strength, SceneFile{}));
}

}  // namespace
}  // namespace spire::scene
