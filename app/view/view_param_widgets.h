#pragma once
// The registry's parameters as Dear ImGui widgets (the view window's "Parameters" section), so a
// parameter added to app/config/params.cpp appears in the panel with no panel code: grouped by the key's
// prefix ("sss.maps" → sss), one widget chosen from the type — enum: combo; bool: checkbox; int and
// float: slider (logarithmic over wide positive ranges) or drag box; vec3: three of them — labelled
// with its name and unit ("map_size [texels]"), with the help, range and default as tooltip, and a
// right-click menu that resets it to its default (or the preset's value, where the preset sets it).
// Edits go through a caller-given setter (the registry's set); a refused value is not applied and
// its one-line message stays under the widget until the next accepted edit of that parameter.
#include <nlohmann/json.hpp>

#include <functional>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "app/config/config.h"
#include "app/config/registry.h"

namespace tallow::app {

/// The panel's group of a key: the part before the first dot; a key without a dot joins the group
/// of its own name when other keys extend it ("material" with "material.eta"), else "general".
std::string paramGroup(const std::string& key, const std::vector<std::string>& keys);

/// Which widget a parameter gets (exposed for the tests of the choice).
enum class ParamWidget { Checkbox, Combo, Slider, LogSlider, Drag };
ParamWidget paramWidget(const Registry::Param& param);

/// The widget's label: the key without its group, and the unit in brackets when it has one that
/// does not just repeat the name ("maps", "map_size [texels]", "sigma_a [mm⁻¹]").
std::string paramLabel(const Registry::Param& param, const std::string& group);

/// The value an "auto" parameter takes when its checkbox is cleared: what the renderer chose, else
/// Param::autoOffValue; within the parameter's range.
std::int64_t autoOffValue(const Registry::Param& param, std::optional<std::int64_t> chosen);

class ParamWidgets {
 public:
  /// Returns "" or the refusal of setting `key` to `value`.
  using Setter = std::function<std::string(const std::string& key, const nlohmann::json& value)>;
  /// What the renderer chose for an int parameter now "auto" (nothing: not known).
  using AutoChoice = std::function<std::optional<std::int64_t>(const std::string& key)>;

  /// Draws every parameter of `registry` with its value in `config` (inside an ImGui window);
  /// `presetValues` (a registry snapshot) is what resetting a parameter without a default restores;
  /// `autoChoice`: shown beside an "auto" and kept when it is unticked (else Param::autoOffValue).
  void draw(const Registry& registry, const Config& config, const nlohmann::json& presetValues, const Setter& set,
            const AutoChoice& autoChoice = {});

 private:
  void drawParam(const Registry::Param& p, const nlohmann::json& value, const nlohmann::json& presetValue,
                 const std::string& label, const Setter& set, const AutoChoice& autoChoice);
  void resetMenu(const Registry::Param& p, const nlohmann::json& value, const nlohmann::json& presetValue,
                 const Setter& set);
  void apply(const Registry::Param& p, const nlohmann::json& value, const Setter& set);

  std::map<std::string, std::string> errors_;   ///< refusals on show, by key
  std::map<std::string, int> pendingInts_;      ///< integers being dragged (applied on release)
  std::map<std::string, std::string> filters_;  ///< text filters of long combos
};

}  // namespace tallow::app
