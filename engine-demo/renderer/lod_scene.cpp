#include "renderer/lod_scene.h"

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include <algorithm>
#include <map>

#include "scene/scatter.h"

namespace spire::engine {

namespace {

// One level of every prototype: the programs and what preparing them made
// (materials, bakes, and a draw item per prototype that validated them).
struct Level {
  lod::LodLevel drawnAs;                 // the policy level it was compiled for (its band aside)
  std::vector<VariantProgram> programs;  // per prototype
  PreparedScene prepared;
};

// Objects drawn with one pipeline: the programs of (prototype, level) pairs
// whose Vertex and Fragment kernels and shared values are the same.
struct DrawGroup {
  uint32_t level = 0;
  uint32_t representative = 0;              // the prototype whose material and mesh set the group up
  std::vector<uint32_t> prototypes;         // in texture-array layer order
  std::map<uint32_t, uint32_t> layerOf;     // prototype -> its layer
  std::unique_ptr<BakeArrays> arrays;       // the prototypes' texture bakes, one layer each
  DrawItem item;                            // pipeline, descriptors, per-instance record buffers
  SharedPipeline overlay;                   // the same, blended over: cross-fades
  std::map<uint32_t, VertexInputs> inputs;  // by mesh index
};

lod::ObjectBounds meshBounds(const scene::Mesh& mesh) {
  glm::vec3 lo(std::numeric_limits<float>::max());
  glm::vec3 hi(std::numeric_limits<float>::lowest());
  for (const scene::Vertex& v : mesh.vertices) {
    lo = glm::min(lo, v.position);
    hi = glm::max(hi, v.position);
  }
  float radius = 0.0F;
  for (const scene::Vertex& v : mesh.vertices) radius = std::max(radius, glm::distance(v.position, (lo + hi) * 0.5F));
  return lod::ObjectBounds::box(lo, hi, radius);
}

// Whether the program's kernels read the cross-fade weight (lod::DrawGroups::fades).
bool readsLodFade(const VariantProgram& program) {
  return std::any_of(program.kernels.begin(), program.kernels.end(), [](const KernelProgram& kernel) {
    return std::any_of(kernel.inputs.begin(), kernel.inputs.end(),
                       [](const KernelInput& input) { return input.component == "lodFade"; });
  });
}

// What the kernels read that is the same for every object of a batch: the
// material's values. A value that differs per object but is not read per
// instance (a uniform bake read as a uniform, a texture bake read as a
// plain sampler) cannot be shared, so its object gets a group of its own.
std::string sharedValues(const KernelProgram& kernel, const MaterialValues& material, uint32_t prototype) {
  std::string identity;
  for (const KernelInput& input : kernel.inputs) {
    const auto role = kernel.sourceRole(input);
    const bool perObject = (role == WorldRole::UniformBake && input.kind == InputKind::UniformMember) ||
                           (role == WorldRole::TextureBake && input.layer.empty());
    if (perObject) return fmt::format("object {}", prototype);
    if (const auto it = material.find(input.component); it != material.end()) {
      identity += fmt::format("{}={};", input.component, it->second.identity);
    }
  }
  return identity;
}

}  // namespace

struct LodScene::Impl {
  SceneRenderer& renderer;
  lod::LodPolicy policy;
  LodOptions options;
  std::vector<Level> levels;
  std::vector<const GpuMesh*> meshes;  // distinct meshes
  std::vector<bool> doubleSided;       // per prototype
  std::vector<lod::SceneInstance> instances;
  std::vector<glm::mat4> models;
  std::vector<std::unique_ptr<DrawGroup>> groups;
  uint32_t blockCount = 1;
  std::vector<uint32_t> meshOfPrototype;
  std::optional<lod::InstanceBatcher> batcher;  // made once the draw groups are known
  std::optional<lod::LodSelector> selector;
  lod::FrameBatches batches;
  std::vector<uint32_t> drawnOnly;  // empty: every instance
  LodFrameStats stats;

  Impl(SceneRenderer& r, lod::LodPolicy p, LodOptions o) : renderer(r), policy(std::move(p)), options(o) {}

