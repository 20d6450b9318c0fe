// The compiler on pipelines it was not written for: the paper's Figure 4
// pipeline as drawn (a world fed by two location-based producers), routes
// that do not depend on the order imports are declared in, routing ties,
// and locked worlds whose kernels every derived shader shares.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>

#include "codegen/kernel_generator.h"
#include "codegen/spirv_compiler.h"
#include "driver/shader_library.h"
#include "support/diagnostic_renderer.h"

namespace spire::codegen {
namespace {

// Figure 4 of the paper as drawn: PrebakeVertex feeds Vertex and PrebakeTex
// through standardImport, so Vertex reads `in` variables from the mesh and
// from the vertex bake. `IMPORTS` is replaced by the import lines.
constexpr const char* kFigure4 = R"(
pipeline Figure4 {
    abstract world FrameUniform;
    abstract world MaterialUniform;
    abstract world MeshVertex;
    world PrebakeUniform : "GLSL" export bufferExport;
    world PrebakeVertex : "GLSL" export bufferExport;
    world PrebakeTex : "GLSL" export standardExport;
    world Vertex : "GLSL" export vertexExport(projPos);
    world Fragment : "GLSL" export standardExport;
IMPORTS
    @MeshVertex vec3 vert_pos;
    @MeshVertex vec2 vert_uv;
    @MeshVertex vec3 vert_normal;
    @MeshVertex vec4 vert_tangent;
    abstract @Vertex vec4 projPos;
    abstract export @Fragment vec4 output;
}

shader Leather using Figure4 {
    @FrameUniform mat4 viewProj;
    @FrameUniform vec3 lightDir;
    @MaterialUniform sampler2D grainMap;
    @MaterialUniform float roughness;
    vec4 projPos = viewProj * vec4(vert_pos, 1.0);
    vec3 n = normalize(vert_normal);
    vec3 t = normalize(vert_tangent.xyz);
    vec3 b = cross(n, t) * vert_tangent.w;
    vec4 grain = texture(grainMap, vert_uv * 4.0);
    float wear = grain.y * roughness;
    vec3 shadingNormal = normalize(n + (grain.x - 0.5) * t + (grain.z - 0.5) * b);
    float diffuse = max(dot(shadingNormal, lightDir), 0.0);
    vec4 output = vec4(grain.rgb * (diffuse + wear), 1.0);
}
)";

const std::vector<std::string> kFigure4Imports = {
    "import MeshVertex->PrebakeUniform using bufferImport;",
    "import MeshVertex->PrebakeVertex using bufferImport;",
    "import MeshVertex->Vertex using standardImport;",
    "import MeshVertex->PrebakeTex using standardImport;",
    "import MaterialUniform->PrebakeUniform using uniformImport;",
    "import MaterialUniform->PrebakeVertex using uniformImport;",
    "import MaterialUniform->PrebakeTex using uniformImport;",
    "import MaterialUniform->Vertex using uniformImport;",
    "import MaterialUniform->Fragment using uniformImport;",
    "import FrameUniform->Vertex using uniformImport;",
    "import FrameUniform->Fragment using uniformImport;",
    "import PrebakeUniform->PrebakeVertex using uniformImport;",
    "import PrebakeUniform->PrebakeTex using uniformImport;",
    "import PrebakeUniform->Vertex using uniformImport;",
    "import PrebakeUniform->Fragment using uniformImport;",
    "import PrebakeVertex->Vertex using standardImport;",
    "import PrebakeVertex->PrebakeTex using standardImport;",
    "import Vertex->Fragment using standardImport;",
    "import PrebakeTex->Fragment using textureImport(vert_uv);",
};

std::string figure4(const std::vector<std::string>& imports) {
  std::string lines;
  for (const std::string& i : imports) lines += "    " + i + "\n";
  std::string text = kFigure4;
  text.replace(text.find("IMPORTS"), 7, lines);
  return text;
}

struct Compiled {
  std::unique_ptr<ShaderLibrary> library = std::make_unique<ShaderLibrary>();
  std::string rendered() const {
    return renderDiagnostics(library->sources(), library->diagnostics(), DiagnosticFormat::Text);
  }
};

Compiled compileSource(const std::string& text) {
  Compiled c;
  c.library->addSource("test.spire", text);
  EXPECT_TRUE(c.library->compile()) << c.rendered();
  return c;
}

// Kernels that glslang and spirv-val accept, with every `in` at a location
// its producer writes the same component to.
std::vector<Kernel> checkedKernels(Compiled& c, const graph::Variant& variant) {
  auto generated = generateKernels(c.library->model(), c.library->sources(), variant, StrategyRegistry::builtin(),
                                   c.library->diagnostics());
  EXPECT_TRUE(generated) << c.rendered();
  if (!generated) return {};
  for (const Kernel& k : generated->kernels) {
    const SpirvResult spirv = compileGlslToSpirv(k.stage, k.glsl, k.world);
    EXPECT_TRUE(spirv.ok()) << spirv.log << k.glsl;
    if (spirv.ok()) {
      EXPECT_TRUE(validateSpirv(spirv.words)) << k.glsl;
    }
    std::set<uint64_t> used;
    for (const reflection::KernelInput& input : k.reflection.inputs) {
      if (input.kind != reflection::InputKind::Varying) continue;
      EXPECT_TRUE(used.insert(input.location).second) << "location reused in " << k.glsl;
    }
  }
  return std::move(generated->kernels);
}

const Kernel& kernelOf(const std::vector<Kernel>& kernels, const std::string& world) {
  auto it = std::find_if(kernels.begin(), kernels.end(), [&](const Kernel& k) { return k.world == world; });
  EXPECT_NE(it, kernels.end()) << world;
  return *it;
}

TEST(AnyPipeline, AWorldFedByTwoProducersGetsDisjointLocations) {
  Compiled c = compileSource(figure4(kFigure4Imports));
  // n and t baked per vertex reach Vertex as `in` variables beside the mesh.
  const auto variant = c.library->buildVariant("Leather", {{"n", "PrebakeVertex"}, {"t", "PrebakeVertex"}});
  ASSERT_TRUE(variant);
  const std::vector<Kernel> kernels = checkedKernels(c, *variant);
  const Kernel& vertex = kernelOf(kernels, "Vertex");
  std::set<std::string> fromBake;
  for (const reflection::KernelInput& input : vertex.reflection.inputs) {
    if (input.from == "PrebakeVertex") fromBake.insert(input.component);
  }
  EXPECT_EQ(fromBake, (std::set<std::string>{"n", "t"})) << vertex.glsl;
  // Every varying Fragment reads is written by Vertex at the same location.
  const Kernel& fragment = kernelOf(kernels, "Fragment");
  for (const reflection::KernelInput& input : fragment.reflection.inputs) {
    if (input.from != "Vertex") continue;
    bool written = false;
    for (const reflection::KernelOutput& output : vertex.reflection.outputs) {
      written = written || (output.kind == reflection::OutputKind::Varying && output.component == input.component &&
                            output.location == input.location);
    }
    EXPECT_TRUE(written) << input.component;
  }
}

TEST(AnyPipeline, EveryVariantOfFigure4CompilesWithMatchingInterfaces) {
  Compiled c = compileSource(figure4(kFigure4Imports));
  const std::vector<Choice> choices = c.library->choices("Leather");
  std::mt19937 rng(7);
  for (int i = 0; i < 60; ++i) {
    std::map<std::string, std::string> decisions;
    for (const Choice& choice : choices)
      decisions[choice.key.substr(choice.key.find('.') + 1)] = choice.names[rng() % choice.names.size()];
    const auto variant = c.library->buildVariant("Leather", decisions);
    ASSERT_TRUE(variant);
    checkedKernels(c, *variant);
  }
}

std::string routesOf(Compiled& c, const std::map<std::string, std::string>& decisions) {
  const auto variant = c.library->buildVariant("Leather", decisions);
  EXPECT_TRUE(variant);
  return variant ? variant->describeRoutes() : "";
}

TEST(AnyPipeline, RoutesDoNotDependOnTheOrderOfImports) {
  const std::map<std::string, std::string> decisions = {{"n", "PrebakeVertex"}, {"grain", "Fragment"}};
  Compiled reference = compileSource(figure4(kFigure4Imports));
  const std::string expected = routesOf(reference, decisions);
  // Mesh attributes read per fragment are interpolated through Vertex, never
  // averaged through PrebakeUniform or resampled through PrebakeTex.
  EXPECT_NE(expected.find("vert_uv: MeshVertex -> Vertex -> Fragment"), std::string::npos) << expected;
  std::mt19937 rng(11);
  for (int i = 0; i < 12; ++i) {
    std::vector<std::string> imports = kFigure4Imports;
    std::shuffle(imports.begin(), imports.end(), rng);
    Compiled shuffled = compileSource(figure4(imports));
    EXPECT_EQ(routesOf(shuffled, decisions), expected) << "imports in the order:\n" << figure4(imports);
  }
}

constexpr const char* kDiamond = R"(
pipeline Diamond {
    abstract world Mesh;
    world A : "GLSL" export bufferExport;
    world B : "GLSL" export bufferExport;
    world C : "GLSL" export bufferExport;
    world V : "GLSL" export vertexExport(projPos);
    world F : "GLSL" export standardExport;
    import Mesh->A using bufferImport;
    import Mesh->V using standardImport;
    PRIORITY import A->B using bufferImport;
    import A->C using bufferImport;
    import B->V using bufferImport;
    import C->V using bufferImport;
    import V->F using standardImport;
    @Mesh vec3 pos;
    abstract @V vec4 projPos;
    abstract export @F vec4 output;
}
shader S using Diamond {
    @A float a = pos.x;
    vec4 projPos = vec4(pos, a);
    vec4 output = vec4(1.0);
}
)";

