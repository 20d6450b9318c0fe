// bufferImport: a std430 storage buffer of per-element records, read at the
// vertex index (vertex kernels) or the invocation index (compute kernels).
// The record fetches are shared with instanceImport, which reads at the
// instance index.
#include <fmt/format.h>

#include "codegen/strategies/strategy_support.h"

namespace spire::codegen {
void emitRecordFetches(ImportSite& site, const std::string& index, std::string_view strategy) {
  KernelBuilder& kernel = site.consumer;
  const std::string& from = site.pipeline.worlds[site.import.from].name;
  // The record is the producer's whole record, so its layout matches what
  // the producer wrote; values arrive under their own names, so the
  // record's members get generated ones and the fetch copies out the
  // values this kernel uses.
  std::vector<KernelValue> members = site.producerOutputs;
  for (KernelValue& m : members) m.glslName = kernel.names().generate(from + "_" + m.sourceName);
  const BlockDeclaration block =
      declareBlock(kernel, from + "_in", members, BlockLayout::Std430, "readonly buffer", strategy);
  for (const KernelValue& v : site.values) {
    size_t member = 0;
    while (members[member].component != v.component) ++member;
    kernel.declareGlobal(v.type, v.glslName);
    kernel.addFetch(fmt::format("{} = {}[{}].{};", v.glslName, block.recordsName, index, members[member].glslName));
    reflection::KernelInput entry = importEntry(site, v, reflection::InputKind::BufferMember, strategy);
    entry.slot = slotAt(kernel, block.binding);
    entry.block = block.blockName;
    entry.offset = block.offsets[member];
    entry.index = index;
    kernel.reflectInput(std::move(entry));
  }
}

namespace {

class BufferImport final : public Strategy {
 public:
  const sem::StrategySignature& signature() const override { return signature_; }

  Expected<void, Failure> emitImport(ImportSite& site) const override {
    KernelBuilder& kernel = site.consumer;
    std::string index;
    switch (kernel.stage()) {
      case ShaderStage::Vertex: index = "gl_VertexIndex"; break;
      case ShaderStage::Compute: index = "gl_GlobalInvocationID.x"; break;
      case ShaderStage::Fragment:
        return Failure{
            fmt::format("bufferImport reads one record per vertex or invocation and cannot feed the fragment "
                        "world '{}'",
                        kernel.world())};
    }
    emitRecordFetches(site, index, "bufferImport");
    return {};
  }

 private:
  sem::StrategySignature signature_ = makeSignature("bufferImport", sem::StrategyRole::Import, {},
                                                    "std430 storage buffer read at the vertex or invocation index");
};

}  // namespace

std::unique_ptr<Strategy> makeBufferImport() { return std::make_unique<BufferImport>(); }

}  // namespace spire::codegen
