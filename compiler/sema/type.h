// Spire's types: the GLSL 4.50 subset the language supports. Types are interned
// in a TypeTable, so two types are equal exactly when their pointers are.
#pragma once

#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <tuple>
#include <unordered_map>
#include <vector>

namespace spire::sem {

enum class TypeKind : uint8_t { Error, Void, Scalar, Vector, Matrix, Sampler, Struct, Array };
enum class ScalarKind : uint8_t { Bool, Int, Uint, Float };
enum class SamplerKind : uint8_t { Sampler2D, Sampler3D, SamplerCube, Sampler2DArray };

struct Type;

struct StructField {
  std::string name;
  const Type* type;
};

struct Type {
  TypeKind kind = TypeKind::Error;
  ScalarKind scalar = ScalarKind::Float;  // Scalar, Vector and Matrix
  uint8_t rows = 1;                       // vector size, or matrix rows
  uint8_t columns = 1;                    // matrix columns
  SamplerKind sampler = SamplerKind::Sampler2D;
  const Type* element = nullptr;    // Array
  uint32_t arraySize = 0;           // Array
  std::string structName;           // Struct
  std::vector<StructField> fields;  // Struct

  bool isError() const { return kind == TypeKind::Error; }
  bool isVoid() const { return kind == TypeKind::Void; }
  bool isScalar() const { return kind == TypeKind::Scalar; }
  bool isVector() const { return kind == TypeKind::Vector; }
  bool isMatrix() const { return kind == TypeKind::Matrix; }
  bool isSampler() const { return kind == TypeKind::Sampler; }
  bool isStruct() const { return kind == TypeKind::Struct; }
  bool isArray() const { return kind == TypeKind::Array; }
  // Scalars and vectors of any base type, and float matrices.
  bool isNumericShape() const { return isScalar() || isVector() || isMatrix(); }
  bool isBoolShape() const { return (isScalar() || isVector()) && scalar == ScalarKind::Bool; }
  bool isIntegerShape() const {
    return (isScalar() || isVector()) && (scalar == ScalarKind::Int || scalar == ScalarKind::Uint);
  }
  bool isFloatShape() const { return isNumericShape() && scalar == ScalarKind::Float; }
  // Number of scalar components in a scalar, vector or matrix.
  uint32_t componentCount() const { return isMatrix() ? rows * columns : rows; }
  // Types that may be held by a component or passed between worlds.
  bool isOpaque() const { return isSampler(); }
  bool containsOpaque() const;

  std::string name() const;  // GLSL spelling: "vec3", "mat4x3", "float[4]"
};

class TypeTable {
 public:
  TypeTable();
  TypeTable(const TypeTable&) = delete;
  TypeTable& operator=(const TypeTable&) = delete;

  const Type* error() const { return error_; }
  const Type* voidType() const { return void_; }
  const Type* boolType() const { return scalar(ScalarKind::Bool); }
  const Type* intType() const { return scalar(ScalarKind::Int); }
  const Type* uintType() const { return scalar(ScalarKind::Uint); }
  const Type* floatType() const { return scalar(ScalarKind::Float); }
  const Type* scalar(ScalarKind kind) const { return scalars_[static_cast<size_t>(kind)]; }
  // size 1 gives the scalar, so generic code can ask for "vector of n".
  const Type* vector(ScalarKind kind, uint32_t size) const;
  const Type* matrix(uint32_t columns, uint32_t rows) const;
  const Type* sampler(SamplerKind kind) const { return samplers_[static_cast<size_t>(kind)]; }
  const Type* array(const Type* element, uint32_t size);
  // Registers a new struct type; the caller checks for redefinition.
  const Type* structType(std::string name, std::vector<StructField> fields);

  // Built-in type keywords (`vec3`, `mat4`, `sampler2D`), or null.
  const Type* lookupBuiltin(std::string_view name) const;
  std::vector<std::string_view> builtinNames() const;

  // The same shape with another base type: withScalar(vec3, Int) == ivec3.
  const Type* withScalar(const Type* type, ScalarKind kind) const;

 private:
  const Type* make(Type t);

  std::deque<Type> storage_;
  const Type* error_ = nullptr;
  const Type* void_ = nullptr;
  const Type* scalars_[4] = {};
  const Type* vectors_[4][5] = {};   // [scalar][size]
  const Type* matrices_[5][5] = {};  // [columns][rows]
  const Type* samplers_[4] = {};
  std::map<std::pair<const Type*, uint32_t>, const Type*> arrays_;
  std::unordered_map<std::string, const Type*> builtinNames_;
};

// GLSL 4.50 implicit conversions (section 4.1.10): int -> uint, int/uint ->
// float and the same for vectors of equal size. Identity counts as convertible.
bool isImplicitlyConvertible(const Type* from, const Type* to);

}  // namespace spire::sem
