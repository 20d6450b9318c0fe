// vertexExport(position): `out` variables plus `gl_Position = position`.
#include <fmt/format.h>

#include "codegen/strategies/strategy_support.h"

namespace spire::codegen {
namespace {

class VertexExport final : public Strategy {
 public:
  const sem::StrategySignature& signature() const override { return signature_; }
  std::optional<ShaderStage> stage() const override { return ShaderStage::Vertex; }
  Expected<void, Failure> emitExport(ExportSite& site) const override {
    if (auto checked = emitOutVariables(site, "vertexExport"); !checked) return checked;
    site.producer.addStore(fmt::format("gl_Position = {};", site.args.at(0)));
    reflection::KernelOutput entry;
    entry.kind = reflection::OutputKind::BuiltIn;
    entry.component = "gl_Position";
    entry.expression = site.args.at(0);
    entry.strategy = "vertexExport";
    site.producer.reflectOutput(std::move(entry));
    return {};
  }

 private:
  sem::StrategySignature signature_ =
      makeSignature("vertexExport", sem::StrategyRole::Export, {{"position", "vec4"}},
                    "'out' variables plus gl_Position", sem::ValueTransfer::Exact, true);
};

}  // namespace

std::unique_ptr<Strategy> makeVertexExport() { return std::make_unique<VertexExport>(); }

}  // namespace spire::codegen