  // The levels' programs compiled here, or taken from `compiled`.
  Expected<void> compileLevels(LevelPrograms* compiled);
  Expected<void> placeInstances(uint32_t blocksPerSide);
  Expected<void> formGroups();
  Expected<void> buildGroup(DrawGroup& group, uint32_t representative);
  void writeRecords(const FrameState& frame);
  void recordBatches(VkCommandBuffer cmd) const;
};

Expected<void> LodScene::Impl::compileLevels(LevelPrograms* compiled) {
  const size_t prototypes = renderer.scene().instances.size();
  if (compiled && (compiled->size() != policy.levels.size() ||
                   std::any_of(compiled->begin(), compiled->end(),
                               [&](const std::vector<VariantProgram>& l) { return l.size() != prototypes; }))) {
    return Error{
        fmt::format("programs for {} level(s) of {} instance(s) were expected", policy.levels.size(), prototypes),
        {},
        {}};
  }
  for (size_t l = 0; l < policy.levels.size(); ++l) {
    const lod::LodLevel& policyLevel = policy.levels[l];
    Level level;
    level.drawnAs = policyLevel;
    if (compiled) level.programs = std::move((*compiled)[l]);
    for (size_t p = level.programs.size(); p < prototypes; ++p) {
      auto program = renderer.compileLevel(p, policyLevel);
      if (!program) return program.error();
      level.programs.push_back(std::move(program).value());
    }
    // Every level draws into one frame. Programs compiled elsewhere are
    // prepared while an earlier scene may still be drawing (createCompiled):
    // its target must stay.
    const bool keep = compiled != nullptr || l > 0;
    auto prepared = renderer.prepare(
        level.programs, keep ? SceneRenderer::TargetUse::Keep : SceneRenderer::TargetUse::Fit, options.diagnostics);
    if (!prepared) return prepared.error();
    level.prepared = std::move(prepared).value();
    levels.push_back(std::move(level));
  }
  return {};
}

Expected<void> LodScene::Impl::placeInstances(uint32_t blocksPerSide) {
  const scene::SceneFile& scene = renderer.scene();
  std::map<const GpuMesh*, uint32_t> meshIndex;
  std::vector<lod::ObjectBounds> meshBoxes;
  std::vector<uint32_t> meshOf;
  for (size_t p = 0; p < scene.instances.size(); ++p) {
    const DrawItem& item = levels.front().prepared.items[p];
    const auto [it, fresh] = meshIndex.emplace(item.mesh, static_cast<uint32_t>(meshes.size()));
    if (fresh) {
      meshes.push_back(item.mesh);
      meshBoxes.push_back(meshBounds(item.mesh->mesh));
    }
    meshOf.push_back(it->second);
    doubleSided.push_back(scene.instances[p].doubleSided.value_or(item.mesh->mesh.doubleSided));
    auto placements = scene::placementsOf(scene.instances[p], scene);
    if (!placements) return Error{placements.error().message, scene.instances[p].range, {}};
    for (const glm::mat4& model : *placements) {
      instances.push_back({meshBoxes[it->second].transformed(model), static_cast<uint32_t>(p), 0});
      models.push_back(model);
    }
  }
  // Blocks: a grid over the instances' extent in the XZ plane.
  glm::vec2 lo(std::numeric_limits<float>::max());
  glm::vec2 hi(std::numeric_limits<float>::lowest());
  for (const lod::SceneInstance& i : instances) {
    lo = glm::min(lo, glm::vec2(i.bounds.center.x, i.bounds.center.z));
    hi = glm::max(hi, glm::vec2(i.bounds.center.x, i.bounds.center.z));
  }
  const glm::vec2 cell = glm::max((hi - lo) / static_cast<float>(blocksPerSide), glm::vec2(1e-6F));
  for (lod::SceneInstance& i : instances) {
    const auto bx = std::min(static_cast<uint32_t>((i.bounds.center.x - lo.x) / cell.x), blocksPerSide - 1);
    const auto bz = std::min(static_cast<uint32_t>((i.bounds.center.z - lo.y) / cell.y), blocksPerSide - 1);
    i.block = bz * blocksPerSide + bx;
  }
  meshOfPrototype = std::move(meshOf);
  blockCount = blocksPerSide * blocksPerSide;
  return {};
}

Expected<void> LodScene::Impl::formGroups() {
  lod::DrawGroups drawGroups;
  drawGroups.meshOf = meshOfPrototype;
  const size_t prototypes = renderer.scene().instances.size();
  drawGroups.groupOf.assign(prototypes, std::vector<uint32_t>(levels.size(), 0));
  std::map<std::string, uint32_t> byKey;
  for (uint32_t level = 0; level < levels.size(); ++level) {
    for (uint32_t p = 0; p < prototypes; ++p) {
      const VariantProgram& program = levels[level].programs[p];
      const KernelProgram* vertex = program.kernelWithRole(WorldRole::VertexStage);
      const KernelProgram* fragment = program.kernelWithRole(WorldRole::FragmentStage);
      if (!vertex || !fragment) return Error{fmt::format("'{}' has no kernels to draw with", program.shader), {}, {}};
      const MaterialValues& material = levels[level].prepared.materials[p];
      // Levels never share a group: their bakes differ even where their
      // kernels do not.
      const std::string key = fmt::format("{}|{}|{}|{}|{}|{}", level, vertex->key, fragment->key, doubleSided[p],
                                          sharedValues(*vertex, material, p), sharedValues(*fragment, material, p));
      const auto [it, fresh] = byKey.emplace(key, static_cast<uint32_t>(groups.size()));
      if (fresh) {
        groups.push_back(std::make_unique<DrawGroup>());
        groups.back()->level = level;
        groups.back()->representative = p;
        drawGroups.fades.push_back(readsLodFade(program) ? 1 : 0);
      }
      DrawGroup& group = *groups[it->second];
      group.layerOf.emplace(p, static_cast<uint32_t>(group.prototypes.size()));
      group.prototypes.push_back(p);
      drawGroups.groupOf[p][level] = it->second;
    }
  }
  drawGroups.groupCount = static_cast<uint32_t>(groups.size());
  batcher.emplace(std::move(drawGroups), blockCount);
  for (const auto& group : groups) {
    if (auto built = buildGroup(*group, group->representative); !built) return built.error();
  }
  return {};
}

Expected<void> LodScene::Impl::buildGroup(DrawGroup& group, uint32_t representative) {
  const Level& level = levels[group.level];
  const VariantProgram& program = level.programs[representative];
  const KernelProgram* vertex = program.kernelWithRole(WorldRole::VertexStage);
  const KernelProgram* fragment = program.kernelWithRole(WorldRole::FragmentStage);
  // Capacity: every copy of every prototype in the group.
  uint32_t capacity = 0;
  for (const lod::SceneInstance& i : instances) capacity += group.layerOf.contains(i.prototype) ? 1 : 0;
  std::vector<const TextureBakeResult*> layers;
  for (uint32_t p : group.prototypes) layers.push_back(level.prepared.textureBakes[p]);
  const KernelProgram* kernels[] = {vertex, fragment};
  auto arrays = buildBakeArrays(renderer.context(), kernels, layers);
  if (!arrays) return arrays.error();
  group.arrays = std::make_unique<BakeArrays>(std::move(arrays).value());
  const DrawItem& prepared = level.prepared.items[representative];
  BindingSources sources;
  sources.mesh = prepared.mesh;
  sources.material = &level.prepared.materials[representative];
  sources.uniformBake = level.prepared.uniformBakes[representative];
  sources.textureBake = level.prepared.textureBakes[representative];
  const scene::SceneFile& scene = renderer.scene();
  DrawPlacement placement{glm::mat4(1.0F), doubleSided[representative], VkExtent2D{scene.width, scene.height},
                          std::max(capacity, 1U), &group.arrays->textures};
  const TargetFormats& formats = renderer.target()->formats();
  auto item = createDrawItem(renderer.context(), renderer.caches(), program, sources, placement, formats);
  if (!item) return Error{fmt::format("'{}': {}", program.shader, item.error().message), {}, item.error().details};
  group.item = std::move(item).value();
  auto overlay = createOverlayPipeline(renderer.context(), renderer.caches(), program, group.item, placement, formats);
  if (!overlay) return overlay.error();
  group.overlay = std::move(overlay).value();
  for (uint32_t p : group.prototypes) {
    const uint32_t mesh = meshOfPrototype[p];
    if (group.inputs.contains(mesh)) continue;
    BindingSources meshSources = sources;
    meshSources.mesh = meshes[mesh];
    auto inputs = vertexInputs(*vertex, meshSources);
    if (!inputs) return inputs.error();
    group.inputs.emplace(mesh, std::move(inputs).value());
  }
  return {};
}

void LodScene::Impl::writeRecords(const FrameState& frame) {
  for (size_t g = 0; g < groups.size(); ++g) {
    DrawGroup& group = *groups[g];
    const std::vector<lod::InstanceRecord>& records = batches.records[g];
    if (records.empty()) continue;
    // Frame values first: they also write record 0 for a draw of one object.
    updateFrameValues(group.item, frame);
    const Level& level = levels[group.level];
    for (uint32_t r = 0; r < records.size(); ++r) {
      const lod::InstanceRecord& record = records[r];
      const uint32_t p = instances[record.instance].prototype;
      const InstanceState state{models[record.instance], static_cast<float>(group.layerOf.at(p)), record.fade};
      for (const BoundKernel& kernel : group.item.kernels) {
        for (const InstanceBlock& block : kernel.instanceBlocks) {
          writeInstanceRecord(block, r, state, level.prepared.uniformBakes[p]);
        }
      }
    }
  }
}

void LodScene::Impl::recordBatches(VkCommandBuffer cmd) const {
  for (const lod::Batch& batch : batches.batches) {
    const DrawGroup& group = *groups[batch.group];
    const vk::Pipeline& pipeline = batch.overlay ? *group.overlay : *group.item.pipeline;
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline.pipeline.get());
    bindDescriptors(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline.layout.get(), group.item.descriptors);
    for (uint32_t d = batch.firstDraw; d < batch.firstDraw + batch.drawCount; ++d) {
      const lod::MeshDraw& draw = batches.draws[d];
      const GpuMesh& mesh = *meshes[draw.mesh];
      group.inputs.at(draw.mesh).bind(cmd);
      vkCmdBindIndexBuffer(cmd, mesh.indices.handle(), 0, VK_INDEX_TYPE_UINT32);
      vkCmdDrawIndexed(cmd, mesh.indexCount(), draw.instanceCount, 0, 0, draw.firstInstance);
    }
  }
}

