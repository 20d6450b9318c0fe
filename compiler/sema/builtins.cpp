// The GLSL 4.50 built-in function table (GLSL 4.50 specification, sections
// 8.1-8.9 and 8.13), restricted to the types Spire has: no doubles, no
// images, no atomic counters, no shadow or integer samplers. Generic
// signatures of the specification (genType, genIType, genUType, genBType,
// mat, gvec4, ...) are expanded here into one overload per concrete type so
// that overload resolution only ever compares concrete types.
#include "sema/builtins.h"

#include <algorithm>
#include <initializer_list>
#include <utility>

namespace spire::sem {
namespace {

using ast::ParamDirection;

constexpr ScalarKind kFloat = ScalarKind::Float;
constexpr ScalarKind kInt = ScalarKind::Int;
constexpr ScalarKind kUint = ScalarKind::Uint;
constexpr ScalarKind kBool = ScalarKind::Bool;

// Fills one table. Overloads whose parameter types repeat an existing
// overload of the same name are dropped, so generic expansions that coincide
// at size 1 (mod(float, float) from both mod forms, min(float, float), ...)
// appear once.
class Builder {
 public:
  Builder(TypeTable& types, std::unordered_map<std::string_view, std::vector<BuiltinOverload>>& overloads)
      : t_(types), overloads_(overloads) {}

  const Type* f() const { return t_.floatType(); }
  const Type* i() const { return t_.intType(); }
  const Type* u() const { return t_.uintType(); }
  const Type* b() const { return t_.boolType(); }
  const Type* vec(uint32_t n) const { return t_.vector(kFloat, n); }
  const Type* ivec(uint32_t n) const { return t_.vector(kInt, n); }
  const Type* uvec(uint32_t n) const { return t_.vector(kUint, n); }
  const Type* bvec(uint32_t n) const { return t_.vector(kBool, n); }
  const Type* gen(ScalarKind k, uint32_t n) const { return t_.vector(k, n); }
  const Type* mat(uint32_t columns, uint32_t rows) const { return t_.matrix(columns, rows); }
  const Type* sampler(SamplerKind k) const { return t_.sampler(k); }
  const Type* voidType() const { return t_.voidType(); }
  const Type* array(const Type* element, uint32_t size) { return t_.array(element, size); }

  static BuiltinParam in(const Type* type) { return {type, ParamDirection::In}; }
  static BuiltinParam out(const Type* type) { return {type, ParamDirection::Out}; }

  // `name` must have static storage: the table keeps the view.
  void add(std::string_view name, const Type* result, std::initializer_list<BuiltinParam> params) {
    insert(name, result, std::vector<BuiltinParam>(params));
  }
  // All parameters `in`.
  void add(std::string_view name, const Type* result, std::initializer_list<const Type*> params) {
    std::vector<BuiltinParam> converted;
    converted.reserve(params.size());
    for (const Type* p : params) converted.push_back(in(p));
    insert(name, result, std::move(converted));
  }

 private:
  void insert(std::string_view name, const Type* result, std::vector<BuiltinParam> params) {
    std::vector<BuiltinOverload>& set = overloads_[name];
    for (const BuiltinOverload& existing : set) {
      if (std::equal(existing.params.begin(), existing.params.end(), params.begin(), params.end(),
                     [](const BuiltinParam& x, const BuiltinParam& y) { return x.type == y.type; })) {
        return;
      }
    }
    set.push_back(BuiltinOverload{result, std::move(params)});
  }

