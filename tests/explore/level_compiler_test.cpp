// The LOD mode's level worker, without a window: while a policy's levels
// compile and are prepared (bakes and pipelines), the caller's frames go on
// (poll answers at once, with nothing); a request submitted meanwhile
// replaces any waiting one, and only the newest request's scene comes back.
// The prepare runs on the worker after a compile that succeeded, with its
// programs. (The scene here is null: a LodScene needs a renderer, which the
// window tests give it.)
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <future>
#include <optional>
#include <string>
#include <thread>

#include "explore/level_compiler.h"

namespace spire::explore {
namespace {

lod::LodPolicy policyOf(const std::string& member) {
  lod::LodPolicy policy;
  policy.levels = {{member, INFINITY, {}, {}}};
  return policy;
}

// The next outcome, polling as a frame loop does; nullopt after 10 s.
std::optional<LevelCompiler::Outcome> nextOutcome(LevelCompiler& compiler) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (std::chrono::steady_clock::now() < deadline) {
    if (auto outcome = compiler.poll()) return outcome;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return std::nullopt;
}

class LevelCompilerTest : public ::testing::Test {
 protected:
  std::promise<void> release_;
  std::shared_future<void> released_ = release_.get_future().share();
  std::vector<std::string> compiled_;  // the worker's only, read once it is idle
  std::vector<std::string> prepared_;  // likewise
  std::thread::id caller_ = std::this_thread::get_id();
  // Each compile waits until the test releases them all. Last: its
  // destructor waits for the worker, which uses the members above.
  LevelCompiler compiler_{[this](const lod::LodPolicy& policy) -> engine::Expected<LevelCompiler::Programs> {
                            compiled_.push_back(policy.levels.front().member);
                            released_.wait();
                            if (policy.levels.front().member == "LodBroken")
                              return engine::Error{"cannot compile LodBroken"};
                            return LevelCompiler::Programs(policy.levels.size());
                          },
                          [this](const lod::LodPolicy& policy, LevelCompiler::Programs programs,
                                 DiagnosticList& diagnostics) -> engine::Expected<LevelCompiler::Scene> {
                            EXPECT_NE(std::this_thread::get_id(), caller_) << "prepared on the worker";
                            EXPECT_EQ(programs.size(), policy.levels.size());
                            prepared_.push_back(policy.levels.front().member);
                            if (policy.levels.front().member == "LodUnbakeable") {
                              diagnostics.report(DiagCode::E7102, {}, "input 'tint' is not bound");
                              return engine::Error{"cannot bake LodUnbakeable"};
                            }
                            return LevelCompiler::Scene{};
                          }};
};

TEST_F(LevelCompilerTest, TheCallersFramesGoOnWhileTheLevelsCompile) {
  compiler_.submit(1, policyOf("LodMQ"));
  EXPECT_TRUE(compiler_.busy());
  for (int frame = 0; frame < 10; ++frame) EXPECT_FALSE(compiler_.poll()) << "frame " << frame;
  release_.set_value();
  const auto outcome = nextOutcome(compiler_);
  ASSERT_TRUE(outcome);
  EXPECT_EQ(outcome->request, 1U);
  EXPECT_EQ(outcome->policy.levels.front().member, "LodMQ");
  EXPECT_FALSE(outcome->error);
  EXPECT_GT(outcome->compileMs, 0.0);
  EXPECT_EQ(prepared_, (std::vector<std::string>{"LodMQ"}));
  EXPECT_FALSE(compiler_.busy());
  EXPECT_FALSE(compiler_.poll()) << "an outcome comes back once";
}

TEST_F(LevelCompilerTest, OnlyTheNewestRequestComesBack) {
  compiler_.submit(1, policyOf("LodMQ"));
  compiler_.submit(2, policyOf("LodLQ"));      // waits
  compiler_.submit(3, policyOf("LodBroken"));  // replaces request 2
  release_.set_value();
  const auto outcome = nextOutcome(compiler_);
  ASSERT_TRUE(outcome);
  EXPECT_EQ(outcome->request, 3U) << "request 1's levels are dropped: a newer request waited";
  ASSERT_TRUE(outcome->error);
  EXPECT_EQ(outcome->error->message, "cannot compile LodBroken");
  EXPECT_EQ(outcome->prepareMs, 0.0);
  EXPECT_FALSE(compiler_.busy());
  EXPECT_EQ(compiled_, (std::vector<std::string>{"LodMQ", "LodBroken"})) << "request 2 never compiled";
  EXPECT_EQ(prepared_, (std::vector<std::string>{"LodMQ"})) << "a failed compile is not prepared";
}

TEST_F(LevelCompilerTest, APrepareErrorComesBackAsTheOutcomesErrorWithItsDiagnostics) {
  compiler_.submit(1, policyOf("LodUnbakeable"));
  release_.set_value();
  const auto outcome = nextOutcome(compiler_);
  ASSERT_TRUE(outcome);
  ASSERT_TRUE(outcome->error);
  EXPECT_EQ(outcome->error->message, "cannot bake LodUnbakeable");
  EXPECT_EQ(outcome->scene, nullptr);
  ASSERT_EQ(outcome->diagnostics.size(), 1U) << "what the prepare reported comes back with it";
  EXPECT_EQ(outcome->diagnostics.front().message, "input 'tint' is not bound");
}

}  // namespace
}  // namespace spire::explore
