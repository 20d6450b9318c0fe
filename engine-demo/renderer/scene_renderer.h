// The engine's top level for one scene file: compiles each instance's
// variant (in process through the compiler library, or from a spirec output
// directory), loads only the meshes and textures the variants use, runs the
// bakes they need, and renders and times frames. The demo and the tuner both
// drive it; neither knows about any particular shader.
#pragma once

#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "driver/shader_library.h"
#include "lod/lod_policy.h"
#include "renderer/bake_cache.h"
#include "renderer/hazard_records.h"
#include "renderer/pipeline_cache.h"
#include "renderer/render_target.h"
#include "scene/scene_file.h"

namespace spire::engine {

struct PreparedScene {
  std::vector<MaterialValues> materials;               // per instance
  std::vector<DrawItem> items;                         // per instance
  std::vector<BakeRecord> bakes;                       // every bake world the variants use, run or reused
  std::vector<std::string> fingerprints;               // per instance: its kernels' hashes
  std::vector<const TextureBakeResult*> textureBakes;  // per instance: its PrebakeTex result, or null
  std::vector<const UniformBakeResult*> uniformBakes;  // per instance: its PrebakeUniform result, or null
  // The graphics pipelines this prepare built, and those it shared with
  // scenes prepared before that were still alive (pipeline_cache.h).
  PipelineCounts pipelines;
};

struct FrameStats {
  double firstFrameMs = 0.0;  // host time of the first frame: lavapipe compiles shaders at first draw
  double medianGpuMs = 0.0;   // over the measured frames, from timestamps
  double medianHostMs = 0.0;  // over the measured frames, submit to fence
  std::vector<double> gpuMs;  // every measured frame
};

// Frame statistics from the first frame's host time and measured frames.
FrameStats summarizeFrames(double firstFrameMs, const std::vector<FrameTiming>& measured);

struct Capture {
  measure::FloatImage color;
  std::vector<uint8_t> coverage;
  FrameTiming timing;  // of the frame read back
};

class SceneRenderer {
 public:
  // `sceneSources` holds the scene file, `diags` receives every problem with
  // the scene's values (with their file:line:col).
  SceneRenderer(const vk::Context& ctx, const scene::SceneFile& scene, DiagnosticList& diags,
                TextureBakeOptions bakeOptions = {});
  // A renderer of the same scene with other bake options that shares
  // `other`'s meshes, textures and compiled libraries, which depend on the
  // scene alone: building a scene's procedural textures again costs more
  // than a frame.
  SceneRenderer(SceneRenderer& other, DiagnosticList& diags, TextureBakeOptions bakeOptions);

  // The variant of every instance: its own decisions, or `decisions` (a
  // scene variant) for all of them. Compiler diagnostics come back as the
  // error's details; warnings accumulate in compilerWarnings().
  Expected<std::vector<VariantProgram>> compile(const std::optional<std::filesystem::path>& decisions);

  // The tuner's path: instance `index` built from in-memory decisions
  // (component -> "World[:variation]") through the compiler library, without
  // re-parsing. `skipped` receives decisions that were not applied
  // (infeasible together with the others).
  Expected<VariantProgram> compileVariant(size_t index, const std::map<std::string, std::string>& decisions,
                                          std::vector<std::string>* skipped = nullptr,
                                          const ShaderLibrary::Attributes& attributes = {});
  // As compileVariant, in `library` (one of instance `index`'s source, such
  // as loadLibrary made): touches nothing else of the renderer, so a tool may
  // call it on a thread of its own while this renderer draws.
  Expected<VariantProgram> compileVariantIn(ShaderLibrary& library, size_t index,
                                            const std::map<std::string, std::string>& decisions,
                                            std::vector<std::string>* skipped = nullptr,
                                            const ShaderLibrary::Attributes& attributes = {}) const;
  // A fresh library of instance `index`'s source, read from disk again (the
  // explorer's live source editing); the renderer's own stays as it is. The
  // error's details are the compiler's diagnostics, rendered.
  Expected<std::unique_ptr<ShaderLibrary>> loadLibrary(size_t index) const {
    return loadLibrary(scene_.instances.at(index));
  }
  // Instance `index` compiled as a level of detail draws it
  // (levelInstance): as a member of its group (`Rock<LodMQ>`), with the
  // level's decision file for its shader or else its own decisions.
  Expected<VariantProgram> compileLevel(size_t index, const lod::LodLevel& level);
  // As compileLevel, in `library` (such as library(index) gave, or
  // loadLibrary made), without the renderer's cache: touches nothing else
  // of the renderer, so a tool may call it on a thread of its own while
  // this renderer draws, as long as nothing else uses `library` meanwhile.
  // The compiler's warnings are added to `warnings`.
  Expected<VariantProgram> compileLevelIn(ShaderLibrary& library, size_t index, const lod::LodLevel& level,
                                          std::string& warnings) const;
  // The library compiled for instance `index` (compiling it on first use).
  Expected<ShaderLibrary*> library(size_t index) { return libraryFor(scene_.instances.at(index)); }

