// spire-explore --script files: every action parses, and every malformed
// line is an E7201 error at its place, all of them reported, none run.
#include <gtest/gtest.h>

#include <string>

#include "explore/explore_script.h"
#include "support/diagnostic_renderer.h"

namespace spire::explore {
namespace {

struct Parsed {
  SourceManager sources;
  DiagnosticList diags;
  std::vector<ScriptAction> actions;
};

void parse(Parsed& p, std::string text) {
  const FileId file = p.sources.addFile("s.explore", std::move(text));
  p.actions = parseScript(p.sources, file, p.diags);
}

TEST(ExploreScript, ParsesEveryAction) {
  Parsed p;
  parse(p,
        "# a comment\n"
        "set Terrain.albedo = PrebakeTex   // trailing comment\n"
        "unset albedo\nreset\nload a.decisions\nsave b.decisions\nundo\nview split\n"
        "wait-frames 12\nwait-reload\nscreenshot x.png\nscreenshot-window y.png\nwalk 30 7\n"
        "load-tune tuned\napply-front 0\ninstance 1\n\n   quit\n");
  ASSERT_FALSE(p.diags.hasErrors()) << renderDiagnostics(p.sources, p.diags, DiagnosticFormat::Text);
  ASSERT_EQ(p.actions.size(), 16U);
  EXPECT_EQ(p.actions[0].kind, ActionKind::Set);
  EXPECT_EQ(p.actions[0].target, "Terrain.albedo");
  EXPECT_EQ(p.actions[0].value, "PrebakeTex");
  EXPECT_EQ(describeAction(p.sources, p.actions[0]), "set Terrain.albedo = PrebakeTex");
  EXPECT_EQ(p.actions[1].kind, ActionKind::Unset);
  EXPECT_EQ(p.actions[6].kind, ActionKind::View);
  EXPECT_EQ(p.actions[6].target, "split");
  EXPECT_EQ(p.actions[7].count, 12U);
  EXPECT_EQ(p.actions[8].kind, ActionKind::WaitReload);
  EXPECT_EQ(p.actions[10].kind, ActionKind::WindowShot);
  EXPECT_EQ(p.actions[11].kind, ActionKind::Walk);
  EXPECT_EQ(p.actions[11].count, 30U);
  EXPECT_EQ(p.actions[11].seed, 7U);
  EXPECT_EQ(p.actions[12].kind, ActionKind::LoadTune);
  EXPECT_EQ(p.actions[12].target, "tuned");
  EXPECT_EQ(p.actions[13].kind, ActionKind::ApplyFront);
  EXPECT_EQ(p.actions[13].count, 0U);
  EXPECT_EQ(p.actions[14].kind, ActionKind::Instance);
  EXPECT_EQ(p.actions[14].count, 1U);
  EXPECT_EQ(p.actions[15].kind, ActionKind::Quit);
  EXPECT_EQ(p.sources.begin(p.actions[15].range).column, 4U);
}

TEST(ExploreScript, EveryMalformedLineIsAnErrorAtItsPlace) {
  Parsed p;
  parse(p,
        "set albedo PrebakeTex x\n"
        "wait-frames 0\n"
        "view sideways\n"
        "explode now\n"
        "undo twice\n"
        "apply-front first\n"
        "instance -1\n"
        "set albedo = Fragment\n");
  EXPECT_TRUE(p.actions.empty()) << "a script with errors runs nothing";
  EXPECT_EQ(
      renderDiagnostics(p.sources, p.diags, DiagnosticFormat::Text),
      "s.explore:1:12: error[E7201]: expected 'set CHOICE = PLACEMENT'\n"
      " 1 | set albedo PrebakeTex x\n"
      "   |            ^~~~~~~~~~\n"
      "s.explore:2:13: error[E7201]: expected a frame count from 1 to 100000\n"
      " 2 | wait-frames 0\n"
      "   |             ^\n"
      "s.explore:3:6: error[E7201]: unknown view 'sideways' (views: variant, reference, error, hazards, split)\n"
      " 3 | view sideways\n"
      "   |      ^~~~~~~~\n"
      "s.explore:4:1: error[E7201]: unknown action 'explode' (actions: set, unset, reset, load, save, undo, walk, "
      "view, wait-frames, wait-reload, screenshot, screenshot-window, load-tune, apply-front, instance, quit, "
      "policy until, policy member, policy hysteresis, policy transition, policy add, policy remove, policy save, "
      "policy undo, policy redo, fly-frame)\n"
      " 4 | explode now\n"
      "   | ^~~~~~~\n"
      "s.explore:5:6: error[E7201]: 'undo' takes nothing after it\n"
      " 5 | undo twice\n"
      "   |      ^~~~~\n"
      "s.explore:6:13: error[E7201]: expected a front point from 0 (the fastest) to 100000\n"
      " 6 | apply-front first\n"
      "   |             ^~~~~\n"
      "s.explore:7:10: error[E7201]: expected an instance index from 0 to 100000\n"
      " 7 | instance -1\n"
      "   |          ^~\n"
      "7 errors generated.\n");
}

TEST(ExploreScript, ParsesThePolicyEditsOfALevelOfDetailScene) {
  Parsed p;
  parse(p,
        "policy until 0 20.5\npolicy   member 2 LodMQ\npolicy hysteresis 0.2\npolicy transition 6\n"
        "policy add LodMQ 50\npolicy remove 1\npolicy save\npolicy save out.json\nfly-frame 7\npolicy undo\n"
        "policy redo\n");
  ASSERT_FALSE(p.diags.hasErrors()) << renderDiagnostics(p.sources, p.diags, DiagnosticFormat::Text);
  ASSERT_EQ(p.actions.size(), 11U);
  EXPECT_EQ(p.actions[0].kind, ActionKind::PolicyUntil);
  EXPECT_EQ(p.actions[0].count, 0U);
  EXPECT_EQ(p.actions[0].number, 20.5);
  EXPECT_EQ(p.actions[1].kind, ActionKind::PolicyMember);
  EXPECT_EQ(p.actions[1].count, 2U);
  EXPECT_EQ(p.actions[1].value, "LodMQ");
  EXPECT_EQ(describeAction(p.sources, p.actions[1]), "policy   member 2 LodMQ");
  EXPECT_EQ(p.actions[2].number, 0.2);
  EXPECT_EQ(p.actions[3].kind, ActionKind::PolicyTransition);
  EXPECT_EQ(p.actions[3].count, 6U);
  EXPECT_EQ(p.actions[4].kind, ActionKind::PolicyAdd);
  EXPECT_EQ(p.actions[4].value, "LodMQ");
  EXPECT_EQ(p.actions[4].number, 50.0);
  EXPECT_EQ(p.actions[5].kind, ActionKind::PolicyRemove);
  EXPECT_EQ(p.actions[6].kind, ActionKind::PolicySave);
  EXPECT_EQ(p.actions[6].target, "");
  EXPECT_EQ(p.actions[7].target, "out.json");
  EXPECT_EQ(p.actions[8].kind, ActionKind::FlyFrame);
  EXPECT_EQ(p.actions[8].count, 7U);
  EXPECT_EQ(p.actions[9].kind, ActionKind::PolicyUndo);
  EXPECT_EQ(p.actions[10].kind, ActionKind::PolicyRedo);
  for (const ScriptAction& action : p.actions) EXPECT_TRUE(isLodAction(action.kind));
}

TEST(ExploreScript, MalformedPolicyEditsAreErrorsAtTheirPlace) {
  Parsed p;
  parse(p,
        "policy until one 5\npolicy hysteresis much\npolicy frobnicate 2\npolicy\npolicy member 1\nfly-frame -2\n"
        "policy undo 2\n");
  EXPECT_TRUE(p.actions.empty());
  const std::string text = renderDiagnostics(p.sources, p.diags, DiagnosticFormat::Text);
  EXPECT_NE(text.find("s.explore:1:14: error[E7201]: expected a level from 0 to 254"), std::string::npos) << text;
  EXPECT_NE(text.find("s.explore:2:19: error[E7201]: expected a hysteresis (a number)"), std::string::npos) << text;
  EXPECT_NE(text.find("s.explore:3:1: error[E7201]: unknown action 'policy frobnicate'"), std::string::npos) << text;
  EXPECT_NE(text.find("s.explore:4:1: error[E7201]: unknown action 'policy'"), std::string::npos) << text;
  EXPECT_NE(text.find("s.explore:5:15: error[E7201]: expected 'policy member LEVEL NAME'"), std::string::npos) << text;
  EXPECT_NE(text.find("s.explore:6:11: error[E7201]: expected a fly-through frame from 0 to 100000"), std::string::npos)
      << text;
  EXPECT_NE(text.find("s.explore:7:13: error[E7201]: 'policy undo' takes nothing after it"), std::string::npos) << text;
}

}  // namespace
}  // namespace spire::explore
