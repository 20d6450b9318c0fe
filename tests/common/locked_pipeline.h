// The pipeline of the locked-placement tests: C0 computes once per mesh, V0
// and F0 rasterize, and a sampler in U0 reaches C0 (and whatever
// `moreImports` adds) but never V0, so V0 cannot compute what reads it.
// The shaders finalize V0.
#pragma once

#include <string>

namespace spire::testing_util {

inline std::string lockedTestPipeline(const std::string& moreImports) {
  return R"(
pipeline P {
    abstract world U0;
    abstract world M0;
    world C0 : "GLSL" export bufferExport;
    world V0 : "GLSL" export vertexExport(clip0);
    world F0 : "GLSL" export standardExport;
    import U0->C0 using uniformImport;
    import C0->V0 using uniformImport;
    import M0->V0 using standardImport;
    import V0->F0 using standardImport;
)" + moreImports +
         R"(
    @M0 vec3 m0_pos;
    abstract @V0 vec4 clip0;
    abstract export @F0 vec4 output;
}
)";
}

}  // namespace spire::testing_util
