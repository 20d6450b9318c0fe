#include "explore/explorer.h"

#include <fmt/format.h>
#include <glm/gtc/constants.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <memory>
#include <random>
#include <span>

#include "demo/camera_path.h"
#include "driver/exit_codes.h"
#include "explore/decision_state.h"
#include "explore/explore_script.h"
#include "explore/explorer_model.h"
#include "explore/explorer_panels.h"
#include "explore/instance_session.h"
#include "explore/live_compiler.h"
#include "explore/lod_explorer.h"
#include "explore/source_watch.h"
#include "explore/tune_results.h"
#include "explore/view_images.h"
#include "explore/window_presenter.h"
#include "graph/decision_file.h"
#include "renderer/gpu_resources.h"
#include "scene/texture.h"
#include "support/diagnostic_renderer.h"
#include "support/file_io.h"
#include "vk/timer.h"

namespace spire::explore {
namespace fs = std::filesystem;
namespace {

constexpr double kSecondsPerView = 4.0;     // the camera's loop in interactive use, as spire-demo --window
constexpr float kRadiansPerPixel = 0.005F;  // orbit speed of a mouse drag
constexpr uint32_t kReferenceFrames = 10;   // frames timed for the reference's frame time
constexpr float kHeatScale = 0.25F;         // error shown yellow in the heat map

// The images of the fixed camera view that metrics and the derived views
// come from.
struct ViewCaptures {
  std::optional<engine::Capture> reference;
  std::optional<engine::Capture> variant;
  std::vector<uint8_t> coverage;  // either image covered
};

// The worker's side of a change: the library variants are compiled in,
// replaced by a fresh one when a source was saved and still defines the
// shader, and the scene that draws the new variant, prepared beside the
// frame loop's draws of the previous one.
class VariantCompiler {
 public:
  VariantCompiler(engine::SceneRenderer& renderer, size_t instance, std::string shader, ShaderLibrary& library)
      : renderer_(renderer),
        instance_(instance),
        shader_(std::move(shader)),
        // Not owned: the renderer's own library outlives the worker.
        library_(std::shared_ptr<void>(), &library) {}

  void operator()(const CompileJob& job, CompileOutcome& outcome) {
    if (job.reload && !reload(outcome)) return;
    outcome.program = renderer_.compileVariantIn(*library_, instance_, job.placement, &outcome.skipped, job.attributes);
    if (outcome.program) prepare(job.programs, outcome);
  }

 private:
  bool reload(CompileOutcome& outcome) {
    auto fresh = renderer_.loadLibrary(instance_);
    if (!fresh) {
      outcome.program = fresh.error();
      return false;
    }
    if ((*fresh)->choiceSpace(shader_) == nullptr) {
      outcome.program = engine::Error{fmt::format("the edited source no longer defines the shader '{}'", shader_)};
      return false;
    }
    library_ = std::shared_ptr<ShaderLibrary>(std::move(fresh).value());
    outcome.library = library_;
    return true;
  }

  // The window shows the renderer's target, which the previous variant
  // draws into meanwhile: it stays (TargetUse::Keep).
  void prepare(std::vector<engine::VariantProgram> programs, CompileOutcome& outcome) {
    programs.at(instance_) = *outcome.program;
    DiagnosticList diagnostics;
    const vk::HostTimer timer;
    outcome.prepared = renderer_.prepare(programs, engine::SceneRenderer::TargetUse::Keep, &diagnostics);
    outcome.prepareMs = timer.elapsedMs();
    outcome.diagnostics = diagnostics.all();
  }

  engine::SceneRenderer& renderer_;
  size_t instance_;
  std::string shader_;
  std::shared_ptr<ShaderLibrary> library_;
};

std::vector<fs::path> sourcePaths(const ShaderLibrary& library) {
  std::vector<fs::path> paths;
  for (size_t i = 0; i < library.sources().fileCount(); ++i)
    paths.emplace_back(library.sources().file(static_cast<FileId>(i)).path);
  return paths;
}

class Explorer {
 public:
  Explorer(const ExploreOptions& options, engine::ToolRun& run, demo::GlfwWindow& window, std::ostream& out)
      : options_(options), run_(run), renderer_(run.renderer()), window_(window), out_(out) {}
  int run();

