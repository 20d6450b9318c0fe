// The LOD policy editor without a window: every edit is checked by the
// policy file's reader, an invalid edit keeps the last valid policy and
// says why with the reader's codes, and the edited text reads back to the
// edited policy; edits are undone and redone, an invalid one with the
// valid policy that drew then.
#include <gtest/gtest.h>

#include <cmath>

#include "explore/policy_editor.h"

namespace spire::explore {
namespace {

lod::LodPolicy threeLevels() {
  lod::LodPolicy policy;
  policy.levels = {{"LodHQ", 12.0F, {}, {}}, {"LodMQ", 35.0F, {}, {}}, {"LodLQ", INFINITY, {}, {}}};
  return policy;
}

TEST(PolicyEditor, AValidEditIsTheNewValidPolicy) {
  PolicyEditor editor(threeLevels());
  ASSERT_TRUE(editor.setUntil(0, 20.0F));
  ASSERT_TRUE(editor.setMember(1, "LodLQ"));
  editor.setHysteresis(0.25F);
  editor.setTransitionFrames(3);
  EXPECT_TRUE(editor.isValid()) << editor.diagnostics();
  EXPECT_EQ(editor.valid().levels[0].until, 20.0F);
  EXPECT_EQ(editor.valid().levels[1].member, "LodLQ");
  EXPECT_EQ(editor.valid().hysteresis, 0.25F);
  EXPECT_EQ(editor.valid().transitionFrames, 3U);
}

TEST(PolicyEditor, BandsOutOfOrderAreTheReadersErrorAndTheLastValidPolicyStays) {
  PolicyEditor editor(threeLevels());
  ASSERT_TRUE(editor.setUntil(1, 10.0F));
  EXPECT_FALSE(editor.isValid());
  EXPECT_NE(
      editor.diagnostics().find(
          "edited policy:4:5: error[E7004]: level 1 ends at 10, not beyond level 0 (12): bands go from near to far"),
      std::string::npos)
      << editor.diagnostics();
  EXPECT_EQ(editor.valid().levels[1].until, 35.0F);
  EXPECT_EQ(editor.edited().levels[1].until, 10.0F);
  editor.setHysteresis(1.5F);
  EXPECT_NE(editor.diagnostics().find("error[E7004]"), std::string::npos) << "both problems are reported";
  EXPECT_NE(editor.diagnostics().find("'hysteresis'"), std::string::npos) << editor.diagnostics();
  editor.setHysteresis(0.1F);
  ASSERT_TRUE(editor.setUntil(1, 40.0F));
  EXPECT_TRUE(editor.isValid()) << editor.diagnostics();
  EXPECT_EQ(editor.valid().levels[1].until, 40.0F);
}

TEST(PolicyEditor, BandsAreAddedByTheirEdgeAndRemovedWithIt) {
  PolicyEditor editor(threeLevels());
  editor.addLevel("LodMQ", 20.0F);
  ASSERT_EQ(editor.edited().levels.size(), 4U);
  EXPECT_EQ(editor.edited().levels[1].until, 20.0F);
  editor.addLevel("LodLQ", 100.0F);  // beyond every edge: before the farthest level
  ASSERT_EQ(editor.edited().levels.size(), 5U);
  EXPECT_EQ(editor.edited().levels[3].until, 100.0F);
  EXPECT_TRUE(std::isinf(editor.edited().levels[4].until));
  EXPECT_TRUE(editor.isValid()) << editor.diagnostics();
  ASSERT_TRUE(editor.removeLevel(4));
  EXPECT_TRUE(std::isinf(editor.edited().levels.back().until)) << "the new last level reaches to infinity";
  EXPECT_TRUE(editor.isValid()) << editor.diagnostics();
  EXPECT_FALSE(editor.removeLevel(9));
  for (int i = 0; i < 3; ++i) ASSERT_TRUE(editor.removeLevel(0));
  EXPECT_FALSE(editor.removeLevel(0)) << "a policy keeps one level";
  EXPECT_TRUE(editor.isValid()) << editor.diagnostics();
}

TEST(PolicyEditor, TheTextReadsBackToTheEditedPolicy) {
  PolicyEditor editor(threeLevels());
  ASSERT_TRUE(editor.setUntil(0, 7.25F));
  SourceManager sources;
  DiagnosticList diags;
  const auto read = lod::parseLodPolicy("p.json", editor.text(), sources, diags);
  ASSERT_TRUE(read);
  ASSERT_EQ(read->levels.size(), 3U);
  EXPECT_EQ(read->levels[0].until, 7.25F);
  EXPECT_EQ(read->levels[1].member, "LodMQ");
  EXPECT_EQ(lod::formatLodPolicy(*read), editor.text());
  EXPECT_FALSE(editor.setUntil(3, 1.0F)) << "no level 3";
}

TEST(PolicyEditor, UndoGoesBackEditByEditToTheStartAndRedoForward) {
  const std::string original = lod::formatLodPolicy(threeLevels());
  PolicyEditor editor(threeLevels());
  EXPECT_FALSE(editor.canUndo());
  EXPECT_FALSE(editor.undo()) << "nothing to undo at the start";
  EXPECT_FALSE(editor.redo());
  EXPECT_EQ(editor.text(), original) << "a failed undo changes nothing";
  ASSERT_TRUE(editor.setMember(1, "LodLQ"));
  const std::string afterMember = editor.text();
  ASSERT_TRUE(editor.setUntil(0, 20.0F));
  ASSERT_TRUE(editor.undo());
  EXPECT_EQ(editor.text(), afterMember);
  EXPECT_EQ(lod::formatLodPolicy(editor.valid()), afterMember);
  ASSERT_TRUE(editor.undo());
  EXPECT_EQ(editor.text(), original);
  EXPECT_EQ(lod::formatLodPolicy(editor.valid()), original);
  EXPECT_FALSE(editor.undo()) << "back at the start";
  EXPECT_EQ(editor.text(), original);
  ASSERT_TRUE(editor.redo());
  EXPECT_EQ(editor.text(), afterMember);
  editor.setHysteresis(0.5F);
  EXPECT_FALSE(editor.redo()) << "a new edit forgets what could be redone";
  EXPECT_FALSE(editor.setUntil(7, 1.0F));
  ASSERT_TRUE(editor.undo()) << "an edit that could not be made is not undone";
  EXPECT_EQ(editor.text(), afterMember);
}

TEST(PolicyEditor, UndoingToAnInvalidEditRestoresTheValidPolicyThatDrewWithIt) {
  PolicyEditor editor(threeLevels());
  ASSERT_TRUE(editor.setUntil(1, 10.0F));  // before level 0's edge: invalid
  ASSERT_FALSE(editor.isValid());
  ASSERT_TRUE(editor.setUntil(0, 5.0F));  // valid again
  ASSERT_TRUE(editor.isValid()) << editor.diagnostics();
  ASSERT_TRUE(editor.undo());
  EXPECT_FALSE(editor.isValid());
  EXPECT_NE(editor.diagnostics().find("error[E7004]"), std::string::npos) << editor.diagnostics();
  EXPECT_EQ(lod::formatLodPolicy(editor.valid()), lod::formatLodPolicy(threeLevels()))
      << "the policy that drew while the invalid edit was shown";
}

TEST(PolicyEditor, AnAmendedReplaceIsOneEditWithTheOneItContinues) {
  PolicyEditor editor(threeLevels());
  lod::LodPolicy dragged = threeLevels();
  for (float edge : {13.0F, 14.0F, 15.0F}) {
    dragged.levels[0].until = edge;
    editor.replace(dragged, edge != 13.0F);
  }
  EXPECT_EQ(editor.edited().levels[0].until, 15.0F);
  ASSERT_TRUE(editor.undo());
  EXPECT_EQ(editor.text(), lod::formatLodPolicy(threeLevels())) << "one undo takes back the whole drag";
  EXPECT_FALSE(editor.canUndo());
}

}  // namespace
}  // namespace spire::explore
