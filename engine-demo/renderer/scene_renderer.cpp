#include "renderer/scene_renderer.h"

#include "renderer/stereo.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>

#include "driver/compiler.h"
#include "graph/decision_file.h"
#include "renderer/material.h"
#include "renderer/world_roles.h"
#include "scene/scene_resources.h"
#include "support/diagnostic_renderer.h"
#include "vk/timer.h"

namespace spire::engine {

namespace {

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const size_t mid = values.size() / 2;
  return values.size() % 2 == 1 ? values[mid] : (values[mid - 1] + values[mid]) / 2.0;
}

std::string renderAll(const SourceManager& sources, const std::vector<Diagnostic>& diagnostics) {
  std::string text;
  for (const Diagnostic& d : diagnostics) text += renderDiagnostic(sources, d);
  return text;
}

}  // namespace

SceneRenderer::SceneRenderer(const vk::Context& ctx, const scene::SceneFile& scene, DiagnosticList& diags,
                             TextureBakeOptions bakeOptions)
    : ctx_(ctx), scene_(scene), diags_(diags), bakes_(bakeOptions), readBindings_(scene.instances.size()) {}

SceneRenderer::SceneRenderer(SceneRenderer& other, DiagnosticList& diags, TextureBakeOptions bakeOptions)
    : ctx_(other.ctx_),
      scene_(other.scene_),
      diags_(diags),
      bakes_(bakeOptions),
      assets_(other.assets_),
      readBindings_(other.scene_.instances.size()) {}

namespace {

// One library per source and retargeting: the same file retargeted to two
// pipelines is two programs.
std::string libraryKey(const scene::InstanceDesc& instance) {
  return fmt::format("{}|{}|{}", instance.source.string(), instance.pipeline,
                     instance.pipelineSource ? instance.pipelineSource->string() : "");
}

}  // namespace

Expected<std::unique_ptr<ShaderLibrary>> SceneRenderer::loadLibrary(const scene::InstanceDesc& instance) const {
  const std::string source = instance.source.string();
  const std::string pipelineSource = instance.pipelineSource ? instance.pipelineSource->string() : "";
  FrontEndOptions options;
  for (const auto& dir : scene_.includePaths) options.includeDirs.push_back(dir.string());
  options.pipeline = instance.pipeline;
  auto library = std::make_unique<ShaderLibrary>(options);
  if (!library->addFile(source)) {
    return Error{fmt::format("cannot read Spire source '{}'", source), instance.sourceRange, {}};
  }
  if (!pipelineSource.empty() && !library->addFile(pipelineSource)) {
    return Error{fmt::format("cannot read pipeline source '{}'", pipelineSource), instance.pipelineRange, {}};
  }
  if (!library->compile()) {
    const std::string retargeted =
        instance.pipeline.empty() ? "" : fmt::format(" against pipeline '{}'", instance.pipeline);
    return Error{fmt::format("'{}' does not compile{}", source, retargeted),
                 instance.pipeline.empty() ? instance.sourceRange : instance.pipelineRange,
                 renderDiagnostics(library->sources(), library->diagnostics(), DiagnosticFormat::Text)};
  }
  return library;
}

Expected<ShaderLibrary*> SceneRenderer::libraryFor(const scene::InstanceDesc& instance) {
  const std::string key = libraryKey(instance);
  if (const auto it = assets_->libraries.find(key); it != assets_->libraries.end()) return it->second.get();
  auto library = loadLibrary(instance);
  if (!library) return library.error();
  return assets_->libraries.emplace(key, std::move(library).value()).first->second.get();
}

bool SceneRenderer::knownToAnotherSource(const scene::InstanceDesc& instance, std::string_view prefix) {
  for (const scene::InstanceDesc& other : scene_.instances) {
    if (other.kernels || libraryKey(other) == libraryKey(instance)) continue;
    auto library = libraryFor(other);
    if (library && ((*library)->model().findShader(prefix) || (*library)->model().findGroup(prefix))) return true;
  }
  return false;
}

Expected<VariantProgram> SceneRenderer::compileInstance(const scene::InstanceDesc& instance,
                                                        const std::optional<std::filesystem::path>& decisions) {
  if (instance.kernels) {
    if (decisions) {
      return Error{
          "this instance uses precompiled kernels, so a scene variant cannot recompile it; give it "
          "\"source\" and \"shader\" instead",
          instance.kernelsRange,
          {}};
    }
    auto program = loadProgram(*instance.kernels);
    if (!program) return Error{program.error().message, instance.kernelsRange, {}};
    return program;
  }
  const std::optional<std::filesystem::path> decisionPath = decisions ? decisions : instance.decisions;
  const std::string key =
      fmt::format("{}|{}|{}", libraryKey(instance), instance.shader, decisionPath ? decisionPath->string() : "");
  if (const auto it = programs_.find(key); it != programs_.end()) return it->second;

  auto library = libraryFor(instance);
  if (!library) return library.error();
  auto program = compileIn(
      **library, instance, decisions, [&](std::string_view prefix) { return knownToAnotherSource(instance, prefix); },
      compilerWarnings_);
  if (!program) return program.error();
  return programs_.emplace(key, std::move(program).value()).first->second;
}

