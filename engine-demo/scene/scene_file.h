// The demo engine's scene file (docs/scene.md, schema docs/scene.schema.json):
// meshes, textures, mesh instances with their shader, decisions and material
// bindings by component name, camera views, light, resolution and frame
// counts. Everything a run needs that is not a compiled shader comes from
// here, so a new shader, material or scene needs no C++ change.
//
// Every value keeps the source range it was written at, so that the renderer,
// which only learns types from a variant's reflection, can still report a
// wrong type or an unbound input at the scene-file line (E7xxx diagnostics,
// rendered like every compiler diagnostic).
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "scene/mesh.h"
#include "scene/pixel_format.h"
#include "support/diagnostic.h"
#include "support/source_manager.h"

namespace spire::scene {

enum class MeshKind { Terrain, Sphere, Plane, Gltf, Box, Cylinder, Rock };

struct MeshDesc {
  std::string name;
  SourceRange range;  // the mesh's key in "meshes"
  MeshKind kind = MeshKind::Plane;
  // Terrain and plane: side length and quads per side; terrain heights in
  // [0, height] from noise with `seed`.
  float size = 10.0F;
  uint32_t resolution = 64;
  float height = 1.0F;
  uint32_t seed = 1;
  // Sphere, cylinder (radius, height, segments), rock (radius, rings,
  // segments, seed, roughness); box: size x height x size.
  float radius = 1.0F;
  uint32_t rings = 32;
  uint32_t segments = 64;
  float roughness = 0.3F;
  // Terrain: drawn as tiles x tiles meshes, so that each tile has its own
  // bounds (culling, level of detail) and its own bakes. The loader
  // replaces every instance of a tiled mesh by one instance per tile, of the
  // meshes NAME[x,z] it adds (see splitTiles).
  uint32_t tiles = 1;
  GridTile tile;  // which tile this mesh is: set on the added meshes
  // glTF: the file, absolute or resolved against the scene file's directory.
  std::filesystem::path file;
};

enum class TextureKind { File, Gltf, Noise, Checker, NormalMap, Solid, GgxLut, Pack };

// One channel of a Pack texture: channel `channel` (0..3, RGBA) of the
// texture named `texture`.
struct ChannelSource {
  std::string texture;
  uint32_t channel = 0;
  SourceRange range;  // the "name.c" string
};

struct TextureDesc {
  std::string name;
  SourceRange range;  // the texture's key in "textures"
  TextureKind kind = TextureKind::Solid;
  std::filesystem::path file;                // File (PNG, JPEG) and Gltf (.gltf/.glb), resolved like MeshDesc::file
  uint32_t image = 0;                        // Gltf: index into the file's images array
  uint32_t size = 256;                       // procedural kinds: width and height
  uint32_t seed = 1;                         // Noise, NormalMap
  uint32_t octaves = 5;                      // Noise
  uint32_t cells = 8;                        // Checker
  float strength = 1.0F;                     // NormalMap
  glm::vec4 color{1.0F};                     // Solid; Checker's first color (components in [0, 1])
  glm::vec4 color2{0.0F, 0.0F, 0.0F, 1.0F};  // Checker's second color
  bool clamp = false;                        // sampler addressing: "address", default repeat (clamp for GgxLut)
  std::vector<ChannelSource> channels;       // Pack: its R, G, B, A in order (1 to 4 of them)
  // The texels' and the GPU texture's format, "format"; when absent, the
  // file's own (RGBA8, RGBA16 for a 16-bit PNG, RGBA32F for .hdr), RGBA8 for
  // procedural kinds, a pack's sources' widerFormat.
  std::optional<PixelFormat> format;
};

// A material value for one shader input, by component name. Either the name
// of a texture in "textures" (for sampler inputs), a literal: a number or a
// flat array of numbers (a vector or a column-major matrix), whose arity and
// type the renderer checks against the reflection; or {"engine": NAME}, a
// value the engine supplies every frame (the camera's matrices, the light,
// time), which the renderer checks against the values it supplies.
struct MaterialBinding {
  std::string component;
  SourceRange keyRange;    // the component name
  SourceRange valueRange;  // the value
  std::optional<std::string> texture;
  std::optional<std::string> engineValue;
  std::vector<double> numbers;  // when neither texture nor engineValue is set
};

// "scatter": `count` copies of an instance at seeded random places on the
// terrain mesh `on`, each turned by a random angle about +Y and scaled by a
// random factor in [scaleMin, scaleMax]; the instance's transform is applied
// first.
struct ScatterDesc {
  uint32_t count = 1;
  uint32_t seed = 1;
  std::string on;  // a terrain mesh of "meshes"
  SourceRange onRange;
  float scaleMin = 1.0F;
  float scaleMax = 1.0F;
};

struct InstanceDesc {
  SourceRange range;  // the instance object
  std::string mesh;   // a key of "meshes"
  SourceRange meshRange;
  // Library path: compile `source` in process and build the variant of
  // `shader` from `decisions` (optional; no file means default placement).
  std::filesystem::path source;
  SourceRange sourceRange;
  std::string shader;
  SourceRange shaderRange;
  std::optional<std::filesystem::path> decisions;
  SourceRange decisionsRange;
  // File path: a spirec output directory holding reflection.json and the
  // .spv kernels; used instead of compiling `source` when present.
  std::optional<std::filesystem::path> kernels;
  SourceRange kernelsRange;
  // Retargeting: compile `shader` against the pipeline `pipeline` instead of
  // the one it is written `using`; `pipelineSource` declares it, when the
  // shader's source does not load it. Empty: no retargeting.
  std::string pipeline;
  std::optional<std::filesystem::path> pipelineSource;
  SourceRange pipelineRange;
  // Model matrix from "transform": {"translate", "rotate" (Euler degrees,
  // applied X then Y then Z), "scale" (a number or a vec3)}.
  glm::mat4 transform{1.0F};
  std::vector<MaterialBinding> material;
  SourceRange materialRange;  // the "material" object, or the instance when absent
  // Whether back faces are drawn too; when absent, the mesh decides (only a
  // glTF material can make a mesh double-sided).
  std::optional<bool> doubleSided;
  // Copies of this instance scattered over a terrain mesh (scatter.h):
  // the level-of-detail scene's thousands of objects.
  std::optional<ScatterDesc> scatter;
};

struct CameraView {
  glm::vec3 position{0.0F, 2.0F, 5.0F};
  glm::vec3 target{0.0F};
  SourceRange range;
};

// Stereo rendering: every image holds both eyes side by side, the left eye
// on the left. Each eye is the camera moved by half `eyeSeparation` along its
// right vector, looking parallel to it (its target moves likewise).
struct StereoDesc {
  float eyeSeparation = 0.064F;
  // Object-space passes run once per frame, from the centre camera, and both
  // eyes sample their results; otherwise each eye runs its own.
  bool shareObjectSpace = true;
};

struct CameraDesc {
  float fovYDegrees = 45.0F;
  float nearPlane = 0.1F;
  float farPlane = 100.0F;
  glm::vec3 up{0.0F, 1.0F, 0.0F};
  // At least one. Frame timing renders views[0]; image error is measured over
  // every view; window mode moves the camera through them in a loop.
  std::vector<CameraView> views;
  std::optional<StereoDesc> stereo;
};

struct LightDesc {
  glm::vec3 direction{0.3F, 1.0F, 0.2F};  // towards the light, world space; normalized by the loader
  glm::vec3 color{1.0F};
};

// One decision file applied to every instance (overriding its own
// "decisions"): the scene is rendered once per variant and every variant is
// compared against the first.
struct VariantDesc {
  std::string name;
  std::filesystem::path decisions;
  SourceRange range;
};

// "lod": the scene is drawn with level of detail (docs/lod.md): each
// instance's shader is a shader derived from a group, drawn as shader<member>
// with the member the policy gives for its distance, instances batched by
// kernel key within `blocks` x `blocks` spatial blocks.
struct LodDesc {
  std::filesystem::path policy;
  SourceRange policyRange;
  uint32_t blocks = 8;
  SourceRange range;
};

// The largest image or texture side a scene may ask for, and that
// `--resolution` may.
inline constexpr uint32_t kMaxImageSide = 8192;

struct SceneFile {
  FileId file = kNoFile;
  std::filesystem::path directory;  // relative paths in the file resolve against it
  uint32_t width = 640;
  uint32_t height = 480;
  uint32_t frames = 10;       // measured frames per variant
  uint32_t warmupFrames = 1;  // rendered first, not measured (lavapipe compiles shaders at first draw)
  glm::vec4 clearColor{0.0F, 0.0F, 0.0F, 1.0F};
  CameraDesc camera;
  LightDesc light;
  std::vector<std::filesystem::path> includePaths;  // "-I" directories for `using` in .spire sources
  std::vector<MeshDesc> meshes;
  std::vector<TextureDesc> textures;
  std::vector<InstanceDesc> instances;  // at least one
  std::vector<VariantDesc> variants;    // may be empty
  std::optional<LodDesc> lod;

  const MeshDesc* findMesh(std::string_view name) const;
  const TextureDesc* findTexture(std::string_view name) const;
};

// Reads and checks a scene file. Syntax errors, unknown keys, wrong value
// types, out-of-range numbers and dangling mesh/texture names are reported
// with their file:line:col (E7001-E7099) and give std::nullopt. Files named by
// the scene are not opened here: the renderer reports a missing file at its
// range. The text is added to `sources` so diagnostics can show it.
std::optional<SceneFile> loadSceneFile(const std::filesystem::path& path, SourceManager& sources,
                                       DiagnosticList& diags);
std::optional<SceneFile> parseSceneFile(std::string displayPath, std::string text,
                                        const std::filesystem::path& directory, SourceManager& sources,
                                        DiagnosticList& diags);

}  // namespace spire::scene
