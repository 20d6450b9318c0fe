#include "scene/scene_file.h"

#include <fmt/format.h>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <limits>
#include <utility>

#include "scene/json_document.h"
#include "scene/json_value_checker.h"
#include "scene/terrain_tiles.h"
#include "support/file_io.h"

namespace spire::scene {
namespace {

namespace fs = std::filesystem;

// Keys of each object, in the order docs/scene.md lists them; unknown keys
// get a "did you mean" from these.
const KeyList kSceneKeys = {"resolution", "frames", "warmupFrames", "clearColor", "includePaths", "camera",
                            "light",      "meshes", "textures",     "instances",  "variants",     "lod"};
const KeyList kScatterKeys = {"count", "seed", "on", "scale"};
const KeyList kLodKeys = {"policy", "blocks"};
const KeyList kCameraKeys = {"fovY", "near", "far", "up", "views", "stereo"};
const KeyList kStereoKeys = {"eyeSeparation", "shareObjectSpace"};
const KeyList kViewKeys = {"position", "target"};
const KeyList kLightKeys = {"direction", "color"};
const KeyList kInstanceKeys = {"mesh",     "source",    "shader",   "decisions",   "kernels",
                               "pipeline", "transform", "material", "doubleSided", "scatter"};
const KeyList kPipelineKeys = {"name", "source"};
const KeyList kTransformKeys = {"translate", "rotate", "scale"};
const KeyList kVariantKeys = {"name", "decisions"};

// The keys that apply to one "type" of mesh or texture.
template <typename Kind>
struct KindKeys {
  Kind kind;
  std::string_view name;
  KeyList keys;
};

const std::vector<KindKeys<MeshKind>> kMeshKinds = {
    {MeshKind::Terrain, "terrain", {"type", "size", "resolution", "height", "seed", "tiles"}},
    {MeshKind::Sphere, "sphere", {"type", "radius", "rings", "segments"}},
    {MeshKind::Plane, "plane", {"type", "size", "resolution"}},
    {MeshKind::Gltf, "gltf", {"type", "file"}},
    {MeshKind::Box, "box", {"type", "size", "height"}},
    {MeshKind::Cylinder, "cylinder", {"type", "radius", "height", "segments"}},
    {MeshKind::Rock, "rock", {"type", "radius", "rings", "segments", "seed", "roughness"}},
};

const std::vector<KindKeys<TextureKind>> kTextureKinds = {
    {TextureKind::File, "file", {"type", "file", "address", "format"}},
    {TextureKind::Gltf, "gltf", {"type", "file", "image", "address", "format"}},
    {TextureKind::Noise, "noise", {"type", "size", "seed", "octaves", "color", "color2", "address", "format"}},
    {TextureKind::Checker, "checker", {"type", "size", "cells", "color", "color2", "address", "format"}},
    {TextureKind::NormalMap, "normalMap", {"type", "size", "seed", "strength", "address", "format"}},
    {TextureKind::Solid, "solid", {"type", "size", "color", "address", "format"}},
    {TextureKind::GgxLut, "ggxLut", {"type", "size", "address", "format"}},
    {TextureKind::Pack, "pack", {"type", "channels", "address", "format"}},
};

constexpr uint32_t kMaxFrames = 100000;
constexpr uint32_t kMaxGridResolution = 4096;
// A tiled terrain draws tiles^2 meshes; beyond 64 x 64 a tile is a few quads.
constexpr uint32_t kMaxTilesPerSide = 64;
constexpr uint32_t kMaxOctaves = 16;
constexpr size_t kMaxMaterialNumbers = 16;  // a mat4
constexpr uint32_t kMaxUint32 = std::numeric_limits<uint32_t>::max();

// The "format" names of kPixelFormats, for JsonValueChecker::choice.
const std::vector<std::pair<std::string_view, PixelFormat>> kFormatOptions = [] {
  std::vector<std::pair<std::string_view, PixelFormat>> options;
  for (const PixelFormatName& entry : kPixelFormats) options.emplace_back(entry.name, entry.format);
  return options;
}();

template <typename Kind>
KeyList kindNames(const std::vector<KindKeys<Kind>>& kinds) {
  KeyList names;
  for (const KindKeys<Kind>& kind : kinds) names.push_back(kind.name);
  return names;
}

template <typename Kind>
KeyList allKindKeys(const std::vector<KindKeys<Kind>>& kinds) {
  KeyList keys;
  for (const KindKeys<Kind>& kind : kinds) {
    for (std::string_view key : kind.keys) {
      if (std::find(keys.begin(), keys.end(), key) == keys.end()) keys.push_back(key);
    }
  }
  return keys;
}

bool contains(const KeyList& keys, std::string_view key) {
  return std::find(keys.begin(), keys.end(), key) != keys.end();
}

// Checks one scene file's JSON value by value. Every problem is reported and
// the value it concerns keeps its default, so one pass finds all errors.
class SceneReader {
 public:
  SceneReader(const SourceManager& sources, fs::path directory, DiagnosticList& diags)
      : check_(sources, diags), directory_(std::move(directory)), diags_(diags) {}