Expected<VariantProgram> SceneRenderer::compileIn(ShaderLibrary& lib, const scene::InstanceDesc& instance,
                                                  const std::optional<std::filesystem::path>& decisions,
                                                  const std::function<bool(std::string_view)>& knownElsewhere,
                                                  std::string& warnings) const {
  const std::optional<std::filesystem::path> decisionPath = decisions ? decisions : instance.decisions;
  DiagnosticList& diags = lib.diagnostics();
  const size_t mark = diags.size();
  graph::DecisionFile decisionFile;
  if (decisionPath) {
    if (const auto id = lib.frontEnd().loadAuxiliaryFile(decisionPath->string())) {
      decisionFile = graph::parseDecisionFile(lib.sources(), *id, diags);
      graph::checkDecisionPrefixes(decisionFile, lib.model(), diags, [&](std::string_view prefix) {
        // A scene-wide variant names the shaders of every instance's source.
        return decisions && knownElsewhere(prefix);
      });
    }
  }
  const SourceRange where = decisions || !instance.decisions ? instance.shaderRange : instance.decisionsRange;
  const bool unreadable = diags.hasErrors();
  std::vector<Diagnostic> reported = diags.takeSince(mark);
  const bool skipped = std::any_of(reported.begin(), reported.end(),
                                   [](const Diagnostic& d) { return d.severity == Severity::Warning; });
  if (unreadable) {
    return Error{fmt::format("cannot read the decisions for '{}'", instance.shader), where,
                 renderAll(lib.sources(), reported)};
  }
  if (skipped && strictDecisions_) {
    return Error{
        fmt::format("not every decision for '{}' applies, so this is not the variant asked for", instance.shader),
        where, renderAll(lib.sources(), reported)};
  }
  CompileOptions options;
  options.strictDecisions = strictDecisions_;
  options.instrumentHazards = hazards_ != nullptr;
  const CompileResult compiled = spire::compileVariant(lib, instance.shader, decisionFile, options);
  if (!compiled) {
    const CompileError& error = compiled.error();
    reported.insert(reported.end(), error.diagnostics.begin(), error.diagnostics.end());
    return Error{fmt::format("'{}': {}", instance.source.string(), error.message),
                 error.diagnostics.empty() ? instance.shaderRange : where, renderAll(lib.sources(), reported)};
  }
  warnings += renderAll(lib.sources(), reported) + renderAll(lib.sources(), (*compiled)->warnings);
  auto program = programFrom(**compiled);
  if (!program) return Error{program.error().message, instance.shaderRange, program.error().details};
  return program;
}

Expected<VariantProgram> SceneRenderer::compileVariant(size_t index,
                                                       const std::map<std::string, std::string>& decisions,
                                                       std::vector<std::string>* skipped,
                                                       const ShaderLibrary::Attributes& attributes) {
  auto library = libraryFor(scene_.instances.at(index));
  if (!library) return library.error();
  return compileVariantIn(**library, index, decisions, skipped, attributes);
}

Expected<VariantProgram> SceneRenderer::compileVariantIn(ShaderLibrary& lib, size_t index,
                                                         const std::map<std::string, std::string>& decisions,
                                                         std::vector<std::string>* skipped,
                                                         const ShaderLibrary::Attributes& attributes) const {
  const scene::InstanceDesc& instance = scene_.instances.at(index);
  // The tuner's points may decide what is infeasible: it records the skipped
  // decisions instead of refusing them.
  CompileOptions options;
  options.instrumentHazards = hazards_ != nullptr;
  const CompileResult compiled = spire::compileVariant(lib, instance.shader, Decisions{decisions, attributes}, options);
  if (!compiled) {
    return Error{fmt::format("'{}': {}", instance.source.string(), compiled.error().message), instance.shaderRange,
                 renderAll(lib.sources(), compiled.error().diagnostics)};
  }
  if (skipped) *skipped = (*compiled)->skippedDecisions;
  auto program = programFrom(**compiled);
  if (!program) return Error{program.error().message, instance.shaderRange, program.error().details};
  return program;
}

