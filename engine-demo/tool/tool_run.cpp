#include "tool/tool_run.h"

#include <fmt/format.h>

#include "driver/exit_codes.h"
#include "renderer/host_allocator.h"
#include "support/diagnostic_renderer.h"

namespace spire::engine {

ToolRun::ToolRun(std::string tool, std::ostream& err)
    : tool_(std::move(tool)), err_(err), reporter_(sources_, diags_, err, tool_) {
  stabilizeHostAllocator();
}

std::optional<int> ToolRun::loadScene(const std::string& path, std::optional<ImageSize> resolution) {
  scene_ = scene::loadSceneFile(path, sources_, diags_);
  if (scene_ && resolution) {
    scene_->width = resolution->width;
    scene_->height = resolution->height;
  }
  if (scene_) return std::nullopt;
  reporter_.flush();
  return kExitInputError;
}

std::optional<int> ToolRun::loadLodPolicy() {
  if (!scene_->lod) return fail(Error{"the scene has no 'lod': no level-of-detail policy to read", {}, {}});
  policy_ = lod::loadLodPolicy(scene_->lod->policy, sources_, diags_, scene_->lod->policyRange);
  if (policy_) return std::nullopt;
  reporter_.flush();
  return kExitInputError;
}

std::optional<int> ToolRun::openDevice(const DeviceOptions& options) {
  vk::ContextOptions contextOptions;
  contextOptions.validation = options.validation;
  contextOptions.deviceFilter = options.filter;
  contextOptions.applicationName = tool_;
  contextOptions.instanceExtensions = options.instanceExtensions;
  auto context = vk::Context::create(contextOptions, options.surfaceFactory);
  if (!context) {
    err_ << fmt::format("{}: error: no usable Vulkan device: {}\n", tool_, context.error().message());
    return kExitNoDevice;
  }
  context_.emplace(std::move(context).value());
  return std::nullopt;
}

SceneRenderer& ToolRun::startRenderer(uint32_t defaultBakeSize) {
  TextureBakeOptions bakeOptions;
  bakeOptions.defaultSize = defaultBakeSize;
  return renderer_.emplace(*context_, *scene_, diags_, bakeOptions);
}

std::string ToolRun::adoptDiagnostics(std::vector<Diagnostic> diagnostics) {
  const size_t mark = diags_.size();
  diags_.reportAll(std::move(diagnostics));
  return renderSince(mark);
}

std::string ToolRun::renderSince(size_t mark) const {
  std::string text;
  for (size_t i = mark; i < diags_.size(); ++i) text += renderDiagnostic(sources_, diags_.all()[i]);
  return text;
}

int ToolRun::finish(int status) const { return reportValidation(*context_, status, err_); }

}  // namespace spire::engine