  void read(const JsonValue& root, SceneFile& scene) {
    if (!root.is(JsonKind::Object)) {
      diags_.report(DiagCode::E7003, root.openingRange(),
                    fmt::format("a scene file must hold a JSON object, found {}", check_.kindOf(root)));
      return;
    }
    // Instances may name meshes and textures defined further down.
    meshNames_ = namesIn(root.find("meshes"));
    textureNames_ = namesIn(root.find("textures"));
    for (const JsonMember& member : root.members) readSceneMember(member, scene);
    checkPackSources(scene);
    // The default direction too: the renderer relies on a unit vector.
    scene.light.direction = glm::normalize(scene.light.direction);
    if (root.find("camera") == nullptr) {
      diags_.report(DiagCode::E7005, root.openingRange(), "the scene has no 'camera' (it needs at least one view)");
    }
    if (root.find("instances") == nullptr) {
      diags_.report(DiagCode::E7005, root.openingRange(), "the scene has no 'instances' (it needs at least one)");
    }
  }

 private:
  void readSceneMember(const JsonMember& member, SceneFile& scene) {
    const JsonValue& value = member.value;
    const std::string_view key = member.key;
    if (key == "resolution") {
      readResolution(value, scene);
    } else if (key == "frames") {
      assign(scene.frames, check_.integer(value, "'frames'", 1, kMaxFrames));
    } else if (key == "warmupFrames") {
      assign(scene.warmupFrames, check_.integer(value, "'warmupFrames'", 0, kMaxFrames));
    } else if (key == "clearColor") {
      assign(scene.clearColor, check_.color(value, "'clearColor'", true));
    } else if (key == "includePaths") {
      readIncludePaths(value, scene.includePaths);
    } else if (key == "camera") {
      readCamera(value, scene.camera);
    } else if (key == "light") {
      readLight(value, scene.light);
    } else if (key == "meshes") {
      readNamed(value, "'meshes'", [&](const JsonMember& mesh) { scene.meshes.push_back(readMesh(mesh)); });
    } else if (key == "textures") {
      readNamed(value, "'textures'",
                [&](const JsonMember& texture) { scene.textures.push_back(readTexture(texture)); });
    } else if (key == "instances") {
      readList(value, "'instances'", "instance",
               [&](const JsonValue& instance) { scene.instances.push_back(readInstance(instance)); });
    } else if (key == "variants") {
      readVariants(value, scene.variants);
    } else if (key == "lod") {
      scene.lod = readLod(value);
    } else {
      check_.unknownKey(member, kSceneKeys, "the scene");
    }
  }

  template <typename T>
  static void assign(T& target, std::optional<T> value) {
    if (value) target = std::move(*value);
  }

  // Relative paths are relative to the scene file, not to the working
  // directory, so a scene can be run from anywhere.
  std::optional<fs::path> path(const JsonValue& value, std::string_view what) {
    const std::optional<std::string> given = check_.text(value, what);
    if (!given) return std::nullopt;
    const fs::path relative(*given);
    return (relative.is_absolute() ? relative : directory_ / relative).lexically_normal();
  }

  // Names referenced from instances must be defined; a misspelling gets a
  // suggestion.
  void checkReference(const JsonValue& value, const std::vector<std::string>& names, std::string_view kind,
                      std::string_view section) {
    checkName(value.string, value.range, names, kind, section);
  }

  void checkName(const std::string& name, SourceRange range, const std::vector<std::string>& names,
                 std::string_view kind, std::string_view section) {
    if (std::find(names.begin(), names.end(), name) != names.end()) return;
    const std::vector<std::string_view> candidates(names.begin(), names.end());
    const std::optional<std::string> suggestion = closestSpelling(name, candidates);
    std::string message = fmt::format("unknown {} {}", kind, quotedForMessage(name));
    if (suggestion) message += fmt::format("; did you mean '{}'?", *suggestion);
    Diagnostic& diagnostic = diags_.report(DiagCode::E7006, range, std::move(message));
    if (names.empty()) diagnostic.note({}, fmt::format("the scene has no '{}'", section));
  }

  static std::vector<std::string> namesIn(const JsonMember* section) {
    std::vector<std::string> names;
    if (section == nullptr) return names;
    for (const JsonMember& member : section->value.members) names.push_back(member.key);
    return names;
  }

  void readResolution(const JsonValue& value, SceneFile& scene) {
    if (!check_.expectArray(value, "'resolution'", 2, 2, "an array of 2 integers [width, height]")) return;
    assign(scene.width, check_.integer(value.elements[0], "the width in 'resolution'", 1, kMaxImageSide));
    assign(scene.height, check_.integer(value.elements[1], "the height in 'resolution'", 1, kMaxImageSide));
  }