Expected<VariantProgram> SceneRenderer::compileLevel(size_t index, const lod::LodLevel& level) {
  return compileInstance(levelInstance(scene_.instances.at(index), level), std::nullopt);
}

Expected<VariantProgram> SceneRenderer::compileLevelIn(ShaderLibrary& library, size_t index, const lod::LodLevel& level,
                                                       std::string& warnings) const {
  // The instance's own decisions or the level's: no scene variant, so no
  // other source's names.
  return compileIn(
      library, levelInstance(scene_.instances.at(index), level), std::nullopt, [](std::string_view) { return false; },
      warnings);
}

Expected<std::vector<VariantProgram>> SceneRenderer::compile(const std::optional<std::filesystem::path>& decisions) {
  std::vector<VariantProgram> programs;
  for (const scene::InstanceDesc& instance : scene_.instances) {
    auto program = compileInstance(instance, decisions);
    if (!program) return program.error();
    programs.push_back(std::move(program).value());
  }
  return programs;
}

const GpuMesh* SceneRenderer::meshFor(const std::string& name, SourceRange range, DiagnosticList& diags) {
  if (const auto it = assets_->meshes.find(name); it != assets_->meshes.end()) return it->second.get();
  const scene::MeshDesc* desc = scene_.findMesh(name);
  if (!desc) {
    diags.report(DiagCode::E7006, range, fmt::format("no mesh named '{}'", name));
    return nullptr;
  }
  auto mesh = scene::buildMesh(*desc);
  if (!mesh) {
    diags.report(DiagCode::E7101, desc->range, fmt::format("mesh '{}': {}", name, mesh.error().message));
    return nullptr;
  }
  auto uploaded = uploadMesh(ctx_, std::move(mesh).value());
  if (!uploaded) {
    diags.report(DiagCode::E7101, desc->range, fmt::format("mesh '{}': {}", name, uploaded.error().message));
    return nullptr;
  }
  return assets_->meshes.emplace(name, std::move(uploaded).value()).first->second.get();
}

const GpuTexture* SceneRenderer::textureFor(const std::string& name, SourceRange range, DiagnosticList& diags) {
  if (const auto it = assets_->textures.find(name); it != assets_->textures.end()) return it->second.get();
  const scene::TextureDesc* desc = scene_.findTexture(name);
  if (!desc) {
    diags.report(DiagCode::E7006, range, fmt::format("no texture named '{}'", name));
    return nullptr;
  }
  auto image = scene::buildTexture(*desc, scene_);
  if (!image) {
    diags.report(DiagCode::E7101, desc->range, fmt::format("texture '{}': {}", name, image.error().message));
    return nullptr;
  }
  auto uploaded = uploadTexture(ctx_, *image, desc->clamp);
  if (!uploaded) {
    diags.report(DiagCode::E7101, desc->range, fmt::format("texture '{}': {}", name, uploaded.error().message));
    return nullptr;
  }
  return assets_->textures.emplace(name, std::move(uploaded).value()).first->second.get();
}

Expected<std::string> SceneRenderer::solidTexture(const std::vector<double>& rgba) {
  scene::TextureDesc desc;
  desc.name = fmt::format("solid texture ({})", fmt::join(rgba, ", "));
  if (assets_->textures.contains(desc.name)) return desc.name;
  desc.kind = scene::TextureKind::Solid;
  desc.size = 4;
  // Float texels: a sampled range may go beyond [0, 1].
  desc.format = scene::PixelFormat::RGBA32F;
  for (size_t c = 0; c < 4 && c < rgba.size(); ++c) desc.color[static_cast<int>(c)] = static_cast<float>(rgba[c]);
  auto image = scene::buildTexture(desc, scene_);
  if (!image) return Error{fmt::format("{}: {}", desc.name, image.error().message), {}, {}};
  auto uploaded = uploadTexture(ctx_, *image, desc.clamp);
  if (!uploaded) return Error{fmt::format("{}: {}", desc.name, uploaded.error().message), {}, {}};
  assets_->textures.emplace(desc.name, std::move(uploaded).value());
  return desc.name;
}

Expected<RenderTarget*> SceneRenderer::targetFor(size_t colorTargets, TargetUse use) {
  if (target_ && target_->formats().colors.size() == colorTargets) return &*target_;
  if (target_ && use == TargetUse::Keep) {
    return Error{fmt::format("these fragment kernels write {} color output(s), and the target the scene's other draws "
                             "use has {}: they cannot draw into one frame",
                             colorTargets, target_->formats().colors.size()),
                 {},
                 {}};
  }
  target_.reset();
  auto target = RenderTarget::create(ctx_, scene_.width, scene_.height, colorTargets);
  if (!target) return target.error();
  target_ = std::move(target).value();
  return &*target_;
}

