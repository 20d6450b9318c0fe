#include "explore/level_compiler.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <iterator>
#include <memory>

namespace spire::explore {

void LevelCompiler::submit(uint64_t request, lod::LodPolicy policy) {
  if (running_.valid()) {
    queued_.emplace(request, std::move(policy));
    return;
  }
  launch(request, std::move(policy));
}

void LevelCompiler::launch(uint64_t request, lod::LodPolicy policy) {
  running_ = std::async(std::launch::async, [this, request, policy = std::move(policy)]() mutable {
    using Clock = std::chrono::steady_clock;
    const auto ms = [](Clock::time_point from) {
      return std::chrono::duration<double, std::milli>(Clock::now() - from).count();
    };
    Outcome outcome;
    outcome.request = request;
    const auto start = Clock::now();
    auto programs = compile_(policy);
    outcome.compileMs = ms(start);
    if (!programs) {
      outcome.error = programs.error();
    } else {
      const auto prepareStart = Clock::now();
      DiagnosticList diagnostics;
      auto scene = prepare_(policy, std::move(programs).value(), diagnostics);
      outcome.prepareMs = ms(prepareStart);
      outcome.diagnostics = diagnostics.all();
      if (scene) {
        outcome.scene = std::move(scene).value();
      } else {
        outcome.error = scene.error();
      }
    }
    outcome.policy = std::move(policy);
    return outcome;
  });
}

std::optional<LevelCompiler::Outcome> LevelCompiler::poll() {
  if (!running_.valid() || running_.wait_for(std::chrono::seconds(0)) != std::future_status::ready) {
    return std::nullopt;
  }
  Outcome outcome = running_.get();
  if (!queued_) return outcome;
  // Only the newest request is worth showing.
  auto [request, policy] = std::move(*queued_);
  queued_.reset();
  launch(request, std::move(policy));
  return std::nullopt;
}

LevelCompiler::CompileFunction compileLevelsIn(const engine::SceneRenderer& renderer,
                                               std::vector<ShaderLibrary*> libraries) {
  // Programs by instance and by what their level draws them as
  // (LodLevel::drawsAs); only the worker uses the cache, one request at a
  // time.
  struct Compiled {
    size_t instance;
    lod::LodLevel level;
    engine::VariantProgram program;
  };
  auto cache = std::make_shared<std::vector<Compiled>>();
  return [&renderer, libraries = std::move(libraries),
          cache](const lod::LodPolicy& policy) -> engine::Expected<LevelCompiler::Programs> {
    LevelCompiler::Programs programs;
    for (const lod::LodLevel& level : policy.levels) {
      std::vector<engine::VariantProgram>& row = programs.emplace_back();
      for (size_t p = 0; p < libraries.size(); ++p) {
        auto it = std::find_if(cache->begin(), cache->end(),
                               [&](const Compiled& c) { return c.instance == p && c.level.drawsAs(level); });
        if (it == cache->end()) {
          // The members' warnings were the compiler's to give when the scene
          // started; a member new to the session is checked by its errors.
          std::string warnings;
          auto program = renderer.compileLevelIn(*libraries[p], p, level, warnings);
          if (!program) return program.error();
          cache->push_back({p, level, std::move(program).value()});
          it = std::prev(cache->end());
        }
        row.push_back(it->program);
      }
    }
    return programs;
  };
}

}  // namespace spire::explore
