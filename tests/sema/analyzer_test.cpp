// Semantic analysis on small programs: what the model records and which
// diagnostics each mistake produces.
#include <gtest/gtest.h>

#include "common/test_pipeline.h"
#include "driver/frontend.h"
#include "sema/group_members.h"
#include "support/diagnostic_renderer.h"

namespace spire {
namespace {

using testing_util::kPipeline;

struct Compiled {
  std::unique_ptr<FrontEnd> frontEnd;
  const sem::Model* model;

  std::vector<std::string> codes() const {
    std::vector<std::string> result;
    for (const Diagnostic& d : frontEnd->diagnostics().all()) result.emplace_back(diagCodeInfo(d.code).name);
    return result;
  }
  std::string rendered() const {
    return renderDiagnostics(frontEnd->sources(), frontEnd->diagnostics(), DiagnosticFormat::Text);
  }
};

Compiled compile(const std::string& shaderSource, bool withPipeline = true) {
  Compiled c;
  c.frontEnd = std::make_unique<FrontEnd>();
  c.frontEnd->addSource("test.spire", (withPipeline ? std::string(kPipeline) : std::string()) + shaderSource);
  c.model = &c.frontEnd->analyze();
  return c;
}

std::string shaderWith(const std::string& components) {
  return "shader S using P {\n  @Uniform mat4 mvp;\n  vec4 projPos = mvp * vec4(pos, 1.0);\n" + components + "\n}\n";
}

TEST(Analyzer, PipelineWorldsImportsAndOrder) {
  const Compiled c = compile("");
  ASSERT_EQ(c.codes(), std::vector<std::string>{}) << c.rendered();
  const sem::Pipeline* p = c.model->findPipeline("P");
  ASSERT_NE(p, nullptr);
  ASSERT_EQ(p->worlds.size(), 5u);
  std::vector<std::string> order;
  for (sem::WorldId w : p->topologicalOrder) order.push_back(p->worlds[w].name);
  EXPECT_EQ(order, (std::vector<std::string>{"Uniform", "Mesh", "Bake", "Vertex", "Fragment"}));
  EXPECT_TRUE(p->reaches(*p->findWorld("Mesh"), *p->findWorld("Fragment")));
  EXPECT_FALSE(p->reaches(*p->findWorld("Fragment"), *p->findWorld("Vertex")));
  const sem::World& vertex = p->worlds[*p->findWorld("Vertex")];
  ASSERT_TRUE(vertex.exportStrategy.has_value());
  EXPECT_EQ(vertex.exportStrategy->componentArgs, std::vector<std::string>{"projPos"});
  ASSERT_EQ(p->imports.size(), 7u);
  EXPECT_EQ(p->imports.back().strategy.componentArgs, std::vector<std::string>{"uv"});
}

TEST(Analyzer, ComponentsDefinitionsAndDependencies) {
  const Compiled c = compile(shaderWith(R"(
  @Uniform sampler2D tex;
  float shade = texture(tex, uv).x;
  @Vertex vec3 n = pos;
  @Fragment vec3 n = normalize(pos);
  float light:basic = shade * 0.5;
  float light:fancy = shade * n.x;
  vec4 output = vec4(light);)"));
  ASSERT_FALSE(c.frontEnd->diagnostics().hasErrors()) << c.rendered();
  const sem::Shader* s = c.model->findShader("S");
  ASSERT_NE(s, nullptr);
  const sem::Component* n = s->findComponent("n");
  ASSERT_NE(n, nullptr);
  ASSERT_EQ(n->definitions.size(), 2u);
  EXPECT_EQ(s->pipeline->worlds[*n->definitions[0].world].name, "Vertex");
  const sem::Component* light = s->findComponent("light");
  ASSERT_EQ(light->definitions.size(), 2u);
  EXPECT_EQ(light->definitions[0].variation, "basic");
  EXPECT_FALSE(light->definitions[0].world.has_value());
  // light:fancy reads shade and n.
  std::vector<std::string> deps;
  for (sem::ComponentId id : light->definitions[1].dependencies) deps.push_back(s->components[id].name);
  EXPECT_EQ(deps, (std::vector<std::string>{"shade", "n"}));  // in declaration order
  const sem::Component* output = s->findComponent("output");
  EXPECT_TRUE(output->isExport);
  EXPECT_TRUE(output->isAbstract);
  EXPECT_EQ(output->definitions.size(), 1u);
  // The abstract `@Fragment` requirement places the world-less definition.
  EXPECT_EQ(s->pipeline->worlds[*output->definitions[0].world].name, "Fragment");
  EXPECT_EQ(c.model->typeOf(*output->definitions[0].decl->init)->name(), "vec4");
}

TEST(Analyzer, InheritanceFlattensAndPrefixesOrigin) {
  const Compiled c = compile(R"(
shader Base using P {
  @Uniform mat4 mvp;
  vec4 projPos = mvp * vec4(pos, 1.0);
  abstract @Fragment vec3 albedo;
  float k = 0.5;
  vec4 output = vec4(albedo * k, 1.0);
}
shader Derived : Base {
  vec3 albedo = vec3(uv, 1.0);
}
)");
  ASSERT_FALSE(c.frontEnd->diagnostics().hasErrors()) << c.rendered();
  const sem::Shader* d = c.model->findShader("Derived");
  ASSERT_NE(d, nullptr);
  EXPECT_EQ(d->base, c.model->findShader("Base"));
  EXPECT_EQ(d->findComponent("k")->origin, "Base");
  const sem::Component* albedo = d->findComponent("albedo");
  ASSERT_EQ(albedo->definitions.size(), 1u);
  EXPECT_EQ(albedo->definitions[0].origin, "Derived");
  EXPECT_EQ(d->pipeline->worlds[*albedo->definitions[0].world].name, "Fragment");
}

TEST(Analyzer, GroupsSynthesizeOneShaderPerMember) {
  const Compiled c = compile(R"(
shader Base using P {
  @Uniform mat4 mvp;
  vec4 projPos = mvp * vec4(pos, 1.0);
  abstract @Fragment vec4 color_in;
  vec4 output = color_in;
}
shader HQ : Base { abstract @Fragment vec4 color; @Fragment vec4 color_in = color; }
shader LQ : Base finalizes Vertex, Fragment { abstract @Bake vec4 color; @Bake vec4 color_in = color; }
shader Strict : Base { abstract @Fragment float color; @Fragment vec4 color_in = vec4(color); }
group Family { shader HQ; optional shader LQ; optional shader Strict; }
shader Material : Family {
  vec4 color = vec4(uv, 0.0, 1.0);
}
)");
  ASSERT_FALSE(c.frontEnd->diagnostics().hasErrors()) << c.rendered();
  const sem::Group* family = c.model->findGroup("Material");
  ASSERT_NE(family, nullptr);
  ASSERT_EQ(family->members.size(), 2u);
  EXPECT_EQ(family->members[0].shader->name, "Material<HQ>");
  EXPECT_EQ(family->members[1].shader->name, "Material<LQ>");
  const sem::Shader* lq = family->members[1].shader;
  EXPECT_EQ(lq->finalizedWorlds.size(), 2u);
  EXPECT_EQ(lq->pipeline->worlds[*lq->findComponent("color")->definitions[0].world].name, "Bake");
  // Strict wants a float color: it is left out with one warning.
  ASSERT_EQ(c.codes(), std::vector<std::string>{"W4101"}) << c.rendered();
  EXPECT_EQ(c.model->findShader("Material<Strict>"), nullptr);
}

// A shader derived from a shader derived from a group is a group's too; its
// shaders keep the original members' names, so an engine that looks for
// `Shader<Member>` finds them at any depth.
TEST(Analyzer, ShadersDerivedFromAGroupsShaderKeepTheMembersNames) {
  const Compiled c = compile(R"(
shader Base using P {
  @Uniform mat4 mvp;
  vec4 projPos = mvp * vec4(pos, 1.0);
  abstract @Fragment vec4 color;
  vec4 output = color;
}
shader HQ : Base { }
shader MQ : Base { }
group Family { shader HQ; optional shader MQ; }
shader Material : Family {
  vec4 color = vec4(uv, 0.0, 1.0);
}
shader Tinted : Material {
  vec4 color = vec4(uv, 1.0, 1.0);
}
shader Deeper : Tinted { }
)");
  ASSERT_FALSE(c.frontEnd->diagnostics().hasErrors()) << c.rendered();
  for (const std::string name : {"Tinted", "Deeper"}) {
    const sem::Group* group = c.model->findGroup(name);
    ASSERT_NE(group, nullptr) << name;
    ASSERT_EQ(group->members.size(), 2u);
    EXPECT_EQ(group->members[0].shader->name, name + "<HQ>");
    EXPECT_EQ(group->members[1].shader->name, name + "<MQ>");
    EXPECT_EQ(sem::memberName(*group->members[1].shader), "MQ");
  }
  EXPECT_EQ(c.model->findShader("Tinted<MQ>")->base, c.model->findShader("Material<MQ>"));
  EXPECT_EQ(c.model->findShader("Deeper<HQ>")->base, c.model->findShader("Tinted<HQ>"));
}

TEST(Analyzer, FinalizesOnDerivedShader) {
  const Compiled c = compile(R"(
shader Base using P {
  @Uniform mat4 mvp;
  vec4 projPos = mvp * vec4(pos, 1.0);
  vec4 output = vec4(1.0);
}
shader Locked : Base finalizes Vertex {}
shader Derived : Locked { @Vertex float extra = 1.0; }
)");
  EXPECT_EQ(c.codes(), std::vector<std::string>{"E4020"}) << c.rendered();
}

struct ErrorCase {
  const char* name;
  const char* components;
  const char* code;
};

void PrintTo(const ErrorCase& c, std::ostream* os) { *os << c.name; }

class AnalyzerErrors : public testing::TestWithParam<ErrorCase> {};

TEST_P(AnalyzerErrors, ReportsExactlyOneError) {
  const Compiled c = compile(shaderWith(GetParam().components));
  EXPECT_EQ(c.codes(), std::vector<std::string>{GetParam().code}) << c.rendered();
}

INSTANTIATE_TEST_SUITE_P(
    Sema, AnalyzerErrors,
    testing::Values(
        ErrorCase{"UndeclaredName", "vec4 output = vec4(posx, 1.0);", "E3001"},
        ErrorCase{"UnknownType", "vec5 v = vec4(1.0); vec4 output = vec4(1.0);", "E3002"},
        ErrorCase{"Vec3ToVec4", "vec4 output = pos;", "E3004"},
        ErrorCase{"MatTimesWrongVector", "vec4 output = mvp * pos;", "E3005"},
        ErrorCase{"BoolArithmetic", "vec4 output = vec4(true + 1);", "E3005"},
        ErrorCase{"NoMatchingBuiltin", "vec4 output = vec4(dot(pos, uv));", "E3007"},
        ErrorCase{"BadSwizzle", "vec4 output = vec4(uv.xyz, 1.0);", "E3008"},
        ErrorCase{"MixedSwizzleSets", "vec4 output = vec4(pos.xg, 1.0, 1.0);", "E3008"},
        ErrorCase{"IndexOutOfBounds", "vec4 output = vec4(pos[3]);", "E3009"},
        ErrorCase{"TooFewComponents", "vec4 output = vec4(pos);", "E3010"},
        ErrorCase{"TooManyArgs", "vec4 output = vec4(pos, uv, 1.0);", "E3010"},
        ErrorCase{"NonBoolCondition", "vec4 output { if (1.0) return vec4(1.0); return vec4(0.0); }", "E3011"},
        ErrorCase{"ComponentIsImmutable", "float k = 1.0; vec4 output { k = 2.0; return vec4(k); }", "E3012"},
        ErrorCase{"ConstLocal", "vec4 output { const float k = 1.0; k += 1.0; return vec4(k); }", "E3012"},
        ErrorCase{"BreakOutsideLoop", "vec4 output { break; return vec4(1.0); }", "E3013"},
        ErrorCase{"MissingReturn", "vec4 output { if (pos.x > 0.0) return vec4(1.0); }", "E3014"},
        ErrorCase{"NegativeArraySize", "vec4 output { float a[-1]; return vec4(1.0); }", "E3015"},
        ErrorCase{"RedefinedComponent", "float k = 1.0; float k = 2.0; vec4 output = vec4(k);", "E3003"},
        ErrorCase{"RedefinedLocal", "vec4 output { float a = 1.0; float a = 2.0; return vec4(a); }", "E3003"},
        ErrorCase{"FunctionAsValue", "vec4 output = vec4(normalize);", "E3018"},
        ErrorCase{"Cycle", "float a = b; float b = a; vec4 output = vec4(a);", "E4007"},
        ErrorCase{"SelfCycle", "float a = a + 1.0; vec4 output = vec4(a);", "E4007"},
        ErrorCase{"UnknownWorld", "@Fragmnet vec4 output = vec4(1.0);", "E4001"},
        ErrorCase{"DefineInAbstractWorld", "@Uniform float k = 1.0; vec4 output = vec4(k);", "E4011"},
        ErrorCase{"InputAtConcreteWorld", "@Vertex float k; vec4 output = vec4(k);", "E4011"},
        ErrorCase{"ExportInShader", "export float k = 1.0; vec4 output = vec4(k);", "E4011"},
        ErrorCase{"ConflictingOverloadTypes", "@Vertex float k = 1.0; @Fragment vec2 k = uv; vec4 output = vec4(1.0);",
                  "E4008"},
        ErrorCase{"ComputedSampler", "@Uniform sampler2D t; sampler2D u = t; vec4 output = vec4(1.0);", "E4011"}),
    [](const testing::TestParamInfo<ErrorCase>& param) { return param.param.name; });

TEST(Analyzer, ValidExpressionsTypeCheck) {
  const Compiled c = compile(R"(
struct Light { vec3 dir; float power[2]; };
float weight(in float x, out float y, inout vec2 z) { y = x * 2.0; z.yx += vec2(1); return y; }
float weight(float x) { return x; }
vec3 tint(Light l) { return l.dir * l.power[1]; }
)" + shaderWith(R"(
  @Uniform Light light;
  @Uniform int count;
  @Uniform uint mask;
  vec4 output {
    float acc = 0.0;
    vec2 zz = uv;
    for (int i = 0; i < count; ++i) {
      float y;
      acc += weight(float(i), y, zz) + weight(1);
      if (i == 3) continue; else if (i > 10) break;
    }
    int j = 0;
    while (j < 4) { j++; }
    do { j -= 1; } while (j > 0);
    uint bits = (mask >> 2u) & 0xFFu | uint(j) << 1;
    mat3 m = mat3(1.0);
    vec3 v = m * light.dir + tint(light) * vec3(1, 2, 3);
    vec3 w = v * m;
    mat2x3 outer = outerProduct(v, uv);
    bool flag = any(lessThan(v, w)) ^^ (bits != 0u);
    float arr[3] = float[3](1.0, 2, acc);
    acc = flag ? arr[2] : float(bits) - -acc;
    acc *= 2;
    vec4 c4 = vec4(outer[1], 1.0);
    c4.xz = vec2(acc);
    c4 = mvp * c4;
    return c4 + vec4(v.zyx, w.x) * 0.5;
  }
)"));
  EXPECT_FALSE(c.frontEnd->diagnostics().hasErrors()) << c.rendered();
}

TEST(Analyzer, GlslNamedComponentsAreValid) {
  const Compiled c = compile(shaderWith(R"(
  @Uniform sampler2D filter;
  vec4 input = texture(filter, uv);
  vec4 texture = input * 2.0;
  vec4 output = texture;)"));
  EXPECT_FALSE(c.frontEnd->diagnostics().hasErrors()) << c.rendered();
}

TEST(Analyzer, RecursionIsRejected) {
  const Compiled c = compile(R"(
float f(float x);
float g(float x) { return f(x); }
float f(float x) { return g(x); }
)",
                             false);
  EXPECT_EQ(c.codes(), std::vector<std::string>{"E3017"}) << c.rendered();
}

TEST(Analyzer, DidYouMeanPointsAtDeclaration) {
  const Compiled c = compile(shaderWith("float mixFactor = 0.5;\nvec4 output = vec4(mixFactr);"));
  ASSERT_EQ(c.codes(), std::vector<std::string>{"E3001"});
  const Diagnostic& d = c.frontEnd->diagnostics().all()[0];
  EXPECT_NE(d.message.find("did you mean 'mixFactor'?"), std::string::npos);
  ASSERT_EQ(d.notes.size(), 1u);
  EXPECT_EQ(c.frontEnd->sources().text(d.notes[0].range), "mixFactor");
}

TEST(Analyzer, PipelineErrors) {
  EXPECT_EQ(compile(R"(pipeline Q { abstract world U : "GLSL"; })", false).codes(), std::vector<std::string>{"E4010"});
  EXPECT_EQ(compile(R"(pipeline Q { world W; })", false).codes(), (std::vector<std::string>{"E4010", "E4010"}));
  EXPECT_EQ(compile(R"(pipeline Q { world W : "HLSL" export standardExport; })", false).codes(),
            std::vector<std::string>{"E4010"});
  EXPECT_EQ(compile(R"(pipeline Q { world W : "GLSL" export uniformImport; })", false).codes(),
            std::vector<std::string>{"E4002"});
  EXPECT_EQ(compile(R"(pipeline Q { world W : "GLSL" export vertexExport; })", false).codes(),
            std::vector<std::string>{"E4003"});
  EXPECT_EQ(compile(R"(pipeline Q { @U float k; abstract world U; world W : "GLSL" export vertexExport(k); })", false)
                .codes(),
            std::vector<std::string>{"E4003"});
  EXPECT_EQ(compile(R"(pipeline Q { abstract world U; world W : "GLSL" export standardExport;
                      import U->W using uniformImport; import U->W using uniformImport; })",
                    false)
                .codes(),
            std::vector<std::string>{"E3003"});
  EXPECT_EQ(compile(R"(pipeline Q { abstract world U; world W : "GLSL" export standardExport;
                      import W->U using standardImport; })",
                    false)
                .codes(),
            std::vector<std::string>{"E4010"});
}

TEST(Analyzer, ShaderErrors) {
  EXPECT_EQ(compile("shader A using Pipe {}").codes(), std::vector<std::string>{"E4005"});
  EXPECT_EQ(compile("shader A : Bse {}").codes(), std::vector<std::string>{"E4006"});
  EXPECT_EQ(compile("shader A : B {} shader B : A {}").codes(), std::vector<std::string>{"E4009"});
  EXPECT_EQ(compile("group G { shader Nope; }").codes(), std::vector<std::string>{"E4006"});
}

}  // namespace
}  // namespace spire