namespace {

// The policy as `options` draws it: one level, or no cross-fades.
Expected<lod::LodPolicy> appliedPolicy(lod::LodPolicy policy, const LodOptions& options) {
  if (options.fixedLevel) {
    if (*options.fixedLevel >= policy.levels.size()) {
      return Error{fmt::format("level {} of a policy of {} levels", *options.fixedLevel, policy.levels.size()), {}, {}};
    }
    lod::LodLevel only = policy.levels[*options.fixedLevel];
    only.until = std::numeric_limits<float>::infinity();
    policy.levels = {only};
  }
  if (!options.transitions || options.fixedLevel) policy.transitionFrames = 0;
  return policy;
}

}  // namespace

Expected<std::unique_ptr<LodScene>> LodScene::create(SceneRenderer& renderer, lod::LodPolicy policy,
                                                     const LodOptions& options) {
  return make(renderer, std::move(policy), options, nullptr);
}

Expected<std::unique_ptr<LodScene>> LodScene::createCompiled(SceneRenderer& renderer, lod::LodPolicy policy,
                                                             LevelPrograms programs, const LodOptions& options) {
  return make(renderer, std::move(policy), options, &programs);
}

Expected<std::unique_ptr<LodScene>> LodScene::make(SceneRenderer& renderer, lod::LodPolicy policy,
                                                   const LodOptions& options, LevelPrograms* programs) {
  auto applied = appliedPolicy(std::move(policy), options);
  if (!applied) return applied.error();
  auto impl = std::make_unique<Impl>(renderer, std::move(applied).value(), options);
  const uint32_t blocks = renderer.scene().lod ? renderer.scene().lod->blocks : 1;
  if (auto ok = impl->compileLevels(programs); !ok) return ok.error();
  if (auto ok = impl->placeInstances(blocks); !ok) return ok.error();
  if (auto ok = impl->formGroups(); !ok) return ok.error();
  impl->selector.emplace(impl->policy, impl->instances.size());
  return std::unique_ptr<LodScene>(new LodScene(std::move(impl)));
}

