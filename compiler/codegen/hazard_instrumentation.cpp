#include "codegen/hazard_instrumentation.h"

#include <fmt/format.h>

#include "codegen/glsl_names.h"
#include "codegen/strategies/strategy_support.h"

namespace spire::codegen {
namespace {

// A value with more float parts than this is checked on its first ones
// only, and dumps stop at kMaxDumpFloats: a check per array element would
// make the kernel's code grow with the data, not the shader.
constexpr size_t kMaxCheckedParts = 64;
constexpr uint32_t kMaxDumpFloats = 256;

// The vectors and scalars of `type` held in `value`, each a GLSL expression
// that the kind function accepts (float, vec2, vec3, vec4).
void floatParts(const sem::Type* type, const std::string& value, std::vector<std::string>& parts) {
  if (parts.size() >= kMaxCheckedParts) return;
  switch (type->kind) {
    case sem::TypeKind::Scalar:
    case sem::TypeKind::Vector:
      if (type->scalar == sem::ScalarKind::Float) parts.push_back(value);
      return;
    case sem::TypeKind::Matrix:
      for (uint32_t c = 0; c < type->columns; ++c) parts.push_back(fmt::format("{}[{}]", value, c));
      return;
    case sem::TypeKind::Array:
      for (uint32_t i = 0; i < type->arraySize; ++i) floatParts(type->element, fmt::format("{}[{}]", value, i), parts);
      return;
    case sem::TypeKind::Struct:
      for (const sem::StructField& f : type->fields) {
        const std::string field = isReservedInGlsl(f.name) ? f.name + "_" : f.name;
        floatParts(f.type, fmt::format("{}.{}", value, field), parts);
      }
      return;
    default: return;
  }
}

// max() over the parts' kinds: NaN wins over Inf, either over finite.
std::string kindOfParts(const std::vector<std::string>& parts, const std::string& function) {
  std::string expression = fmt::format("{}({})", function, parts.back());
  for (size_t i = parts.size() - 1; i-- > 0;) {
    expression = fmt::format("max({}({}), {})", function, parts[i], expression);
  }
  return expression;
}

// The floats of a numeric value, in reflection order (column by column).
std::vector<std::string> dumpedFloats(const sem::Type* type, const std::string& value) {
  std::vector<std::string> floats;
  if (type->isScalar()) floats.push_back(fmt::format("float({})", value));
  if (type->isVector()) {
    for (uint32_t i = 0; i < type->rows; ++i) floats.push_back(fmt::format("float({}[{}])", value, i));
  }
  if (type->isMatrix()) {
    for (uint32_t c = 0; c < type->columns; ++c) {
      for (uint32_t r = 0; r < type->rows; ++r) floats.push_back(fmt::format("{}[{}][{}]", value, c, r));
    }
  }
  return floats;
}

std::string indexName(ShaderStage stage) {
  switch (stage) {
    case ShaderStage::Fragment: return "pixel";
    case ShaderStage::Vertex: return "gl_VertexIndex";
    case ShaderStage::Compute: return "gl_GlobalInvocationID.x";
  }
  return "";
}

std::string indexExpression(ShaderStage stage, const std::string& buffer) {
  switch (stage) {
    case ShaderStage::Fragment: return fmt::format("uint(gl_FragCoord.y) * {}.width + uint(gl_FragCoord.x)", buffer);
    case ShaderStage::Vertex: return "uint(gl_VertexIndex)";
    case ShaderStage::Compute: return "gl_GlobalInvocationID.x";
  }
  return "0u";
}

}  // namespace

HazardInstrumentation::HazardInstrumentation(KernelBuilder& kernel, const std::vector<InstrumentedValue>& values)
    : stage_(kernel.stage()),
      probe_(kernel.names().generate("checkOperation"), kernel.names().generate("failedOperation")) {
  // A fragment records only what passed the depth test, so a pixel's record
  // is the surface that shows there, not one hidden behind it; unless the
  // kernel writes depth itself, which early tests would bypass.
  earlyTests_ = stage_ == ShaderStage::Fragment;
  for (const reflection::KernelOutput& o : kernel.outputs()) {
    if (o.kind == reflection::OutputKind::BuiltIn && o.component == "gl_FragDepth") earlyTests_ = false;
  }
  buffer_ = kernel.names().generate("hazards");
  hazard_ = kernel.names().generate("hazard");
  operation_ = kernel.names().generate("hazardOperation");
  index_ = kernel.names().generate("hazardIndex");
  slot_ = kernel.names().generate("hazardSlot");
  kindFunction_ = kernel.names().generate("nonFinite");
  record_.index = indexName(stage_);
  uint32_t dumpFloats = 0;
  for (const InstrumentedValue& v : values) {
    reflection::HazardValue entry{v.component, reflectedType(v.type), 0, {}, {}, {}, std::nullopt};
    std::vector<std::string> parts;
    if (v.computed) floatParts(v.type, v.glslName, parts);
    if (!parts.empty()) {
      entry.code = static_cast<uint32_t>(checked_.size() + 1);
      entry.definition = v.definition;
      entry.source = v.source;
      entry.reads = v.reads;
      checked_.push_back({v.component, entry.code, kindOfParts(parts, kindFunction_)});
    }
    const std::vector<std::string> floats =
        v.type->isNumericShape() ? dumpedFloats(v.type, v.glslName) : std::vector<std::string>{};
    if (!floats.empty() && dumpFloats + floats.size() <= kMaxDumpFloats) {
      entry.dumpOffset = dumpFloats;
      for (const std::string& f : floats) dumps_.emplace_back(f, dumpFloats++);
    }
    record_.values.push_back(std::move(entry));
  }
  record_.slots = std::max<uint32_t>(1, static_cast<uint32_t>(checked_.size()));
  record_.dumpFloats = std::max<uint32_t>(1, dumpFloats);
  declare(kernel);
}

void HazardInstrumentation::declare(KernelBuilder& kernel) {
  record_.slot = {kernel.descriptorSet(), kernel.allocateBinding()};
  if (earlyTests_) kernel.declare("layout(early_fragment_tests) in;");
  kernel.declare(
      fmt::format("layout(set = {}, binding = {}, std430) buffer {} {{\n"
                  "    uint width;\n"
                  "    uint reserved[3];\n"
                  "    uint claims[{}];\n"
                  "    uint first[{}];\n"
                  "    uint operations[{}];\n"
                  "    float dumps[{}];\n"
                  "    uint codes[];\n"
                  "}} {};",
                  record_.slot.set, record_.slot.binding, kernel.names().generate("HazardRecord"), record_.slots,
                  record_.slots, record_.slots, record_.slots * record_.dumpFloats, buffer_));
  // Overloads for each float shape; a matrix, array or struct is checked
  // part by part.
  std::string functions;
  for (const char* type : {"float", "vec2", "vec3", "vec4"}) {
    const bool scalar = std::string_view(type) == "float";
    functions += fmt::format("{}uint {}({} v) {{ return {} ? {}u : ({} ? {}u : 0u); }}", functions.empty() ? "" : "\n",
                             kindFunction_, type, scalar ? "isnan(v)" : "any(isnan(v))", reflection::kHazardNaN,
                             scalar ? "isinf(v)" : "any(isinf(v))", reflection::kHazardInf);
  }
  kernel.declare(std::move(functions));
  // A checked operation passes its value through and notes itself when the
  // value is the first non-finite one since the component began.
  kernel.declare(fmt::format("uint {} = 0u;", probe_.noted()));
  std::string probes;
  for (const char* type : {"float", "vec2", "vec3", "vec4"}) {
    probes += fmt::format("{}{} {}({} v, uint operation) {{ if ({} == 0u && {}(v) != 0u) {} = operation; return v; }}",
                          probes.empty() ? "" : "\n", type, probe_.function(), type, probe_.noted(), kindFunction_,
                          probe_.noted());
  }
  kernel.declare(std::move(probes));
}

std::string HazardInstrumentation::entry() const {
  return fmt::format("uint {} = 0u; uint {} = 0u;", hazard_, operation_);
}

reflection::HazardRecord HazardInstrumentation::reflection() const {
  reflection::HazardRecord record = record_;
  record.operations = probe_.operations();
  return record;
}

std::string HazardInstrumentation::checkAfter(std::string_view component) const {
  for (const Checked& c : checked_) {
    if (c.component != component) continue;
    return fmt::format("if ({0} == 0u) {{ {0} = {1}; {0} = {0} == 0u ? 0u : ({2}u << 2) | {0}; {3} = {4}; }}", hazard_,
                       c.kindExpression, c.code, operation_, probe_.noted());
  }
  return {};
}

std::vector<std::string> HazardInstrumentation::record() const {
  std::vector<std::string> lines;
  lines.push_back(fmt::format("uint {} = {};", index_, indexExpression(stage_, buffer_)));
  // A fragment's record replaces what an earlier surface left at its pixel;
  // vertices and bake texels keep any hazard once recorded.
  const std::string keep = stage_ == ShaderStage::Fragment ? "" : fmt::format("{} != 0u && ", hazard_);
  lines.push_back(fmt::format("if ({}{} < uint({}.codes.length())) {}.codes[{}] = {};", keep, index_, buffer_, buffer_,
                              index_, hazard_));
  lines.push_back(fmt::format("if ({} != 0u) {{", hazard_));
  lines.push_back(fmt::format("    uint {} = ({} >> 2) - 1u;", slot_, hazard_));
  lines.push_back(fmt::format("    if (atomicCompSwap({}.claims[{}], 0u, 1u) == 0u) {{", buffer_, slot_));
  lines.push_back(fmt::format("        {}.first[{}] = {};", buffer_, slot_, index_));
  lines.push_back(fmt::format("        {}.operations[{}] = {};", buffer_, slot_, operation_));
  for (const auto& [value, offset] : dumps_) {
    lines.push_back(
        fmt::format("        {}.dumps[{} * {}u + {}u] = {};", buffer_, slot_, record_.dumpFloats, offset, value));
  }
  lines.push_back("    }");
  lines.push_back("}");
  return lines;
}

}  // namespace spire::codegen