 private:
  std::optional<int> start();
  // Makes instance `index` the explored one: the session kept for it, or a
  // new one starting from the decisions its program was compiled with.
  engine::Expected<void> selectInstance(size_t index);
  engine::Expected<void> openSession(size_t index);
  std::optional<int> startPresentation();
  struct FileDecisions {
    Placement placement;
    ShaderLibrary::Attributes attributes;
  };
  engine::Expected<FileDecisions> readDecisions(const fs::path& path);
  // Save and Load, for the window's buttons and the script's actions alike:
  // the explored instance's decisions written to `path`, or replaced by the
  // ones read from it (the caller starts the change).
  Expected<void, Failure> saveDecisions(const fs::path& path) const;
  Expected<void, Failure> loadDecisions(const fs::path& path);
  std::optional<int> loadScript();
  // Reads a spire-tune output directory for the Pareto view, replacing any
  // loaded before.
  Expected<void, Failure> loadTune(const fs::path& dir);
  // Script: runs actions until one has to wait (a change, wait-frames) or the
  // script ends. False when the explorer should close.
  bool stepScript();
  bool runAction(const ScriptAction& action);
  bool changeAction(const ScriptAction& action);
  // One random single-decision change to an alternative still possible;
  // false when no choice has one.
  bool walkStep();
  bool scriptError(const ScriptAction& action, const std::string& message);
  void handleRequests(const PanelRequests& requests);
  void startChange(std::string action, bool reload = false);
  void adoptLibrary(const std::shared_ptr<ShaderLibrary>& library);
  void pollCompile();
  void failChange(const std::string& message, const std::string& details);
  void finishChange();
  engine::Expected<void> updateMetrics();
  engine::Expected<void> updateStaticImage();
  engine::Expected<void> screenshot(const fs::path& path);
  // The image the window shows: the renderer's frame, or the panel copy of
  // a derived view's.
  vk::Image& shownImage();
  // The image just presented, panels included, read back.
  engine::Expected<void> windowScreenshot(const fs::path& path);
  engine::Expected<void> present();
  scene::CameraView cameraView(const demo::WindowInput& input, double now);
  fs::path scriptRelative(const std::string& path) const;
  // A script's `save`/`load` file; without one, the Save and Load buttons' (--save-to).
  fs::path buttonsOrScriptRelative(const std::string& path) const;
  // The diagnostics reported since the list's size was `mark`, rendered.
  std::optional<int> startSession();
  // One frame: script, compile results, render, panels, present.
  engine::Expected<bool> frame(const demo::WindowInput& input);
  PanelState panelState() const;
  int finish(int status);

