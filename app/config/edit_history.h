#pragma once
// Undo and redo of parameter edits (the view window's Ctrl-Z / Ctrl-Y): each step holds the whole
// configuration before and after an edit — a panel widget released, a script's set, a material
// picked — so undoing restores the values exactly (a material's name and coefficients together,
// which single-key inverse edits could not). The camera is navigation, not an edit: camera moves
// make no step, and undo and redo keep the camera where it is (R resets it).
#include <nlohmann/json.hpp>

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "app/config/config.h"
#include "app/config/registry.h"

namespace tallow::app {

class EditHistory {
 public:
  /// At most this many steps are kept (the oldest go first).
  static constexpr std::size_t kMaxSteps = 200;

  /// Starts at `start` (nothing to undo).
  EditHistory(const Registry& registry, const Config& start);

  /// Records what changed since the last commit as one step (nothing when only the camera moved);
  /// a new step drops what could have been redone. Returns true when a step was added.
  bool commit(const Config& now);

  bool canUndo() const { return position_ > 0; }
  bool canRedo() const { return position_ < steps_.size(); }
  /// The configuration before the last step, with `now`'s camera; empty when there is nothing to
  /// undo. `now` must have been committed (commit it first).
  std::optional<Config> undo(const Config& now);
  /// The configuration after the step undone last, with `now`'s camera; empty when nothing to redo.
  std::optional<Config> redo(const Config& now);

  /// "sss.maps 4 → 8" (several keys: "material and 4 more"): what undo (redo) would change back.
  std::string undoLabel() const;
  std::string redoLabel() const;

 private:
  struct Step {
    Config before, after;
    std::string label;
  };
  nlohmann::json editable(const Config& config) const;  ///< the snapshot without the camera

  const Registry& registry_;
  std::vector<Step> steps_;
  std::size_t position_ = 0;  ///< steps_[0, position_) are done, the rest undone
  Config committed_;
  nlohmann::json committedValues_;
};

/// Whether a key is the camera's (camera.*): navigation that EditHistory leaves alone.
bool isCameraKey(const std::string& key);

}  // namespace tallow::app
