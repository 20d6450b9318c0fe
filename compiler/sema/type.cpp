#include "sema/type.h"

#include <fmt/format.h>

#include <algorithm>

namespace spire::sem {
namespace {

std::string_view scalarName(ScalarKind kind) {
  switch (kind) {
    case ScalarKind::Bool: return "bool";
    case ScalarKind::Int: return "int";
    case ScalarKind::Uint: return "uint";
    case ScalarKind::Float: return "float";
  }
  return "float";
}

std::string_view vectorPrefix(ScalarKind kind) {
  switch (kind) {
    case ScalarKind::Bool: return "b";
    case ScalarKind::Int: return "i";
    case ScalarKind::Uint: return "u";
    case ScalarKind::Float: return "";
  }
  return "";
}

std::string_view samplerName(SamplerKind kind) {
  switch (kind) {
    case SamplerKind::Sampler2D: return "sampler2D";
    case SamplerKind::Sampler3D: return "sampler3D";
    case SamplerKind::SamplerCube: return "samplerCube";
    case SamplerKind::Sampler2DArray: return "sampler2DArray";
  }
  return "sampler2D";
}

}  // namespace

bool Type::containsOpaque() const {
  if (isSampler()) return true;
  if (isArray()) return element->containsOpaque();
  if (isStruct()) {
    for (const StructField& f : fields) {
      if (f.type->containsOpaque()) return true;
    }
  }
  return false;
}

std::string Type::name() const {
  switch (kind) {
    case TypeKind::Error: return "<error>";
    case TypeKind::Void: return "void";
    case TypeKind::Scalar: return std::string(scalarName(scalar));
    case TypeKind::Vector: return fmt::format("{}vec{}", vectorPrefix(scalar), rows);
    case TypeKind::Matrix:
      return columns == rows ? fmt::format("mat{}", columns) : fmt::format("mat{}x{}", columns, rows);
    case TypeKind::Sampler: return std::string(samplerName(sampler));
    case TypeKind::Struct: return structName;
    case TypeKind::Array: {
      // Nested arrays print outermost dimension first: float[2][3].
      const Type* base = this;
      std::string dims;
      while (base->isArray()) {
        dims += fmt::format("[{}]", base->arraySize);
        base = base->element;
      }
      return base->name() + dims;
    }
  }
  return "<error>";
}

TypeTable::TypeTable() {
  error_ = make(Type{});
  Type v;
  v.kind = TypeKind::Void;
  void_ = make(v);
  for (ScalarKind k : {ScalarKind::Bool, ScalarKind::Int, ScalarKind::Uint, ScalarKind::Float}) {
    Type s;
    s.kind = TypeKind::Scalar;
    s.scalar = k;
    const Type* scalarType = make(s);
    scalars_[static_cast<size_t>(k)] = scalarType;
    vectors_[static_cast<size_t>(k)][1] = scalarType;
    builtinNames_[std::string(scalarName(k))] = scalarType;
    for (uint8_t n = 2; n <= 4; ++n) {
      Type vec;
      vec.kind = TypeKind::Vector;
      vec.scalar = k;
      vec.rows = n;
      const Type* vt = make(vec);
      vectors_[static_cast<size_t>(k)][n] = vt;
      builtinNames_[vt->name()] = vt;
    }
  }
  for (uint8_t c = 2; c <= 4; ++c) {
    for (uint8_t r = 2; r <= 4; ++r) {
      Type m;
      m.kind = TypeKind::Matrix;
      m.scalar = ScalarKind::Float;
      m.columns = c;
      m.rows = r;
      const Type* mt = make(m);
      matrices_[c][r] = mt;
      builtinNames_[fmt::format("mat{}x{}", c, r)] = mt;
      if (c == r) builtinNames_[fmt::format("mat{}", c)] = mt;
    }
  }
  for (SamplerKind k :
       {SamplerKind::Sampler2D, SamplerKind::Sampler3D, SamplerKind::SamplerCube, SamplerKind::Sampler2DArray}) {
    Type s;
    s.kind = TypeKind::Sampler;
    s.sampler = k;
    samplers_[static_cast<size_t>(k)] = make(s);
    builtinNames_[std::string(samplerName(k))] = samplers_[static_cast<size_t>(k)];
  }
  builtinNames_["void"] = void_;
}

const Type* TypeTable::make(Type t) {
  storage_.push_back(std::move(t));
  return &storage_.back();
}

const Type* TypeTable::vector(ScalarKind kind, uint32_t size) const {
  if (size < 1 || size > 4) return error_;
  return vectors_[static_cast<size_t>(kind)][size];
}

const Type* TypeTable::matrix(uint32_t columns, uint32_t rows) const {
  if (columns < 2 || columns > 4 || rows < 2 || rows > 4) return error_;
  return matrices_[columns][rows];
}

const Type* TypeTable::array(const Type* element, uint32_t size) {
  auto [it, inserted] = arrays_.try_emplace({element, size}, nullptr);
  if (inserted) {
    Type a;
    a.kind = TypeKind::Array;
    a.element = element;
    a.arraySize = size;
    it->second = make(a);
  }
  return it->second;
}

const Type* TypeTable::structType(std::string name, std::vector<StructField> fields) {
  Type s;
  s.kind = TypeKind::Struct;
  s.structName = std::move(name);
  s.fields = std::move(fields);
  return make(std::move(s));
}

const Type* TypeTable::lookupBuiltin(std::string_view name) const {
  auto it = builtinNames_.find(std::string(name));
  return it == builtinNames_.end() ? nullptr : it->second;
}

std::vector<std::string_view> TypeTable::builtinNames() const {
  std::vector<std::string_view> names;
  names.reserve(builtinNames_.size());
  for (const auto& [name, type] : builtinNames_) names.push_back(name);
  std::sort(names.begin(), names.end());
  return names;
}

const Type* TypeTable::withScalar(const Type* type, ScalarKind kind) const {
  if (type->isScalar() || type->isVector()) return vector(kind, type->rows);
  if (type->isMatrix() && kind == ScalarKind::Float) return type;
  return error_;
}

bool isImplicitlyConvertible(const Type* from, const Type* to) {
  if (from == to) return true;
  if (!(from->isScalar() || from->isVector()) || from->kind != to->kind || from->rows != to->rows) return false;
  switch (from->scalar) {
    case ScalarKind::Int: return to->scalar == ScalarKind::Uint || to->scalar == ScalarKind::Float;
    case ScalarKind::Uint: return to->scalar == ScalarKind::Float;
    default: return false;
  }
}

}  // namespace spire::sem
