#include "app/view/view_param_widgets.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cctype>
#include <cmath>

namespace tallow::app {

namespace {

using json = nlohmann::json;

// Widget choice (ParamWidget): linear sliders over spans a slider can resolve, logarithmic ones over
// positive ranges spanning decades, drag boxes for the rest (coordinates, counts from 0).
constexpr double kMaxLinearIntSpan = 1024;
constexpr double kMaxLinearFloatSpan = 200;
constexpr double kMinLogRatio = 100;
/// Long choice lists (the materials) get a text filter in their combo.
constexpr std::size_t kFilterChoices = 12;
/// Drag speed of float drag boxes: this fraction of the value per pixel, at least kMinDragSpeed.
constexpr float kDragFraction = 0.005f;
constexpr float kMinDragSpeed = 1e-4f;
const ImVec4 kErrorColour{1.0f, 0.35f, 0.3f, 1.0f};

bool containsNoCase(const std::string& text, const std::string& part) {
  const auto lower = [](std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
  };
  return lower(text).find(lower(part)) != std::string::npos;
}

void tooltip(const Registry::Param& p) {
  if (!ImGui::IsItemHovered()) return;
  ImGui::BeginTooltip();
  ImGui::PushTextWrapPos(ImGui::GetFontSize() * 30.0f);
  ImGui::TextUnformatted(p.key.c_str());
  ImGui::Separator();
  ImGui::TextUnformatted(p.help.c_str());
  if (!p.units.empty()) ImGui::Text("units: %s", p.units.c_str());
  if (p.type == "int" || p.type == "float" || p.type == "vec3")
    ImGui::Text("range: [%s, %s]", formatNumber(p.min).c_str(), formatNumber(p.max).c_str());
  ImGui::Text("default: %s", p.defaultValue ? p.defaultValue->dump().c_str() : "the preset's");
  ImGui::TextDisabled("right-click: reset");
  ImGui::PopTextWrapPos();
  ImGui::EndTooltip();
}

}  // namespace

std::string paramGroup(const std::string& key, const std::vector<std::string>& keys) {
  const std::size_t dot = key.find('.');
  if (dot != std::string::npos) return key.substr(0, dot);
  for (const std::string& k : keys)
    if (k.size() > key.size() && k.compare(0, key.size(), key) == 0 && k[key.size()] == '.') return key;
  return "general";
}

std::string paramLabel(const Registry::Param& p, const std::string& group) {
  std::string label = p.key.size() > group.size() && p.key.compare(0, group.size() + 1, group + ".") == 0
                          ? p.key.substr(group.size() + 1)
                          : p.key;
  // A count's unit that repeats its name ("maps [maps]") says nothing.
  const std::string last = p.key.substr(p.key.rfind('.') == std::string::npos ? 0 : p.key.rfind('.') + 1);
  if (!p.units.empty() && p.units != last) label += " [" + p.units + "]";
  return label;
}

ParamWidget paramWidget(const Registry::Param& p) {
  if (p.type == "bool") return ParamWidget::Checkbox;
  if (p.type == "enum") return ParamWidget::Combo;
  const double span = p.max - p.min;
  if (span <= (p.type == "int" ? kMaxLinearIntSpan : kMaxLinearFloatSpan)) return ParamWidget::Slider;
  if (p.min > 0.0 && p.max / p.min >= kMinLogRatio) return ParamWidget::LogSlider;
  return ParamWidget::Drag;
}

void ParamWidgets::apply(const Registry::Param& p, const json& value, const Setter& set) {
  const std::string refused = set(p.key, value);
  if (refused.empty()) errors_.erase(p.key);
  else errors_[p.key] = refused;
}

void ParamWidgets::resetMenu(const Registry::Param& p, const json& value, const json& presetValue, const Setter& set) {
  if (!ImGui::BeginPopupContextItem("reset")) return;
  const auto item = [&](const char* what, const json& target) {
    if (target.is_null()) return;
    const std::string text = std::string(what) + ": " + (target.is_string() ? target.get<std::string>() : target.dump());
    if (ImGui::MenuItem(text.c_str(), nullptr, false, target != value)) apply(p, target, set);
  };
  if (p.defaultValue) item("reset to default", *p.defaultValue);
  if (!p.defaultValue || presetValue != *p.defaultValue) item("reset to the preset's value", presetValue);
  ImGui::EndPopup();
}

std::int64_t autoOffValue(const Registry::Param& param, std::optional<std::int64_t> chosen) {
  const double value = chosen ? static_cast<double>(*chosen) : param.autoOffValue;
  return static_cast<std::int64_t>(std::clamp(value, param.min, param.max));
}

void ParamWidgets::draw(const Registry& registry, const Config& config, const json& presetValues, const Setter& set,
                        const AutoChoice& autoChoice) {
  const std::vector<std::string> keys = registry.keys();
  std::vector<std::string> groups;
  for (const std::string& k : keys) {
    const std::string g = paramGroup(k, keys);
    if (std::find(groups.begin(), groups.end(), g) == groups.end()) groups.push_back(g);
  }
  const json values = registry.snapshot(config);
  for (const std::string& group : groups) {
    ImGui::PushID(group.c_str());
    const bool open = ImGui::TreeNodeEx(group.c_str(), group == "general" || group == "sss" ? ImGuiTreeNodeFlags_DefaultOpen : 0);
    if (open) {
      for (const Registry::Param& p : registry.params()) {
        if (paramGroup(p.key, keys) != group) continue;
        drawParam(p, values.at(p.key), presetValues.value(p.key, json()), paramLabel(p, group), set, autoChoice);
      }
      ImGui::TreePop();
    }
    ImGui::PopID();
  }
}

void ParamWidgets::drawParam(const Registry::Param& p, const json& value, const json& presetValue,
                             const std::string& label, const Setter& set, const AutoChoice& autoChoice) {
  ImGui::PushID(p.key.c_str());
  if (value.is_null()) {
    ImGui::TextDisabled("%s: not in this scene", label.c_str());
    tooltip(p);
    ImGui::PopID();
    return;
  }
  const ParamWidget widget = paramWidget(p);
  const char* name = label.c_str();
  if (p.type == "bool") {
    bool v = value.get<bool>();
    if (ImGui::Checkbox(name, &v)) apply(p, v, set);
    tooltip(p);
  } else if (p.type == "enum") {
    const std::string current = value.get<std::string>();
    if (ImGui::BeginCombo(name, current.c_str(), ImGuiComboFlags_HeightLarge)) {
      std::string& filter = filters_[p.key];
      if (p.choices.size() > kFilterChoices) {
        if (ImGui::IsWindowAppearing()) ImGui::SetKeyboardFocusHere();
        ImGui::InputTextWithHint("##filter", "filter", &filter);
      }
      for (const std::string& choice : p.choices) {
        if (!filter.empty() && !containsNoCase(choice, filter)) continue;
        const bool selected = choice == current;
        if (ImGui::Selectable(choice.c_str(), selected) && !selected) apply(p, choice, set);
        if (selected) ImGui::SetItemDefaultFocus();
      }
      ImGui::EndCombo();
    }
    tooltip(p);
  } else if (p.type == "int" && p.acceptsAuto && value.is_string()) {
    // "auto": the renderer chooses (shown beside it); clearing the checkbox keeps that choice as a
    // number to edit, so the picture does not change (Param::autoOffValue when nothing is chosen yet).
    const std::optional<std::int64_t> chosen = autoChoice ? autoChoice(p.key) : std::nullopt;
    const std::string shown = label + ": auto" + (chosen ? " (" + std::to_string(*chosen) + ")" : std::string());
    bool automatic = true;
    if (ImGui::Checkbox((shown + "###" + p.key).c_str(), &automatic) && !automatic)
      apply(p, autoOffValue(p, chosen), set);
    tooltip(p);
  } else if (p.type == "int") {
    // Applied when the drag ends: each new integer may reallocate textures or restart the maps.
    if (p.acceptsAuto) {
      bool automatic = false;
      if (ImGui::Checkbox(("auto##" + p.key).c_str(), &automatic) && automatic) apply(p, "auto", set);
      ImGui::SameLine();
    }
    const auto pending = pendingInts_.find(p.key);
    int v = pending != pendingInts_.end() ? pending->second : static_cast<int>(value.get<std::int64_t>());
    const int lo = static_cast<int>(p.min), hi = static_cast<int>(p.max);
    bool changed = false;
    if (widget == ParamWidget::Drag) changed = ImGui::DragInt(name, &v, 1.0f, lo, hi);
    else changed = ImGui::SliderInt(name, &v, lo, hi, "%d", widget == ParamWidget::LogSlider ? ImGuiSliderFlags_Logarithmic : 0);
    if (changed) pendingInts_[p.key] = v;
    if (ImGui::IsItemDeactivatedAfterEdit()) {
      apply(p, v, set);
      pendingInts_.erase(p.key);
    } else if (!ImGui::IsItemActive()) {
      pendingInts_.erase(p.key);
    }
    tooltip(p);
    // Applied on release; meanwhile what the new value would cost (issue 40).
    const int current = value.is_number_integer() ? static_cast<int>(value.get<std::int64_t>()) : 0;
    if (p.costPower > 0 && pendingInts_.count(p.key) && current > 0 && v != current) {
      const double ratio = std::pow(static_cast<double>(v) / current, p.costPower);
      ImGui::TextColored(ratio > 2.0 ? ImVec4(1.0f, 0.6f, 0.3f, 1.0f) : ImVec4(0.7f, 0.7f, 0.7f, 1.0f),
                         "on release: about %.2gx the work of the passes it feeds", ratio);
    }
  } else if (p.type == "float") {
    float v = value.get<float>();
    const float lo = static_cast<float>(p.min), hi = static_cast<float>(p.max);
    bool changed = false;
    if (widget == ParamWidget::Drag)
      changed = ImGui::DragFloat(name, &v, std::max(std::abs(v) * kDragFraction, kMinDragSpeed), lo, hi, "%.4g");
    else
      changed = ImGui::SliderFloat(name, &v, lo, hi, "%.4g",
                                   widget == ParamWidget::LogSlider ? ImGuiSliderFlags_Logarithmic : 0);
    if (changed) apply(p, floatToJson(v), set);
    tooltip(p);
  } else {  // vec3
    float v[3] = {value[0].get<float>(), value[1].get<float>(), value[2].get<float>()};
    const float lo = static_cast<float>(p.min), hi = static_cast<float>(p.max);
    bool changed = false;
    if (widget == ParamWidget::Slider) {
      changed = ImGui::SliderFloat3(name, v, lo, hi, "%.3f");
    } else {
      const float largest = std::max({std::abs(v[0]), std::abs(v[1]), std::abs(v[2])});
      changed = ImGui::DragFloat3(name, v, std::max(largest * kDragFraction, kMinDragSpeed), lo, hi, "%.4g");
    }
    if (changed) apply(p, json::array({floatToJson(v[0]), floatToJson(v[1]), floatToJson(v[2])}), set);
    tooltip(p);
  }
  resetMenu(p, value, presetValue, set);  // on the widget just drawn (the last item)
  if (const auto e = errors_.find(p.key); e != errors_.end()) {
    ImGui::PushStyleColor(ImGuiCol_Text, kErrorColour);
    ImGui::TextWrapped("%s", e->second.c_str());
    ImGui::PopStyleColor();
  }
  ImGui::PopID();
}

}  // namespace tallow::app