  // Whether a decision that is not applied (unknown, infeasible,
  // conflicting) fails the instance's compile; on by default, since
  // measuring a variant other than the one asked for is worthless.
  void setStrictDecisions(bool strict) { strictDecisions_ = strict; }
  // With a collector, compile() and compileVariant() make instrumented
  // kernels (CompileOptions::instrumentHazards) and prepare() gives their
  // records to `hazards`; for diagnosis, in a renderer of its own, since
  // instrumented kernels cost more and bakes are cached per renderer.
  void collectHazards(HazardCollector* hazards) { hazards_ = hazards; }

  // Material values that replace the scene's for every instance that binds
  // the component, in the next prepare() calls: the tuner samples uniform
  // parameters over ranges this way. A component bound to a texture gets a
  // solid RGBA32F texture of the four values instead. Empty restores the
  // scene's values.
  void setParameterOverrides(std::map<std::string, std::vector<double>> overrides) {
    overrides_ = std::move(overrides);
  }

  // What prepare may do with the frame's target when the programs write
  // another number of color outputs than it has.
  enum class TargetUse {
    Fit,   // make a new one that fits (the first prepare of a tool, or a whole new scene)
    Keep,  // keep it, and fail: draws prepared before use it (another thread may be drawing them)
  };
  // Resolves materials (reporting problems to `diagnostics`, else to the
  // renderer's list), runs the bakes the programs need and builds their
  // draws.
  //
  // One thread may prepare while another draws scenes prepared before, with
  // TargetUse::Keep: prepare then changes nothing a draw reads. That thread
  // passes a list of its own, since the other one may report meanwhile. Two
  // prepares at once are not allowed.
  Expected<PreparedScene> prepare(const std::vector<VariantProgram>& programs, TargetUse target = TargetUse::Fit,
                                  DiagnosticList* diagnostics = nullptr);
  // W7101 for each material binding that no variant prepared so far read:
  // called once after a tool's variants are prepared, since one variant not
  // reading a value another reads is expected.
  void reportUnreadBindings();

  // Renders `warmup` frames (the first one timed separately), then `frames`
  // measured ones, from camera view 0.
  Expected<FrameStats> measure(const PreparedScene& prepared, uint32_t warmup, uint32_t frames);
  // One frame from camera view 0 at frame number `frame` (its time), not read back.
  Expected<FrameTiming> renderFrame(const PreparedScene& prepared, uint32_t frame);
  // One frame from `view` at `time` seconds, not read back (spire-demo
  // --window blits it from colorImage()).
  Expected<FrameTiming> renderView(const PreparedScene& prepared, const scene::CameraView& view, float time);
  // Color target 0 of the last frame rendered (RGBA32F, TRANSFER_SRC usage);
  // nullptr before prepare().
  vk::Image* colorImage() { return target_ ? target_->color() : nullptr; }
  // One frame from `view`, read back.
  Expected<Capture> capture(const PreparedScene& prepared, const scene::CameraView& view);