  void readIncludePaths(const JsonValue& value, std::vector<fs::path>& paths) {
    if (!check_.expectKind(value, JsonKind::Array, "'includePaths'")) return;
    for (const JsonValue& element : value.elements) {
      if (const std::optional<fs::path> dir = path(element, "each element of 'includePaths'")) paths.push_back(*dir);
    }
  }

  // An object whose keys are names (meshes, textures).
  template <typename ReadOne>
  void readNamed(const JsonValue& value, std::string_view what, ReadOne readOne) {
    if (!check_.expectKind(value, JsonKind::Object, what)) return;
    for (const JsonMember& member : value.members) {
      if (member.key.empty()) {
        diags_.report(DiagCode::E7004, member.keyRange, fmt::format("names in {} must not be empty", what));
      }
      readOne(member);
    }
  }

  // An array that must not be empty (instances, views).
  template <typename ReadOne>
  void readList(const JsonValue& value, std::string_view what, std::string_view element, ReadOne readOne) {
    if (!check_.expectKind(value, JsonKind::Array, what)) return;
    if (value.elements.empty()) {
      diags_.report(DiagCode::E7004, value.range, fmt::format("{} must contain at least one {}", what, element));
    }
    for (const JsonValue& item : value.elements) {
      if (check_.expectKind(item, JsonKind::Object, fmt::format("each element of {}", what))) readOne(item);
    }
  }

  std::optional<StereoDesc> readStereo(const JsonValue& value) {
    if (!check_.expectKind(value, JsonKind::Object, "'stereo'")) return std::nullopt;
    StereoDesc stereo;
    for (const JsonMember& member : value.members) {
      if (member.key == "eyeSeparation") {
        assign(stereo.eyeSeparation, check_.real(member.value, "'eyeSeparation'", greaterThan(0.0)));
      } else if (member.key == "shareObjectSpace") {
        assign(stereo.shareObjectSpace, check_.flag(member.value, "'shareObjectSpace'"));
      } else {
        check_.unknownKey(member, kStereoKeys, "'stereo'");
      }
    }
    return stereo;
  }

  void readCamera(const JsonValue& value, CameraDesc& camera) {
    if (!check_.expectKind(value, JsonKind::Object, "'camera'")) return;
    const JsonValue* farValue = nullptr;
    std::vector<const JsonValue*> views;
    bool upValid = true;
    for (const JsonMember& member : value.members) {
      const JsonValue& v = member.value;
      if (member.key == "fovY") {
        Bounds bounds = greaterThan(0.0);
        bounds.max = 180.0;
        bounds.maxExclusive = true;
        assign(camera.fovYDegrees, check_.real(v, "'fovY'", bounds));
      } else if (member.key == "near") {
        assign(camera.nearPlane, check_.real(v, "'near'", greaterThan(0.0)));
      } else if (member.key == "far") {
        const std::optional<float> farPlane = check_.real(v, "'far'", greaterThan(0.0));
        assign(camera.farPlane, farPlane);
        if (farPlane) farValue = &v;
      } else if (member.key == "up") {
        const std::optional<glm::vec3> up = check_.nonZeroVector(v, "'up'");
        assign(camera.up, up);
        upValid = up.has_value();
      } else if (member.key == "views") {
        readList(v, "'views'", "view", [&](const JsonValue& view) {
          if (const std::optional<CameraView> parsed = readView(view)) {
            camera.views.push_back(*parsed);
            views.push_back(&view);
          }
        });
      } else if (member.key == "stereo") {
        camera.stereo = readStereo(v);
      } else {
        check_.unknownKey(member, kCameraKeys, "'camera'");
      }
    }
    // Checked once the whole camera is read: 'near' and 'up' may come last.
    if (farValue != nullptr && camera.farPlane <= camera.nearPlane) {
      diags_.report(
          DiagCode::E7004, farValue->range,
          fmt::format("'far' must be greater than 'near' ({}), found {}", camera.nearPlane, check_.written(*farValue)));
    }
    if (value.find("views") == nullptr) check_.missing(value, "'camera' has no 'views' (it needs at least one)");
    for (size_t i = 0; i < camera.views.size(); ++i) checkViewDirection(camera.views[i], *views[i], camera, upValid);
  }

  // lookAt needs a direction, and has no defined orientation when looking
  // along the up vector.
  void checkViewDirection(const CameraView& view, const JsonValue& value, const CameraDesc& camera, bool upValid) {
    if (view.position == view.target) {
      diags_.report(DiagCode::E7004, value.openingRange(), "a view's 'position' and 'target' must differ");
      return;
    }
    const glm::vec3 direction = glm::normalize(view.target - view.position);
    if (upValid && glm::length(glm::cross(direction, glm::normalize(camera.up))) < 1e-4F) {
      diags_.report(DiagCode::E7004, value.openingRange(),
                    "this view looks along the camera's 'up' vector, so its orientation is undefined");
    }
  }

