// Retargeting (paper section 7.3): the shaders of examples/ compile against
// every pipeline of pipelines/ without editing their component code, by
// naming the pipeline in the library options (spirec --pipeline, the scene's
// "pipeline" key). The new pipelines' worlds then appear as choices, and
// placing a component in each of them gives kernels that glslang accepts and
// spirv-val validates.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "driver/compiler.h"
#include "driver/shader_library.h"
#include "support/diagnostic_renderer.h"

namespace spire {
namespace {

namespace fs = std::filesystem;

const fs::path kRoot = SPIRE_SOURCE_DIR;

struct Target {
  std::string file;      // in pipelines/
  std::string pipeline;  // its name
  std::vector<std::string> newWorlds;
};

const std::vector<Target> kTargets = {
    {"engine.spire", "EnginePipeline", {}},
    {"five_world.spire", "FiveWorldPipeline", {"PrebakeUniform", "PrebakeVertex"}},
    {"multi_rate.spire", "MultiRatePipeline", {"LowResVertex", "LowResFragment"}},
    {"object_space.spire", "ObjectSpacePipeline", {"ObjSpaceVertex", "ObjSpaceFrag"}},
};

// The examples written for InstancedPipeline read its per-instance values
// (matModel, lodFade), which no other pipeline provides: they are not
// retargeted.
bool readsInstanceValues(const fs::path& example) {
  const std::string name = example.filename().string();
  return name == "lod_levels.spire" || name == "lod_materials.spire";
}

std::vector<fs::path> exampleFiles() {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(kRoot / "examples")) {
    if (entry.path().extension() == ".spire" && !readsInstanceValues(entry.path())) files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::unique_ptr<ShaderLibrary> retargeted(const fs::path& example, const Target& target) {
  FrontEndOptions options;
  options.pipeline = target.pipeline;
  auto library = std::make_unique<ShaderLibrary>(options);
  EXPECT_TRUE(library->addFile(example.string()));
  EXPECT_TRUE(library->addFile((kRoot / "pipelines" / target.file).string()));
  EXPECT_TRUE(library->compile()) << renderDiagnostics(library->sources(), library->diagnostics(),
                                                       DiagnosticFormat::Text);
  return library;
}

// Every choice alternative in a new world, one variant each, compiles to
// validated SPIR-V.
void expectEveryNewWorldCompiles(ShaderLibrary& library, const std::string& shader, const Target& target) {
  for (const Choice& choice : library.choices(shader)) {
    const std::string component = choice.key.substr(choice.key.rfind('.') + 1);
    for (const std::string& name : choice.names) {
      const std::string world = name.substr(0, name.find(':'));
      if (std::find(target.newWorlds.begin(), target.newWorlds.end(), world) == target.newWorlds.end()) continue;
      CompileOptions options;
      options.strictDecisions = true;
      const auto compiled = compileVariant(library, shader, Decisions{{{component, name}}, {}}, options);
      ASSERT_TRUE(compiled) << shader << "." << component << " = " << name << ": " << compiled.error().message;
      EXPECT_EQ((*compiled)->reflection.pipeline, target.pipeline);
    }
  }
}

TEST(Retarget, EveryExampleShaderCompilesAgainstEveryPipeline) {
  size_t newWorldChoices = 0;
  for (const fs::path& example : exampleFiles()) {
    for (const Target& target : kTargets) {
      SCOPED_TRACE(example.filename().string() + " -> " + target.pipeline);
      auto library = retargeted(example, target);
      ASSERT_FALSE(library->shaderNames().empty());
      for (const std::string& shader : library->shaderNames()) {
        EXPECT_EQ(library->model().findShader(shader)->pipeline->name, target.pipeline);
        const auto compiled = compileVariant(*library, shader, Decisions{});
        ASSERT_TRUE(compiled) << shader << ": " << compiled.error().message;
        for (const Choice& choice : library->choices(shader)) {
          for (const std::string& name : choice.names) {
            const std::string world = name.substr(0, name.find(':'));
            newWorldChoices += std::count(target.newWorlds.begin(), target.newWorlds.end(), world);
          }
        }
        expectEveryNewWorldCompiles(*library, shader, target);
      }
    }
  }
  // The new worlds really are choices, not only declared.
  EXPECT_GT(newWorldChoices, 40U);
}

TEST(Retarget, AnUnknownPipelineIsAnErrorAtTheUsingItReplaces) {
  FrontEndOptions options;
  options.pipeline = "MultiRatePipelin";
  ShaderLibrary library(options);
  ASSERT_TRUE(library.addFile((kRoot / "examples/terrain.spire").string()));
  ASSERT_TRUE(library.addFile((kRoot / "pipelines/multi_rate.spire").string()));
  EXPECT_FALSE(library.compile());
  const std::string text = renderDiagnostics(library.sources(), library.diagnostics(), DiagnosticFormat::Text);
  EXPECT_NE(text.find("terrain.spire:26:22: error[E4005]: cannot retarget 'Terrain' to pipeline 'MultiRatePipelin', "
                      "which no loaded file declares (did you mean 'MultiRatePipeline'?); loaded pipelines: "
                      "EnginePipeline, MultiRatePipeline"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("shader Terrain using EnginePipeline {"), std::string::npos) << text;
}

// A pipeline may declare an input that its shaders declare too (the
// multi-rate pipeline positions its low-resolution pass with matMVP): the
// same world and type are the same input. Anything else still conflicts.
TEST(Retarget, AShaderMayRepeatAPipelineInputButNotChangeIt) {
  const std::string pipeline = R"(
pipeline P {
    abstract world Frame;
    abstract world Mesh;
    world Vertex : "GLSL" export vertexExport(projPos);
    world Fragment : "GLSL" export standardExport;
    import Frame->Vertex using uniformImport;
    import Frame->Fragment using uniformImport;
    import Mesh->Vertex using standardImport;
    import Vertex->Fragment using standardImport;
    @Mesh vec3 vert_pos;
    @Frame mat4 matMVP;
    abstract @Vertex vec4 projPos;
    abstract export @Fragment vec4 output;
}
)";
  const auto compile = [&](const std::string& shaderBody) {
    ShaderLibrary library;
    library.addSource("p.spire", pipeline + "shader S using P {\n" + shaderBody +
                                     "    vec4 projPos = matMVP * vec4(vert_pos, 1.0);\n"
                                     "    vec4 output = vec4(1.0);\n}\n");
    const bool ok = library.compile();
    return std::pair{ok, renderDiagnostics(library.sources(), library.diagnostics(), DiagnosticFormat::Text)};
  };
  EXPECT_TRUE(compile("    @Frame mat4 matMVP;\n").first);
  const auto [otherWorld, otherText] = compile("    @Mesh mat4 matMVP;\n");
  EXPECT_FALSE(otherWorld);
  EXPECT_NE(otherText.find("E3003"), std::string::npos) << otherText;
  const auto [otherType, typeText] = compile("    @Frame mat3 matMVP;\n");
  EXPECT_FALSE(otherType);
  EXPECT_NE(typeText.find("conflicting types for component 'matMVP'"), std::string::npos) << typeText;
  const auto [twice, twiceText] = compile("    @Frame mat4 matMVP;\n    @Frame mat4 matMVP;\n");
  EXPECT_FALSE(twice);
  EXPECT_NE(twiceText.find("E3003"), std::string::npos) << twiceText;
}

// screenTextureImport samples at the fragment's screen position, which only a
// fragment kernel has: into a vertex world it is a compile error naming both.
TEST(Retarget, ScreenTextureImportIntoAVertexWorldIsAnError) {
  ShaderLibrary library;
  library.addSource("screen.spire", R"(
pipeline P {
    abstract world Frame;
    abstract world Mesh;
    world Low : "GLSL" export standardExport;
    world Vertex : "GLSL" export vertexExport(projPos);
    world Fragment : "GLSL" export standardExport;
    import Frame->Low using uniformImport;
    import Frame->Vertex using uniformImport;
    import Mesh->Vertex using standardImport;
    import Low->Vertex using screenTextureImport(size);
    import Vertex->Fragment using standardImport;
    @Mesh vec3 vert_pos;
    @Frame mat4 matMVP;
    @Frame vec2 size;
    abstract @Vertex vec4 projPos;
    abstract export @Fragment vec4 output;
}
shader S using P {
    @Frame float level;
    float shade = level * 0.5;
    vec4 projPos = matMVP * vec4(vert_pos, shade + 1.0);
    vec4 output = vec4(shade);
}
)");
  ASSERT_TRUE(library.compile()) << renderDiagnostics(library.sources(), library.diagnostics(), DiagnosticFormat::Text);
  const auto compiled = compileVariant(library, "S", Decisions{{{"shade", "Low"}}, {}});
  ASSERT_FALSE(compiled);
  std::string text = compiled.error().message;
  for (const Diagnostic& d : compiled.error().diagnostics) text += "\n" + d.message;
  EXPECT_NE(text.find("screenTextureImport reads the screen position, so it can only import into a fragment world, "
                      "not into 'Vertex'"),
            std::string::npos)
      << text;
}

}  // namespace
}  // namespace spire