  const std::string& compilerWarnings() const { return compilerWarnings_; }
  const TextureBakeOptions& textureBakeOptions() const { return bakes_.textureOptions(); }
  const vk::Context& context() const { return ctx_; }
  // The shader modules and pipelines draws are built from (lod_scene.h
  // builds draws of its own).
  PipelineCaches caches() { return {modules_, pipelines_}; }
  // Pipelines built and reused since the renderer was made.
  const PipelineCounts& pipelineCounts() const { return pipelines_.counts(); }
  // The frame's target; nullptr before prepare().
  RenderTarget* target() { return target_ ? &*target_ : nullptr; }
  const scene::SceneFile& scene() const { return scene_; }
  size_t shaderModuleCount() const { return modules_.size(); }
  size_t bakeCount() const { return bakes_.size(); }
  // The bakes' pipelines, apart from the draws' (pipelineCounts).
  const PipelineCounts& bakePipelineCounts() const { return bakes_.pipelineCounts(); }
  size_t textureCount() const { return assets_->textures.size(); }

  // The frame state for `view` at `time` seconds.
  FrameState frameState(const scene::CameraView& view, float time) const;

 private:
  // A stereo frame: shared object-space passes (when the scene shares them),
  // then each eye's passes and draw; with `captures`, each eye read back.
  Expected<FrameTiming> renderEyes(const PreparedScene& prepared, const scene::CameraView& view, float time,
                                   std::vector<Capture>* captures);
  Expected<Capture> readBack(const FrameTiming& timing);
  Expected<VariantProgram> compileInstance(const scene::InstanceDesc& instance,
                                           const std::optional<std::filesystem::path>& decisions);
  // `instance` compiled in `lib` with its decisions, or `decisions` (a
  // scene variant, whose shader names `knownElsewhere` checks); touches
  // nothing of the renderer but reads its settings.
  Expected<VariantProgram> compileIn(ShaderLibrary& lib, const scene::InstanceDesc& instance,
                                     const std::optional<std::filesystem::path>& decisions,
                                     const std::function<bool(std::string_view)>& knownElsewhere,
                                     std::string& warnings) const;
  Expected<ShaderLibrary*> libraryFor(const scene::InstanceDesc& instance);
  // Whether the source of another instance than `instance` declares a shader
  // or group named `prefix`.
  bool knownToAnotherSource(const scene::InstanceDesc& instance, std::string_view prefix);
  Expected<std::unique_ptr<ShaderLibrary>> loadLibrary(const scene::InstanceDesc& instance) const;
  const GpuMesh* meshFor(const std::string& name, SourceRange range, DiagnosticList& diags);
  const GpuTexture* textureFor(const std::string& name, SourceRange range, DiagnosticList& diags);
  // The name of a solid texture of `rgba`, made on first use, that
  // textureFor then gives.
  Expected<std::string> solidTexture(const std::vector<double>& rgba);
  Expected<RenderTarget*> targetFor(size_t colorTargets, TargetUse use);
  Expected<std::vector<const DrawItem*>> drawList(const PreparedScene& prepared);

  const vk::Context& ctx_;
  const scene::SceneFile& scene_;
  DiagnosticList& diags_;
  ModuleCache modules_;
  PipelineCache pipelines_;
  BakeCache bakes_;
  struct SceneAssets {
    std::map<std::string, std::unique_ptr<ShaderLibrary>> libraries;
    std::map<std::string, std::unique_ptr<GpuMesh>> meshes;
    std::map<std::string, std::unique_ptr<GpuTexture>> textures;
  };
  std::shared_ptr<SceneAssets> assets_ = std::make_shared<SceneAssets>();
  std::map<std::string, VariantProgram> programs_;
  std::optional<RenderTarget> target_;
  std::string compilerWarnings_;
  std::map<std::string, std::vector<double>> overrides_;
  // Per instance: the material bindings some prepared variant read;
  // nullopt until one of its variants gets that far (a variant that failed
  // to compile read nothing, and says so itself).
  std::vector<std::optional<std::set<std::string, std::less<>>>> readBindings_;
  bool strictDecisions_ = true;
  HazardCollector* hazards_ = nullptr;
};

}  // namespace spire::engine