  std::optional<CameraView> readView(const JsonValue& value) {
    CameraView view;
    view.range = value.range;
    bool ok = true;
    for (const JsonMember& member : value.members) {
      if (member.key == "position" || member.key == "target") {
        const std::optional<glm::vec3> point = check_.vector3(member.value, fmt::format("'{}'", member.key));
        assign(member.key == "position" ? view.position : view.target, point);
        ok = ok && point.has_value();
      } else {
        check_.unknownKey(member, kViewKeys, "a camera view");
      }
    }
    return ok ? std::optional<CameraView>(view) : std::nullopt;
  }

  void readLight(const JsonValue& value, LightDesc& light) {
    if (!check_.expectKind(value, JsonKind::Object, "'light'")) return;
    for (const JsonMember& member : value.members) {
      if (member.key == "direction") {
        assign(light.direction, check_.nonZeroVector(member.value, "'direction'"));
      } else if (member.key == "color") {
        if (const std::optional<glm::vec4> rgb = check_.color(member.value, "'color'", false)) {
          light.color = glm::vec3(*rgb);
        }
      } else {
        check_.unknownKey(member, kLightKeys, "'light'");
      }
    }
  }

  // The "type" of a mesh or texture; keys that belong to another type are
  // reported as not applying to this one.
  template <typename Kind>
  const KindKeys<Kind>* readKind(const JsonMember& named, const std::vector<KindKeys<Kind>>& kinds,
                                 std::string_view noun) {
    const JsonMember* type = named.value.find("type");
    if (type == nullptr) {
      check_.missing(named.value, fmt::format("{} {} has no 'type' (one of {})", noun, quotedForMessage(named.key),
                                              quotedList(kindNames(kinds), "or")));
      return nullptr;
    }
    std::vector<std::pair<std::string_view, const KindKeys<Kind>*>> options;
    for (const KindKeys<Kind>& kind : kinds) options.emplace_back(kind.name, &kind);
    return check_.choice(type->value, fmt::format("{} type", noun), options).value_or(nullptr);
  }

  // Whether `member` may appear in an object of `kind` (all kinds when the
  // type is unknown); reports it otherwise.
  template <typename Kind>
  bool keyApplies(const JsonMember& member, const KindKeys<Kind>* kind, const std::vector<KindKeys<Kind>>& kinds,
                  std::string_view noun) {
    if (kind != nullptr && contains(kind->keys, member.key)) return true;
    const KeyList everyKey = allKindKeys(kinds);
    if (kind == nullptr && contains(everyKey, member.key)) return true;
    if (kind != nullptr && contains(everyKey, member.key)) {
      diags_.report(DiagCode::E7002, member.keyRange,
                    fmt::format("key '{}' does not apply to a {} {} (its keys are {})", member.key, kind->name, noun,
                                quotedList(kind->keys, "and")));
      return false;
    }
    if (kind == nullptr) {
      check_.unknownKey(member, everyKey, fmt::format("a {}", noun));
    } else {
      check_.unknownKey(member, kind->keys, fmt::format("a {} {}", kind->name, noun));
    }
    return false;
  }

  // Every tile needs at least one quad of the terrain's grid.
  void checkTiles(const JsonValue& object, const MeshDesc& mesh) {
    const JsonMember* tiles = object.find("tiles");
    if (tiles && mesh.tiles > mesh.resolution) {
      diags_.report(DiagCode::E7004, tiles->value.range,
                    fmt::format("'tiles' ({}) exceeds the terrain's 'resolution' ({}): each tile needs at least one "
                                "quad per side",
                                mesh.tiles, mesh.resolution));
    }
  }

  MeshDesc readMesh(const JsonMember& named) {
    MeshDesc mesh;
    mesh.name = named.key;
    mesh.range = named.keyRange;
    if (!check_.expectKind(named.value, JsonKind::Object, fmt::format("mesh {}", quotedForMessage(named.key)))) {
      return mesh;
    }
    const KindKeys<MeshKind>* kind = readKind(named, kMeshKinds, "mesh");
    if (kind != nullptr) mesh.kind = kind->kind;
    for (const JsonMember& member : named.value.members) {
      if (member.key == "type" || !keyApplies(member, kind, kMeshKinds, "mesh")) continue;
      const JsonValue& v = member.value;
      if (member.key == "size") assign(mesh.size, check_.real(v, "'size'", greaterThan(0.0)));
      if (member.key == "resolution") assign(mesh.resolution, check_.integer(v, "'resolution'", 1, kMaxGridResolution));
      if (member.key == "height") assign(mesh.height, check_.real(v, "'height'", atLeast(0.0)));
      if (member.key == "seed") assign(mesh.seed, check_.integer(v, "'seed'", 0, kMaxUint32));
      if (member.key == "radius") assign(mesh.radius, check_.real(v, "'radius'", greaterThan(0.0)));
      if (member.key == "rings") assign(mesh.rings, check_.integer(v, "'rings'", 2, kMaxGridResolution));
      if (member.key == "segments") assign(mesh.segments, check_.integer(v, "'segments'", 3, kMaxGridResolution));
      if (member.key == "roughness") assign(mesh.roughness, check_.real(v, "'roughness'", between(0.0, 0.9)));
      if (member.key == "file") assign(mesh.file, path(v, "'file'"));
      if (member.key == "tiles") assign(mesh.tiles, check_.integer(v, "'tiles'", 1, kMaxTilesPerSide));
    }
    checkTiles(named.value, mesh);
    if (kind != nullptr && kind->kind == MeshKind::Gltf && named.value.find("file") == nullptr) {
      check_.missing(named.value, fmt::format("gltf mesh {} has no 'file'", quotedForMessage(named.key)));
    }
    return mesh;
  }

