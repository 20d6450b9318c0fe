// bufferExport: a compute kernel writing one std430 record per invocation,
// with a bounds check against the buffer's length.
#include <fmt/format.h>

#include "codegen/strategies/strategy_support.h"

namespace spire::codegen {
namespace {

class BufferExport final : public Strategy {
 public:
  const sem::StrategySignature& signature() const override { return signature_; }
  std::optional<ShaderStage> stage() const override { return ShaderStage::Compute; }

  Expected<void, Failure> emitExport(ExportSite& site) const override {
    KernelBuilder& kernel = site.producer;
    if (kernel.stage() != ShaderStage::Compute) {
      return Failure{fmt::format("bufferExport writes per invocation and needs world '{}' to be a compute kernel",
                                 kernel.world())};
    }
    if (site.values.empty()) return {};
    std::vector<KernelValue> members = site.values;
    for (KernelValue& m : members) m.glslName = kernel.names().generate("rec_" + m.glslName);
    const BlockDeclaration block =
        declareBlock(kernel, kernel.world() + "_out", members, BlockLayout::Std430, "writeonly buffer", "bufferExport");
    kernel.addEntry(fmt::format("if (gl_GlobalInvocationID.x >= uint({}.length())) {{\n        return;\n    }}",
                                block.recordsName));
    for (size_t i = 0; i < site.values.size(); ++i) {
      const KernelValue& v = site.values[i];
      kernel.addStore(
          fmt::format("{}[gl_GlobalInvocationID.x].{} = {};", block.recordsName, members[i].glslName, v.glslName));
      reflection::KernelOutput entry = exportEntry(v, reflection::OutputKind::BufferMember, "bufferExport");
      entry.slot = slotAt(kernel, block.binding);
      entry.block = block.blockName;
      entry.offset = block.offsets[i];
      kernel.reflectOutput(std::move(entry));
    }
    return {};
  }

 private:
  sem::StrategySignature signature_ =
      makeSignature("bufferExport", sem::StrategyRole::Export, {}, "std430 storage buffer written per invocation");
};

}  // namespace

std::unique_ptr<Strategy> makeBufferExport() { return std::make_unique<BufferExport>(); }

}  // namespace spire::codegen
