// screenTextureImport(screenSize): one sampler per component, fetched at the
// consuming fragment's screen position, gl_FragCoord.xy / screenSize. It
// carries values an engine rendered into screen-aligned textures in an
// earlier pass, at whatever resolution: the multi-rate pipeline's
// LowResFragment results, stored at a quarter of the pixels (paper section
// 7.3). Only a fragment kernel has a screen position.
#include <fmt/format.h>

#include "codegen/strategies/strategy_support.h"

namespace spire::codegen {
namespace {

class ScreenTextureImport final : public Strategy {
 public:
  const sem::StrategySignature& signature() const override { return signature_; }

  Expected<void, Failure> emitImport(ImportSite& site) const override {
    if (site.consumer.stage() != ShaderStage::Fragment) {
      return Failure{
          fmt::format("screenTextureImport reads the screen position, so it can only import into a "
                      "fragment world, not into '{}'",
                      site.consumer.world())};
    }
    const std::string uv = fmt::format("(gl_FragCoord.xy / {})", site.args.at(0));
    return emitTextureFetches(site, {"sampler2D", uv, uv, ""}, "screenTextureImport");
  }

 private:
  sem::StrategySignature signature_ =
      makeSignature("screenTextureImport", sem::StrategyRole::Import, {{"screenSize", "vec2"}},
                    "one sampler per component, fetched at the fragment's screen position gl_FragCoord.xy / screenSize",
                    sem::ValueTransfer::Resampled);
};

}  // namespace

std::unique_ptr<Strategy> makeScreenTextureImport() { return std::make_unique<ScreenTextureImport>(); }

}  // namespace spire::codegen