  TypeTable& t_;
  std::unordered_map<std::string_view, std::vector<BuiltinOverload>>& overloads_;
};

// 8.1 Angle and trigonometry functions; all component-wise over genType.
void addTrigonometry(Builder& B) {
  for (std::string_view name :
       {"radians", "degrees", "sin", "cos", "tan", "asin", "acos", "sinh", "cosh", "tanh", "asinh", "acosh", "atanh"}) {
    for (uint32_t n = 1; n <= 4; ++n) B.add(name, B.vec(n), {B.vec(n)});
  }
  for (uint32_t n = 1; n <= 4; ++n) {
    B.add("atan", B.vec(n), {B.vec(n), B.vec(n)});  // atan(y, x)
    B.add("atan", B.vec(n), {B.vec(n)});            // atan(y_over_x)
  }
}

// 8.2 Exponential functions.
void addExponential(Builder& B) {
  for (uint32_t n = 1; n <= 4; ++n) {
    B.add("pow", B.vec(n), {B.vec(n), B.vec(n)});
    for (std::string_view name : {"exp", "log", "exp2", "log2", "sqrt", "inversesqrt"}) {
      B.add(name, B.vec(n), {B.vec(n)});
    }
  }
}

// 8.3 Common functions.
void addCommon(Builder& B) {
  for (uint32_t n = 1; n <= 4; ++n) {
    const Type* v = B.vec(n);
    const Type* iv = B.ivec(n);
    const Type* uv = B.uvec(n);
    const Type* bv = B.bvec(n);

    B.add("abs", v, {v});
    B.add("abs", iv, {iv});
    B.add("sign", v, {v});
    B.add("sign", iv, {iv});
    for (std::string_view name : {"floor", "trunc", "round", "roundEven", "ceil", "fract"}) B.add(name, v, {v});

    B.add("mod", v, {v, B.f()});
    B.add("mod", v, {v, v});
    B.add("modf", v, {Builder::in(v), Builder::out(v)});

    for (std::string_view name : {"min", "max"}) {
      B.add(name, v, {v, v});
      B.add(name, v, {v, B.f()});
      B.add(name, iv, {iv, iv});
      B.add(name, iv, {iv, B.i()});
      B.add(name, uv, {uv, uv});
      B.add(name, uv, {uv, B.u()});
    }
    B.add("clamp", v, {v, v, v});
    B.add("clamp", v, {v, B.f(), B.f()});
    B.add("clamp", iv, {iv, iv, iv});
    B.add("clamp", iv, {iv, B.i(), B.i()});
    B.add("clamp", uv, {uv, uv, uv});
    B.add("clamp", uv, {uv, B.u(), B.u()});

    B.add("mix", v, {v, v, v});
    B.add("mix", v, {v, v, B.f()});
    B.add("mix", v, {v, v, bv});
    B.add("mix", iv, {iv, iv, bv});
    B.add("mix", uv, {uv, uv, bv});
    B.add("mix", bv, {bv, bv, bv});

    B.add("step", v, {v, v});
    B.add("step", v, {B.f(), v});
    B.add("smoothstep", v, {v, v, v});
    B.add("smoothstep", v, {B.f(), B.f(), v});

    B.add("isnan", bv, {v});
    B.add("isinf", bv, {v});
    B.add("floatBitsToInt", iv, {v});
    B.add("floatBitsToUint", uv, {v});
    B.add("intBitsToFloat", v, {iv});
    B.add("uintBitsToFloat", v, {uv});

    B.add("fma", v, {v, v, v});
    B.add("frexp", v, {Builder::in(v), Builder::out(iv)});
    B.add("ldexp", v, {v, iv});
  }
}

// 8.4 Floating-point pack and unpack functions (no double packing).
void addPacking(Builder& B) {
  B.add("packUnorm2x16", B.u(), {B.vec(2)});
  B.add("packSnorm2x16", B.u(), {B.vec(2)});
  B.add("packUnorm4x8", B.u(), {B.vec(4)});
  B.add("packSnorm4x8", B.u(), {B.vec(4)});
  B.add("unpackUnorm2x16", B.vec(2), {B.u()});
  B.add("unpackSnorm2x16", B.vec(2), {B.u()});
  B.add("unpackUnorm4x8", B.vec(4), {B.u()});
  B.add("unpackSnorm4x8", B.vec(4), {B.u()});
  B.add("packHalf2x16", B.u(), {B.vec(2)});
  B.add("unpackHalf2x16", B.vec(2), {B.u()});
}

// 8.5 Geometric functions (ftransform is compatibility-profile only).
void addGeometric(Builder& B) {
  for (uint32_t n = 1; n <= 4; ++n) {
    const Type* v = B.vec(n);
    B.add("length", B.f(), {v});
    B.add("distance", B.f(), {v, v});
    B.add("dot", B.f(), {v, v});
    B.add("normalize", v, {v});
    B.add("faceforward", v, {v, v, v});
    B.add("reflect", v, {v, v});
    B.add("refract", v, {v, v, B.f()});
  }
  B.add("cross", B.vec(3), {B.vec(3), B.vec(3)});
}

// 8.6 Matrix functions. Types are matCxR: C columns of R rows.
void addMatrix(Builder& B) {
  for (uint32_t c = 2; c <= 4; ++c) {
    for (uint32_t r = 2; r <= 4; ++r) {
      const Type* m = B.mat(c, r);
      B.add("matrixCompMult", m, {m, m});
      // outerProduct(c, r): the first argument is a column vector (R rows),
      // the second a row vector (C columns).
      B.add("outerProduct", m, {B.vec(r), B.vec(c)});
      B.add("transpose", B.mat(r, c), {m});
    }
    const Type* square = B.mat(c, c);
    B.add("determinant", B.f(), {square});
    B.add("inverse", square, {square});
  }
}

// 8.7 Vector relational functions (vectors only, no scalars).
void addVectorRelational(Builder& B) {
  for (uint32_t n = 2; n <= 4; ++n) {
    const Type* bv = B.bvec(n);
    for (ScalarKind k : {kFloat, kInt, kUint}) {
      const Type* v = B.gen(k, n);
      for (std::string_view name :
           {"lessThan", "lessThanEqual", "greaterThan", "greaterThanEqual", "equal", "notEqual"}) {
        B.add(name, bv, {v, v});
      }
    }
    B.add("equal", bv, {bv, bv});
    B.add("notEqual", bv, {bv, bv});
    B.add("any", B.b(), {bv});
    B.add("all", B.b(), {bv});
    B.add("not", bv, {bv});
  }
}

// 8.8 Integer functions.
void addInteger(Builder& B) {
  for (uint32_t n = 1; n <= 4; ++n) {
    const Type* iv = B.ivec(n);
    const Type* uv = B.uvec(n);
    B.add("uaddCarry", uv, {Builder::in(uv), Builder::in(uv), Builder::out(uv)});
    B.add("usubBorrow", uv, {Builder::in(uv), Builder::in(uv), Builder::out(uv)});
    B.add("umulExtended", B.voidType(), {Builder::in(uv), Builder::in(uv), Builder::out(uv), Builder::out(uv)});
    B.add("imulExtended", B.voidType(), {Builder::in(iv), Builder::in(iv), Builder::out(iv), Builder::out(iv)});
    for (const Type* g : {iv, uv}) {
      B.add("bitfieldExtract", g, {g, B.i(), B.i()});
      B.add("bitfieldInsert", g, {g, g, B.i(), B.i()});
      B.add("bitfieldReverse", g, {g});
      // bitCount, findLSB and findMSB return signed integers for both.
      B.add("bitCount", iv, {g});
      B.add("findLSB", iv, {g});
      B.add("findMSB", iv, {g});
    }
  }
}

// 8.9 Texture functions over the float samplers Spire has. For each sampler:
// P is its coordinate, size what textureSize returns, offset the texel offset
// type, grad the derivative type (dPdx/dPdy) and lodCoord the coordinate of
// textureQueryLod (arrays drop the layer).
struct SamplerShape {
  SamplerKind kind;
  uint32_t coord;     // components of P
  uint32_t size;      // components of textureSize's result
  uint32_t offset;    // 0 when the sampler takes no offsets (cube maps)
  uint32_t grad;      // components of dPdx and dPdy
  uint32_t lodCoord;  // components of textureQueryLod's P
  bool fetch;         // texelFetch and friends (not for cube maps)
  bool proj;          // textureProj and friends (2D and 3D)
  bool gather;        // textureGather (2D, 2D array, cube)
};

// 8.9.1 Texture query functions.
void addTextureQueries(Builder& B, const SamplerShape& s) {
  const Type* smp = B.sampler(s.kind);
  B.add("textureSize", B.ivec(s.size), {smp, B.i()});
  B.add("textureQueryLod", B.vec(2), {smp, B.vec(s.lodCoord)});
  B.add("textureQueryLevels", B.i(), {smp});
}

// 8.9.2 Texel lookup functions, without the projective ones.
void addTexelLookups(Builder& B, const SamplerShape& s) {
  const Type* f = B.f();
  const Type* i = B.i();
  const Type* v4 = B.vec(4);
  const Type* smp = B.sampler(s.kind);
  const Type* P = B.vec(s.coord);
  const Type* off = s.offset ? B.ivec(s.offset) : nullptr;
  const Type* d = B.vec(s.grad);
  B.add("texture", v4, {smp, P});
  B.add("texture", v4, {smp, P, f});  // with LOD bias
  B.add("textureLod", v4, {smp, P, f});
  B.add("textureGrad", v4, {smp, P, d, d});
  if (off) {
    B.add("textureOffset", v4, {smp, P, off});
    B.add("textureOffset", v4, {smp, P, off, f});
    B.add("textureLodOffset", v4, {smp, P, f, off});
    B.add("textureGradOffset", v4, {smp, P, d, d, off});
  }
  if (s.fetch) {
    const Type* iP = B.ivec(s.coord);
    B.add("texelFetch", v4, {smp, iP, i});
    B.add("texelFetchOffset", v4, {smp, iP, i, off});
  }
}

// textureProj divides P's leading components by its last one. 2D samplers
// take vec3 or vec4 (q in .w, .z ignored); 3D takes vec4.
void addProjectiveLookups(Builder& B, const SamplerShape& s) {
  if (!s.proj) return;
  const Type* f = B.f();
  const Type* v4 = B.vec(4);
  const Type* smp = B.sampler(s.kind);
  const Type* off = s.offset ? B.ivec(s.offset) : nullptr;
  const Type* d = B.vec(s.grad);
  std::vector<const Type*> projCoords;
  if (s.kind == SamplerKind::Sampler2D) projCoords.push_back(B.vec(3));
  projCoords.push_back(B.vec(4));
  for (const Type* pp : projCoords) {
    B.add("textureProj", v4, {smp, pp});
    B.add("textureProj", v4, {smp, pp, f});
    B.add("textureProjLod", v4, {smp, pp, f});
    B.add("textureProjGrad", v4, {smp, pp, d, d});
    B.add("textureProjOffset", v4, {smp, pp, off});
    B.add("textureProjOffset", v4, {smp, pp, off, f});
    B.add("textureProjLodOffset", v4, {smp, pp, f, off});
    B.add("textureProjGradOffset", v4, {smp, pp, d, d, off});
  }
}

// 8.9.4 Texture gather functions; `comp` selects the channel (0-3).
void addTextureGathers(Builder& B, const SamplerShape& s) {
  if (!s.gather) return;
  const Type* i = B.i();
  const Type* v4 = B.vec(4);
  const Type* smp = B.sampler(s.kind);
  const Type* P = B.vec(s.coord);
  const Type* off = s.offset ? B.ivec(s.offset) : nullptr;
  B.add("textureGather", v4, {smp, P});
  B.add("textureGather", v4, {smp, P, i});
  if (off) {
    B.add("textureGatherOffset", v4, {smp, P, off});
    B.add("textureGatherOffset", v4, {smp, P, off, i});
    const Type* offsets = B.array(off, 4);
    B.add("textureGatherOffsets", v4, {smp, P, offsets});
    B.add("textureGatherOffsets", v4, {smp, P, offsets, i});
  }
}

void addTexture(Builder& B) {
  const SamplerShape shapes[] = {
      {SamplerKind::Sampler2D, 2, 2, 2, 2, 2, true, true, true},
      {SamplerKind::Sampler3D, 3, 3, 3, 3, 3, true, true, false},
      {SamplerKind::SamplerCube, 3, 2, 0, 3, 3, false, false, true},
      {SamplerKind::Sampler2DArray, 3, 3, 2, 2, 2, true, false, true},
  };
  // Overloads are listed in the order added, which candidate notes show.
  for (const SamplerShape& s : shapes) {
    addTextureQueries(B, s);
    addTexelLookups(B, s);
    addProjectiveLookups(B, s);
    addTextureGathers(B, s);
  }
}

// 8.13.1 Derivative functions (fragment processing).
void addDerivatives(Builder& B) {
  for (std::string_view name :
       {"dFdx", "dFdy", "dFdxFine", "dFdyFine", "dFdxCoarse", "dFdyCoarse", "fwidth", "fwidthFine", "fwidthCoarse"}) {
    for (uint32_t n = 1; n <= 4; ++n) B.add(name, B.vec(n), {B.vec(n)});
  }
}

}  // namespace

BuiltinTable::BuiltinTable(TypeTable& types) {
  Builder builder(types, overloads_);
  addTrigonometry(builder);
  addExponential(builder);
  addCommon(builder);
  addPacking(builder);
  addGeometric(builder);
  addMatrix(builder);
  addVectorRelational(builder);
  addInteger(builder);
  addTexture(builder);
  addDerivatives(builder);

  names_.reserve(overloads_.size());
  for (const auto& entry : overloads_) names_.push_back(entry.first);
  std::sort(names_.begin(), names_.end());
}

const std::vector<BuiltinOverload>* BuiltinTable::lookup(std::string_view name) const {
  auto it = overloads_.find(name);
  return it == overloads_.end() ? nullptr : &it->second;
}

}  // namespace spire::sem
