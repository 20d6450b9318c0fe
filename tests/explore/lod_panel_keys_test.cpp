// The LOD policy panel's keys: Ctrl+Z undoes, Ctrl+Y and Ctrl+Shift+Z
// redo, only when there is something to undo or redo, and a held key acts
// once. Drawn in a headless Dear ImGui context, whose keyboard the test sets
// as GLFW's backend would (ImGui 1.86: a key map into KeysDown).
#include <gtest/gtest.h>
#include <imgui.h>

#include <limits>
#include <string>
#include <vector>

#include "explore/lod_panel.h"
#include "lod/lod_policy.h"

namespace spire::explore {
namespace {

constexpr int kKeyY = 89;  // GLFW_KEY_Y and GLFW_KEY_Z: what the backend maps ImGuiKey_Y/Z to
constexpr int kKeyZ = 90;

class LodPanelKeysTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;
    io.DisplaySize = ImVec2(800.0F, 600.0F);
    io.KeyMap[ImGuiKey_Y] = kKeyY;
    io.KeyMap[ImGuiKey_Z] = kKeyZ;
    unsigned char* pixels = nullptr;
    int width = 0;
    int height = 0;
    io.Fonts->GetTexDataAsRGBA32(&pixels, &width, &height);
    policy_.levels.push_back({"LodHQ", 10.0F, {}, {}});
    policy_.levels.push_back({"LodLQ", std::numeric_limits<float>::infinity(), {}, {}});
    state_.edited = &policy_;
    state_.drawn = &policy_;
    state_.members = &members_;
    state_.metrics = &metrics_;
  }
  void TearDown() override { ImGui::DestroyContext(); }

  // One frame with these keys down (and no others).
  LodPanelRequests frame(bool ctrl, bool shift, std::vector<int> keys) {
    ImGuiIO& io = ImGui::GetIO();
    io.DeltaTime = 1.0F / 60.0F;
    io.KeyCtrl = ctrl;
    io.KeyShift = shift;
    for (bool& down : io.KeysDown) down = false;
    for (int key : keys) io.KeysDown[key] = true;
    ImGui::NewFrame();
    LodPanelRequests requests = drawLodPanels(state_);
    ImGui::Render();
    return requests;
  }

  lod::LodPolicy policy_;
  std::vector<std::string> members_{"LodHQ", "LodLQ"};
  LodMetrics metrics_;
  LodPanelState state_;
};

TEST_F(LodPanelKeysTest, CtrlZUndoesOnceWhileHeld) {
  state_.canUndo = true;
  EXPECT_FALSE(frame(false, false, {}).undo);
  EXPECT_FALSE(frame(false, false, {kKeyZ}).undo) << "Z without Ctrl";
  frame(true, false, {});
  const LodPanelRequests pressed = frame(true, false, {kKeyZ});
  EXPECT_TRUE(pressed.undo);
  EXPECT_FALSE(pressed.redo);
  EXPECT_FALSE(frame(true, false, {kKeyZ}).undo) << "a held key acts once";
}

TEST_F(LodPanelKeysTest, CtrlYAndCtrlShiftZRedo) {
  state_.canRedo = true;
  frame(true, false, {});
  const LodPanelRequests y = frame(true, false, {kKeyY});
  EXPECT_TRUE(y.redo);
  EXPECT_FALSE(y.undo);
  frame(true, true, {});
  const LodPanelRequests shiftZ = frame(true, true, {kKeyZ});
  EXPECT_TRUE(shiftZ.redo);
  EXPECT_FALSE(shiftZ.undo) << "Ctrl+Shift+Z is redo, not undo";
}

TEST_F(LodPanelKeysTest, KeysDoNothingWithNothingToUndoOrRedo) {
  frame(true, false, {});
  EXPECT_FALSE(frame(true, false, {kKeyZ}).undo);
  frame(true, false, {});
  EXPECT_FALSE(frame(true, false, {kKeyY}).redo);
  frame(true, true, {});
  EXPECT_FALSE(frame(true, true, {kKeyZ}).redo);
}

}  // namespace
}  // namespace spire::explore