  TextureDesc readTexture(const JsonMember& named) {
    TextureDesc texture;
    texture.name = named.key;
    texture.range = named.keyRange;
    if (!check_.expectKind(named.value, JsonKind::Object, fmt::format("texture {}", quotedForMessage(named.key)))) {
      return texture;
    }
    const KindKeys<TextureKind>* kind = readKind(named, kTextureKinds, "texture");
    if (kind != nullptr) texture.kind = kind->kind;
    // A lookup table's axes end at its borders: repeating would blend the
    // roughest row into the smoothest.
    texture.clamp = texture.kind == TextureKind::GgxLut;
    const JsonValue* cells = nullptr;
    for (const JsonMember& member : named.value.members) {
      if (member.key == "type" || !keyApplies(member, kind, kTextureKinds, "texture")) continue;
      const JsonValue& v = member.value;
      if (member.key == "file") assign(texture.file, path(v, "'file'"));
      if (member.key == "image") assign(texture.image, check_.integer(v, "'image'", 0, kMaxUint32));
      if (member.key == "size") assign(texture.size, check_.integer(v, "'size'", 1, kMaxImageSide));
      if (member.key == "seed") assign(texture.seed, check_.integer(v, "'seed'", 0, kMaxUint32));
      if (member.key == "octaves") assign(texture.octaves, check_.integer(v, "'octaves'", 1, kMaxOctaves));
      if (member.key == "strength") assign(texture.strength, check_.real(v, "'strength'", atLeast(0.0)));
      if (member.key == "color") assign(texture.color, check_.color(v, "'color'", true));
      if (member.key == "color2") assign(texture.color2, check_.color(v, "'color2'", true));
      if (member.key == "cells") {
        const std::optional<uint32_t> count = check_.integer(v, "'cells'", 1, kMaxImageSide);
        assign(texture.cells, count);
        if (count) cells = &v;
      }
      if (member.key == "address") {
        const std::optional<bool> clamp = check_.choice<bool>(v, "address mode", {{"repeat", false}, {"clamp", true}});
        assign(texture.clamp, clamp);
      }
      if (member.key == "channels") readChannels(v, texture.channels);
      if (member.key == "format") texture.format = check_.choice(v, "texture format", kFormatOptions);
    }
    // A checker cell must be at least one pixel wide.
    if (cells != nullptr && texture.cells > texture.size) {
      diags_.report(DiagCode::E7004, cells->range,
                    fmt::format("'cells' must be at most the texture's 'size' ({}), found {}", texture.size,
                                check_.written(*cells)));
    }
    const bool needsFile = kind != nullptr && (kind->kind == TextureKind::File || kind->kind == TextureKind::Gltf);
    if (needsFile && named.value.find("file") == nullptr) {
      check_.missing(named.value, fmt::format("{} texture {} has no 'file'", kind->name, quotedForMessage(named.key)));
    }
    if (kind != nullptr && kind->kind == TextureKind::Pack && named.value.find("channels") == nullptr) {
      check_.missing(named.value, fmt::format("pack texture {} has no 'channels'", quotedForMessage(named.key)));
    }
    return texture;
  }

  // "channels": ["wear.r", "dirt.r", ...], one "texture.channel" each for R,
  // G, B and A, 1 to 4 of them.
  void readChannels(const JsonValue& value, std::vector<ChannelSource>& channels) {
    if (!check_.expectArray(value, "'channels'", 1, 4, "an array of 1 to 4 channels such as \"wear.r\"")) return;
    for (const JsonValue& element : value.elements) {
      if (!check_.expectKind(element, JsonKind::String, "each element of 'channels'")) continue;
      const std::string& text = element.string;
      const size_t dot = text.rfind('.');
      constexpr std::string_view kLetters = "rgba";
      const bool named = dot != std::string::npos && dot > 0 && dot + 2 == text.size();
      if (!named || kLetters.find(text.back()) == std::string_view::npos) {
        diags_.report(DiagCode::E7004, element.range,
                      fmt::format("channel {} must be a texture name, a dot and one of r, g, b or a, such as "
                                  "\"wear.r\"",
                                  quotedForMessage(text)));
        continue;
      }
      ChannelSource source{text.substr(0, dot), static_cast<uint32_t>(kLetters.find(text.back())), element.range};
      checkName(source.texture, element.range, textureNames_, "texture", "textures");
      channels.push_back(std::move(source));
    }
  }

