#include "codegen/glsl_names.h"

#include <array>
#include <string>

#include "sema/builtins.h"

namespace spire::codegen {
namespace {

// GLSL 4.50 keywords and reserved words (section 3.6) plus built-in type names.
// clang-format off
constexpr std::array kReserved = {
    "attribute", "const", "uniform", "varying", "buffer", "shared", "coherent", "volatile", "restrict", "readonly",
    "writeonly", "atomic_uint", "layout", "centroid", "flat", "smooth", "noperspective", "patch", "sample", "break",
    "continue", "do", "for", "while", "switch", "case", "default", "if", "else", "subroutine", "in", "out", "inout",
    "float", "double", "int", "void", "bool", "true", "false", "invariant", "precise", "discard", "return", "mat2",
    "mat3", "mat4", "dmat2", "dmat3", "dmat4", "mat2x2", "mat2x3", "mat2x4", "dmat2x2", "dmat2x3", "dmat2x4", "mat3x2",
    "mat3x3", "mat3x4", "dmat3x2", "dmat3x3", "dmat3x4", "mat4x2", "mat4x3", "mat4x4", "dmat4x2", "dmat4x3", "dmat4x4",
    "vec2", "vec3", "vec4", "ivec2", "ivec3", "ivec4", "bvec2", "bvec3", "bvec4", "dvec2", "dvec3", "dvec4", "uint",
    "uvec2", "uvec3", "uvec4", "lowp", "mediump", "highp", "precision", "sampler1D", "sampler2D", "sampler3D",
    "samplerCube", "sampler1DShadow", "sampler2DShadow", "samplerCubeShadow", "sampler1DArray", "sampler2DArray",
    "sampler1DArrayShadow", "sampler2DArrayShadow", "isampler1D", "isampler2D", "isampler3D", "isamplerCube",
    "isampler1DArray", "isampler2DArray", "usampler1D", "usampler2D", "usampler3D", "usamplerCube", "usampler1DArray",
    "usampler2DArray", "sampler2DRect", "sampler2DRectShadow", "isampler2DRect", "usampler2DRect", "samplerBuffer",
    "isamplerBuffer", "usamplerBuffer", "sampler2DMS", "isampler2DMS", "usampler2DMS", "sampler2DMSArray",
    "isampler2DMSArray", "usampler2DMSArray", "samplerCubeArray", "samplerCubeArrayShadow", "isamplerCubeArray",
    "usamplerCubeArray", "image1D", "iimage1D", "uimage1D", "image2D", "iimage2D", "uimage2D", "image3D", "iimage3D",
    "uimage3D", "image2DRect", "iimage2DRect", "uimage2DRect", "imageCube", "iimageCube", "uimageCube", "imageBuffer",
    "iimageBuffer", "uimageBuffer", "image1DArray", "iimage1DArray", "uimage1DArray", "image2DArray", "iimage2DArray",
    "uimage2DArray", "imageCubeArray", "iimageCubeArray", "uimageCubeArray", "image2DMS", "iimage2DMS", "uimage2DMS",
    "image2DMSArray", "iimage2DMSArray", "uimage2DMSArray", "struct", "common", "partition", "active", "asm", "class",
    "union", "enum", "typedef", "template", "this", "resource", "goto", "inline", "noinline", "public", "static",
    "extern", "external", "interface", "long", "short", "half", "fixed", "unsigned", "superp", "input", "output",
    "hvec2", "hvec3", "hvec4", "fvec2", "fvec3", "fvec4", "sampler3DRect", "filter", "sizeof", "cast", "namespace",
    "using", "texture1D", "main", "texture", "sampler", "samplerShadow", "subpassInput", "isubpassInput",
    "usubpassInput", "subpassInputMS", "texture2D", "texture3D", "textureCube", "demote", "terminateInvocation",
    "rayPayloadEXT", "hitAttributeEXT", "callableDataEXT", "nonuniformEXT", "devicecoherent", "queuefamilycoherent",
    "workgroupcoherent", "subgroupcoherent", "nonprivate", "float16_t", "int64_t", "uint64_t",
};
// clang-format on

const std::set<std::string, std::less<>>& reservedSet() {
  static const std::set<std::string, std::less<>> set = [] {
    std::set<std::string, std::less<>> s(kReserved.begin(), kReserved.end());
    sem::TypeTable types;
    sem::BuiltinTable builtins(types);
    for (std::string_view name : builtins.names()) s.emplace(name);
    return s;
  }();
  return set;
}

}  // namespace

bool isReservedInGlsl(std::string_view name) {
  return reservedSet().count(name) > 0 || name.substr(0, 3) == "gl_" || name.find("__") != std::string_view::npos;
}

namespace {

// A spelling GLSL accepts for a user name: no double underscores, no `gl_`
// prefix, and a trailing `_` on reserved words and on names in the
// generator's own `spire_` namespace.
std::string acceptableSpelling(std::string_view source) {
  std::string base(source);
  for (size_t at = base.find("__"); at != std::string::npos; at = base.find("__")) base.replace(at, 2, "_x_");
  if (base.rfind("gl_", 0) == 0) base.replace(0, 3, "glx_");
  if (isReservedInGlsl(base) || base.rfind("spire_", 0) == 0) base += '_';
  return base;
}

}  // namespace

std::string NameTable::unique(const std::string& base, std::string_view source) {
  std::string candidate = base;
  for (int n = 2; taken_.count(candidate); ++n) candidate = base + std::to_string(n);
  taken_.insert(candidate);
  if (candidate != source) introduced_.insert(candidate);
  return candidate;
}

std::string NameTable::claim(std::string_view source) { return unique(acceptableSpelling(source), source); }

std::string NameTable::generate(std::string_view hint) { return unique("spire_" + std::string(hint), {}); }

std::string NameTable::local(std::string_view source) const {
  const std::string base = acceptableSpelling(source);
  std::string candidate = base;
  for (int n = 2; introduced_.count(candidate); ++n) candidate = base + "_l" + std::to_string(n);
  return candidate;
}

}  // namespace spire::codegen
