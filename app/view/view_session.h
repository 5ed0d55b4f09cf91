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
#include <vector>

#include "app/config/edit_history.h"
#include "app/config/registry.h"
#include "app/config/setup.h"
#include "app/playback/playback.h"
#include "sss/frame_plan.h"
#include "sss/renderer.h"

namespace tallow::app {

/// What the window shows of the renderer after a frame (the panel, the title, the "auto" choices):
/// copied from it once per render, so that the panel reads it while the next frame renders on the
/// render thread (app/view/render_worker.h) as well as in the lockstep loop.
struct RenderSummary {
  bool hasMaps = false;  ///< the renderer keeps radiosity maps (whether they apply: the config's)
  int maps = 0;          ///< K, the maps in use
  int mapFrames = 0;     ///< frames accumulated into them
  int mapLayers = 0;     ///< layers of the maps' array texture (the debug view's "map k")
  int mapSize = 0, lightMapSize = 0;  ///< the sizes in use
  int chosenMaps = 0;    ///< what sss.maps=auto chose (0: none)
  std::size_t gpuBytes = 0;
  std::vector<sss::PlannedPass> plan;  ///< the passes of the frame rendered, and why
  nlohmann::json mapsRecord;           ///< stats.json's "sss" of the frame (frame_stats.h mapsRecord)
};
/// The summary of `renderer` after rendering `config` at `timeS`.
RenderSummary summarize(const sss::Renderer& renderer, const Config& config, double timeS);

/// The last frame's linear radiance of `renderer` as EXR (half, atomically), named by preset and
/// time. Throws on failure.
void writeRadiance(const std::filesystem::path& file, const sss::Renderer& renderer, const std::string& presetName,
                   double timeS);

class ViewSession {
 public:
  /// Loads the preset (--preset, --size, --set) and, with `rendersHere`, builds its renderer (the
  /// GL context must be current); without, a render thread renders the session's configuration
  /// (app/view/render_worker.h) and renderer() must not be called. Throws as loadScene and the
  /// Renderer do.
  ViewSession(const SceneOptions& options, const gpu::ShaderLibrary& shaders, bool rendersHere = true);

  Config& config() { return loaded_.config; }
  const Config& config() const { return loaded_.config; }
  const Registry& registry() const { return registry_; }
  const sss::MaterialTable& materials() const { return loaded_.materials; }
  sss::Renderer& renderer();
  const sss::Renderer& renderer() const;
  /// The renderer as of the last frame rendered (render(), or the render thread's setSummary).
  const RenderSummary& summary() const { return summary_; }
  void setSummary(RenderSummary summary) { summary_ = std::move(summary); }
  /// The render thread refused the configuration: back to the one it rendered instead.
  void restore(const Config& rendered) { loaded_.config = rendered; }
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
  /// The window's pictures are rendered here (render()), not on a render thread.
  bool rendersHere() const { return rendersHere_; }
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
  bool rendersHere_ = true;
  RenderSummary summary_;
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

/// Renders `config` at `timeS` with `renderer` (Frame's wall time and the newest known GPU times
/// included); when the GPU refuses it (std::invalid_argument, e.g. RadiosityMaps::checkLimits),
/// puts `lastGood` back into `config`, renders that and says why in Frame::refused. `lastGood`
/// becomes `config` when it renders. Shared by the window's lockstep loop and its render thread.
ViewSession::Frame renderOrLastGood(sss::Renderer& renderer, Config& config, Config& lastGood, double timeS);

}  // namespace tallow::app
