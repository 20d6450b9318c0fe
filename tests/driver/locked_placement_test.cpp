// A derived shader's read does not move what its finalizing base places
// (paper section 6.2; tests/gen/FINDINGS.md, F7). Impl's int c0 reads a
// sampler only C0 and F0 import, so the locked V0 cannot compute it, and
// the base reads it in F0. Mat2 reads it in C0: computing it there for Mat2
// alone would send it to F0 through V0, whose kernel Mat and Mat2 share.
#include <gtest/gtest.h>

#include <map>
#include <string>

#include "common/locked_pipeline.h"
#include "driver/compiler.h"
#include "driver/shader_library.h"
#include "support/diagnostic_renderer.h"

namespace spire {
namespace {

// `extraImport` adds an import line to the pipeline.
std::string program(const std::string& extraImport = "") {
  return testing_util::lockedTestPipeline("    import U0->F0 using uniformImport;\n    " + extraImport + "\n") + R"(
shader Impl using P {
    @U0 sampler2D tex;
    int c0 = int(texture(tex, vec2(0.5)).x * 4.0);
    abstract @F0 vec4 slot_in;
    vec4 clip0 = vec4(m0_pos, 1.0);
    vec4 output = vec4(float(c0)) * slot_in;
}
shader LQ : Impl finalizes V0 {
    abstract @C0 vec4 slot;
    @F0 vec4 slot_in = slot;
}
shader Mat : LQ {
    vec4 slot = vec4(1.0);
}
shader Mat2 : LQ {
    vec4 slot = vec4(float(c0));
}
)";
}

struct Compiled {
  std::string error;                             // the failure's message and diagnostics, rendered
  std::map<std::string, std::string> keys;       // world -> kernel key
  std::map<std::string, std::string> placement;  // component -> world
};

Compiled compile(ShaderLibrary& library, const std::string& shader, const Decisions& decisions) {
  Compiled out;
  const CompileResult result = compileVariant(library, shader, decisions);
  if (!result) {
    DiagnosticList diags;
    diags.reportAll(result.error().diagnostics);
    out.error = result.error().message + "\n" + renderDiagnostics(library.sources(), diags, DiagnosticFormat::Text);
    return out;
  }
  for (const reflection::Kernel& kernel : (*result)->reflection.kernels) out.keys[kernel.world] = kernel.key;
  for (const auto& [component, world] : (*result)->reflection.placement) out.placement[component] = world;
  return out;
}

TEST(LockedPlacement, ADerivedReadThatWouldMoveAnInheritedValueThroughALockedWorldIsRefused) {
  ShaderLibrary library;
  library.addSource("locked.spire", program());
  ASSERT_TRUE(library.compile()) << renderDiagnostics(library.sources(), library.diagnostics(), DiagnosticFormat::Text);
  const Compiled mat = compile(library, "Mat", {});
  ASSERT_TRUE(mat.error.empty()) << mat.error;
  EXPECT_EQ(mat.placement.at("c0"), "F0");
  const Compiled mat2 = compile(library, "Mat2", {});
  EXPECT_NE(mat2.error.find("locked.spire:35:28: error[E4015]: 'c0' is not available in world 'C0', where 'slot' is "
                            "defined: shaders derived from 'LQ' compute 'c0' in 'F0', and computing it in 'C0' would "
                            "send it through the finalized world 'V0', whose kernel they all share; to compute it "
                            "there for all of them, decide 'LQ.c0 = C0'"),
            std::string::npos)
      << mat2.error;
  EXPECT_NE(mat2.error.find("locked.spire:27:28: note: 'V0' is finalized here"), std::string::npos) << mat2.error;
}

TEST(LockedPlacement, TheDecisionTheErrorNamesGivesBothShadersTheSameLockedKernel) {
  ShaderLibrary library;
  library.addSource("locked.spire", program());
  ASSERT_TRUE(library.compile());
  const Decisions decided{{{"c0", "C0"}}, {}};
  const Compiled mat = compile(library, "Mat", decided);
  const Compiled mat2 = compile(library, "Mat2", decided);
  ASSERT_TRUE(mat.error.empty()) << mat.error;
  ASSERT_TRUE(mat2.error.empty()) << mat2.error;
  EXPECT_EQ(mat.placement.at("c0"), "C0");
  EXPECT_EQ(mat.keys.at("V0"), mat2.keys.at("V0"));
}

// With an import from C0 straight to F0, Mat2's read moves c0 without
// touching V0: Mat2 computes it in C0, Mat in F0, and V0 stays shared.
TEST(LockedPlacement, AReadThatMovesAValueAroundTheLockedWorldStaysAllowed) {
  ShaderLibrary library;
  library.addSource("locked.spire", program("import C0->F0 using uniformImport;"));
  ASSERT_TRUE(library.compile());
  const Compiled mat = compile(library, "Mat", {});
  const Compiled mat2 = compile(library, "Mat2", {});
  ASSERT_TRUE(mat.error.empty()) << mat.error;
  ASSERT_TRUE(mat2.error.empty()) << mat2.error;
  EXPECT_EQ(mat.placement.at("c0"), "F0");
  EXPECT_EQ(mat2.placement.at("c0"), "C0");
  EXPECT_EQ(mat.keys.at("V0"), mat2.keys.at("V0"));
}

// What the base leaves abstract without a world, a derived shader places;
// it may not pass through the locked V0 on its way to the base's reader.
TEST(LockedPlacement, ADerivedDefinitionThatReachesTheBaseOnlyThroughALockedWorldIsRefused) {
  ShaderLibrary library;
  library.addSource("through.spire", testing_util::lockedTestPipeline("") + R"(
shader Impl using P {
    abstract vec4 slot;
    vec4 clip0 = vec4(m0_pos, 1.0);
    vec4 output = slot;
}
shader LQ : Impl finalizes V0 {
}
shader Mat : LQ {
    @U0 vec4 u;
    vec4 slot = u * 2.0;
}
shader Mat2 : LQ {
    vec4 slot = vec4(1.0);
}
)");
  ASSERT_TRUE(library.compile()) << renderDiagnostics(library.sources(), library.diagnostics(), DiagnosticFormat::Text);
  const Compiled mat2 = compile(library, "Mat2", {});
  ASSERT_TRUE(mat2.error.empty()) << mat2.error;
  EXPECT_EQ(mat2.placement.at("slot"), "F0");
  const Compiled mat = compile(library, "Mat", {});
  EXPECT_NE(mat.error.find("through.spire:27:10: error[E4015]: 'slot', computed in 'C0', reaches 'output' in world "
                           "'F0' only through the finalized world 'V0', and a shader derived from 'LQ' passes nothing "
                           "through it that 'LQ' does not"),
            std::string::npos)
      << mat.error;
  EXPECT_NE(mat.error.find("through.spire:21:19: note: 'output' reads it here"), std::string::npos) << mat.error;
  EXPECT_NE(mat.error.find("through.spire:23:28: note: 'V0' is finalized here"), std::string::npos) << mat.error;
}

}  // namespace
}  // namespace spire
