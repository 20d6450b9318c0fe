// The files a scene reads: what spire-tune hashes so that an edited mesh,
// image or glTF buffer is not resumed as if nothing changed.
#include "scene/scene_inputs.h"

#include <gtest/gtest.h>

#include <fstream>

#include "temp_dir.h"

namespace spire::scene {
namespace {

namespace fs = std::filesystem;

TEST(SceneInputs, ListsEachFileOnceWithAGltfsExternalFiles) {
  testing::TempDir dir;
  const fs::path gltf = dir.path() / "couch.gltf";
  std::ofstream(gltf) << R"({"asset": {"version": "2.0"},
    "buffers": [{"uri": "my%20mesh.bin", "byteLength": 4}, {"uri": "data:application/octet-stream;base64,AAAA", "byteLength": 3}],
    "images": [{"uri": "maps/albedo.png"}, {"bufferView": 0, "mimeType": "image/png"}, {"uri": "data:image/png;base64,AA"}]})";

  SceneFile scene;
  MeshDesc procedural;
  MeshDesc fromFile;
  fromFile.file = gltf;
  scene.meshes = {procedural, fromFile};
  TextureDesc image;
  image.kind = TextureKind::File;
  image.file = dir.path() / "leather.png";
  TextureDesc gltfImage;  // the same glTF again: listed once
  gltfImage.kind = TextureKind::Gltf;
  gltfImage.file = gltf;
  TextureDesc noise;
  noise.kind = TextureKind::Noise;
  scene.textures = {image, gltfImage, noise};
  scene.lod = LodDesc{};
  scene.lod->policy = dir.path() / "policy.json";

  const std::vector<fs::path> expected{gltf, dir.path() / "my mesh.bin", dir.path() / "maps/albedo.png",
                                       dir.path() / "leather.png", dir.path() / "policy.json"};
  EXPECT_EQ(sceneInputFiles(scene), expected);
}

TEST(SceneInputs, ABinaryOrUnreadableGltfNamesNothingElse) {
  testing::TempDir dir;
  std::ofstream(dir.path() / "broken.gltf") << "{\"buffers\": [";
  EXPECT_TRUE(gltfExternalFiles(dir.path() / "broken.gltf").empty());
  EXPECT_TRUE(gltfExternalFiles(dir.path() / "missing.gltf").empty());
  std::ofstream(dir.path() / "mesh.glb") << "glTF";
  EXPECT_TRUE(gltfExternalFiles(dir.path() / "mesh.glb").empty());
}

}  // namespace
}  // namespace spire::scene
