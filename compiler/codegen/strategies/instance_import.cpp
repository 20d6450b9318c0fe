// instanceImport: a std430 storage buffer of per-instance records, read at
// gl_InstanceIndex. It carries what an engine supplies per object of an
// instanced draw (a model matrix, a texture-array layer, a fade weight) and
// per-object baked values (PrebakeUniform results), so objects whose values
// differ still share one draw. The record is the producer's whole record,
// as for bufferImport; for an abstract producer (the engine) it holds the
// values this consumer reads, so the engine lays records out per consumer
// block. Only a vertex kernel has an instance index.
#include <fmt/format.h>

#include "codegen/strategies/strategy_support.h"

namespace spire::codegen {
namespace {

class InstanceImport final : public Strategy {
 public:
  const sem::StrategySignature& signature() const override { return signature_; }

  Expected<void, Failure> emitImport(ImportSite& site) const override {
    if (site.consumer.stage() != ShaderStage::Vertex) {
      return Failure{
          fmt::format("instanceImport reads one record per instance at gl_InstanceIndex, which only a vertex "
                      "kernel has, and cannot feed the {} world '{}'",
                      site.consumer.stage() == ShaderStage::Fragment ? "fragment" : "compute", site.consumer.world())};
    }
    emitRecordFetches(site, "gl_InstanceIndex", "instanceImport");
    return {};
  }

 private:
  sem::StrategySignature signature_ =
      makeSignature("instanceImport", sem::StrategyRole::Import, {},
                    "std430 storage buffer of per-instance records, read at gl_InstanceIndex");
};

}  // namespace

std::unique_ptr<Strategy> makeInstanceImport() { return std::make_unique<InstanceImport>(); }

}  // namespace spire::codegen