std::string diamond(const std::string& priority) {
  std::string text = kDiamond;
  text.replace(text.find("PRIORITY"), 8, priority);
  return text;
}

TEST(AnyPipeline, EquallyGoodRoutesAreReportedAndAPriorityChooses) {
  Compiled tied = compileSource(diamond(""));
  const std::string warnings = tied.rendered();
  EXPECT_NE(warnings.find("warning[W4110]"), std::string::npos) << warnings;
  EXPECT_NE(warnings.find("world 'V' equally well from 'B' and from 'C'"), std::string::npos) << warnings;
  const auto byName = tied.library->buildVariant("S", {});
  ASSERT_TRUE(byName);
  EXPECT_NE(byName->describeRoutes().find("a: A -> B -> V"), std::string::npos) << byName->describeRoutes();

  Compiled chosen = compileSource(diamond("[Priority: \"-1\"]"));
  EXPECT_EQ(chosen.rendered().find("W4110"), std::string::npos) << chosen.rendered();
  const auto variant = chosen.library->buildVariant("S", {});
  ASSERT_TRUE(variant);
  EXPECT_NE(variant->describeRoutes().find("a: A -> C -> V"), std::string::npos) << variant->describeRoutes();
}

TEST(AnyPipeline, AMalformedPriorityIsAnError) {
  ShaderLibrary library;
  library.addSource("test.spire", diamond("[Priority: \"high\"]"));
  EXPECT_FALSE(library.compile());
  const std::string text = renderDiagnostics(library.sources(), library.diagnostics(), DiagnosticFormat::Text);
  EXPECT_NE(text.find("error[E4021]: [Priority] takes an integer"), std::string::npos) << text;
}

