#include "explore/lod_explorer.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <memory>

#include "demo/camera_path.h"
#include "driver/exit_codes.h"
#include "explore/explore_script.h"
#include "explore/explorer_model.h"
#include "explore/explorer_panels.h"
#include "explore/level_compiler.h"
#include "explore/lod_panel.h"
#include "explore/policy_editor.h"
#include "explore/window_presenter.h"
#include "renderer/lod_scene.h"
#include "support/diagnostic_renderer.h"
#include "support/file_io.h"
#include "vk/timer.h"

namespace spire::explore {
namespace fs = std::filesystem;
namespace {

constexpr double kSecondsPerView = 4.0;  // the fly-through's pace while it plays, as spire-demo --window

// The members that the group of every instance's shader offers, in the
// first one's order: read from the compiled libraries, so an optional
// member a material could not be made with (W4101) is not offered.
engine::Expected<std::vector<std::string>> offeredMembers(engine::SceneRenderer& renderer) {
  std::vector<std::string> offered;
  const std::vector<scene::InstanceDesc>& instances = renderer.scene().instances;
  for (size_t i = 0; i < instances.size(); ++i) {
    auto library = renderer.library(i);
    if (!library) return library.error();
    std::vector<std::string> members;
    for (const auto& group : (*library)->model().groups) {
      if (!group->derivedDecl || group->name != instances[i].shader) continue;
      for (const sem::GroupMember& member : group->members) {
        if ((*library)->choiceSpace(member.shader->name)) members.push_back(member.shader->base->name);
      }
    }
    if (members.empty()) {
      return engine::Error{
          fmt::format("'{}' is not derived from a group: it has no members to draw levels with", instances[i].shader),
          instances[i].shaderRange};
    }
    if (i == 0) offered = members;
    std::erase_if(offered,
                  [&](const std::string& m) { return std::find(members.begin(), members.end(), m) == members.end(); });
  }
  return offered;
}

struct EditRecord {
  std::string action;
  bool ok = false;
  double applyMs = 0.0;  // from the edit to its policy drawing
  std::string error;
  // The drawn policy's switches that cannot cross-fade (W7102) once it was
  // made, rendered: an edit can make one (a member that does not read
  // lodFade) or take it away.
  std::string warnings;
  std::vector<uint32_t> levels;       // instances per level of the drawn policy once it was made
  double compileMs = 0.0;             // the new levels' compile on the worker, when the edit needed one
  double prepareMs = 0.0;             // their bakes and pipelines, on the worker after the compile
  uint32_t framesWhileCompiling = 0;  // presented meanwhile (compile and prepare), with the previous levels
  bool scripted = false;
  uint64_t request = 0;  // of the level compile
  double startMs = 0.0;
};

std::string errorText(const engine::Error& error) {
  return error.details.empty() ? error.message : error.message + "\n" + error.details;
}

std::vector<uint32_t> levelCounts(const engine::LodScene& scene) {
  std::vector<uint32_t> counts(scene.policy().levels.size(), 0);
  for (size_t i = 0; i < scene.instanceCount(); ++i) ++counts.at(scene.levelOf(i));
  return counts;
}

class LodExplorer {
 public:
  LodExplorer(const ExploreOptions& options, engine::ToolRun& run, demo::GlfwWindow& window, std::ostream& out)
      : options_(options), run_(run), editor_(run.lodPolicy()), renderer_(run.renderer()), window_(window), out_(out) {}
  int run();

 private:
  std::optional<int> start();
  // After an edit: the editor's valid policy drawn, its levels compiling,
  // or why not.
  void edited(std::string action, bool scripted);
  // True when the policy needs new levels, which are now compiling.
  engine::Expected<bool> applyPolicy();
  void pollLevels();
  // An edit that compiled levels for a policy a later edit replaced.
  void dropPending();
  void finishEdit(EditRecord record, std::string error);
  Expected<void, Failure> save(const fs::path& path) const;
  bool stepScript();
  bool runAction(const ScriptAction& action);
  bool policyAction(const ScriptAction& action);
  bool scriptError(const ScriptAction& action, const std::string& message);
  fs::path scriptRelative(const std::string& path) const;
  void handleRequests(const LodPanelRequests& requests);
  void moveCamera(double nowMs);
  void updateMetrics(const engine::FrameTiming& timing);
  LodPanelState panelState() const;
  // What is wrong with the edited policy: the reader's diagnostics, else
  // why the valid policy could not be drawn.
  std::string editError() const { return editor_.isValid() ? applyError_ : editor_.diagnostics(); }
  // The message the Diagnostics panel shows: that, and while the policy is
  // valid, the drawn one's warnings.
  std::string diagnostics() const { return editError() + (editor_.isValid() ? warnings_ : std::string()); }
  // The drawn policy's switches into a level that cannot cross-fade
  // (W7102), rendered.
  std::string fadeWarnings() const;
  engine::Expected<bool> frame();
  int finish(int status);

