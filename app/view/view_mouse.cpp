#include "app/view/view_mouse.h"

#include <imgui.h>

#include <cmath>

#include "app/config/input_error.h"
#include "app/playback/orbit_camera.h"
#include "app/playback/scene_controls.h"
#include "app/view/view_session.h"

namespace tallow::app {

namespace {
/// Zoom per wheel notch: 10% closer (or farther).
constexpr double kZoomPerNotch = 0.9;
constexpr double kPi = 3.14159265358979323846;
}  // namespace

void mouseCamera(ViewSession& session, int height) {
  const ImGuiIO& io = ImGui::GetIO();
  if (io.WantCaptureMouse || height <= 0) return;
  sss::Camera camera = session.config().scene.camera;
  const bool pan = io.MouseDown[1] || io.MouseDown[2] || (io.MouseDown[0] && io.KeyShift);
  const int button = io.MouseDown[0] ? 0 : io.MouseDown[1] ? 1 : 2;
  // A drag starts where its button went down: in the frame of the click, the motion from the cursor's
  // position one (slow) frame earlier to the click is not part of it (issue 40: it flung the camera).
  const ImVec2 delta = io.MouseClicked[button] ? ImVec2(io.MousePos.x - io.MouseClickedPos[button].x,
                                                        io.MousePos.y - io.MouseClickedPos[button].y)
                                               : io.MouseDelta;
  const double dx = delta.x / height, dy = delta.y / height;  // screen y grows downward
  const bool moved = dx != 0.0 || dy != 0.0;
  bool changed = false;
  if (moved && pan) {
    panCamera(camera, dx, -dy);
    changed = true;
  } else if (moved && io.MouseDown[0]) {
    // Drag right: the scene turns right (the camera goes left); drag down: the camera rises.
    orbitCamera(camera, -dx * kPi, dy * kPi);
    changed = true;
  }
  if (io.MouseWheel != 0.0f) {
    zoomCamera(camera, std::pow(kZoomPerNotch, io.MouseWheel));
    changed = true;
  }
  if (!changed) return;
  // All or nothing: a camera the registry refuses (beyond its coordinate range) stays where it was.
  Config trial = session.config();
  try {
    setCamera(trial, session.registry(), camera);
  } catch (const InputError&) {
    return;
  }
  session.config() = std::move(trial);
}

}  // namespace tallow::app