void SceneRenderer::reportUnreadBindings() {
  for (size_t i = 0; i < scene_.instances.size(); ++i) {
    if (readBindings_[i]) engine::reportUnreadBindings(scene_.instances[i], *readBindings_[i], diags_);
  }
}

Expected<PreparedScene> SceneRenderer::prepare(const std::vector<VariantProgram>& programs, TargetUse targetUse,
                                               DiagnosticList* diagnostics) {
  DiagnosticList& diags = diagnostics ? *diagnostics : diags_;
  PreparedScene prepared;
  std::vector<const GpuMesh*> meshes;
  const size_t errorsBefore = diags.errorCount();
  for (size_t i = 0; i < programs.size(); ++i) {
    scene::InstanceDesc instance = scene_.instances[i];
    for (scene::MaterialBinding& binding : instance.material) {
      const auto it = overrides_.find(binding.component);
      if (it == overrides_.end()) continue;
      if (binding.texture) {
        auto solid = solidTexture(it->second);
        if (!solid) return solid.error();
        binding.texture = std::move(solid).value();
      } else {
        binding.numbers = it->second;
      }
    }
    meshes.push_back(meshFor(instance.mesh, instance.meshRange, diags));
    const TextureLookup lookup = [this, &diags](const std::string& name, SourceRange range) {
      return textureFor(name, range, diags);
    };
    ResolvedMaterial material = resolveMaterial(programs[i], instance, lookup, diags);
    if (!readBindings_[i]) readBindings_[i].emplace();
    readBindings_[i]->merge(material.read);
    prepared.materials.push_back(material.values ? std::move(*material.values) : MaterialValues{});
  }
  if (diags.errorCount() != errorsBefore) return Error{"nothing was rendered: the scene has errors", {}, {}};

  size_t colorTargets = 0;
  for (const VariantProgram& program : programs) {
    const KernelProgram* fragment = program.kernelWithRole(WorldRole::FragmentStage);
    if (!fragment) return Error{fmt::format("'{}' has no fragment kernel", program.shader), {}, {}};
    auto outputs = fragmentOutputs(*fragment);
    if (!outputs) return outputs.error();
    colorTargets = std::max(colorTargets, outputs->size());
  }
  auto target = targetFor(colorTargets, targetUse);
  if (!target) return target.error();

  const PipelineCounts before = pipelines_.counts();
  for (size_t i = 0; i < programs.size(); ++i) {
    const scene::InstanceDesc& instance = scene_.instances[i];
    if (hazards_) hazards_->setInstance(fmt::format("instance {} ({})", i, programs[i].shader));
    auto baked = bakes_.bake(ctx_, modules_, programs[i], *meshes[i], instance.mesh, prepared.materials[i], hazards_);
    if (!baked) return Error{baked.error().message, instance.range, baked.error().details};
    prepared.bakes.insert(prepared.bakes.end(), baked->records.begin(), baked->records.end());
    prepared.textureBakes.push_back(baked->texture);
    prepared.uniformBakes.push_back(baked->uniform);
    BindingSources sources;
    sources.mesh = meshes[i];
    sources.material = &prepared.materials[i];
    sources.uniformBake = baked->uniform;
    sources.vertexBake = baked->vertex;
    sources.textureBake = baked->texture;
    sources.hazards = hazards_;
    const DrawPlacement placement{instance.transform, instance.doubleSided.value_or(meshes[i]->mesh.doubleSided),
                                  VkExtent2D{scene_.width, scene_.height}};
    auto item = createDrawItem(ctx_, caches(), programs[i], sources, placement, (*target)->formats());
    if (!item) return Error{item.error().message, instance.range, item.error().details};
    prepared.items.push_back(std::move(item).value());
    prepared.fingerprints.push_back(programs[i].fingerprint());
  }
  prepared.pipelines = {pipelines_.counts().created - before.created, pipelines_.counts().reused - before.reused};
  return prepared;
}

FrameState SceneRenderer::frameState(const scene::CameraView& view, float time) const {
  FrameState frame;
  frame.view = glm::lookAt(view.position, view.target, scene_.camera.up);
  frame.projection = glm::perspectiveRH_ZO(glm::radians(scene_.camera.fovYDegrees),
                                           static_cast<float>(scene_.width) / static_cast<float>(scene_.height),
                                           scene_.camera.nearPlane, scene_.camera.farPlane);
  frame.projection[1][1] *= -1.0F;  // Vulkan's clip space has y pointing down
  frame.cameraPosition = view.position;
  frame.lightDirection = scene_.light.direction;
  frame.lightColor = scene_.light.color;
  frame.time = time;
  frame.resolution = {static_cast<float>(scene_.width), static_cast<float>(scene_.height)};
  return frame;
}