  // A pack takes its channels from textures built from the scene alone, not
  // from another pack, so building one never recurses.
  void checkPackSources(const SceneFile& scene) {
    for (const TextureDesc& texture : scene.textures) {
      for (const ChannelSource& source : texture.channels) {
        const TextureDesc* from = scene.findTexture(source.texture);
        if (from != nullptr && from->kind == TextureKind::Pack) {
          diags_.report(DiagCode::E7004, source.range,
                        fmt::format("pack texture {} takes a channel of {}, another pack; name the textures that one "
                                    "packs instead",
                                    quotedForMessage(texture.name), quotedForMessage(source.texture)));
        }
      }
    }
  }

  InstanceDesc readInstance(const JsonValue& value) {
    InstanceDesc instance;
    instance.range = value.range;
    instance.materialRange = value.range;
    for (const JsonMember& member : value.members) {
      const JsonValue& v = member.value;
      if (member.key == "mesh") {
        instance.meshRange = v.range;
        if (const std::optional<std::string> mesh = check_.text(v, "'mesh'")) {
          instance.mesh = *mesh;
          checkReference(v, meshNames_, "mesh", "meshes");
        }
      } else if (member.key == "source") {
        instance.sourceRange = v.range;
        assign(instance.source, path(v, "'source'"));
      } else if (member.key == "shader") {
        instance.shaderRange = v.range;
        assign(instance.shader, check_.text(v, "'shader'"));
      } else if (member.key == "decisions") {
        instance.decisionsRange = v.range;
        if (const std::optional<fs::path> decisions = path(v, "'decisions'")) instance.decisions = *decisions;
      } else if (member.key == "kernels") {
        instance.kernelsRange = v.range;
        if (const std::optional<fs::path> kernels = path(v, "'kernels'")) instance.kernels = *kernels;
      } else if (member.key == "pipeline") {
        instance.pipelineRange = v.range;
        readPipeline(v, instance);
      } else if (member.key == "transform") {
        assign(instance.transform, readTransform(v));
      } else if (member.key == "material") {
        instance.materialRange = v.range;
        readMaterial(v, instance.material);
      } else if (member.key == "doubleSided") {
        instance.doubleSided = check_.flag(v, "'doubleSided'");
      } else if (member.key == "scatter") {
        instance.scatter = readScatter(v);
      } else {
        check_.unknownKey(member, kInstanceKeys, "an instance");
      }
    }
    checkShaderSource(value);
    return instance;
  }

  ScatterDesc readScatter(const JsonValue& value) {
    ScatterDesc scatter;
    if (!check_.expectKind(value, JsonKind::Object, "'scatter'")) return scatter;
    for (const JsonMember& member : value.members) {
      const JsonValue& v = member.value;
      if (member.key == "count") {
        assign(scatter.count, check_.integer(v, "'count'", 1, 1000000));
      } else if (member.key == "seed") {
        assign(scatter.seed, check_.integer(v, "'seed'", 0, kMaxUint32));
      } else if (member.key == "on") {
        scatter.onRange = v.range;
        if (const std::optional<std::string> on = check_.text(v, "'on'")) {
          scatter.on = *on;
          checkReference(v, meshNames_, "mesh", "meshes");
        }
      } else if (member.key == "scale") {
        if (!check_.expectArray(v, "'scale'", 2, 2, "[min, max]")) continue;
        const auto lo = check_.real(v.elements[0], "the smallest scale", greaterThan(0.0));
        const auto hi = check_.real(v.elements[1], "the largest scale", greaterThan(0.0));
        if (lo && hi && *hi < *lo) {
          diags_.report(DiagCode::E7004, v.range, "the largest scale is smaller than the smallest");
        } else if (lo && hi) {
          scatter.scaleMin = *lo;
          scatter.scaleMax = *hi;
        }
      } else {
        check_.unknownKey(member, kScatterKeys, "'scatter'");
      }
    }
    if (!value.find("on")) check_.missing(value, "'scatter' needs 'on', the terrain mesh to place the copies on");
    return scatter;
  }

  LodDesc readLod(const JsonValue& value) {
    LodDesc lod;
    lod.range = value.openingRange();
    if (!check_.expectKind(value, JsonKind::Object, "'lod'")) return lod;
    for (const JsonMember& member : value.members) {
      if (member.key == "policy") {
        lod.policyRange = member.value.range;
        assign(lod.policy, path(member.value, "'policy'"));
      } else if (member.key == "blocks") {
        assign(lod.blocks, check_.integer(member.value, "'blocks'", 1, 256));
      } else {
        check_.unknownKey(member, kLodKeys, "'lod'");
      }
    }
    if (!value.find("policy")) check_.missing(value, "'lod' needs a 'policy' file");
    return lod;
  }

