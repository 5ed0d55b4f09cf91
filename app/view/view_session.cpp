#include "app/view/view_session.h"

#include <chrono>
#include <stdexcept>

#include "app/config/input_error.h"
#include "app/config/params.h"
#include "app/config/preset_writer.h"
#include "app/playback/scene_controls.h"
#include "sss/maps/radiosity_maps.h"
#include "gpu/image_io.h"

namespace tallow::app {

ViewSession::ViewSession(const SceneOptions& options, const gpu::ShaderLibrary& shaders)
    : shaders_(shaders), options_(options), loaded_(loadScene(options)), registry_(parameterRegistry(loaded_.materials)) {
  auto renderer = std::make_unique<sss::Renderer>(shaders_, loaded_.config.scene, loaded_.config.render);
  LoadedScene loaded = std::move(loaded_);
  start(std::move(loaded), std::move(renderer));
}

void ViewSession::start(LoadedScene loaded, std::unique_ptr<sss::Renderer> renderer) {
  presetText_ = readInputFile(loaded.presetPath);
  loaded_ = std::move(loaded);
  renderer_ = std::move(renderer);
  const sss::Scene& scene = loaded_.config.scene;
  playback_.emplace(scene.startS, scene.durationS, scene.loop);
  home_ = scene.camera;
  lastGood_ = loaded_.config;
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
    auto renderer = std::make_unique<sss::Renderer>(shaders_, loaded.config.scene, loaded.config.render);
    renderer_.reset();  // free the old scene's GPU memory before the new one fills it
    start(std::move(loaded), std::move(renderer));
    return "";
  } catch (const std::exception& e) {
    return e.what();
  }
}

std::optional<std::int64_t> ViewSession::autoChoice(std::string_view key) const {
  const sss::RadiosityMaps* maps = renderer_->module<sss::RadiosityMaps>();
  int chosen = 0;
  if (key == "sss.maps") chosen = renderer_->chosenMapCount(loaded_.config.scene, loaded_.config.render).value_or(0);
  else if (key == "sss.map_size" && maps) chosen = maps->mapSize();
  else if (key == "sss.light_map_size" && maps) chosen = maps->lightMapSize();
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

ViewSession::Frame ViewSession::render() {
  Config& config = loaded_.config;
  Frame frame;
  frame.timeS = playback_->time();
  const auto start = std::chrono::steady_clock::now();
  try {
    frame.gpu = renderer_->render(config.scene, config.render, frame.timeS);
    lastGood_ = config;
  } catch (const std::invalid_argument& e) {
    frame.refused = e.what();
    config = lastGood_;
    frame.gpu = renderer_->render(config.scene, config.render, frame.timeS);
  }
  frame.wallMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  frame.shown = renderer_->latestTimings();
  return frame;
}

void ViewSession::savePreset(const std::filesystem::path& file) const {
  PresetState state;
  state.timeS = std::max(playback_->time(), 0.0);
  state.loop = playback_->loop();
  writePreset(file, presetText_, loaded_.config, registry_, state);
}

void ViewSession::saveRadiance(const std::filesystem::path& file) const {
  gpu::writeExr(file, renderer_->readRadiance(), gpu::ExrPixelType::Half,
                {{"tallow.preset", loaded_.presetName}, {"tallow.time_s", formatNumber(playback_->time())}});
}

}  // namespace tallow::app