Expected<std::vector<const DrawItem*>> SceneRenderer::drawList(const PreparedScene& prepared) {
  if (!target_) return Error{"prepare() must run before rendering", {}, {}};
  std::vector<const DrawItem*> items;
  for (const DrawItem& item : prepared.items) items.push_back(&item);
  return items;
}

Expected<FrameTiming> SceneRenderer::renderFrame(const PreparedScene& prepared, uint32_t frame) {
  constexpr float kFrameSeconds = 1.0F / 60.0F;
  return renderView(prepared, scene_.camera.views.front(), static_cast<float>(frame) * kFrameSeconds);
}

Expected<FrameTiming> SceneRenderer::renderView(const PreparedScene& prepared, const scene::CameraView& view,
                                                float time) {
  if (scene_.camera.stereo) return renderEyes(prepared, view, time, nullptr);
  auto items = drawList(prepared);
  if (!items) return items.error();
  return target_->render(ctx_, *items, frameState(view, time), scene_.clearColor);
}

Expected<FrameTiming> SceneRenderer::renderEyes(const PreparedScene& prepared, const scene::CameraView& view,
                                                float time, std::vector<Capture>* captures) {
  auto items = drawList(prepared);
  if (!items) return items.error();
  const scene::StereoDesc& stereo = *scene_.camera.stereo;
  FrameTiming total;
  const auto add = [&](const FrameTiming& t) {
    total.gpuMs += t.gpuMs;
    total.hostMs += t.hostMs;
  };
  if (stereo.shareObjectSpace) {
    auto shared = target_->render(ctx_, *items, frameState(view, time), scene_.clearColor, {false, true, false});
    if (!shared) return shared.error();
    add(*shared);
  }
  for (const scene::CameraView& eye : eyeViews(view, scene_.camera.up, stereo.eyeSeparation)) {
    auto timing =
        target_->render(ctx_, *items, frameState(eye, time), scene_.clearColor, {true, !stereo.shareObjectSpace, true});
    if (!timing) return timing.error();
    add(*timing);
    if (!captures) continue;
    auto read = readBack(*timing);
    if (!read) return read.error();
    captures->push_back(std::move(read).value());
  }
  return total;
}

Expected<Capture> SceneRenderer::readBack(const FrameTiming& timing) {
  auto color = target_->readColor(ctx_);
  if (!color) return color.error();
  auto coverage = target_->readCoverage(ctx_);
  if (!coverage) return coverage.error();
  return Capture{std::move(color).value(), std::move(coverage).value(), timing};
}

Expected<FrameStats> SceneRenderer::measure(const PreparedScene& prepared, uint32_t warmup, uint32_t frames) {
  double firstFrameMs = 0.0;
  std::vector<FrameTiming> measured;
  for (uint32_t f = 0; f < warmup + frames; ++f) {
    auto timing = renderFrame(prepared, f);
    if (!timing) return timing.error();
    if (f == 0) firstFrameMs = timing->hostMs;
    if (f >= warmup) measured.push_back(*timing);
  }
  return summarizeFrames(firstFrameMs, measured);
}

FrameStats summarizeFrames(double firstFrameMs, const std::vector<FrameTiming>& measured) {
  FrameStats stats;
  stats.firstFrameMs = firstFrameMs;
  std::vector<double> hostMs;
  for (const FrameTiming& t : measured) {
    stats.gpuMs.push_back(t.gpuMs);
    hostMs.push_back(t.hostMs);
  }
  stats.medianGpuMs = median(stats.gpuMs);
  stats.medianHostMs = median(hostMs);
  return stats;
}

Expected<Capture> SceneRenderer::capture(const PreparedScene& prepared, const scene::CameraView& view) {
  if (scene_.camera.stereo) {
    std::vector<Capture> eyes;
    auto timing = renderEyes(prepared, view, 0.0F, &eyes);
    if (!timing) return timing.error();
    return Capture{sideBySide(eyes[0].color, eyes[1].color),
                   sideBySide(eyes[0].coverage, eyes[1].coverage, eyes[0].color.width), *timing};
  }
  auto items = drawList(prepared);
  if (!items) return items.error();
  auto timing = target_->render(ctx_, *items, frameState(view, 0.0F), scene_.clearColor);
  if (!timing) return timing.error();
  return readBack(*timing);
}

}  // namespace spire::engine
