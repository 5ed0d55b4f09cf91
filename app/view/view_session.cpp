#include "app/view/view_session.h"

#include <chrono>
#include <stdexcept>

#include "app/config/input_error.h"
#include "app/config/params.h"
#include "app/commands/frame_stats.h"
#include "app/config/preset_writer.h"
#include "app/playback/scene_controls.h"
#include "sss/maps/radiosity_maps.h"
#include "gpu/image_io.h"

namespace tallow::app {

RenderSummary summarize(const sss::Renderer& renderer, const Config& config, double timeS) {
  RenderSummary s;
  if (const sss::RadiosityMaps* maps = renderer.module<sss::RadiosityMaps>()) {
    s.hasMaps = true;
    s.maps = static_cast<int>(maps->views().size());
    s.mapFrames = maps->frames();
    s.mapLayers = maps->maps().depth();
    s.mapSize = maps->mapSize();
    s.lightMapSize = maps->lightMapSize();
  }
  s.chosenMaps = renderer.chosenMapCount(config.scene, config.render).value_or(0);
  s.gpuBytes = renderer.gpuBytes();
  s.plan = renderer.planFrame(config.scene, config.render, timeS);
  s.mapsRecord = mapsRecord(renderer);
  return s;
}

ViewSession::ViewSession(const SceneOptions& options, const gpu::ShaderLibrary& shaders, bool rendersHere)
    : shaders_(shaders),
      rendersHere_(rendersHere),
      options_(options),
      loaded_(loadScene(options)),
      registry_(parameterRegistry(loaded_.materials)) {
  std::unique_ptr<sss::Renderer> renderer;
  if (rendersHere_) renderer = std::make_unique<sss::Renderer>(shaders_, loaded_.config.scene, loaded_.config.render);
  LoadedScene loaded = std::move(loaded_);
  start(std::move(loaded), std::move(renderer));
}

sss::Renderer& ViewSession::renderer() {
  if (!renderer_) throw std::logic_error("ViewSession::renderer: the render thread owns the renderer");
  return *renderer_;
}

const sss::Renderer& ViewSession::renderer() const {
  if (!renderer_) throw std::logic_error("ViewSession::renderer: the render thread owns the renderer");
  return *renderer_;
}

void ViewSession::start(LoadedScene loaded, std::unique_ptr<sss::Renderer> renderer) {
  presetText_ = readInputFile(loaded.presetPath);
  loaded_ = std::move(loaded);
  renderer_ = std::move(renderer);
  const sss::Scene& scene = loaded_.config.scene;
  playback_.emplace(scene.startS, scene.durationS, scene.loop);
  home_ = scene.camera;
  lastGood_ = loaded_.config;
  summary_ = RenderSummary();
  presetValues_ = registry_.snapshot(loaded_.config);
  history_.emplace(registry_, loaded_.config);
  ++generation_;
}

std::string ViewSession::loadPreset(const std::string& nameOrPath) {
  SceneOptions next = options_;
  next.preset = nameOrPath;
  next.sets.clear();  // --set applied to the first preset only
  next.size = std::to_string(loaded_.config.render.width) + "x" + std::to_string(loaded_.config.render.height);
  try {
    LoadedScene loaded = loadScene(next);
    std::unique_ptr<sss::Renderer> renderer;  // the render thread builds its own on the new generation
    if (rendersHere_) renderer = std::make_unique<sss::Renderer>(shaders_, loaded.config.scene, loaded.config.render);
    renderer_.reset();  // free the old scene's GPU memory before the new one fills it
    start(std::move(loaded), std::move(renderer));
    return "";
  } catch (const std::exception& e) {
    return e.what();
  }
}

std::optional<std::int64_t> ViewSession::autoChoice(std::string_view key) const {
  int chosen = 0;
  if (key == "sss.maps") chosen = summary_.chosenMaps;
  else if (key == "sss.map_size" && summary_.hasMaps) chosen = summary_.mapSize;
  else if (key == "sss.light_map_size" && summary_.hasMaps) chosen = summary_.lightMapSize;
  if (chosen <= 0) return std::nullopt;
  return chosen;
}

std::string ViewSession::set(std::string_view key, const nlohmann::json& value) {
  Config trial = loaded_.config;
  try {
    registry_.set(trial, key, value);
  } catch (const InputError& e) {
    return e.what();
  }
  loaded_.config = std::move(trial);
  return "";
}

void ViewSession::resetCamera() { setCamera(loaded_.config, registry_, home_); }

std::string ViewSession::undo() {
  history_->commit(loaded_.config);
  const std::string label = history_->undoLabel();
  std::optional<Config> restored = history_->undo(loaded_.config);
  if (!restored) return "";
  loaded_.config = std::move(*restored);
  return label;
}

std::string ViewSession::redo() {
  history_->commit(loaded_.config);
  const std::string label = history_->redoLabel();
  std::optional<Config> restored = history_->redo(loaded_.config);
  if (!restored) return "";
  loaded_.config = std::move(*restored);
  return label;
}

ViewSession::Frame renderOrLastGood(sss::Renderer& renderer, Config& config, Config& lastGood, double timeS) {
  ViewSession::Frame frame;
  frame.timeS = timeS;
  const auto start = std::chrono::steady_clock::now();
  try {
    frame.gpu = renderer.render(config.scene, config.render, timeS);
    lastGood = config;
  } catch (const std::invalid_argument& e) {
    frame.refused = e.what();
    config = lastGood;
    frame.gpu = renderer.render(config.scene, config.render, timeS);
  }
  frame.wallMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  frame.shown = renderer.latestTimings();
  return frame;
}

ViewSession::Frame ViewSession::render() {
  Frame frame = renderOrLastGood(*renderer_, loaded_.config, lastGood_, playback_->time());
  summary_ = summarize(*renderer_, loaded_.config, frame.timeS);
  return frame;
}

void ViewSession::savePreset(const std::filesystem::path& file) const {
  PresetState state;
  state.timeS = std::max(playback_->time(), 0.0);
  state.loop = playback_->loop();
  writePreset(file, presetText_, loaded_.config, registry_, state);
}

void writeRadiance(const std::filesystem::path& file, const sss::Renderer& renderer, const std::string& presetName,
                   double timeS) {
  gpu::writeExr(file, renderer.readRadiance(), gpu::ExrPixelType::Half,
                {{"tallow.preset", presetName}, {"tallow.time_s", formatNumber(timeS)}});
}

void ViewSession::saveRadiance(const std::filesystem::path& file) const {
  writeRadiance(file, renderer(), loaded_.presetName, playback_->time());
}

}  // namespace tallow::app
