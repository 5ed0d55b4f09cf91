#include "app/view/view_panel.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>

#include "app/commands/progress.h"
#include "app/config/setup.h"
#include "app/playback/hotkeys.h"
#include "app/view/numbered_file.h"
#include "sss/debug_view_pass.h"
#include "sss/maps/radiosity_maps.h"

namespace tallow::app {

namespace {

/// The timing graph shows the frames of the last kGraphSeconds, on a log scale of at least one
/// decade: one slow frame (a restart of the maps, 13 s on llvmpipe) takes a decade at the top
/// instead of flattening every other frame onto the axis.
constexpr double kGraphSeconds = 10.0;
constexpr float kGraphHeight = 110.0f;
/// The scale's floor: faster passes (timer noise, a pass that did nothing) sit on the axis. At most
/// kGraphDecades decades are shown, down from the slowest value's.
constexpr double kGraphFloorMs = 1e-3;
constexpr double kGraphDecades = 4.0;
const ImVec4 kErrorColour{1.0f, 0.35f, 0.3f, 1.0f};
const ImVec4 kOkColour{0.5f, 0.9f, 0.5f, 1.0f};
/// Distinct colours for the passes' lines (cycled; Okabe and Ito's palette), and the frame's wall time.
const ImU32 kPassColours[] = {IM_COL32(230, 159, 0, 255),  IM_COL32(86, 180, 233, 255), IM_COL32(0, 158, 115, 255),
                              IM_COL32(240, 228, 66, 255), IM_COL32(0, 114, 178, 255),  IM_COL32(213, 94, 0, 255),
                              IM_COL32(204, 121, 167, 255), IM_COL32(200, 200, 200, 255)};
const ImU32 kWallColour = IM_COL32(255, 255, 255, 255);
constexpr float kSpeedMin = 0.05f, kSpeedMax = 8.0f;

double steadySeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

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

void hoverText(const char* text) {
  if (!ImGui::IsItemHovered()) return;
  ImGui::BeginTooltip();
  ImGui::PushTextWrapPos(ImGui::GetFontSize() * 30.0f);
  ImGui::TextUnformatted(text);
  ImGui::PopTextWrapPos();
  ImGui::EndTooltip();
}

std::string megabytes(std::size_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f MiB", static_cast<double>(bytes) / (1024.0 * 1024.0));
  return text;
}

std::string millisecondsText(double ms) {
  char text[32];
  if (ms >= 1000.0) std::snprintf(text, sizeof text, "%g s", ms / 1000.0);
  else std::snprintf(text, sizeof text, "%g ms", ms);
  return text;
}

}  // namespace

std::string AccumulationProgress::text() const {
  std::string t = "accumulating " + std::to_string(done) + " of " + std::to_string(total) + " frames";
  if (secondsLeft >= 0.0) t += ", about " + formatDuration(secondsLeft) + " left";
  return t;
}

std::optional<AccumulationProgress> accumulationProgress(const ViewSession& session, double frameMs) {
  const RenderSummary& r = session.summary();
  const Config& c = session.config();
  if (!r.hasMaps || !sss::RadiosityMaps::applies(c.scene, c.render) || r.mapFrames >= c.render.sss.frames)
    return std::nullopt;
  AccumulationProgress p;
  p.done = r.mapFrames;
  p.total = c.render.sss.frames;
  if (frameMs > 0.0) p.secondsLeft = (p.total - p.done) * frameMs / 1000.0;
  return p;
}

std::string defaultSaveBase(const std::string& presetName) { return "tallow-" + presetName; }

void ViewPanel::record(const ViewSession::Frame& frame) {
  const double now = steadySeconds();
  // GPU times of the newest frame the GPU has finished (a frame or two behind: nothing waits).
  for (const auto& pass : frame.shown.passes)
    if (!history_.count(pass.name)) {
      passNames_.push_back(pass.name);
      history_[pass.name] = std::deque<float>(times_.size(), std::numeric_limits<float>::quiet_NaN());
    }
  for (auto& [name, values] : history_) {
    float ms = std::numeric_limits<float>::quiet_NaN();
    for (const auto& pass : frame.shown.passes)
      if (pass.name == name) ms = static_cast<float>(pass.gpuMs);
    values.push_back(ms);
  }
  times_.push_back(now);
  wallHistory_.push_back(static_cast<float>(frame.wallMs));
  // Older frames than the graph shows go; two stay, so that a slow frame rate still draws a line.
  while (times_.size() > 2 && now - times_.front() > kGraphSeconds) {
    times_.pop_front();
    wallHistory_.pop_front();
    for (auto& [name, values] : history_) values.pop_front();
  }
}

std::string ViewPanel::draw(ViewSession& session, sss::DebugView& debug, const ViewFeedback& feedback,
                            ViewRequests& requests, int width, int height) {
  // Pinned to the left edge at the window's height; only its right edge moves (dragged).
  const ImVec2 scale = ImGui::GetIO().DisplayFramebufferScale;
  const float displayW = static_cast<float>(width) / std::max(scale.x, 1e-3f);
  const float displayH = static_cast<float>(height) / std::max(scale.y, 1e-3f);
  const float maxW = std::max(kMinWidth, kMaxShare * displayW);
  ImGui::SetNextWindowPos(ImVec2(0, 0), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(std::min(kDefaultWidth, maxW), displayH), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSizeConstraints(ImVec2(kMinWidth, displayH), ImVec2(maxW, displayH));
  std::string status;
  ImGui::Begin("Tallow (F1 hides the panel)", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoSavedSettings);
  width_ = static_cast<int>(std::lround(ImGui::GetWindowSize().x * scale.x));
  ImGui::PushItemWidth(-ImGui::GetFontSize() * 11.0f);  // room for the labels with their units
  // What the picture is waiting for, first: the accumulation's progress with the time left.
  if (const std::optional<AccumulationProgress> p = accumulationProgress(session, feedback.frame.wallMs)) {
    ImGui::ProgressBar(static_cast<float>(p->done) / static_cast<float>(std::max(p->total, 1)), ImVec2(-1.0f, 0.0f),
                       p->text().c_str());
    if (feedback.preview) ImGui::TextDisabled("preview while you move: accumulation resumes when you stop");
  }
  status = drawPreset(session);
  if (ImGui::CollapsingHeader("Playback and camera", ImGuiTreeNodeFlags_DefaultOpen))
    drawPlayback(session, requests, feedback);
  if (ImGui::CollapsingHeader("Feedback", ImGuiTreeNodeFlags_DefaultOpen)) drawFeedback(session, feedback);
  if (ImGui::CollapsingHeader("Debug view")) drawDebugView(session, debug, feedback);
  if (ImGui::CollapsingHeader("Save")) drawSave(session, requests);
  if (ImGui::CollapsingHeader("Hotkeys")) {
    for (const Hotkey k : allHotkeys()) {
      ImGui::Text("%-8s", std::string(hotkeyName(k)).c_str());
      ImGui::SameLine();
      ImGui::TextDisabled("%s", std::string(hotkeyHelp(k)).c_str());
    }
  }
  statusLine(feedback.status, feedback.statusIsError);
  if (ImGui::CollapsingHeader("Parameters", ImGuiTreeNodeFlags_DefaultOpen))
    params_.draw(
        session.registry(), session.config(), session.presetValues(),
        [&session](const std::string& key, const nlohmann::json& value) { return session.set(key, value); },
        [&session](const std::string& key) { return session.autoChoice(key); });
  ImGui::PopItemWidth();
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
  hoverText("read the preset file again (after editing it)");
  return status;
}

void ViewPanel::drawPlayback(ViewSession& session, ViewRequests& requests, const ViewFeedback& feedback) {
  const double stepFps = feedback.stepFps;
  Playback& clock = session.playback();
  if (ImGui::Button(clock.playing() ? "pause" : "play ")) clock.playing() ? clock.pause() : clock.play();
  hoverText("Space");
  ImGui::SameLine();
  if (ImGui::ArrowButton("##back", ImGuiDir_Left)) {
    clock.pause();
    clock.seek(clock.time() - 1.0 / stepFps);
  }
  hoverText("one frame back (←)");
  ImGui::SameLine();
  if (ImGui::ArrowButton("##on", ImGuiDir_Right)) {
    clock.pause();
    clock.seek(clock.time() + 1.0 / stepFps);
  }
  hoverText("one frame on (→)");
  ImGui::SameLine();
  bool loop = clock.loop();
  if (ImGui::Checkbox("loop", &loop)) clock.setLoop(loop);
  ImGui::SameLine();
  if (ImGui::Button("reset camera")) session.resetCamera();
  hoverText("R: back to the preset's camera");
  float t = static_cast<float>(clock.time());
  if (clock.durationS() > 0.0) {
    if (ImGui::SliderFloat("time [s]", &t, 0.0f, static_cast<float>(clock.durationS()), "%.2f")) clock.seek(t);
  } else {
    ImGui::Text("time %.2f s (static scene)", t);
  }
  float speed = static_cast<float>(clock.speed());
  if (ImGui::SliderFloat("speed", &speed, kSpeedMin, kSpeedMax, "%.2fx", ImGuiSliderFlags_Logarithmic))
    clock.setSpeed(speed);
  if (clock.playing() && feedback.realTimeShare < 1.0) {
    ImGui::TextColored(ImVec4(1.0f, 0.75f, 0.3f, 1.0f), "behind real time: playing at %.2gx", feedback.realTimeShare);
    hoverText("each frame takes longer than --max-step, so the clock moves by that much per frame: "
              "a slow machine plays slower instead of skipping (--max-step 0 follows wall time)");
  }
  ImGui::TextDisabled("mouse: left drag orbits, right drag pans, wheel zooms");

  const EditHistory& history = session.history();
  ImGui::BeginDisabled(!history.canUndo());
  if (ImGui::Button("undo")) requests.undo = true;
  ImGui::EndDisabled();
  hoverText(history.canUndo() ? ("Ctrl-Z: " + history.undoLabel()).c_str() : "Ctrl-Z: nothing to undo");
  ImGui::SameLine();
  ImGui::BeginDisabled(!history.canRedo());
  if (ImGui::Button("redo")) requests.redo = true;
  ImGui::EndDisabled();
  hoverText(history.canRedo() ? ("Ctrl-Y: " + history.redoLabel()).c_str() : "Ctrl-Y: nothing to redo");
  if (history.canUndo()) {
    ImGui::SameLine();
    ImGui::TextDisabled("%s", history.undoLabel().c_str());
  }
}

void ViewPanel::drawFeedback(const ViewSession& session, const ViewFeedback& feedback) {
  const ViewSession::Frame& f = feedback.frame;
  // No figure before it is measured: the first frame's panel is drawn before that frame renders.
  if (f.wallMs <= 0.0) ImGui::TextDisabled("the first frame is being drawn ...");
  else if (f.shown.gpuKnown())
    ImGui::Text("wall %.1f ms (%.3g fps)   CPU %.1f ms   GPU %.1f ms", f.wallMs, 1000.0 / f.wallMs, f.gpu.cpuTotalMs,
                f.shown.gpuTotalMs);
  else
    ImGui::Text("wall %.1f ms (%.3g fps)   CPU %.1f ms   GPU (not read yet)", f.wallMs, 1000.0 / f.wallMs, f.gpu.cpuTotalMs);
  drawTimingGraph();
  const RenderSummary& r = session.summary();
  if (r.hasMaps && sss::RadiosityMaps::applies(session.config().scene, session.config().render))
    ImGui::Text("maps: K %d, %d of %d frames accumulated", r.maps, r.mapFrames, session.config().render.sss.frames);
  if (feedback.triangles)
    ImGui::Text("GPU memory %s   triangles %zu", megabytes(r.gpuBytes).c_str(), *feedback.triangles);
  else
    ImGui::Text("GPU memory %s   triangles (not counted yet)", megabytes(r.gpuBytes).c_str());
  if (!f.refused.empty()) statusLine("refused: " + f.refused, true);
  if (ImGui::TreeNode("frame plan")) {  // of the frame shown
    for (const sss::PlannedPass& p : r.plan) {
      ImGui::BulletText("%s", p.name.c_str());
      ImGui::SameLine();
      ImGui::TextDisabled("(?)");
      hoverText(p.reason.c_str());
    }
    ImGui::TreePop();
  }
}

void ViewPanel::drawTimingGraph() {
  // One line per pass (GPU ms) and one for the frame's wall time, against the time they were drawn,
  // over the last kGraphSeconds, on a log scale whose decades are labelled.
  double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
  const auto extend = [&](float v) {
    if (std::isfinite(v) && v > 0.0f) {
      lo = std::min(lo, std::max(static_cast<double>(v), kGraphFloorMs));
      hi = std::max(hi, static_cast<double>(v));
    }
  };
  for (float v : wallHistory_) extend(v);
  for (const auto& [name, values] : history_)
    for (float v : values) extend(v);
  if (!(hi > 0.0)) lo = 0.1, hi = 1.0;
  const double decadeHi = std::ceil(std::log10(hi));
  const double decadeLo = std::clamp(std::floor(std::log10(lo)), decadeHi - kGraphDecades, decadeHi - 1.0);
  const double now = times_.empty() ? steadySeconds() : times_.back();

  ImDrawList* draw = ImGui::GetWindowDrawList();
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  const float w = std::max(ImGui::GetContentRegionAvail().x, 50.0f);
  draw->AddRectFilled(origin, ImVec2(origin.x + w, origin.y + kGraphHeight), IM_COL32(20, 20, 24, 255));
  const auto y = [&](float ms) {
    const double d = (std::log10(std::max(static_cast<double>(ms), kGraphFloorMs)) - decadeLo) / (decadeHi - decadeLo);
    return origin.y + kGraphHeight * static_cast<float>(1.0 - std::clamp(d, 0.0, 1.0));
  };
  const auto x = [&](double t) {
    return origin.x + w * static_cast<float>(std::clamp(1.0 - (now - t) / kGraphSeconds, 0.0, 1.0));
  };
  // A line per decade, labelled at the left just below it; the bottom one, the axis, at the right
  // just above it, clear of the label of the decade above.
  for (double d = decadeLo; d <= decadeHi; d += 1.0) {
    const float yy = y(static_cast<float>(std::pow(10.0, d)));
    draw->AddLine(ImVec2(origin.x, yy), ImVec2(origin.x + w, yy), IM_COL32(70, 70, 80, 255));
    const std::string text = millisecondsText(std::pow(10.0, d));
    const ImVec2 at = d == decadeLo ? ImVec2(origin.x + w - ImGui::CalcTextSize(text.c_str()).x - 3.0f,
                                             yy - ImGui::GetFontSize() - 1.0f)
                                    : ImVec2(origin.x + 3.0f, yy + 1.0f);
    draw->AddText(at, IM_COL32(150, 150, 150, 255), text.c_str());
  }
  const auto line = [&](const std::deque<float>& values, ImU32 colour, float thickness) {
    for (std::size_t j = 1; j < values.size() && j < times_.size(); ++j) {
      if (!std::isfinite(values[j - 1]) || !std::isfinite(values[j])) continue;
      draw->AddLine(ImVec2(x(times_[j - 1]), y(values[j - 1])), ImVec2(x(times_[j]), y(values[j])), colour, thickness);
    }
  };
  for (std::size_t i = 0; i < passNames_.size(); ++i)
    line(history_[passNames_[i]], kPassColours[i % std::size(kPassColours)], 1.5f);
  line(wallHistory_, kWallColour, 1.0f);
  ImGui::Dummy(ImVec2(w, kGraphHeight));
  ImGui::TextDisabled("last %.0f s, log scale", kGraphSeconds);
  ImGui::TextColored(ImGui::ColorConvertU32ToFloat4(kWallColour), "%-20s", "frame (wall)");
  ImGui::SameLine();
  ImGui::Text("%7.2f ms", wallHistory_.empty() ? 0.0 : static_cast<double>(wallHistory_.back()));
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
    const int k = session.summary().mapLayers;
    if (k > 0) {
      ImGui::SliderInt("map k", &debug.layer, 0, k - 1);
      debug.layer = std::clamp(debug.layer, 0, k - 1);
    }
  }
  if (debug.kind == sss::DebugViewKind::Map || debug.kind == sss::DebugViewKind::Difference)
    ImGui::SliderFloat("exposure [EV]", &debug.exposureEv, -10.0f, 10.0f, "%.1f");
  statusLine(feedback.debugNote, true);
}

const std::string& ViewPanel::saveBase(const std::string& presetName) {
  if (savedFor_ != presetName) {  // another preset: its own name (what the user typed was for the other)
    saveBase_ = defaultSaveBase(presetName);
    savedFor_ = presetName;
  }
  return saveBase_;
}

void ViewPanel::drawSave(const ViewSession& session, ViewRequests& requests) {
  saveBase(session.presetName());
  ImGui::InputText("file", &saveBase_);
  hoverText("path without number and extension: saving adds -0001.png, -0002.png, … (never overwriting)");
  if (ImGui::Button("PNG")) requests.screenshots.push_back(nextNumberedFile(saveBase_, ".png").string());
  hoverText("the window as shown (S)");
  ImGui::SameLine();
  if (ImGui::Button("EXR")) requests.screenshots.push_back(nextNumberedFile(saveBase_, ".exr").string());
  hoverText("the linear radiance of the image, at its rendered size");
  ImGui::SameLine();
  if (ImGui::Button("preset")) requests.presets.push_back(nextNumberedFile(saveBase_, ".json").string());
  hoverText("a preset that `tallow capture --preset FILE` renders as shown");
}

}  // namespace tallow::app