  const ExploreOptions& options_;
  engine::ToolRun& run_;
  PolicyEditor editor_;  // starts from the scene's policy
  engine::SceneRenderer& renderer_;
  demo::GlfwWindow& window_;
  std::ostream& out_;
  std::vector<std::string> members_;
  std::unique_ptr<engine::LodScene> scene_;
  std::unique_ptr<WindowPresenter> presenter_;
  scene::CameraView view_;
  double flyFrame_ = 0.0;
  bool playing_ = false;
  double lastMs_ = 0.0;
  Metrics frameTimes_;
  LodMetrics metrics_;
  std::string applyError_;
  std::string warnings_;  // fadeWarnings() of the drawn policy
  std::string status_;
  std::vector<EditRecord> edits_;
  std::vector<uint32_t> startLevels_;  // instances per level at the start, for the log
  std::vector<ScriptAction> script_;
  size_t scriptNext_ = 0;
  uint64_t waitFrames_ = 0;
  std::optional<fs::path> shot_;        // the next frame without the panels
  std::optional<fs::path> windowShot_;  // the next frame as the window shows it
  bool scriptFailed_ = false;
  vk::HostTimer clock_;
  bool dragging_ = false;  // a panel value is being dragged, and its first change was an edit
  uint64_t requests_ = 0;
  std::optional<EditRecord> pending_;      // its levels are compiling
  std::unique_ptr<LevelCompiler> levels_;  // last: destroyed first, since its worker uses the renderer's libraries
};

std::optional<int> LodExplorer::start() {
  if (options_.reference || options_.decisions || options_.tuneDir) {
    return run_.fail(
        {"--reference, --decisions and --tune-dir are about one shader's decisions; on a "
         "level-of-detail scene spire-explore edits the policy instead",
         {},
         {}});
  }
  auto members = offeredMembers(renderer_);
  if (!members) return run_.fail(members.error());
  members_ = std::move(members).value();
  const scene::SceneFile& scene = renderer_.scene();
  view_ = scene.camera.views.front();
  auto lodScene = engine::LodScene::create(renderer_, editor_.valid());
  if (!lodScene) return run_.fail(lodScene.error());
  scene_ = std::move(lodScene).value();
  std::vector<ShaderLibrary*> libraries;
  for (size_t i = 0; i < renderer_.scene().instances.size(); ++i) libraries.push_back(*renderer_.library(i));
  // From now on only the worker compiles in the renderer's libraries.
  levels_ = std::make_unique<LevelCompiler>(
      compileLevelsIn(renderer_, std::move(libraries)),
      [&renderer = renderer_](const lod::LodPolicy& policy, LevelCompiler::Programs programs,
                              DiagnosticList& diagnostics) {
        engine::LodOptions options;
        options.diagnostics = &diagnostics;
        return engine::LodScene::createCompiled(renderer, policy, std::move(programs), options);
      });
  scene_->resetLevels(view_);
  startLevels_ = levelCounts(*scene_);
  // Every level is prepared now, as in spire-demo: an unread value is worth
  // a warning, and so is a switch that cannot cross-fade.
  renderer_.reportUnreadBindings();
  scene_->reportSwitchesThatCannotFade(run_.diagnostics());
  run_.reporter().flush();
  warnings_ = fadeWarnings();
  vk::Image* color = renderer_.colorImage();
  if (color == nullptr) return run_.fail({"the scene renders no color output to show", {}, {}});
  auto presenter = WindowPresenter::create(renderer_.context(), window_, *color);
  if (!presenter) return run_.fail(presenter.error());
  presenter_ = std::move(presenter).value();
  playing_ = !options_.script;
  if (options_.script) return loadScriptFile(run_, *options_.script, script_);
  return std::nullopt;
}

engine::Expected<bool> LodExplorer::applyPolicy() {
  const lod::LodPolicy& policy = editor_.valid();
  for (const lod::LodLevel& level : policy.levels) {
    // A level of decision files only draws the instances' own shaders.
    if (!level.member.empty() && std::find(members_.begin(), members_.end(), level.member) == members_.end()) {
      return engine::Error{fmt::format("'{}' is not a member that every instance's group offers ({})", level.member,
                                       fmt::join(members_, ", "))};
    }
  }
  // New edges only: the compiled levels stay.
  if (scene_->setBands(policy, view_)) return false;
  // New levels: compiled on the worker while the previous ones keep drawing.
  pending_->request = ++requests_;
  levels_->submit(pending_->request, policy);
  return true;
}

void LodExplorer::edited(std::string action, bool scripted) {
  EditRecord record;
  record.action = std::move(action);
  record.scripted = scripted;
  record.startMs = clock_.elapsedMs();
  applyError_.clear();
  // An invalid edit leaves the last valid policy's levels compiling.
  if (!editor_.isValid()) return finishEdit(std::move(record), editError());
  dropPending();
  pending_ = std::move(record);
  auto compiling = applyPolicy();
  if (compiling && *compiling) return;
  if (!compiling) applyError_ = errorText(compiling.error());
  record = std::move(*pending_);
  pending_.reset();
  finishEdit(std::move(record), editError());
}

void LodExplorer::dropPending() {
  if (!pending_) return;
  EditRecord dropped = std::move(*pending_);
  pending_.reset();
  finishEdit(std::move(dropped), "replaced by a later edit before its levels were ready");
}

// The worker made the new scene, bakes and pipelines included: here it only
// replaces the one drawn.
void LodExplorer::pollLevels() {
  std::optional<LevelCompiler::Outcome> outcome = levels_->poll();
  if (!outcome || !pending_ || outcome->request != pending_->request) return;
  EditRecord record = std::move(*pending_);
  pending_.reset();
  record.compileMs = outcome->compileMs;
  record.prepareMs = outcome->prepareMs;
  const std::string reported = run_.adoptDiagnostics(std::move(outcome->diagnostics));
  if (outcome->error) {
    applyError_ = errorText(*outcome->error) + reported;
  } else {
    scene_ = std::move(outcome->scene);
    scene_->resetLevels(view_);
  }
  finishEdit(std::move(record), applyError_);
}

std::string LodExplorer::fadeWarnings() const {
  DiagnosticList diags;
  scene_->reportSwitchesThatCannotFade(diags);
  return renderDiagnostics(run_.sources(), diags, DiagnosticFormat::Text);
}

void LodExplorer::finishEdit(EditRecord record, std::string error) {
  record.applyMs = clock_.elapsedMs() - record.startMs;
  record.error = std::move(error);
  record.ok = record.error.empty();
  record.levels = levelCounts(*scene_);
  record.warnings = fadeWarnings();
  if (record.scripted) {
    out_ << (record.ok ? fmt::format("spire-explore: {}: drawn in {:.0f} ms\n", record.action, record.applyMs)
                       : fmt::format("spire-explore: {}: not applied, the last valid policy keeps drawing:\n{}",
                                     record.action, record.error));
    // Said when an edit makes or changes them, not after every edit.
    if (record.warnings != warnings_) out_ << record.warnings;
    out_ << std::flush;
  }
  warnings_ = record.warnings;
  edits_.push_back(std::move(record));
}

Expected<void, Failure> LodExplorer::save(const fs::path& path) const {
  if (!editor_.isValid() || !applyError_.empty()) {
    return Failure{"the edited policy is not the one drawn (see Diagnostics); Save writes only a policy that draws"};
  }
  if (pending_) return Failure{"the edited policy's levels are still compiling; Save writes only a policy that draws"};
  return writeFileAtomically(path.string(), editor_.text());
}

fs::path LodExplorer::scriptRelative(const std::string& path) const {
  return explore::scriptRelative(options_.script, path);
}

bool LodExplorer::scriptError(const ScriptAction& action, const std::string& message) {
  reportScriptError(run_, action, message);
  scriptFailed_ = true;
  return false;
}

bool LodExplorer::policyAction(const ScriptAction& action) {
  const auto level = static_cast<size_t>(action.count);  // the level of the edits that name one
  Expected<void, Failure> ok;
  switch (action.kind) {
    case ActionKind::PolicyUntil: ok = editor_.setUntil(level, static_cast<float>(action.number)); break;
    case ActionKind::PolicyMember: ok = editor_.setMember(level, action.value); break;
    case ActionKind::PolicyHysteresis: editor_.setHysteresis(static_cast<float>(action.number)); break;
    case ActionKind::PolicyTransition: editor_.setTransitionFrames(action.count); break;
    case ActionKind::PolicyAdd: editor_.addLevel(action.value, static_cast<float>(action.number)); break;
    case ActionKind::PolicyUndo:
      if (!editor_.undo()) ok = Failure{"there is no policy edit to undo"};
      break;
    case ActionKind::PolicyRedo:
      if (!editor_.redo()) ok = Failure{"there is no undone policy edit to redo"};
      break;
    default: ok = editor_.removeLevel(level);
  }
  if (!ok) return scriptError(action, ok.error().message);
  edited(describeAction(run_.sources(), action), true);
  return true;
}

bool LodExplorer::runAction(const ScriptAction& action) {
  switch (action.kind) {
    case ActionKind::WaitFrames: waitFrames_ = action.count; return true;
    case ActionKind::Screenshot: shot_ = scriptRelative(action.target); return true;
    case ActionKind::WindowShot: windowShot_ = scriptRelative(action.target); return true;
    case ActionKind::Quit: return false;
    case ActionKind::FlyFrame: {
      const uint32_t frames = std::max<uint32_t>(renderer_.scene().frames, 1);
      if (action.count >= frames) {
        return scriptError(action, fmt::format("the fly-through has {} frames (the scene's 'frames'), from 0", frames));
      }
      // A jump, as the first frame of a camera path: levels placed without
      // cross-fades, so what the script shows next does not depend on
      // where the camera was.
      flyFrame_ = action.count;
      view_ = demo::flyThroughView(renderer_.scene().camera.views, flyFrame_, frames);
      scene_->resetLevels(view_);
      return true;
    }
    case ActionKind::PolicySave: {
      auto ok = save(action.target.empty() ? fs::path(options_.saveTo) : scriptRelative(action.target));
      return ok ? true : scriptError(action, ok.error().message);
    }
    default:
      if (isLodAction(action.kind)) return policyAction(action);
      return scriptError(action,
                         "on a level-of-detail scene a script edits the policy: policy ..., fly-frame, screenshot, "
                         "screenshot-window, wait-frames and quit");
  }
}

// Runs actions until one has to wait for a frame; false to close.
bool LodExplorer::stepScript() {
  // An edit whose levels compile finishes when they draw, so what the
  // script does next sees them.
  while (!pending_ && waitFrames_ == 0 && !shot_ && !windowShot_) {
    if (scriptNext_ == script_.size()) return false;
    if (!runAction(script_[scriptNext_++])) return false;
  }
  return true;
}

void LodExplorer::handleRequests(const LodPanelRequests& requests) {
  if (requests.policy) {
    // One edit per drag, not per frame, for undo.
    editor_.replace(*requests.policy, dragging_);
    edited("panel edit", false);
  }
  dragging_ = requests.dragging && (dragging_ || requests.policy);
  if (requests.undo && editor_.undo()) edited("undo", false);
  if (requests.redo && editor_.redo()) edited("redo", false);
  if (requests.addLevel) {
    // A band before the farthest, as far again as the edge before it.
    const std::vector<lod::LodLevel>& levels = editor_.edited().levels;
    const float edge = levels.size() > 1 ? levels[levels.size() - 2].until : 5.0F;
    editor_.addLevel(levels.back().member, std::isfinite(edge) ? edge * 2.0F : 10.0F);
    edited("add band", false);
  }
  if (requests.removeLevel) {
    if (auto ok = editor_.removeLevel(*requests.removeLevel); ok) edited("remove band", false);
  }
  if (requests.save) {
    auto ok = save(options_.saveTo);
    status_ = ok ? fmt::format("saved {}", options_.saveTo) : ok.error().message;
  }
  if (requests.flyFrame) flyFrame_ = *requests.flyFrame;
  if (requests.togglePlay) playing_ = !playing_;
}

void LodExplorer::moveCamera(double nowMs) {
  const scene::SceneFile& scene = renderer_.scene();
  const uint32_t frames = std::max<uint32_t>(scene.frames, 1);
  if (playing_) {
    const double perSecond = frames / (kSecondsPerView * static_cast<double>(scene.camera.views.size()));
    flyFrame_ = std::fmod(flyFrame_ + (nowMs - lastMs_) / 1000.0 * perSecond, frames);
  }
  lastMs_ = nowMs;
  view_ = demo::flyThroughView(scene.camera.views, flyFrame_, frames);
}

void LodExplorer::updateMetrics(const engine::FrameTiming& timing) {
  frameTimes_.addFrame(timing.gpuMs);
  metrics_.gpuMs = frameTimes_.medianGpuMs();
  const engine::LodFrameStats& stats = scene_->lastStats();
  metrics_.instances = scene_->instanceCount();
  metrics_.visible = stats.visible;
  metrics_.batches = stats.batches;
  metrics_.overlayBatches = stats.overlayBatches;
  metrics_.drawCalls = stats.drawCalls;
  metrics_.perLevel = levelCounts(*scene_);
}

LodPanelState LodExplorer::panelState() const {
  LodPanelState state;
  state.edited = &editor_.edited();
  state.drawn = &scene_->policy();
  state.members = &members_;
  state.valid = editor_.isValid();
  state.canUndo = editor_.canUndo();
  state.canRedo = editor_.canRedo();
  state.compiling = pending_.has_value();
  state.savePath = options_.saveTo;
  state.flyFrame = static_cast<float>(flyFrame_);
  state.flyFrames = std::max<uint32_t>(renderer_.scene().frames, 1);
  state.playing = playing_;
  state.metrics = &metrics_;
  state.status = status_;
  return state;
}

// False when the explorer should close.
engine::Expected<bool> LodExplorer::frame() {
  // Levels that finished compiling first: an edit's levels show no sooner
  // than the frame after it, which draws the previous ones.
  pollLevels();
  if (options_.script && !stepScript()) return false;
  const double now = clock_.elapsedMs();
  moveCamera(now);
  auto timing = scene_->render(view_, options_.script ? 0.0F : static_cast<float>(now / 1000.0));
  if (!timing) return timing.error();
  updateMetrics(*timing);
  vk::Image& shown = *renderer_.colorImage();
  if (shot_) {
    if (auto ok = writeImagePng(renderer_.context(), shown, *shot_); !ok) return ok.error();
    shot_.reset();
  }
  LodPanelRequests requests;
  auto presented = presenter_->present(shown, [&] {
    requests = drawLodPanels(panelState());
    drawDiagnosticsPanel(diagnostics());
  });
  if (!presented) return presented.error();
  handleRequests(requests);
  if (windowShot_) {
    if (auto ok = writeImagePng(renderer_.context(), shown, *windowShot_); !ok) return ok.error();
    windowShot_.reset();
  }
  if (pending_) ++pending_->framesWhileCompiling;
  if (waitFrames_ > 0) --waitFrames_;
  return true;
}

int LodExplorer::finish(int status) {
  if (options_.log) {
    nlohmann::ordered_json edits = nlohmann::ordered_json::array();
    for (const EditRecord& edit : edits_) {
      edits.push_back({{"action", edit.action},
                       {"ok", edit.ok},
                       {"apply_ms", edit.applyMs},
                       {"compile_ms", edit.compileMs},
                       {"prepare_ms", edit.prepareMs},
                       {"frames_while_compiling", edit.framesWhileCompiling},
                       {"error", edit.error},
                       {"warnings", edit.warnings},
                       {"levels", edit.levels}});
    }
    nlohmann::ordered_json levels = nlohmann::ordered_json::array();
    for (size_t i = 0; i < metrics_.perLevel.size(); ++i) {
      levels.push_back({{"member", scene_->policy().levels[i].member}, {"instances", metrics_.perLevel[i]}});
    }
    const nlohmann::ordered_json document{{"scene", options_.scenePath}, {"start_levels", startLevels_},
                                          {"policy_edits", edits},       {"levels", levels},
                                          {"batches", metrics_.batches}, {"draw_calls", metrics_.drawCalls}};
    if (auto ok = writeSessionLog(*options_.log, document); !ok) {
      return run_.fail({ok.error().message, {}, {}});
    }
  }
  return run_.finish(status);
}

int LodExplorer::run() {
  if (auto status = start()) return *status;
  out_ << fmt::format("spire-explore: level-of-detail policy of {} levels over {} instances; {}\n",
                      editor_.valid().levels.size(), scene_->instanceCount(),
                      options_.script ? "running the script" : "close the window or press Escape to quit")
       << std::flush;
  auto ran = runFrameLoop(window_, options_.maxFrames, [this](const demo::WindowInput&) { return frame(); });
  // A window closed while levels compile: the worker is done with the
  // renderer's libraries before the run reports.
  levels_.reset();
  if (!ran) return run_.fail(ran.error());
  return finish(scriptFailed_ ? kExitInputError : kExitSuccess);
}

}  // namespace

int runLodExplorer(const ExploreOptions& options, engine::ToolRun& run, demo::GlfwWindow& window, std::ostream& out) {
  LodExplorer explorer(options, run, window, out);
  return explorer.run();
}

}  // namespace spire::explore
