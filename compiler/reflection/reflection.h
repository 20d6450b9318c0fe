// Reflection as data: what a compiled variant's kernels read and write, and
// where (docs/reflection.md). The strategies fill these records while they
// generate code; reflection_json.h writes them as reflection.json and reads
// them back. An engine therefore sees the same typed records whether it
// compiles in process or loads a spirec output directory, and never guesses a
// value's kind or re-parses its type.
#pragma once

#include <compare>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace spire::reflection {

enum class Stage { Vertex, Fragment, Compute };

std::string_view stageName(Stage stage);  // "vertex", "fragment", "compute"
std::optional<Stage> parseStage(std::string_view name);

// The type of a value crossing a kernel boundary. Numeric values (scalars,
// vectors, matrices and one-dimensional arrays of them) carry their shape;
// samplers and structs only their GLSL spelling.
struct ValueType {
  enum class Kind { Numeric, Sampler, Other };
  enum class Scalar { Float, Int, Uint, Bool };
  Kind kind = Kind::Numeric;
  Scalar scalar = Scalar::Float;
  uint32_t rows = 1;         // vector size; rows of a matrix
  uint32_t columns = 1;      // > 1 for matrices
  uint32_t arrayLength = 0;  // 0 when not an array
  std::string name;          // GLSL spelling: "vec3", "mat3x4", "float[4]", "sampler2D"

  bool isNumeric() const { return kind == Kind::Numeric; }
  bool isMatrix() const { return columns > 1; }
  uint32_t componentCount() const { return rows * columns * (arrayLength == 0 ? 1 : arrayLength); }
  bool operator==(const ValueType&) const = default;
};

// The type a GLSL spelling names. Spellings that are not a numeric type or a
// sampler are Kind::Other (a struct's name, say).
ValueType parseValueType(std::string_view glsl);

// Where a resource is bound: bindings restart at 0 in each kernel, and each
// stage of a GPU pipeline has its own set, so a binding alone is ambiguous.
struct DescriptorSlot {
  uint32_t set = 0;
  uint32_t binding = 0;
  // clang-tidy 14 reports the literal 0 of the defaulted comparison as a null pointer.
  auto operator<=>(const DescriptorSlot&) const = default;  // NOLINT(modernize-use-nullptr)
};

// One member of a uniform block or of a storage buffer's record.
struct BlockMember {
  std::string component;
  std::string glslName;
  ValueType type;
  uint32_t offset = 0;
  uint32_t size = 0;
  uint32_t arrayStride = 0;   // 0 when not an array
  uint32_t matrixStride = 0;  // 0 when not a matrix
  bool operator==(const BlockMember&) const = default;
};

struct Block {
  std::string name;
  bool storage = false;  // a storage buffer of records; otherwise a uniform block
  std::string layout;    // "std140" or "std430"
  DescriptorSlot slot;
  uint32_t size = 0;          // uniform blocks: bytes the buffer needs
  uint32_t recordStride = 0;  // storage blocks: bytes per record
  std::string strategy;
  std::vector<BlockMember> members;

  const BlockMember* member(std::string_view component) const;
  bool operator==(const Block&) const = default;
};

enum class InputKind {
  Varying,        // an `in` variable at `location`
  UniformMember,  // a member of uniform block `block` at `offset`
  Sampler,        // an opaque uniform of its own at `slot`
  Texture,        // a sampler2D (sampler2DArray with a `layer`) at `slot`, fetched at `uv`
  BufferMember,   // a member of the records of storage block `block`, read at `index`
  PushConstant,   // a member of the kernel's push-constant block at `offset`
};

// The kind's name in reflection.json: "varying", "uniform", "sampler", ...
std::string_view inputKindName(InputKind kind);

struct KernelInput {
  InputKind kind = InputKind::Varying;
  std::string component;
  std::string glslName;
  ValueType type;
  std::string strategy;
  std::string from;       // the producing world
  uint32_t location = 0;  // Varying
  DescriptorSlot slot;    // every kind but Varying
  std::string block;      // UniformMember, BufferMember
  uint32_t offset = 0;    // UniformMember, BufferMember, PushConstant
  std::string sampler;    // Texture
  std::string uv;         // Texture: GLSL expression in this kernel
  std::string layer;      // Texture: GLSL expression of the array layer; empty for a sampler2D
  uint32_t channels = 0;  // Texture: components kept, 1 to 4
  std::string index;      // BufferMember: gl_VertexIndex, gl_InstanceIndex or gl_GlobalInvocationID.x
  bool operator==(const KernelInput&) const = default;
};

enum class OutputKind {
  Varying,       // an `out` variable at `location`
  BuiltIn,       // a GLSL built-in (`component` names it) set to `expression`
  BufferMember,  // a member of the records of storage block `block`
};

// Hints from component and decision attributes ([Format], [TextureSize]),
// in the order first given; a later value for a name replaces the earlier.
using Hints = std::vector<std::pair<std::string, std::string>>;