  const ExploreOptions& options_;
  engine::ToolRun& run_;
  engine::SceneRenderer& renderer_;
  demo::GlfwWindow& window_;
  std::ostream& out_;
  // Every library the session's choices and programs came from: a program
  // or the choice space may still point into an older one.
  std::vector<std::shared_ptr<ShaderLibrary>> libraries_;
  // Every instance explored so far, and the one the panels show: switching
  // keeps each one's decisions, undo history and compile worker.
  std::map<size_t, InstanceSession> sessions_;
  InstanceSession* session_ = nullptr;
  // The decisions the scene's programs start from: --reference, else the
  // scene's first variant, else each instance's own.
  std::optional<fs::path> referencePath_;
  bool waitReload_ = false;
  std::optional<fs::path> windowShot_;  // written after the next presented frame
  std::unique_ptr<WindowPresenter> presenter_;
  std::optional<vk::Image> staticImage_;  // error, hazards and split views
  // What the panels are drawn on in those views: a copy of staticImage_ per
  // frame, so the panels of earlier frames do not stay in it.
  std::optional<vk::Image> panelImage_;
  measure::FloatImage staticPixels_;  // what staticImage_ holds
  std::vector<engine::VariantProgram> programs_;
  std::optional<engine::PreparedScene> reference_;
  std::optional<engine::PreparedScene> current_;
  std::optional<engine::PreparedScene> incoming_;  // prepared, its first frame not yet presented
  ViewCaptures captures_;
  Metrics metrics_;
  ViewMode view_ = ViewMode::Variant;
  uint64_t requests_ = 0;
  std::optional<ChangeRecord> pending_;
  std::optional<ChangeRecord> lastChange_;
  std::vector<ChangeRecord> changes_;
  std::string diagnostics_;
  std::vector<ScriptAction> script_;
  size_t scriptNext_ = 0;
  uint64_t waitFrames_ = 0;
  uint64_t walkLeft_ = 0;  // random changes still to make (`walk`)
  std::mt19937_64 walkRandom_;
  bool scriptFailed_ = false;
  float yaw_ = 0.0F;
  float pitch_ = 0.0F;
  vk::HostTimer clock_;
};

fs::path Explorer::scriptRelative(const std::string& path) const {
  return explore::scriptRelative(options_.script, path);
}

fs::path Explorer::buttonsOrScriptRelative(const std::string& path) const {
  return path.empty() ? fs::path(options_.saveTo) : scriptRelative(path);
}

Expected<void, Failure> Explorer::saveDecisions(const fs::path& path) const {
  return writeFileAtomically(path.string(), session_->state->decisionFileText("written by spire-explore"));
}

Expected<void, Failure> Explorer::loadDecisions(const fs::path& path) {
  auto placement = readDecisions(path);
  if (!placement) {
    const engine::Error& error = placement.error();
    return Failure{error.details.empty() ? error.message : error.message + "\n" + error.details};
  }
  return session_->state->replace(placement->placement, placement->attributes);
}

engine::Expected<Explorer::FileDecisions> Explorer::readDecisions(const fs::path& path) {
  auto text = readFileBytes(path.string());
  if (!text)
    return engine::Error{fmt::format("cannot read decision file '{}': {}", path.string(), text.error().message())};
  const FileId file = run_.sources().addFile(path.string(), std::move(text).value());
  DiagnosticList& diags = run_.diagnostics();
  const size_t mark = diags.size();
  const size_t errors = diags.errorCount();
  const graph::DecisionFile decisions = graph::parseDecisionFile(run_.sources(), file, diags);
  if (diags.errorCount() > errors) {
    return engine::Error{fmt::format("decision file '{}' has errors", path.string()), {}, run_.renderSince(mark)};
  }
  FileDecisions result;
  for (const graph::DecisionLine& line : decisions.lines) {
    const std::string key = line.prefix + "." + line.component;
    // A scene variant's file may decide for other shaders too.
    if (!session_->state->isChoice(key)) continue;
    result.placement[key] = line.variation.empty() ? line.world : line.world + ":" + line.variation;
    if (!line.attributes.empty()) result.attributes[key] = line.attributes;
  }
  return result;
}

engine::Expected<void> Explorer::openSession(size_t index) {
  const scene::SceneFile& scene = renderer_.scene();
  if (index >= scene.instances.size()) {
    return engine::Error{
        fmt::format("instance {}: the scene has {} instance(s), from 0", index, scene.instances.size())};
  }
  const scene::InstanceDesc& instance = scene.instances[index];
  if (instance.kernels) {
    return engine::Error{
        "the instance is loaded from a spirec output directory ('kernels'); the explorer compiles its source",
        instance.kernelsRange};
  }
  auto library = renderer_.library(index);
  if (!library) return library.error();
  const graph::ChoiceSpace* space = (*library)->choiceSpace(instance.shader);
  if (!space) {
    return engine::Error{fmt::format("'{}' is not a concrete shader of its source", instance.shader),
                         instance.shaderRange};
  }
  InstanceSession& session = sessions_[index];
  session.instance = index;
  session.shader = instance.shader;
  session.state.emplace(*space);
  session.watch.reset(sourcePaths(**library));
  session.compiler = std::make_unique<LiveCompiler>(VariantCompiler(renderer_, index, instance.shader, **library));
  session_ = &session;
  // The choices show the decisions the instance's program was compiled with.
  if (const std::optional<fs::path> from = referencePath_ ? referencePath_ : instance.decisions) {
    auto placement = readDecisions(*from);
    if (!placement) return placement.error();
    if (auto ok = session.state->replace(placement->placement, placement->attributes); !ok) {
      return engine::Error(ok.error());
    }
    session.state->clearHistory();
  }
  return {};
}

engine::Expected<void> Explorer::selectInstance(size_t index) {
  if (pending_) return engine::Error{"a change is still compiling; switch instances once it is on screen"};
  InstanceSession* previous = session_;
  if (const auto it = sessions_.find(index); it != sessions_.end()) {
    session_ = &it->second;
    return {};
  }
  auto opened = openSession(index);
  if (!opened) {
    sessions_.erase(index);
    session_ = previous;
  }
  return opened;
}

// The instance, its shader's choices, the reference and the starting
// decisions; every variant compiled and prepared before the window shows.
std::optional<int> Explorer::start() {
  const scene::SceneFile& scene = renderer_.scene();
  referencePath_ = options_.reference;
  if (!referencePath_ && !scene.variants.empty()) referencePath_ = scene.variants.front().decisions;
  if (auto ok = selectInstance(options_.instance); !ok) return run_.fail(ok.error());
  auto programs = renderer_.compile(referencePath_);
  if (!programs) return run_.fail(programs.error());
  programs_ = std::move(programs).value();
  auto reference = renderer_.prepare(programs_);
  if (!reference) return run_.fail(reference.error());
  reference_ = std::move(reference).value();
  auto current = renderer_.prepare(programs_);
  if (!current) return run_.fail(current.error());
  current_ = std::move(current).value();
  if (options_.tuneDir) {
    if (auto ok = loadTune(*options_.tuneDir); !ok) return run_.fail({ok.error().message, {}, {}});
  }
  return std::nullopt;
}

Expected<void, Failure> Explorer::loadTune(const fs::path& dir) {
  auto results = loadTuneResults(dir, session_->shader, *session_->state);
  if (!results) return results.error();
  session_->tune = std::move(results).value();
  out_ << fmt::format("spire-explore: {}: {} tuned variants, {} on the front\n", dir.string(),
                      session_->tune->variants.size(), session_->tune->front.size())
       << std::flush;
  return {};
}

// The reference's frame time and image, and the starting decisions when
// they are not the reference's.
std::optional<int> Explorer::startSession() {
  auto stats = renderer_.measure(*reference_, 1, kReferenceFrames);
  if (!stats) return run_.fail(stats.error());
  metrics_.referenceGpuMs = stats->medianGpuMs;
  auto reference = renderer_.capture(*reference_, renderer_.scene().camera.views.front());
  if (!reference) return run_.fail(reference.error());
  captures_.reference = std::move(reference).value();
  if (auto ok = updateMetrics(); !ok) return run_.fail(ok.error());
  if (options_.decisions) {
    auto placement = readDecisions(*options_.decisions);
    if (!placement) return run_.fail(placement.error());
    if (auto ok = session_->state->replace(placement->placement, placement->attributes); !ok) {
      return run_.fail({ok.error().message, {}, {}});
    }
    startChange("load " + options_.decisions->string());
  }
  return std::nullopt;
}

std::optional<int> Explorer::startPresentation() {
  const vk::Context& ctx = renderer_.context();
  vk::Image* color = renderer_.colorImage();
  if (color == nullptr) return run_.fail({"the scene renders no color output to show", {}, {}});
  auto presenter = WindowPresenter::create(ctx, window_, *color);
  if (!presenter) return run_.fail(presenter.error());
  presenter_ = std::move(presenter).value();
  const VkImageUsageFlags usage =
      VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  auto image = vk::Image::create(ctx, {color->extent().width, color->extent().height, color->format(), usage, 0});
  if (!image) return run_.fail(engine::Error::fromVk(image.error()));
  staticImage_.emplace(std::move(image).value());
  auto panelImage = vk::Image::create(ctx, {color->extent().width, color->extent().height, color->format(), usage, 0});
  if (!panelImage) return run_.fail(engine::Error::fromVk(panelImage.error()));
  panelImage_.emplace(std::move(panelImage).value());
  return std::nullopt;
}

std::optional<int> Explorer::loadScript() {
  if (!options_.script) return std::nullopt;
  return loadScriptFile(run_, *options_.script, script_);
}

bool Explorer::scriptError(const ScriptAction& action, const std::string& message) {
  reportScriptError(run_, action, message);
  scriptFailed_ = true;
  return false;
}

bool Explorer::changeAction(const ScriptAction& action) {
  Expected<void, Failure> ok;
  switch (action.kind) {
    case ActionKind::Set: ok = session_->state->set(action.target, action.value); break;
    case ActionKind::Unset: ok = session_->state->unset(action.target); break;
    case ActionKind::Reset: ok = session_->state->replace({}); break;
    case ActionKind::Undo:
      if (!session_->state->undo()) ok = Failure{"there is no change to undo"};
      break;
    case ActionKind::ApplyFront:
      if (!session_->tune)
        return scriptError(action, "no spire-tune output is loaded (--tune-dir DIR or load-tune DIR)");
      if (action.count >= session_->tune->front.size()) {
        return scriptError(action, fmt::format("the front of '{}' has {} point(s), from 0",
                                               session_->tune->dir.string(), session_->tune->front.size()));
      }
      ok = session_->state->replace(session_->tune->variants[session_->tune->front[action.count]].decisions);
      break;
    default: ok = loadDecisions(buttonsOrScriptRelative(action.target));
  }
  if (!ok) return scriptError(action, ok.error().message);
  startChange(describeAction(run_.sources(), action));
  return true;
}

bool Explorer::runAction(const ScriptAction& action) {
  switch (action.kind) {
    case ActionKind::Save: {
      auto ok = saveDecisions(buttonsOrScriptRelative(action.target));
      return ok ? true : scriptError(action, ok.error().message);
    }
    case ActionKind::View: {
      view_ = viewModeNamed(action.target).value_or(ViewMode::Variant);
      auto ok = updateStaticImage();
      return ok ? true : scriptError(action, ok.error().message);
    }
    case ActionKind::WaitFrames: waitFrames_ = action.count; return true;
    case ActionKind::WaitReload: waitReload_ = true; return true;
    case ActionKind::Walk:
      walkLeft_ = action.count;
      walkRandom_.seed(action.seed);
      return true;
    case ActionKind::WindowShot: windowShot_ = scriptRelative(action.target); return true;
    case ActionKind::Screenshot: {
      auto ok = screenshot(scriptRelative(action.target));
      return ok ? true : scriptError(action, ok.error().message);
    }
    case ActionKind::LoadTune: {
      auto ok = loadTune(scriptRelative(action.target));
      return ok ? true : scriptError(action, ok.error().message);
    }
    case ActionKind::Instance: {
      auto ok = selectInstance(action.count);
      return ok ? true : scriptError(action, ok.error().message);
    }
    case ActionKind::Quit: return false;
    default:
      if (isLodAction(action.kind)) {
        return scriptError(action, "the scene has no level-of-detail policy ('lod') to edit or fly through");
      }
      return changeAction(action);
  }
}

bool Explorer::stepScript() {
  while (!pending_ && !incoming_ && waitFrames_ == 0 && !waitReload_ && !windowShot_) {
    if (walkLeft_ > 0) {
      --walkLeft_;
      if (walkStep()) continue;
      walkLeft_ = 0;
    }
    if (scriptNext_ == script_.size()) return false;
    if (!runAction(script_[scriptNext_++])) return false;
  }
  return true;
}

bool Explorer::walkStep() {
  std::vector<std::pair<std::string, std::string>> candidates;
  for (const ChoiceRow& row : session_->state->rows()) {
    for (const Alternative& alt : row.alternatives) {
      if (alt.possible && row.decided != alt.placement) candidates.emplace_back(row.key, alt.placement);
    }
  }
  if (candidates.empty()) return false;
  const auto& [key, placement] = candidates[walkRandom_() % candidates.size()];
  if (!session_->state->set(key, placement)) return false;
  startChange(fmt::format("set {} = {}", key, placement));
  return true;
}

void Explorer::handleRequests(const PanelRequests& requests) {
  if (requests.instance) {
    if (auto ok = selectInstance(*requests.instance); !ok) diagnostics_ = ok.error().message;
  }
  if (requests.view) {
    view_ = *requests.view;
    if (auto ok = updateStaticImage(); !ok) diagnostics_ = ok.error().message;
  }
  const auto apply = [this](const Expected<void, Failure>& ok, std::string action) {
    if (ok)
      startChange(std::move(action));
    else
      diagnostics_ = ok.error().message;
  };
  if (requests.set)
    apply(session_->state->set(requests.set->first, requests.set->second),
          fmt::format("set {} = {}", requests.set->first, requests.set->second));
  if (requests.unset) apply(session_->state->unset(*requests.unset), "unset " + *requests.unset);
  if (requests.undo && session_->state->undo()) startChange("undo");
  if (requests.applyTunePoint) {
    // One change, as `load`: undo goes back to the decisions before it.
    const TunedVariant& tuned = session_->tune->variants.at(*requests.applyTunePoint);
    apply(session_->state->replace(tuned.decisions),
          fmt::format("apply tuned variant {} ({})", tuned.index, decisionsText(tuned)));
  }
  if (requests.reset) apply(session_->state->replace({}), "reset");
  if (requests.save) {
    auto ok = saveDecisions(options_.saveTo);
    diagnostics_ = ok ? "" : ok.error().message;
  }
  if (requests.load) apply(loadDecisions(options_.saveTo), "load " + options_.saveTo);
}

void Explorer::startChange(std::string action, bool reload) {
  ChangeRecord change;
  change.action = std::move(action);
  change.reload = reload;
  change.instance = session_->instance;
  change.request = ++requests_;
  change.startMs = clock_.elapsedMs();
  pending_ = std::move(change);
  incoming_.reset();  // a variant of older decisions is not worth showing now
  session_->compiler->submit(
      {pending_->request, session_->state->decisions(), session_->state->attributes(), reload, programs_});
}

// The sources were read again: the choices are the new library's, keeping
// the decisions that still name a choice and an alternative of it.
void Explorer::adoptLibrary(const std::shared_ptr<ShaderLibrary>& library) {
  libraries_.push_back(library);
  const Placement previous = session_->state->decisions();
  const ShaderLibrary::Attributes attributes = session_->state->attributes();
  session_->state.emplace(*library->choiceSpace(session_->shader));
  Placement kept;
  for (const auto& [component, placement] : previous) {
    if (session_->state->isChoice(component)) kept.emplace(component, placement);
  }
  if (!session_->state->replace(kept, attributes)) (void)session_->state->replace({});
  session_->state->clearHistory();
  session_->watch.reset(sourcePaths(*library));
}

void Explorer::pollCompile() {
  std::optional<CompileOutcome> outcome = session_->compiler->poll();
  if (!outcome || !pending_ || outcome->request != pending_->request) return;
  pending_->compileMs = outcome->milliseconds - outcome->prepareMs;
  pending_->prepareMs = outcome->prepareMs;
  pending_->skipped = outcome->skipped;
  if (outcome->library) adoptLibrary(outcome->library);
  if (!outcome->program) return failChange(outcome->program.error().message, outcome->program.error().details);
  const std::string reported = run_.adoptDiagnostics(std::move(outcome->diagnostics));
  engine::Expected<engine::PreparedScene>& prepared = *outcome->prepared;
  if (!prepared) return failChange(prepared.error().message, prepared.error().details + reported);
  for (const engine::BakeRecord& bake : prepared->bakes) pending_->bakeMs += bake.reused ? 0.0 : bake.milliseconds;
  pending_->pipelinesCreated = prepared->pipelines.created;
  pending_->pipelinesReused = prepared->pipelines.reused;
  programs_[session_->instance] = std::move(outcome->program).value();
  incoming_ = std::move(prepared).value();
}

void Explorer::failChange(const std::string& message, const std::string& details) {
  pending_->ok = false;
  pending_->error = details.empty() ? message : message + "\n" + details;
  pending_->totalMs = clock_.elapsedMs() - pending_->startMs;
  finishChange();
}

void Explorer::finishChange() {
  ChangeRecord& change = *pending_;
  diagnostics_ = change.ok ? "" : change.error;
  if (change.reload) waitReload_ = false;
  if (change.ok) {
    out_ << fmt::format(
        "spire-explore: {}: decision to image {:.0f} ms (compile {:.0f}, prepare {:.0f} with bakes {:.0f} and {} "
        "pipelines built, {} reused, first frame {:.0f})\n",
        change.action, change.totalMs, change.compileMs, change.prepareMs, change.bakeMs, change.pipelinesCreated,
        change.pipelinesReused, change.firstFrameMs);
  } else {
    out_ << fmt::format("spire-explore: {}: failed: {}\n", change.action, change.error);
  }
  out_ << std::flush;
  changes_.push_back(change);
  lastChange_ = std::move(change);
  pending_.reset();
}

engine::Expected<void> Explorer::updateMetrics() {
  auto variant = renderer_.capture(*current_, renderer_.scene().camera.views.front());
  if (!variant) return variant.error();
  captures_.variant = std::move(variant).value();
  const engine::Capture& ref = *captures_.reference;
  const engine::Capture& var = *captures_.variant;
  captures_.coverage = var.coverage;
  for (size_t i = 0; i < captures_.coverage.size() && i < ref.coverage.size(); ++i) {
    captures_.coverage[i] = static_cast<uint8_t>(captures_.coverage[i] | ref.coverage[i]);
  }
  auto error = measure::compareImages(ref.color, var.color, &captures_.coverage);
  metrics_.error = error ? std::optional(*error) : std::nullopt;
  metrics_.nonFinitePixels = measure::nonFinitePixels(var.color);
  metrics_.gpuMs.clear();
  return updateStaticImage();
}

// The derived view's image, made on the host and uploaded for the blit.
engine::Expected<void> Explorer::updateStaticImage() {
  if (view_ == ViewMode::Variant || view_ == ViewMode::Reference || !captures_.variant) return {};
  const measure::FloatImage& ref = captures_.reference->color;
  const measure::FloatImage& var = captures_.variant->color;
  staticPixels_ = view_ == ViewMode::Error     ? errorHeatMap(ref, var, captures_.coverage, kHeatScale)
                  : view_ == ViewMode::Hazards ? hazardMask(var)
                                               : splitImage(ref, var);
  const auto bytes = std::as_bytes(std::span(staticPixels_.rgba));
  if (bytes.size() != staticImage_->byteSize())
    return engine::Error{"the view's image does not match the frame's size"};
  // Left as a transfer source: each frame copies it for the panels.
  return engine::writeImage(renderer_.context(), *staticImage_, bytes, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
}

// What the view shows without the panels, at the fixed camera view.
engine::Expected<void> Explorer::screenshot(const fs::path& path) {
  return writeOpaquePng(path, view_ == ViewMode::Variant     ? captures_.variant->color
                              : view_ == ViewMode::Reference ? captures_.reference->color
                                                             : staticPixels_);
}

vk::Image& Explorer::shownImage() {
  return view_ == ViewMode::Variant || view_ == ViewMode::Reference ? *renderer_.colorImage() : *panelImage_;
}

engine::Expected<void> Explorer::windowScreenshot(const fs::path& path) {
  return writeImagePng(renderer_.context(), shownImage(), path);
}

scene::CameraView Explorer::cameraView(const demo::WindowInput& input, double now) {
  const scene::SceneFile& scene = renderer_.scene();
  if (options_.script) return scene.camera.views.front();
  if (!presenter_->wantsMouse()) {
    yaw_ -= input.drag.x * kRadiansPerPixel;
    pitch_ = std::clamp(pitch_ + input.drag.y * kRadiansPerPixel, -glm::pi<float>(), glm::pi<float>());
  }
  return demo::orbit(demo::cameraOnLoop(scene.camera.views, now / 1000.0 / kSecondsPerView), scene.camera.up, yaw_,
                     pitch_);
}

PanelState Explorer::panelState() const {
  PanelState state;
  state.shader = session_->shader;
  state.instance = session_->instance;
  const std::vector<scene::InstanceDesc>& instances = renderer_.scene().instances;
  for (size_t i = 0; i < instances.size(); ++i)
    state.instances.push_back(fmt::format("{}: {} ({})", i, instances[i].shader, instances[i].mesh));
  state.rows = session_->state->rows();
  state.view = view_;
  state.metrics = &metrics_;
  state.lastChange = lastChange_;
  state.compiling = pending_.has_value();
  state.diagnostics = diagnostics_;
  state.decisionsPath = options_.saveTo;
  if (session_->tune) {
    state.tune = &*session_->tune;
    state.tunedCurrent = matchingVariant(*session_->tune, session_->state->decisions());
  }
  return state;
}

// Draws the panels over the shown image and presents it.
engine::Expected<void> Explorer::present() {
  vk::Image& shown = shownImage();
  std::function<vk::Expected<void>(VkCommandBuffer)> copy;
  if (&shown == &*panelImage_) {
    copy = [this](VkCommandBuffer cmd) { return panelImage_->copyLayerFrom(cmd, *staticImage_, 0); };
  }
  PanelRequests requests;
  const auto panels = [&] { requests = drawPanels(panelState()); };
  if (auto ok = presenter_->present(shown, panels, copy); !ok) return ok;
  handleRequests(requests);
  return {};
}

// False when the explorer should close.
engine::Expected<bool> Explorer::frame(const demo::WindowInput& input) {
  if (options_.script && !stepScript()) return false;
  if (const std::optional<fs::path> saved = session_->watch.poll()) startChange("reload " + saved->string(), true);
  pollCompile();
  const double now = clock_.elapsedMs();
  const scene::CameraView view = cameraView(input, now);
  const float time = options_.script ? 0.0F : static_cast<float>(now / 1000.0);
  std::optional<engine::FrameTiming> first;  // of a new variant, shown for the first time
  if (incoming_) {
    auto timing = renderer_.renderView(*incoming_, view, time);
    if (!timing) return timing.error();
    first = *timing;
    current_ = std::move(incoming_);
    incoming_.reset();
  }
  if (view_ == ViewMode::Reference || (view_ == ViewMode::Variant && !first)) {
    auto timing = renderer_.renderView(view_ == ViewMode::Reference ? *reference_ : *current_, view, time);
    if (!timing) return timing.error();
    if (view_ == ViewMode::Variant) metrics_.addFrame(timing->gpuMs);
  }
  if (auto ok = present(); !ok) return ok.error();
  if (pending_ && !first) ++pending_->framesWhileCompiling;
  if (windowShot_) {
    if (auto ok = windowScreenshot(*windowShot_); !ok) return ok.error();
    windowShot_.reset();
  }
  if (first && pending_) {
    pending_->firstFrameMs = first->hostMs;
    pending_->totalMs = clock_.elapsedMs() - pending_->startMs;
    pending_->ok = true;
    if (auto ok = updateMetrics(); !ok) return ok.error();
    finishChange();
    // The panels' frame time starts with the new variant; its first frame
    // (lavapipe's shader compile) is not typical of it.
  }
  if (waitFrames_ > 0) --waitFrames_;
  return true;
}

int Explorer::finish(int status) {
  // A worker may still be preparing a change: what it reports to Vulkan's
  // validation belongs to this run, which ends below.
  for (auto& [index, session] : sessions_) session.compiler.reset();
  std::vector<double> totals;
  size_t failed = 0;
  nlohmann::ordered_json log = nlohmann::ordered_json::array();
  for (const ChangeRecord& change : changes_) {
    if (change.ok) totals.push_back(change.totalMs);
    failed += change.ok ? 0 : 1;
    log.push_back({{"action", change.action},
                   {"instance", change.instance},
                   {"ok", change.ok},
                   {"compile_ms", change.compileMs},
                   {"prepare_ms", change.prepareMs},
                   {"bake_ms", change.bakeMs},
                   {"pipelines_created", change.pipelinesCreated},
                   {"pipelines_reused", change.pipelinesReused},
                   {"frames_while_compiling", change.framesWhileCompiling},
                   {"first_frame_ms", change.firstFrameMs},
                   {"total_ms", change.totalMs},
                   {"error", change.error},
                   {"skipped", change.skipped}});
  }
  if (!totals.empty()) {
    std::sort(totals.begin(), totals.end());
    const double median = totals[totals.size() / 2];
    const double p90 = totals[std::min(totals.size() - 1, totals.size() * 9 / 10)];
    out_ << fmt::format(
        "spire-explore: decision to image: median {:.0f} ms, p90 {:.0f} ms over {} changes ({} failed)\n", median, p90,
        totals.size(), failed);
  }
  if (options_.log) {
    const nlohmann::ordered_json document{
        {"scene", options_.scenePath}, {"shader", session_->shader}, {"changes", log}};
    if (auto ok = writeSessionLog(*options_.log, document); !ok) {
      return run_.fail({ok.error().message, {}, {}});
    }
  }
  return run_.finish(status);
}

int Explorer::run() {
  if (auto status = start()) return *status;
  if (auto status = startPresentation()) return *status;
  if (auto status = loadScript()) return *status;
  if (auto status = startSession()) return *status;
  out_ << fmt::format("spire-explore: {} ({} choices); {}\n", session_->shader, session_->state->rows().size(),
                      options_.script ? "running the script" : "close the window or press Escape to quit")
       << std::flush;
  auto ran = runFrameLoop(window_, options_.maxFrames, [this](const demo::WindowInput& input) { return frame(input); });
  if (!ran) return run_.fail(ran.error());
  return finish(scriptFailed_ ? kExitInputError : kExitSuccess);
}

}  // namespace

int runExplorer(const ExploreOptions& options, engine::ToolRun& run, demo::GlfwWindow& window, std::ostream& out) {
  if (run.scene().lod) return runLodExplorer(options, run, window, out);
  Explorer explorer(options, run, window, out);
  return explorer.run();
}

}  // namespace spire::explore
