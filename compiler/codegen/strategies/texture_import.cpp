// textureImport(uv): one sampler per component, fetched at the uv
// expression evaluated in the consuming kernel (paper section 5.1). The
// fetches are shared with screenTextureImport, which differs only in where
// it samples, and textureArrayImport, which samples a sampler2DArray.
#include <fmt/format.h>

#include "codegen/strategies/strategy_support.h"

namespace spire::codegen {
Expected<void, Failure> emitTextureFetches(ImportSite& site, const TextureFetch& at, std::string_view strategy) {
  KernelBuilder& kernel = site.consumer;
  for (const KernelValue& v : site.values) {
    const sem::Type* t = v.type;
    if (!(t->isScalar() || t->isVector()) || t->scalar != sem::ScalarKind::Float) {
      return Failure{fmt::format("{} can only carry float scalars and vectors, not '{}' of type '{}'", strategy,
                                 v.sourceName, t->name())};
    }
    static constexpr std::string_view kSwizzles[] = {"", ".x", ".xy", ".xyz", ""};
    const std::string sampler = kernel.names().generate("tex_" + v.glslName);
    const uint32_t binding = kernel.allocateBinding();
    kernel.declare(fmt::format("layout(set = {}, binding = {}) uniform {} {};", kernel.descriptorSet(), binding,
                               at.samplerType, sampler));
    kernel.declareGlobal(t, v.glslName);
    const auto encodedSigned = checkEncoding(v);
    if (!encodedSigned) return encodedSigned.error();
    const std::string fetch = fmt::format("texture({}, {}){}", sampler, at.coordinate, kSwizzles[t->rows]);
    kernel.addFetch(*encodedSigned ? fmt::format("{} = {} * 2.0 - 1.0;", v.glslName, fetch)
                                   : fmt::format("{} = {};", v.glslName, fetch));
    reflection::KernelInput entry = importEntry(site, v, reflection::InputKind::Texture, strategy);
    entry.slot = slotAt(kernel, binding);
    entry.sampler = sampler;
    entry.uv = at.uv;
    entry.layer = at.layer;
    entry.channels = t->rows;
    kernel.reflectInput(std::move(entry));
  }
  return {};
}

namespace {

class TextureImport final : public Strategy {
 public:
  const sem::StrategySignature& signature() const override { return signature_; }

  Expected<void, Failure> emitImport(ImportSite& site) const override {
    const std::string& uv = site.args.at(0);
    return emitTextureFetches(site, {"sampler2D", uv, uv, ""}, "textureImport");
  }

 private:
  sem::StrategySignature signature_ =
      makeSignature("textureImport", sem::StrategyRole::Import, {{"uv", "vec2"}},
                    "one sampler per component, fetched at uv", sem::ValueTransfer::Resampled);
};

}  // namespace

std::unique_ptr<Strategy> makeTextureImport() { return std::make_unique<TextureImport>(); }

}  // namespace spire::codegen