  // Either the library path (source + shader, optionally decisions) or the
  // file path (kernels); both may be given, and kernels then win.
  void checkShaderSource(const JsonValue& instance) {
    const bool hasMesh = instance.find("mesh") != nullptr;
    const bool hasSource = instance.find("source") != nullptr;
    const bool hasShader = instance.find("shader") != nullptr;
    const bool hasKernels = instance.find("kernels") != nullptr;
    if (!hasMesh) check_.missing(instance, "an instance needs a 'mesh'");
    if (!hasSource && !hasShader && !hasKernels) {
      check_.missing(instance,
                     "an instance needs 'source' and 'shader' (compiled in process) or 'kernels' (a spirec output "
                     "directory)");
    } else if (hasSource && !hasShader) {
      check_.missing(instance, "an instance with a 'source' needs the 'shader' to build from it");
    } else if (hasShader && !hasSource) {
      check_.missing(instance, "an instance with a 'shader' needs the 'source' that defines it");
    } else if (instance.find("decisions") != nullptr && !hasSource) {
      check_.missing(instance, "'decisions' apply to a 'source' and 'shader', which this instance does not have");
    } else if (instance.find("pipeline") != nullptr && !hasSource) {
      check_.missing(instance, "'pipeline' retargets a 'source' and 'shader', which this instance does not have");
    }
  }

  // Retargeting: {"name": PIPELINE, "source": FILE}; the file is optional
  // when the shader's own source already loads the pipeline.
  void readPipeline(const JsonValue& value, InstanceDesc& instance) {
    if (!check_.expectKind(value, JsonKind::Object, "'pipeline'")) return;
    for (const JsonMember& member : value.members) {
      if (member.key == "name") {
        assign(instance.pipeline, check_.text(member.value, "the pipeline's 'name'"));
      } else if (member.key == "source") {
        if (const std::optional<fs::path> source = path(member.value, "the pipeline's 'source'")) {
          instance.pipelineSource = *source;
        }
      } else {
        check_.unknownKey(member, kPipelineKeys, "'pipeline'");
      }
    }
    if (value.find("name") == nullptr) check_.missing(value, "'pipeline' needs the 'name' of the pipeline");
  }

  // Model matrix: scale, then rotate about X, Y and Z (degrees), then translate.
  std::optional<glm::mat4> readTransform(const JsonValue& value) {
    if (!check_.expectKind(value, JsonKind::Object, "'transform'")) return std::nullopt;
    glm::vec3 translate(0.0F);
    glm::vec3 rotate(0.0F);
    glm::vec3 scale(1.0F);
    bool ok = true;
    for (const JsonMember& member : value.members) {
      const JsonValue& v = member.value;
      if (member.key == "translate") {
        const std::optional<glm::vec3> t = check_.vector3(v, "'translate'");
        assign(translate, t);
        ok = ok && t.has_value();
      } else if (member.key == "rotate") {
        const std::optional<glm::vec3> r = check_.vector3(v, "'rotate'");
        assign(rotate, r);
        ok = ok && r.has_value();
      } else if (member.key == "scale") {
        // A zero or negative scale would collapse the mesh or turn its faces
        // inside out for back-face culling.
        std::optional<glm::vec3> s;
        if (v.is(JsonKind::Number)) {
          if (const std::optional<float> uniform = check_.real(v, "'scale'", greaterThan(0.0))) s = glm::vec3(*uniform);
        } else if (v.is(JsonKind::Array)) {
          s = check_.vector3(v, "'scale'", greaterThan(0.0));
        } else {
          diags_.report(
              DiagCode::E7003, v.range,
              fmt::format("'scale' must be a number or an array of 3 numbers [x, y, z], found {}", check_.kindOf(v)));
        }
        assign(scale, s);
        ok = ok && s.has_value();
      } else {
        check_.unknownKey(member, kTransformKeys, "'transform'");
      }
    }
    if (!ok) return std::nullopt;
    glm::mat4 model = glm::translate(glm::mat4(1.0F), translate);
    model = glm::rotate(model, glm::radians(rotate.z), glm::vec3(0.0F, 0.0F, 1.0F));
    model = glm::rotate(model, glm::radians(rotate.y), glm::vec3(0.0F, 1.0F, 0.0F));
    model = glm::rotate(model, glm::radians(rotate.x), glm::vec3(1.0F, 0.0F, 0.0F));
    return glm::scale(model, scale);
  }

