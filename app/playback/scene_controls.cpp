#include "app/playback/scene_controls.h"

#include <glm/trigonometric.hpp>

#include "app/config/input_error.h"
#include "app/playback/orbit_camera.h"

namespace tallow::app {

namespace {
nlohmann::json vec3Json(const glm::vec3& v) { return {floatToJson(v.x), floatToJson(v.y), floatToJson(v.z)}; }
}  // namespace

void setCamera(Config& config, const Registry& registry, const sss::Camera& camera) {
  registry.set(config, "camera.position", vec3Json(camera.position));
  registry.set(config, "camera.target", vec3Json(camera.target));
  if (camera.orthographic) registry.set(config, "camera.height", floatToJson(camera.orthoHeight));
}

bool windowOnly(ScriptAction action) {
  return action == ScriptAction::Debug || action == ScriptAction::Screenshot || action == ScriptAction::SavePreset ||
         action == ScriptAction::Key || action == ScriptAction::Quit;
}

bool applyScriptCommand(const ScriptCommand& c, Config& config, const Registry& registry, Playback& playback) {
  try {
    sss::Camera camera = config.scene.camera;
    switch (c.action) {
      case ScriptAction::Set:
        registry.set(config, c.key, c.value);
        return true;
      case ScriptAction::Play:
        playback.play();
        return true;
      case ScriptAction::Pause:
        playback.pause();
        return true;
      case ScriptAction::Loop:
        playback.setLoop(c.on);
        return true;
      case ScriptAction::Speed:
        playback.setSpeed(c.a);
        return true;
      case ScriptAction::Seek:
        playback.seek(c.a);
        return true;
      case ScriptAction::Orbit:
        orbitCamera(camera, glm::radians(c.a), glm::radians(c.b));
        setCamera(config, registry, camera);
        return true;
      case ScriptAction::Pan:
        panCamera(camera, c.a, c.b);
        setCamera(config, registry, camera);
        return true;
      case ScriptAction::Zoom:
        zoomCamera(camera, c.a);
        setCamera(config, registry, camera);
        return true;
      default:
        return false;
    }
  } catch (const InputError& e) {
    throw InputError(c.where + ": " + e.what());
  }
}

}  // namespace tallow::app
