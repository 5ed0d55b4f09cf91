#include "app/view/view_panel.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <filesystem>
#include <limits>

#include "app/config/setup.h"
#include "sss/debug_view_pass.h"
#include "sss/maps/radiosity_maps.h"

namespace tallow::app {

namespace {

/// Frames in the rolling timing graph.
constexpr std::size_t kHistory = 240;
/// The panel's share of the window width, and its bounds in pixels.
constexpr float kPanelShare = 0.4f;
constexpr float kPanelMaxWidth = 430.0f;
constexpr float kPanelAlpha = 0.88f;
constexpr float kGraphHeight = 90.0f;
const ImVec4 kErrorColour{1.0f, 0.35f, 0.3f, 1.0f};
const ImVec4 kOkColour{0.5f, 0.9f, 0.5f, 1.0f};
/// Distinct colours for the passes' lines (cycled).
const ImU32 kPassColours[] = {IM_COL32(230, 159, 0, 255),  IM_COL32(86, 180, 233, 255), IM_COL32(0, 158, 115, 255),
                              IM_COL32(240, 228, 66, 255), IM_COL32(0, 114, 178, 255),  IM_COL32(213, 94, 0, 255),
                              IM_COL32(204, 121, 167, 255), IM_COL32(200, 200, 200, 255)};
constexpr float kSpeedMin = 0.05f, kSpeedMax = 8.0f;

std::vector<std::string> presetNames() {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(presetDir(), ec))
    if (entry.path().extension() == ".json") names.push_back(entry.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

void statusLine(const std::string& text, bool error) {
  if (text.empty()) return;
  ImGui::PushStyleColor(ImGuiCol_Text, error ? kErrorColour : kOkColour);
  ImGui::TextWrapped("%s", text.c_str());
  ImGui::PopStyleColor();
}

std::string megabytes(std::size_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f MiB", static_cast<double>(bytes) / (1024.0 * 1024.0));
  return text;
}

}  // namespace

void ViewPanel::record(const ViewSession::Frame& frame) {
  for (const auto& pass : frame.gpu.passes)
    if (!history_.count(pass.name)) {
      passNames_.push_back(pass.name);
      history_[pass.name] = std::deque<float>(wallHistory_.size(), std::numeric_limits<float>::quiet_NaN());
    }
  for (auto& [name, values] : history_) {
    float ms = std::numeric_limits<float>::quiet_NaN();
    for (const auto& pass : frame.gpu.passes)
      if (pass.name == name) ms = static_cast<float>(pass.gpuMs);
    values.push_back(ms);
    if (values.size() > kHistory) values.pop_front();
  }
  wallHistory_.push_back(static_cast<float>(frame.wallMs));
  if (wallHistory_.size() > kHistory) wallHistory_.pop_front();
}

std::string ViewPanel::draw(ViewSession& session, sss::DebugView& debug, const ViewFeedback& feedback,
                            ViewRequests& requests, int width, int height) {
  const float panelWidth = std::min(kPanelMaxWidth, kPanelShare * static_cast<float>(width));
  ImGui::SetNextWindowPos(ImVec2(0, 0), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(panelWidth, static_cast<float>(height)), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowBgAlpha(kPanelAlpha);
  std::string status;
  const bool open = ImGui::Begin("Tallow");
  // A panel against the left edge covers the window up to its right edge.
  const ImVec2 pos = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
  coveredLeft_ = open && pos.x <= 1.0f ? static_cast<int>(pos.x + size.x) : 0;
  if (open) {
    ImGui::PushItemWidth(-ImGui::GetFontSize() * 8.0f);  // room for the labels
    status = drawPreset(session);
    if (ImGui::CollapsingHeader("Playback and camera", ImGuiTreeNodeFlags_DefaultOpen)) drawPlayback(session);
    if (ImGui::CollapsingHeader("Feedback", ImGuiTreeNodeFlags_DefaultOpen)) drawFeedback(session, feedback);
    if (ImGui::CollapsingHeader("Debug view")) drawDebugView(session, debug, feedback);
    if (ImGui::CollapsingHeader("Save")) drawSave(session, requests);
    statusLine(feedback.status, feedback.statusIsError);
    if (ImGui::CollapsingHeader("Parameters", ImGuiTreeNodeFlags_DefaultOpen))
      params_.draw(session.registry(), session.config(),
                   [&session](const std::string& key, const nlohmann::json& value) { return session.set(key, value); });
    ImGui::PopItemWidth();
  }
  ImGui::End();
  return status;
}

std::string ViewPanel::drawPreset(ViewSession& session) {
  std::string status;
  const std::string current = session.presetName();
  if (ImGui::BeginCombo("preset", current.c_str())) {
    for (const std::string& name : presetNames()) {
      const bool selected = name == current;
      if (ImGui::Selectable(name.c_str(), selected) && !selected) status = session.loadPreset(name);
      if (selected) ImGui::SetItemDefaultFocus();
    }
    ImGui::EndCombo();
  }
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", session.presetPath().string().c_str());
  ImGui::SameLine();
  if (ImGui::SmallButton("reload")) status = session.loadPreset(session.presetPath().string());
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("read the preset file again (after editing it)");
  return status;
}

void ViewPanel::drawPlayback(ViewSession& session) {
  Playback& clock = session.playback();
  if (ImGui::Button(clock.playing() ? "pause" : "play ")) clock.playing() ? clock.pause() : clock.play();
  ImGui::SameLine();
  bool loop = clock.loop();
  if (ImGui::Checkbox("loop", &loop)) clock.setLoop(loop);
  ImGui::SameLine();
  if (ImGui::Button("reset camera")) session.resetCamera();
  float t = static_cast<float>(clock.time());
  if (clock.durationS() > 0.0) {
    if (ImGui::SliderFloat("time [s]", &t, 0.0f, static_cast<float>(clock.durationS()), "%.2f")) clock.seek(t);
  } else {
    ImGui::Text("time %.2f s (static scene)", t);
  }
  float speed = static_cast<float>(clock.speed());
  if (ImGui::SliderFloat("speed", &speed, kSpeedMin, kSpeedMax, "%.2fx", ImGuiSliderFlags_Logarithmic))
    clock.setSpeed(speed);
  ImGui::TextDisabled("mouse: left drag orbits, right drag pans, wheel zooms");
}

void ViewPanel::drawFeedback(const ViewSession& session, const ViewFeedback& feedback) {
  const ViewSession::Frame& f = feedback.frame;
  ImGui::Text("wall %.1f ms (%.3g fps)   GPU %.1f ms", f.wallMs, f.wallMs > 0.0 ? 1000.0 / f.wallMs : 0.0,
              f.gpu.gpuTotalMs);
  drawTimingGraph();
  const sss::RadiosityMaps* maps = session.renderer().radiosityMaps();
  if (maps && sss::RadiosityMaps::applies(session.config().scene, session.config().render))
    ImGui::Text("maps: K %zu, %d of %d frames accumulated", maps->views().size(), maps->frames(),
                session.config().render.sss.frames);
  ImGui::Text("GPU memory %s   triangles %zu", megabytes(session.renderer().gpuBytes()).c_str(), feedback.triangles);
  if (!f.refused.empty()) statusLine("refused: " + f.refused, true);
  if (ImGui::TreeNode("frame plan")) {
    const Config& c = session.config();
    for (const sss::PlannedPass& p : session.renderer().planFrame(c.scene, c.render, session.playback().time())) {
      ImGui::BulletText("%s", p.name.c_str());
      ImGui::SameLine();
      ImGui::TextDisabled("(?)");
      if (ImGui::IsItemHovered()) {
        ImGui::BeginTooltip();
        ImGui::PushTextWrapPos(ImGui::GetFontSize() * 30.0f);
        ImGui::TextUnformatted(p.reason.c_str());
        ImGui::PopTextWrapPos();
        ImGui::EndTooltip();
      }
    }
    ImGui::TreePop();
  }
}

void ViewPanel::drawTimingGraph() {
  // One line per pass, GPU ms against frames, over a shared scale; the legend gives the last value.
  float top = 0.0f;
  for (const auto& [name, values] : history_)
    for (float v : values)
      if (std::isfinite(v)) top = std::max(top, v);
  top = std::max(top * 1.1f, 0.1f);
  ImDrawList* draw = ImGui::GetWindowDrawList();
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  const float w = std::max(ImGui::GetContentRegionAvail().x, 50.0f);
  draw->AddRectFilled(origin, ImVec2(origin.x + w, origin.y + kGraphHeight), IM_COL32(20, 20, 24, 255));
  const float step = w / static_cast<float>(kHistory - 1);
  for (std::size_t i = 0; i < passNames_.size(); ++i) {
    const std::deque<float>& values = history_[passNames_[i]];
    const ImU32 colour = kPassColours[i % std::size(kPassColours)];
    const float x0 = origin.x + w - step * static_cast<float>(values.size() - 1);
    for (std::size_t j = 1; j < values.size(); ++j) {
      if (!std::isfinite(values[j - 1]) || !std::isfinite(values[j])) continue;
      const auto y = [&](float v) { return origin.y + kGraphHeight * (1.0f - v / top); };
      draw->AddLine(ImVec2(x0 + step * static_cast<float>(j - 1), y(values[j - 1])),
                    ImVec2(x0 + step * static_cast<float>(j), y(values[j])), colour, 1.5f);
    }
  }
  char scale[32];
  std::snprintf(scale, sizeof scale, "%.3g ms", top);
  draw->AddText(ImVec2(origin.x + 4, origin.y + 2), IM_COL32(200, 200, 200, 255), scale);
  ImGui::Dummy(ImVec2(w, kGraphHeight));
  for (std::size_t i = 0; i < passNames_.size(); ++i) {
    const std::deque<float>& values = history_[passNames_[i]];
    const float last = values.empty() ? std::numeric_limits<float>::quiet_NaN() : values.back();
    const ImVec4 c = ImGui::ColorConvertU32ToFloat4(kPassColours[i % std::size(kPassColours)]);
    ImGui::TextColored(c, "%-20s", passNames_[i].c_str());
    ImGui::SameLine();
    if (std::isfinite(last)) ImGui::Text("%7.2f ms", last);
    else ImGui::TextDisabled("   (not run)");
  }
}

void ViewPanel::drawDebugView(const ViewSession& session, sss::DebugView& debug, const ViewFeedback& feedback) {
  const auto& names = sss::debugViewNames();
  int kind = static_cast<int>(debug.kind);
  if (ImGui::BeginCombo("view", names[static_cast<std::size_t>(kind)].c_str())) {
    for (std::size_t i = 0; i < names.size(); ++i)
      if (ImGui::Selectable(names[i].c_str(), static_cast<int>(i) == kind)) debug.kind = static_cast<sss::DebugViewKind>(i);
    ImGui::EndCombo();
  }
  const sss::Scene& scene = session.config().scene;
  if (debug.kind == sss::DebugViewKind::GBufferPosition || debug.kind == sss::DebugViewKind::GBufferNormal) {
    const int lights = static_cast<int>(scene.lights.size());
    if (lights > 0) {
      ImGui::SliderInt("light", &debug.light, 0, lights - 1);
      debug.light = std::clamp(debug.light, 0, lights - 1);
      const auto layer = sss::DebugViewPass::lightLayer(scene, debug.light);
      if (layer && layer->cube) ImGui::SliderInt("cube face", &debug.layer, 0, 5);
    }
  } else if (debug.kind == sss::DebugViewKind::Map) {
    const sss::RadiosityMaps* maps = session.renderer().radiosityMaps();
    const int k = maps ? maps->maps().depth() : 0;
    if (k > 0) {
      ImGui::SliderInt("map k", &debug.layer, 0, k - 1);
      debug.layer = std::clamp(debug.layer, 0, k - 1);
    }
  }
  if (debug.kind == sss::DebugViewKind::Map || debug.kind == sss::DebugViewKind::Difference)
    ImGui::SliderFloat("exposure [EV]", &debug.exposureEv, -10.0f, 10.0f, "%.1f");
  statusLine(feedback.debugNote, true);
}

void ViewPanel::drawSave(const ViewSession& session, ViewRequests& requests) {
  if (savedFor_ != session.presetName()) {
    saveBase_ = "tallow-" + session.presetName();
    savedFor_ = session.presetName();
  }
  ImGui::InputText("file", &saveBase_);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("path without extension; .png, .exr or .json is added");
  if (ImGui::Button("PNG")) requests.screenshots.push_back(saveBase_ + ".png");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("the window as shown, panel included");
  ImGui::SameLine();
  if (ImGui::Button("EXR")) requests.screenshots.push_back(saveBase_ + ".exr");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("the linear radiance of the image");
  ImGui::SameLine();
  if (ImGui::Button("preset")) requests.presets.push_back(saveBase_ + ".json");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("a preset that `tallow capture --preset FILE` renders as shown");
}

}  // namespace tallow::app
