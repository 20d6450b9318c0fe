// uniformImport: a std140 uniform block per import edge; opaque values
// (samplers) are separate uniforms since they cannot live in a block.
#include <fmt/format.h>

#include "codegen/strategies/strategy_support.h"

namespace spire::codegen {
namespace {

class UniformImport final : public Strategy {
 public:
  const sem::StrategySignature& signature() const override { return signature_; }

  Expected<void, Failure> emitImport(ImportSite& site) const override {
    KernelBuilder& kernel = site.consumer;
    const std::string& from = site.pipeline.worlds[site.import.from].name;
    std::vector<KernelValue> plain;
    for (const KernelValue& v : site.values) {
      if (!v.type->containsOpaque()) {
        plain.push_back(v);
        continue;
      }
      const uint32_t binding = kernel.allocateBinding();
      kernel.declare(fmt::format("layout(set = {}, binding = {}) uniform {};", kernel.descriptorSet(), binding,
                                 kernel.declaration(v.type, v.glslName)));
      reflection::KernelInput entry = importEntry(site, v, reflection::InputKind::Sampler, "uniformImport");
      entry.slot = slotAt(kernel, binding);
      kernel.reflectInput(std::move(entry));
    }
    if (plain.empty()) return {};
    const BlockDeclaration block = declareBlock(kernel, from, plain, BlockLayout::Std140, "uniform", "uniformImport");
    for (size_t i = 0; i < plain.size(); ++i) {
      reflection::KernelInput entry =
          importEntry(site, plain[i], reflection::InputKind::UniformMember, "uniformImport");
      entry.slot = slotAt(kernel, block.binding);
      entry.block = block.blockName;
      entry.offset = block.offsets[i];
      kernel.reflectInput(std::move(entry));
    }
    return {};
  }

 private:
  sem::StrategySignature signature_ =
      makeSignature("uniformImport", sem::StrategyRole::Import, {}, "std140 uniform block, samplers as uniforms",
                    sem::ValueTransfer::Aggregated, false, true);
};

}  // namespace

std::unique_ptr<Strategy> makeUniformImport() { return std::make_unique<UniformImport>(); }

}  // namespace spire::codegen
