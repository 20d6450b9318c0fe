#include "renderer/hazard_records.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <span>

namespace spire::engine {
namespace {

std::string unitOf(const KernelProgram& kernel) {
  // A uniform bake runs over samples of the surface, not the mesh's vertices.
  if (kernel.pass && kernel.pass->kind == WorldRole::UniformBake) return "surface samples";
  if (kernel.stage != codegen::ShaderStage::Fragment) return "vertices";
  const bool texels = kernel.pass && (kernel.pass->kind == WorldRole::TextureBake ||
                                      kernel.pass->kind == WorldRole::ObjectPassFragment);
  return texels ? "texels" : "px";
}

std::string invocationName(const std::string& unit, uint32_t index, uint32_t width) {
  if (unit == "vertices") return fmt::format("vertex {}", index);
  if (unit == "surface samples") return fmt::format("surface sample {}", index);
  const uint32_t w = std::max(width, 1U);
  return fmt::format("{} ({}, {})", unit == "px" ? "pixel" : "texel", index % w, index / w);
}

std::string number(double value) {
  if (std::isnan(value)) return "NaN";
  if (std::isinf(value)) return value > 0 ? "Inf" : "-Inf";
  return fmt::format("{:.6g}", value);
}

std::string valueText(const std::vector<double>& values) {
  if (values.size() == 1) return number(values.front());
  std::string text = "(";
  for (size_t i = 0; i < values.size(); ++i) text += (i ? ", " : "") + number(values[i]);
  return text + ")";
}

// 35036 -> "35,036": counts of pixels are read at a glance.
std::string grouped(uint64_t n) {
  std::string digits = std::to_string(n);
  for (size_t i = digits.size(); i > 3; i -= 3) digits.insert(i - 3, ",");
  return digits;
}

template <class T>
T readAt(std::span<const std::byte> memory, uint64_t offset) {
  T value{};
  if (offset + sizeof(T) <= memory.size()) std::memcpy(&value, memory.data() + offset, sizeof(T));
  return value;
}

}  // namespace

std::string describeHazard(const Hazard& hazard) {
  const std::string name =
      hazard.definition.find(':') == std::string::npos
          ? hazard.component
          : fmt::format("{}:{}", hazard.component, hazard.definition.substr(hazard.definition.find(':') + 1));
  std::string text = fmt::format("{} ({}) went {} in {} {}", name, hazard.world, hazard.nan ? "NaN" : "Inf",
                                 grouped(hazard.count), hazard.unit);
  if (!hazard.operation.empty()) text += fmt::format(" at `{}` ({})", hazard.operation, hazard.operationSource);
  if (hazard.reads.empty()) return text;
  std::string values;
  for (const auto& [component, value] : hazard.reads) {
    values += fmt::format("{}{} = {}", values.empty() ? "" : ", ", component, valueText(value));
  }
  return fmt::format("{}; {} there{}", text, values, hazard.inherited ? " (it came in with its input)" : "");
}

Expected<VkBuffer> HazardCollector::attach(const vk::Context& ctx, const KernelProgram& kernel, uint32_t invocations,
                                           uint32_t width) {
  if (!kernel.hazards) return Error{fmt::format("the {} kernel is not instrumented", kernel.world), {}, {}};
  if (kernel.stage != codegen::ShaderStage::Compute && !ctx.graphicsStores()) {
    return Error{fmt::format("'{}' cannot write storage buffers from vertex and fragment kernels, which the "
                             "instrumented {} kernel needs",
                             ctx.properties().deviceName, kernel.world),
                 {},
                 {}};
  }
  const reflection::HazardRecord& layout = *kernel.hazards;
  const VkDeviceSize size = layout.codesOffset() + VkDeviceSize{invocations} * 4;
  auto buffer = vk::Buffer::create(ctx, size, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  if (!buffer) return Error::fromVk(buffer.error());
  std::memset(buffer->mapped(), 0, static_cast<size_t>(buffer->size()));
  std::memcpy(buffer->mapped(), &width, sizeof width);
  records_.push_back({instance_, kernel.world, layout, unitOf(kernel), invocations, width,
                      std::make_unique<vk::Buffer>(std::move(buffer).value())});
  return records_.back().buffer->handle();
}

void HazardCollector::readRecord(const Record& record, std::vector<Hazard>& out) const {
  const std::span<const std::byte> memory(static_cast<const std::byte*>(record.buffer->mapped()),
                                          static_cast<size_t>(record.buffer->size()));
  const reflection::HazardRecord& layout = record.layout;
  std::map<uint32_t, uint64_t> counts;  // by code << 2 | kind
  for (uint32_t i = 0; i < record.invocations; ++i) {
    const auto code = readAt<uint32_t>(memory, layout.codesOffset() + uint64_t{i} * 4);
    if (code != 0) ++counts[code];
  }
  for (const auto& [code, count] : counts) {
    const uint32_t slot = (code >> 2) - 1;
    const reflection::HazardValue* value = layout.byCode(code >> 2);
    if (!value || slot >= layout.slots) continue;
    Hazard hazard;
    hazard.instance = record.instance;
    hazard.world = record.world;
    hazard.component = value->component;
    hazard.definition = value->definition;
    hazard.source = value->source;
    hazard.nan = (code & 3) == reflection::kHazardNaN;
    hazard.count = count;
    hazard.unit = record.unit;
    hazard.where =
        invocationName(record.unit, readAt<uint32_t>(memory, layout.firstOffset() + uint64_t{slot} * 4), record.width);
    const auto operation = readAt<uint32_t>(memory, layout.operationsOffset() + uint64_t{slot} * 4);
    if (operation != 0 && operation <= layout.operations.size()) {
      hazard.operation = layout.operations[operation - 1].text;
      hazard.operationSource = layout.operations[operation - 1].source;
    }
    const uint64_t dumps = layout.dumpsOffset() + uint64_t{slot} * layout.dumpFloats * 4;
    for (const std::string& read : value->reads) {
      const reflection::HazardValue* input = layout.value(read);
      if (!input || !input->dumpOffset) continue;
      std::vector<double> values;
      for (uint32_t c = 0; c < input->type.componentCount(); ++c) {
        const double v = readAt<float>(memory, dumps + (uint64_t{*input->dumpOffset} + c) * 4);
        hazard.inherited = hazard.inherited || !std::isfinite(v);
        values.push_back(v);
      }
      hazard.reads.emplace_back(read, std::move(values));
    }
    // An input that came in non-finite makes the first arithmetic on it
    // non-finite too: naming that operation would point at where the value
    // passed through, not where it went wrong.
    if (hazard.inherited) {
      hazard.operation.clear();
      hazard.operationSource.clear();
    }
    out.push_back(std::move(hazard));
  }
}

std::vector<Hazard> HazardCollector::read() const {
  std::vector<Hazard> hazards;
  for (const Record& record : records_) readRecord(record, hazards);
  std::stable_sort(hazards.begin(), hazards.end(), [](const Hazard& a, const Hazard& b) {
    if (a.inherited != b.inherited) return !a.inherited;
    return a.count > b.count;
  });
  return hazards;
}

}  // namespace spire::engine