LodScene::LodScene(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
LodScene::~LodScene() = default;

void LodScene::resetLevels(const scene::CameraView& view) { impl_->selector->reset(impl_->instances, view.position); }

void LodScene::updateLevels(const scene::CameraView& view) { impl_->selector->update(impl_->instances, view.position); }

Expected<FrameTiming> LodScene::render(const scene::CameraView& view, float time) {
  updateLevels(view);
  return draw(view, time);
}

Expected<FrameTiming> LodScene::draw(const scene::CameraView& view, float time) {
  Impl& s = *impl_;
  const FrameState frame = s.renderer.frameState(view, time);
  s.batcher->build(s.instances, *s.selector, frame.projection * frame.view, s.batches, s.drawnOnly);
  s.writeRecords(frame);
  s.stats = {};
  s.stats.visible = s.batches.visibleInstances;
  s.stats.batches = static_cast<uint32_t>(s.batches.batches.size());
  s.stats.drawCalls = static_cast<uint32_t>(s.batches.draws.size());
  for (const lod::Batch& b : s.batches.batches) s.stats.overlayBatches += b.overlay ? 1 : 0;
  return s.renderer.target()->renderWith(s.renderer.context(), s.renderer.scene().clearColor,
                                         [&](VkCommandBuffer cmd) { s.recordBatches(cmd); });
}

Expected<measure::FloatImage> LodScene::readColor() {
  return impl_->renderer.target()->readColor(impl_->renderer.context());
}

Expected<std::vector<uint8_t>> LodScene::readCoverage() {
  return impl_->renderer.target()->readCoverage(impl_->renderer.context());
}

void LodScene::drawOnly(std::vector<uint32_t> instances) { impl_->drawnOnly = std::move(instances); }

Expected<void> LodScene::setBands(const lod::LodPolicy& policy, const scene::CameraView& view) {
  auto applied = appliedPolicy(policy, impl_->options);
  if (!applied) return applied.error();
  const std::vector<Level>& levels = impl_->levels;
  const bool same = std::equal(levels.begin(), levels.end(), applied->levels.begin(), applied->levels.end(),
                               [](const Level& a, const lod::LodLevel& b) { return a.drawnAs.drawsAs(b); });
  if (!same) {
    return Error{
        "the policy's levels draw with other members or decisions than the compiled levels: the scene must be made "
        "again",
        {},
        {}};
  }
  impl_->policy = std::move(applied).value();
  impl_->selector.emplace(impl_->policy, impl_->instances.size());
  resetLevels(view);
  return {};
}

const lod::LodPolicy& LodScene::policy() const { return impl_->policy; }

void LodScene::reportSwitchesThatCannotFade(DiagnosticList& diags) const {
  const lod::LodPolicy& policy = impl_->policy;
  if (policy.transitionFrames == 0) return;
  // A switch from a blend band is seamless: at its edge the blend is the
  // level it hands over to.
  const auto fadesInto = [&](size_t level) {
    const auto popsFrom = [&](size_t other) { return other < policy.levels.size() && !policy.levels[other].blend; };
    return !policy.levels[level].blend && ((level > 0 && popsFrom(level - 1)) || popsFrom(level + 1));
  };
  const lod::DrawGroups& drawGroups = impl_->batcher->groups();
  for (uint32_t g = 0; g < impl_->groups.size(); ++g) {
    const DrawGroup* group = impl_->groups[g].get();
    if (!fadesInto(group->level) || drawGroups.canFade(g)) continue;
    const VariantProgram& program = impl_->levels[group->level].programs[group->representative];
    const lod::LodLevel& level = policy.levels[group->level];
    diags.reportOnce(DiagCode::W7102, level.range,
                     fmt::format("'{}' at level {} ({}) does not read lodFade, so switches into this level are drawn "
                                 "at once, not cross-faded over the policy's {} transitionFrames; a shader fades by "
                                 "writing lodFade into its output's alpha",
                                 program.shader, group->level, lod::levelName(level), policy.transitionFrames));
  }
}
const LodFrameStats& LodScene::lastStats() const { return impl_->stats; }
size_t LodScene::instanceCount() const { return impl_->instances.size(); }
const lod::DrawGroups& LodScene::drawGroups() const { return impl_->batcher->groups(); }
uint32_t LodScene::levelOf(size_t instance) const { return impl_->selector->state(instance).level; }
const lod::SceneInstance& LodScene::instance(size_t instance) const { return impl_->instances[instance]; }

}  // namespace spire::engine