struct KernelOutput {
  OutputKind kind = OutputKind::Varying;
  std::string component;
  std::string glslName;
  ValueType type;
  std::string strategy;
  uint32_t location = 0;   // Varying
  DescriptorSlot slot;     // BufferMember
  std::string block;       // BufferMember
  uint32_t offset = 0;     // BufferMember
  std::string expression;  // BuiltIn
  Hints hints;

  const std::string* hint(std::string_view name) const;
  void setHint(std::string name, std::string value);
  bool operator==(const KernelOutput&) const = default;
};

// One value an instrumented kernel knows (CompileOptions::instrumentHazards):
// a value it computes, which it checks for NaN and Inf, or an input it
// reads; either may be dumped at the first invocation where a check fails.
struct HazardValue {
  std::string component;
  ValueType type;
  // Computed here and checked: its code, 1-based in evaluation order, its
  // definition ("World" or "World:variation"), where that is ("file:line")
  // and the values it reads. An input, or a value with no float in it: 0.
  uint32_t code = 0;
  std::string definition;
  std::string source;
  std::vector<std::string> reads;
  // Numeric values (scalars, vectors, matrices): the index of its first float
  // in a slot's dump; others are not dumped.
  std::optional<uint32_t> dumpOffset;
  bool operator==(const HazardValue&) const = default;
};

// An operation an instrumented kernel checks inside component and function
// bodies (a division, a call of a function that can return NaN or Inf): the
// first of them to go non-finite names where in its component a hazard arose.
struct HazardOperation {
  std::string text;    // as written, abbreviated: "color / divisor"
  std::string source;  // "file:line:col"
  bool operator==(const HazardOperation&) const = default;
};

// Where an instrumented kernel records, for each of its invocations, the
// first value it computes that is not finite. A storage buffer, std430:
//   uint width; uint reserved[3];   // written by the engine: a fragment kernel's target width
//   uint claims[slots];             // per code: set by the first invocation with that code
//   uint first[slots];              // per code: that invocation's index
//   uint operations[slots];         // per code: 1 + the index in `operations` of the first checked
//                                   // operation to go non-finite in that value; 0: none did
//   float dumps[slots * dumpFloats];// per code: the dumped values at that invocation
//   uint codes[];                   // per invocation: code << 2 | kind, 0 while finite
// where kind is kHazardInf or kHazardNaN (NaN wins when a value has both). A
// fragment invocation's index is y * width + x of its pixel.
struct HazardRecord {
  DescriptorSlot slot;
  std::string index;  // "pixel", "gl_VertexIndex" or "gl_GlobalInvocationID.x"
  uint32_t slots = 1;
  uint32_t dumpFloats = 1;
  std::vector<HazardValue> values;  // inputs, then computed values in evaluation order
  std::vector<HazardOperation> operations;

  uint32_t claimsOffset() const { return 16; }
  uint32_t firstOffset() const { return claimsOffset() + 4 * slots; }
  uint32_t operationsOffset() const { return firstOffset() + 4 * slots; }
  uint32_t dumpsOffset() const { return operationsOffset() + 4 * slots; }
  uint32_t codesOffset() const { return dumpsOffset() + 4 * slots * dumpFloats; }
  const HazardValue* byCode(uint32_t code) const;
  const HazardValue* value(std::string_view component) const;
  bool operator==(const HazardRecord&) const = default;
};

inline constexpr uint32_t kHazardInf = 1;
inline constexpr uint32_t kHazardNaN = 2;

struct Kernel {
  std::string world;
  Stage stage = Stage::Fragment;
  std::string entry = "main";
  std::string glslFile;   // "<World>.glsl"
  std::string spirvFile;  // "<World>.spv"
  std::string hash;       // contentHash (support/content_hash.h) of the GLSL text
  std::string spirvHash;  // contentHash of the SPIR-V bytes; empty when none was made
  std::string key;        // kernelKey: equal keys, interchangeable kernels
  std::vector<KernelInput> inputs;
  std::vector<KernelOutput> outputs;
  std::vector<Block> blocks;
  std::optional<HazardRecord> hazards;  // instrumented kernels only

  const Block* block(DescriptorSlot slot) const;
  bool operator==(const Kernel&) const = default;
};

// A world of the variant's pipeline and the engine role its [Role]
// attribute names ("" without one: the engine may know the world by name).
struct World {
  std::string name;
  std::string role;
  bool operator==(const World&) const = default;
};

struct Variant {
  std::string shader;
  std::string pipeline;
  std::vector<World> worlds;  // every world of the pipeline, in declaration order
  // Every live, non-input component -> "World" or "World:variation": the
  // variant as a decision file would state it.
  std::vector<std::pair<std::string, std::string>> placement;
  std::vector<Kernel> kernels;  // producers before consumers

  const Kernel* kernel(std::string_view world) const;
  bool operator==(const Variant&) const = default;
};

}  // namespace spire::reflection
