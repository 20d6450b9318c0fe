// spire-explore's level-of-detail policy editor, without the window: the
// policy as the user has edited it, checked after each edit by the policy
// file's own reader (its JSON text, formatLodPolicy, read back with
// parseLodPolicy), so an edit is valid exactly when the file it saves would
// load; and the last valid policy, which keeps drawing while an edit is not.
// Every edit can be undone and redone, as the explorer's decision changes
// can (decision_state.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "lod/lod_policy.h"
#include "support/expected.h"

namespace spire::explore {

class PolicyEditor {
 public:
  // `start` must be valid (as loadLodPolicy returns it).
  explicit PolicyEditor(lod::LodPolicy start);

  // What the panel shows, valid or not.
  const lod::LodPolicy& edited() const { return edited_; }
  // The last edited policy that passed the reader's checks.
  const lod::LodPolicy& valid() const { return valid_; }
  bool isValid() const { return isValid_; }
  // The reader's diagnostics for the edited policy, rendered with their
  // line:col in its JSON text.
  const std::string& diagnostics() const { return diagnostics_; }
  // The edited policy's JSON text, the file Save writes.
  std::string text() const { return lod::formatLodPolicy(edited_); }

  // Edits. A Failure is an edit that cannot be made at all (no such level,
  // the only level removed): nothing changes. Otherwise the edit is made
  // and checked; see isValid().
  Expected<void, Failure> setMember(size_t level, std::string member);
  Expected<void, Failure> setUntil(size_t level, float until);
  void setHysteresis(float hysteresis);
  void setTransitionFrames(uint32_t frames);
  // A band drawn by `member` that ends at `until`, among the others by its
  // edge (before the last level when it is beyond every edge).
  void addLevel(std::string member, float until);
  // The band's edge goes with it; removing the last level makes the one
  // before it the last, reaching to infinity.
  Expected<void, Failure> removeLevel(size_t level);
  // The whole policy at once (the panel edits a copy). With `amend`, the
  // edit continues the last one (a value dragged over several frames) and
  // undo goes back to the policy before both, not to every frame's.
  void replace(lod::LodPolicy policy, bool amend = false);

  // Restores the edited policy before the last edit; false when there is
  // none. An edit after an undo forgets what could be redone.
  bool undo() { return restore(undo_, redo_); }
  // Makes the last undone edit again; false when there is none.
  bool redo() { return restore(redo_, undo_); }
  bool canUndo() const { return !undo_.empty(); }
  bool canRedo() const { return !redo_.empty(); }

 private:
  Expected<void, Failure> checkLevel(size_t level) const;
  // Before each edit: the edited policy as it was, for undo.
  void remember();
  struct Snapshot;
  bool restore(std::vector<Snapshot>& from, std::vector<Snapshot>& to);
  void check();

  lod::LodPolicy edited_;
  lod::LodPolicy valid_;
  std::string diagnostics_;
  bool isValid_ = true;
  // The edited policy, valid or not, with the valid one that drew then: an
  // undo goes back to what the panel showed and what drew with it.
  struct Snapshot {
    lod::LodPolicy edited;
    lod::LodPolicy valid;
  };
  std::vector<Snapshot> undo_;
  std::vector<Snapshot> redo_;
};

}  // namespace spire::explore