// Two materials derived from the paper's Listing 4 group: their low-quality
// members share the locked Vertex and Fragment kernels byte for byte.
constexpr const char* kMaterials = R"(
using "examples/lod_library.spire";
shader RockLOD : BaseMaterial {
    @MaterialUniform sampler2D rockMap;
    @MaterialUniform float rockScale;
    float grain = texture(rockMap, vert_uv * rockScale).y;
    vec4 albedo = vec4(grain, grain * 0.9, grain * 0.8, 1.0);
    vec3 normal = normalize(vert_normal + vec3(grain * 0.1));
}
)";

TEST(LockedWorlds, DerivedShadersShareTheLockedKernels) {
  Compiled c;
  c.library->addSource(std::string(SPIRE_SOURCE_DIR) + "/materials.spire", kMaterials);
  ASSERT_TRUE(c.library->compile()) << c.rendered();
  const auto terrain = c.library->buildVariant("TerrainLOD<BaseMaterialLQ>", {});
  const auto rock = c.library->buildVariant("RockLOD<BaseMaterialLQ>", {});
  ASSERT_TRUE(terrain && rock);
  const std::vector<Kernel> a = checkedKernels(c, *terrain);
  const std::vector<Kernel> b = checkedKernels(c, *rock);
  for (const char* world : {"Vertex", "Fragment"}) {
    const Kernel& ka = kernelOf(a, world);
    const Kernel& kb = kernelOf(b, world);
    EXPECT_EQ(ka.glsl, kb.glsl) << world;
    EXPECT_EQ(ka.reflection.key, kb.reflection.key) << world;
    EXPECT_EQ(compileGlslToSpirv(ka.stage, ka.glsl, world).words, compileGlslToSpirv(kb.stage, kb.glsl, world).words);
  }
  // The unlocked bake differs, and so does its key.
  EXPECT_NE(kernelOf(a, "PrebakeTex").reflection.key, kernelOf(b, "PrebakeTex").reflection.key);
}

