#pragma once
// The state of a view window's scene, apart from the window and its widgets: the loaded preset and
// its configuration, the registry every change goes through, the renderer, the animation clock and
// the camera the preset started with. The panel, the mouse and scripts act on it; it renders.
#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "app/config/edit_history.h"
#include "app/config/registry.h"
#include "app/config/setup.h"
#include "app/playback/playback.h"
#include "sss/renderer.h"

namespace tallow::app {

class ViewSession {
 public:
  /// Loads the preset (--preset, --size, --set) and builds its renderer; the GL context must be
  /// current. Throws as loadScene and the Renderer do.
  ViewSession(const SceneOptions& options, const gpu::ShaderLibrary& shaders);

  Config& config() { return loaded_.config; }
  const Config& config() const { return loaded_.config; }
  const Registry& registry() const { return registry_; }
  const sss::MaterialTable& materials() const { return loaded_.materials; }
  sss::Renderer& renderer() { return *renderer_; }
  const sss::Renderer& renderer() const { return *renderer_; }
  Playback& playback() { return *playback_; }
  const Playback& playback() const { return *playback_; }
  const std::string& presetName() const { return loaded_.presetName; }
  const std::filesystem::path& presetPath() const { return loaded_.presetPath; }
  /// Counts the scenes loaded (1 after construction): a new value means a new clock and renderer.
  int generation() const { return generation_; }
  /// Every parameter's value when the preset was loaded (with --set): what "reset to the preset's
  /// value" restores, for the parameters whose default is the preset's.
  const nlohmann::json& presetValues() const { return presetValues_; }

  /// Replaces the scene by another preset (a name in the preset folder or a path) at the current
  /// render size, with a new renderer and clock. On failure keeps the current scene and returns the
  /// one-line reason; "" on success.
  std::string loadPreset(const std::string& nameOrPath);

  /// What the renderer chose for an int parameter set to "auto" (sss.maps: K; sss.map_size,
  /// sss.light_map_size: the sizes in use), or nothing when it chose none yet or `key` is not one of
  /// them: unticking the panel's "auto" keeps this value (issue 38).
  std::optional<std::int64_t> autoChoice(std::string_view key) const;
  /// Sets a parameter through the registry; returns "" or the registry's one-line refusal, in which
  /// case nothing changed.
  std::string set(std::string_view key, const nlohmann::json& value);
  /// Back to the camera the preset (with --set) started with.
  void resetCamera();

  /// Records the edits since the last call as one undoable step (app/config/edit_history.h); call it
  /// when no edit is under way (no widget held, no drag).
  void commitEdits() { history_->commit(loaded_.config); }
  const EditHistory& history() const { return *history_; }
  /// Undoes (redoes) the last edit step, keeping the camera; returns what changed back ("" when
  /// there was nothing to undo).
  std::string undo();
  std::string redo();

  struct Frame {
    sss::FrameTimings gpu;    ///< this frame: CPU time per pass (GPU times read later)
    sss::FrameTimings shown;  ///< the newest frame whose GPU times are known (read without waiting)
    double wallMs = 0.0;      ///< CPU wall time of render(), which does not wait for the GPU
    double timeS = 0.0;   ///< animation time rendered
    std::string refused;  ///< the GPU refused the configuration (checkLimits): why, in one line
  };
  /// Renders the frame at the clock's time, at the configuration's render.width × render.height
  /// (the window shows it scaled to fit, app/view/view_layout.h). When the GPU refuses the
  /// configuration (RadiosityMaps::checkLimits and the like), restores the last configuration that
  /// rendered, renders that, and says why in Frame::refused.
  Frame render();

  /// A preset file that reproduces this frame (app/config/preset_writer.h). Throws on failure.
  void savePreset(const std::filesystem::path& file) const;
  /// The last frame's linear radiance as EXR (half, atomically). Throws on failure.
  void saveRadiance(const std::filesystem::path& file) const;

 private:
  void start(LoadedScene loaded, std::unique_ptr<sss::Renderer> renderer);

  const gpu::ShaderLibrary& shaders_;
  SceneOptions options_;
  LoadedScene loaded_;
  std::string presetText_;  ///< the preset file as loaded, the base of a saved preset
  Registry registry_;
  nlohmann::json presetValues_;
  std::optional<EditHistory> history_;  ///< one per scene loaded
  std::unique_ptr<sss::Renderer> renderer_;
  std::optional<Playback> playback_;
  sss::Camera home_;
  Config lastGood_;  ///< the last configuration that rendered
  int generation_ = 0;
};

}  // namespace tallow::app
