// A small three-world pipeline (a texture bake, Vertex and Fragment) that
// the sema and driver tests compile their shaders against.
#pragma once

namespace spire::testing_util {

inline constexpr const char* kPipeline = R"(
pipeline P {
    abstract world Uniform;
    abstract world Mesh;
    world Bake : "GLSL" export standardExport;
    world Vertex : "GLSL" export vertexExport(projPos);
    world Fragment : "GLSL" export standardExport;
    import Uniform->Bake using uniformImport;
    import Uniform->Vertex using uniformImport;
    import Uniform->Fragment using uniformImport;
    import Mesh->Vertex using standardImport;
    import Mesh->Bake using standardImport;
    import Vertex->Fragment using standardImport;
    import Bake->Fragment using textureImport(uv);
    @Mesh vec3 pos;
    @Mesh vec2 uv;
    abstract @Vertex vec4 projPos;
    abstract export @Fragment vec4 output;
}
)";

}  // namespace spire::testing_util