std::string lockedError(const std::string& body) {
  ShaderLibrary library;
  library.addSource(std::string(SPIRE_SOURCE_DIR) + "/sneaky.spire",
                    "using \"examples/lod_library.spire\";\nshader Sneaky : BaseMaterialLQ {\n"
                    "    @MaterialUniform sampler2D m;\n    vec4 albedo = texture(m, vert_uv);\n" +
                        body + "\n}\n");
  EXPECT_FALSE(library.compile());
  return renderDiagnostics(library.sources(), library.diagnostics(), DiagnosticFormat::Text);
}

TEST(LockedWorlds, ADerivedShaderCannotChangeALockedWorld) {
  // Redefining what the pipeline pins to Fragment.
  std::string text = lockedError("    vec4 output = albedo * 2.0;");
  EXPECT_NE(text.find("error[E4020]: 'output' can only be computed in world 'Fragment', which is finalized by "
                      "'BaseMaterialLQ'"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("note: 'Fragment' is finalized here"), std::string::npos) << text;
  // Redefining an inherited component the base may compute in a locked world.
  text = lockedError("    float nDotL = 1.0;");
  EXPECT_NE(text.find("error[E4020]: 'nDotL' is defined by 'BaseImpl'"), std::string::npos) << text;
  // Adding a definition there explicitly.
  text = lockedError("    @Fragment float extra = 1.0;");
  EXPECT_NE(text.find("error[E4020]: world 'Fragment' is finalized by 'BaseMaterialLQ'"), std::string::npos) << text;
  // Reading, in an earlier world, a component the base computes in a locked
  // world would pull it out of that world: it is not available there.
  text = lockedError("    @PrebakeTex vec4 tinted = albedo * nDotL;");
  EXPECT_NE(text.find("error[E4015]: 'nDotL' is not available in world 'PrebakeTex'"), std::string::npos) << text;
  // Redefining what the base pins to an unlocked world stays allowed.
  ShaderLibrary allowed;
  allowed.addSource(std::string(SPIRE_SOURCE_DIR) + "/fine.spire",
                    "using \"examples/lod_library.spire\";\nshader Fine : BaseMaterialLQ {\n"
                    "    @MaterialUniform sampler2D m;\n    vec4 albedo = texture(m, vert_uv);\n"
                    "    @PrebakeTex vec4 albedo_in = albedo * 0.5;\n}\n");
  EXPECT_TRUE(allowed.compile()) << renderDiagnostics(allowed.sources(), allowed.diagnostics(), DiagnosticFormat::Text);
}

}  // namespace
}  // namespace spire::codegen
