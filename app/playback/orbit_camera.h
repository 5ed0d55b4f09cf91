#pragma once
// Mouse camera control of the view window, on sss::Camera: orbit about the target, pan in the
// view plane, zoom (dolly, or an orthographic camera's height). Pure functions, so the tests check
// the geometry without a window.
#include "sss/scene.h"

namespace tallow::app {

/// Turns the camera about its target: `yawRad` about the camera's up vector, then `pitchRad` about
/// its right vector (positive looks down on the target from higher up). The distance to the target
/// is kept; the pitch stops kPitchMarginDeg short of looking along the up vector, where yaw would
/// be undefined.
void orbitCamera(sss::Camera& camera, double yawRad, double pitchRad);
inline constexpr double kPitchMarginDeg = 1.0;

/// Moves position and target together in the view plane by (dx, dy) view heights at the target's
/// distance (dx to the right, dy up), so a point at the target's depth follows a mouse that moved by
/// (dx, dy) of the window's height.
void panCamera(sss::Camera& camera, double dx, double dy);

/// Perspective: the distance to the target times `factor`; orthographic: the view height times
/// `factor`. `factor` must be positive; the distance stays above kMinDistance of the target.
void zoomCamera(sss::Camera& camera, double factor);
inline constexpr double kMinDistance = 1e-4;  ///< metres; the camera never reaches its target

/// Height of the view at the target's distance (perspective: 2 d tan(fov/2); orthographic: its height).
double viewHeightAtTarget(const sss::Camera& camera);

}  // namespace tallow::app