  // Types are checked against the shader's reflection by the renderer; here
  // only the shape: a texture name, a number, or 1 to 16 numbers.
  void readMaterial(const JsonValue& value, std::vector<MaterialBinding>& material) {
    if (!check_.expectKind(value, JsonKind::Object, "'material'")) return;
    for (const JsonMember& member : value.members) {
      const JsonValue& v = member.value;
      MaterialBinding binding;
      binding.component = member.key;
      binding.keyRange = member.keyRange;
      binding.valueRange = v.range;
      const std::string what = fmt::format("the material value of {}", quotedForMessage(member.key));
      if (v.is(JsonKind::String)) {
        binding.texture = v.string;
        checkReference(v, textureNames_, "texture", "textures");
      } else if (v.is(JsonKind::Object)) {
        binding.engineValue = engineValueName(v, what);
      } else if (v.is(JsonKind::Number)) {
        binding.numbers.push_back(v.number);
      } else if (v.is(JsonKind::Array) && !v.elements.empty() && v.elements.size() <= kMaxMaterialNumbers) {
        const std::string elementWhat = fmt::format("each element of {}", what);
        for (const JsonValue& element : v.elements) {
          if (check_.expectKind(element, JsonKind::Number, elementWhat)) binding.numbers.push_back(element.number);
        }
      } else {
        diags_.report(DiagCode::E7003, v.range,
                      fmt::format("{} must be a texture name, a number, an array of 1 to {} numbers or "
                                  "{{\"engine\": NAME}}, found {}",
                                  what, kMaxMaterialNumbers, check_.kindOf(v)));
      }
      material.push_back(std::move(binding));
    }
  }

  // {"engine": NAME}: the one key, a non-empty string (which names a value
  // only the renderer knows).
  std::optional<std::string> engineValueName(const JsonValue& value, const std::string& what) {
    if (value.members.size() == 1 && value.members.front().key == "engine" &&
        value.members.front().value.is(JsonKind::String) && !value.members.front().value.string.empty()) {
      return value.members.front().value.string;
    }
    diags_.report(DiagCode::E7003, value.range,
                  fmt::format("{} as an object must be {{\"engine\": NAME}}, naming a value the engine supplies "
                              "every frame",
                              what));
    return std::nullopt;
  }

  void readVariants(const JsonValue& value, std::vector<VariantDesc>& variants) {
    if (!check_.expectKind(value, JsonKind::Array, "'variants'")) return;
    std::vector<SourceRange> nameRanges;
    for (const JsonValue& item : value.elements) {
      if (!check_.expectKind(item, JsonKind::Object, "each element of 'variants'")) continue;
      VariantDesc variant;
      SourceRange nameRange;
      for (const JsonMember& member : item.members) {
        if (member.key == "name") {
          assign(variant.name, check_.text(member.value, "'name'"));
          nameRange = member.value.range;
        } else if (member.key == "decisions") {
          assign(variant.decisions, path(member.value, "'decisions'"));
          variant.range = member.value.range;
        } else {
          check_.unknownKey(member, kVariantKeys, "a variant");
        }
      }
      if (item.find("name") == nullptr) check_.missing(item, "a variant needs a 'name'");
      if (item.find("decisions") == nullptr) check_.missing(item, "a variant needs 'decisions' (a decision file)");
      for (size_t i = 0; !variant.name.empty() && i < variants.size(); ++i) {
        if (variants[i].name != variant.name) continue;
        diags_
            .report(DiagCode::E7007, nameRange,
                    fmt::format("duplicate variant name {}", quotedForMessage(variant.name)))
            .note(nameRanges[i], "first used here");
        break;
      }
      variants.push_back(std::move(variant));
      nameRanges.push_back(nameRange);
    }
  }

  JsonValueChecker check_;
  fs::path directory_;
  DiagnosticList& diags_;
  std::vector<std::string> meshNames_;
  std::vector<std::string> textureNames_;
};

}  // namespace

const MeshDesc* SceneFile::findMesh(std::string_view name) const {
  const auto it = std::find_if(meshes.begin(), meshes.end(), [&](const MeshDesc& mesh) { return mesh.name == name; });
  return it == meshes.end() ? nullptr : &*it;
}

const TextureDesc* SceneFile::findTexture(std::string_view name) const {
  const auto it =
      std::find_if(textures.begin(), textures.end(), [&](const TextureDesc& texture) { return texture.name == name; });
  return it == textures.end() ? nullptr : &*it;
}

std::optional<SceneFile> loadSceneFile(const fs::path& path, SourceManager& sources, DiagnosticList& diags) {
  std::optional<std::string> text = readWholeFile(path.string());
  if (!text) {
    diags.report(DiagCode::E1101, {}, fmt::format("cannot open scene file '{}'", path.string()));
    return std::nullopt;
  }
  return parseSceneFile(path.string(), std::move(*text), path.parent_path(), sources, diags);
}

std::optional<SceneFile> parseSceneFile(std::string displayPath, std::string text, const fs::path& directory,
                                        SourceManager& sources, DiagnosticList& diags) {
  const uint32_t errorsBefore = diags.errorCount();
  const FileId file = sources.addFile(std::move(displayPath), std::move(text));
  const std::optional<JsonValue> root = parseJson(sources, file, diags);
  if (!root) return std::nullopt;
  SceneFile scene;
  scene.file = file;
  scene.directory = directory;
  SceneReader(sources, directory, diags).read(*root, scene);
  splitTiles(scene, diags);
  // Once the error limit is hit, further errors are not counted.
  if (diags.errorCount() > errorsBefore || diags.limitReached()) return std::nullopt;
  return scene;
}

}  // namespace spire::scene
