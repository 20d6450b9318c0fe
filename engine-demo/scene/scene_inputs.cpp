#include "scene/scene_inputs.h"

#include <algorithm>
#include <optional>
#include <string>
#include <string_view>

#include "scene/json_document.h"
#include "support/file_io.h"
#include "support/hex_digit.h"

namespace spire::scene {
namespace {

namespace fs = std::filesystem;

// glTF URIs are percent-encoded (RFC 3986): "my%20mesh.bin" names
// "my mesh.bin".
std::string percentDecoded(std::string_view uri) {
  std::string path;
  for (size_t i = 0; i < uri.size(); ++i) {
    const std::optional<uint32_t> high = i + 2 < uri.size() ? hexDigitValue(uri[i + 1]) : std::nullopt;
    const std::optional<uint32_t> low = i + 2 < uri.size() ? hexDigitValue(uri[i + 2]) : std::nullopt;
    if (uri[i] == '%' && high && low) {
      path += static_cast<char>(*high * 16 + *low);
      i += 2;
    } else {
      path += uri[i];
    }
  }
  return path;
}

// The "uri" of every object of the array `key` of the document's top level.
void addUris(const JsonValue& document, std::string_view key, const fs::path& folder, std::vector<fs::path>& files) {
  const JsonMember* array = document.find(key);
  if (!array || !array->value.is(JsonKind::Array)) return;
  for (const JsonValue& element : array->value.elements) {
    const JsonMember* uri = element.is(JsonKind::Object) ? element.find("uri") : nullptr;
    if (!uri || !uri->value.is(JsonKind::String) || uri->value.string.starts_with("data:")) continue;
    files.push_back(folder / percentDecoded(uri->value.string));
  }
}

void addOnce(std::vector<fs::path>& files, const fs::path& file) {
  if (file.empty() || std::find(files.begin(), files.end(), file) != files.end()) return;
  files.push_back(file);
  if (file.extension() == ".gltf") {
    for (const fs::path& external : gltfExternalFiles(file)) addOnce(files, external);
  }
}

}  // namespace

std::vector<fs::path> gltfExternalFiles(const fs::path& gltf) {
  if (gltf.extension() != ".gltf") return {};
  const std::optional<std::string> text = readWholeFile(gltf.string());
  if (!text) return {};
  SourceManager sources;
  const FileId file = sources.addFile(gltf.string(), *text);
  DiagnosticList diags;
  const std::optional<JsonValue> document = parseJson(sources, file, diags);
  if (!document || !document->is(JsonKind::Object)) return {};
  std::vector<fs::path> files;
  addUris(*document, "buffers", gltf.parent_path(), files);
  addUris(*document, "images", gltf.parent_path(), files);
  return files;
}

std::vector<fs::path> sceneInputFiles(const SceneFile& scene) {
  std::vector<fs::path> files;
  for (const MeshDesc& mesh : scene.meshes) addOnce(files, mesh.file);
  for (const TextureDesc& texture : scene.textures) {
    if (texture.kind == TextureKind::File || texture.kind == TextureKind::Gltf) addOnce(files, texture.file);
  }
  if (scene.lod) addOnce(files, scene.lod->policy);
  return files;
}

}  // namespace spire::scene
