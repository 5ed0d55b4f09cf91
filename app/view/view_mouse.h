#pragma once
// The view window's mouse camera: left drag orbits about the target, right or middle drag (or
// shift + left) pans, the wheel zooms; only when the panel does not want the mouse. The camera
// changes through the registry (camera.position, camera.target, camera.height), as --set would.
namespace tallow::app {

class ViewSession;

/// Applies this frame's mouse input (Dear ImGui's IO) to the session's camera; `height` is the
/// window's height in pixels (a drag across it orbits by 180°, pans by the view's height).
void mouseCamera(ViewSession& session, int height);

}  // namespace tallow::app
