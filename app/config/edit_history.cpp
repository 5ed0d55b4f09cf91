#include "app/config/edit_history.h"

#include <algorithm>

namespace tallow::app {
namespace {

std::string valueText(const nlohmann::json& v) {
  if (v.is_string()) return v.get<std::string>();
  if (v.is_number_float()) return formatNumber(v.get<double>());
  return v.dump();
}

/// "key old → new" for one changed key, "key and N more" for several. A key that changed because
/// a key extending it did (`material`'s name gains its mark when `material.eta` changes) is the
/// consequence, not the edit, and is not named.
std::string describe(const nlohmann::json& before, const nlohmann::json& after) {
  std::vector<std::string> changed;
  for (auto it = after.begin(); it != after.end(); ++it)
    if (!before.contains(it.key()) || before.at(it.key()) != it.value()) changed.push_back(it.key());
  std::vector<std::string> keys;
  for (const std::string& k : changed)
    if (std::none_of(changed.begin(), changed.end(), [&](const std::string& o) { return o.rfind(k + ".", 0) == 0; }))
      keys.push_back(k);
  if (keys.empty()) return "";
  if (keys.size() == 1) return keys[0] + " " + valueText(before.value(keys[0], nlohmann::json())) + " → " + valueText(after[keys[0]]);
  return keys[0] + " and " + std::to_string(keys.size() - 1) + " more";
}

}  // namespace

bool isCameraKey(const std::string& key) { return key.rfind("camera.", 0) == 0; }

EditHistory::EditHistory(const Registry& registry, const Config& start)
    : registry_(registry), committed_(start), committedValues_(editable(start)) {}

nlohmann::json EditHistory::editable(const Config& config) const {
  nlohmann::json values = registry_.snapshot(config);
  for (auto it = values.begin(); it != values.end();)
    it = isCameraKey(it.key()) ? values.erase(it) : std::next(it);
  return values;
}

bool EditHistory::commit(const Config& now) {
  nlohmann::json values = editable(now);
  if (values == committedValues_) {
    committed_ = now;  // the camera may have moved: the next step starts from here
    return false;
  }
  steps_.resize(position_);
  Step step{committed_, now, describe(committedValues_, values)};
  steps_.push_back(std::move(step));
  if (steps_.size() > kMaxSteps) steps_.erase(steps_.begin());
  position_ = steps_.size();
  committed_ = now;
  committedValues_ = std::move(values);
  return true;
}

std::optional<Config> EditHistory::undo(const Config& now) {
  if (!canUndo()) return std::nullopt;
  Config restored = steps_[--position_].before;
  restored.scene.camera = now.scene.camera;
  committed_ = restored;
  committedValues_ = editable(restored);
  return restored;
}

std::optional<Config> EditHistory::redo(const Config& now) {
  if (!canRedo()) return std::nullopt;
  Config restored = steps_[position_++].after;
  restored.scene.camera = now.scene.camera;
  committed_ = restored;
  committedValues_ = editable(restored);
  return restored;
}

std::string EditHistory::undoLabel() const { return canUndo() ? steps_[position_ - 1].label : ""; }
std::string EditHistory::redoLabel() const { return canRedo() ? steps_[position_].label : ""; }

}  // namespace tallow::app
