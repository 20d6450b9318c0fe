#include "scene/terrain_tiles.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <tuple>

#include "scene/mesh.h"
#include "support/diagnostic_renderer.h"

namespace spire::scene {
namespace {

struct Loaded {
  SourceManager sources;
  DiagnosticList diags{100};
  std::optional<SceneFile> scene;
};

std::unique_ptr<Loaded> parse(const std::string& meshes, const std::string& instances) {
  auto loaded = std::make_unique<Loaded>();
  const std::string text = R"({"camera": {"views": [{"position": [0, 2, 5]}]}, "meshes": {)" + meshes +
                           R"(}, "instances": [)" + instances + "]}";
  loaded->scene = parseSceneFile("scene.json", text, "scenes", loaded->sources, loaded->diags);
  return loaded;
}

const char* const kTiledHills = R"("hills": {"type": "terrain", "resolution": 10, "tiles": 3})";
const char* const kRock = R"("rock": {"type": "rock"})";

TEST(TerrainTiles, EachInstanceOfATiledTerrainBecomesOnePerTileInRowOrder) {
  const auto loaded = parse(std::string(kTiledHills) + ", " + kRock,
                            R"({"mesh": "rock", "source": "a.spire", "shader": "R"},
                               {"mesh": "hills", "source": "a.spire", "shader": "T", "material": {"k": 2}},
                               {"mesh": "rock", "source": "a.spire", "shader": "R2"})");
  ASSERT_TRUE(loaded->scene) << renderDiagnostics(loaded->sources, loaded->diags, DiagnosticFormat::Text);
  const SceneFile& scene = *loaded->scene;
  ASSERT_EQ(scene.instances.size(), 11U);
  EXPECT_EQ(scene.instances.front().shader, "R");
  EXPECT_EQ(scene.instances.back().shader, "R2");
  for (uint32_t t = 0; t < 9; ++t) {
    const InstanceDesc& tile = scene.instances[1 + t];
    EXPECT_EQ(tile.mesh, tileMeshName("hills", t % 3, t / 3));
    EXPECT_EQ(tile.shader, "T");
    EXPECT_EQ(tile.material.size(), 1U);
    const MeshDesc* mesh = scene.findMesh(tile.mesh);
    ASSERT_NE(mesh, nullptr);
    EXPECT_EQ(std::tie(mesh->tile.tiles, mesh->tile.x, mesh->tile.z), std::make_tuple(3U, t % 3, t / 3));
    EXPECT_EQ(mesh->resolution, 10U);
  }
  // The whole terrain stays, for scatters to name.
  ASSERT_NE(scene.findMesh("hills"), nullptr);
  EXPECT_EQ(scene.findMesh("hills")->tiles, 3U);
}

TEST(TerrainTiles, MoreTilesThanQuadsIsAnError) {
  const auto loaded = parse(R"("hills": {"type": "terrain", "resolution": 4, "tiles": 5})",
                            R"({"mesh": "hills", "source": "a.spire", "shader": "T"})");
  EXPECT_FALSE(loaded->scene);
  ASSERT_EQ(loaded->diags.all().size(), 1U);
  EXPECT_EQ(loaded->diags.all()[0].code, DiagCode::E7004);
  EXPECT_EQ(loaded->diags.all()[0].message,
            "'tiles' (5) exceeds the terrain's 'resolution' (4): each tile needs at least one quad per side");
}

TEST(TerrainTiles, AMeshNamedLikeATileIsAnError) {
  const auto loaded = parse(std::string(kTiledHills) + R"(, "hills[1,2]": {"type": "plane"})",
                            R"({"mesh": "hills", "source": "a.spire", "shader": "T"})");
  EXPECT_FALSE(loaded->scene);
  ASSERT_EQ(loaded->diags.all().size(), 1U);
  EXPECT_EQ(loaded->diags.all()[0].code, DiagCode::E7007);
  EXPECT_EQ(loaded->diags.all()[0].message,
            "mesh 'hills[1,2]' is also the name of a tile of the tiled terrain 'hills'; rename one");
}

// Property: for several resolutions and splits (uneven ones included), the
// tiles together are the whole terrain: the same triangles, vertex for
// vertex (position, normal, UV), each exactly once.
TEST(TerrainTiles, TilesTogetherAreTheWholeTerrain) {
  using Key = std::tuple<float, float, float, float, float, float, float, float, float>;
  const auto triangles = [](const Mesh& mesh) {
    std::map<Key, int> count;
    for (size_t i = 0; i < mesh.indices.size(); i += 3) {
      const Vertex& a = mesh.vertices[mesh.indices[i]];
      const Vertex& b = mesh.vertices[mesh.indices[i + 1]];
      const Vertex& c = mesh.vertices[mesh.indices[i + 2]];
      ++count[{a.position.x, a.position.y, a.position.z, b.position.x, b.position.y, b.position.z, c.position.x,
               c.position.y, c.position.z}];
    }
    return count;
  };
  for (const auto& [resolution, tiles] : {std::pair{12U, 3U}, std::pair{10U, 3U}, std::pair{7U, 7U}}) {
    const Mesh whole = makeTerrain(20.0F, resolution, 3.0F, 9);
    std::map<Key, int> together;
    size_t vertices = 0;
    for (uint32_t z = 0; z < tiles; ++z) {
      for (uint32_t x = 0; x < tiles; ++x) {
        const Mesh tile = makeTerrain(20.0F, resolution, 3.0F, 9, {tiles, x, z});
        for (const auto& [key, n] : triangles(tile)) together[key] += n;
        for (const Vertex& v : tile.vertices) {
          const uint32_t i = static_cast<uint32_t>(std::lround(v.uv.x * resolution));
          const uint32_t j = static_cast<uint32_t>(std::lround(v.uv.y * resolution));
          const Vertex& w = whole.vertices[j * (resolution + 1) + i];
          ASSERT_EQ(v.position, w.position);
          ASSERT_EQ(v.normal, w.normal);
          ASSERT_EQ(v.uv, w.uv);
        }
        vertices += tile.vertices.size();
      }
    }
    EXPECT_EQ(together, triangles(whole)) << resolution << " quads in " << tiles << " tiles";
    EXPECT_GE(vertices, whole.vertices.size());
  }
}

}  // namespace
}  // namespace spire::scene
