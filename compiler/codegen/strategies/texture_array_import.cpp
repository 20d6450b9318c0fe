// textureArrayImport(uv, layer): one sampler2DArray per component, fetched
// at texture(s, vec3(uv, layer)) with both expressions evaluated in the
// consuming kernel. It carries values baked into one layer per object of
// texture arrays (a batch's PrebakeTex results), so objects with different
// baked textures share one draw; `layer` picks the object's layer.
#include <fmt/format.h>

#include "codegen/strategies/strategy_support.h"

namespace spire::codegen {
namespace {

class TextureArrayImport final : public Strategy {
 public:
  const sem::StrategySignature& signature() const override { return signature_; }

  Expected<void, Failure> emitImport(ImportSite& site) const override {
    const std::string& uv = site.args.at(0);
    const std::string& layer = site.args.at(1);
    return emitTextureFetches(site, {"sampler2DArray", fmt::format("vec3({}, {})", uv, layer), uv, layer},
                              "textureArrayImport");
  }

 private:
  sem::StrategySignature signature_ =
      makeSignature("textureArrayImport", sem::StrategyRole::Import, {{"uv", "vec2"}, {"layer", "float"}},
                    "one sampler2DArray per component, fetched at vec3(uv, layer)", sem::ValueTransfer::Resampled);
};

}  // namespace

std::unique_ptr<Strategy> makeTextureArrayImport() { return std::make_unique<TextureArrayImport>(); }

}  // namespace spire::codegen
