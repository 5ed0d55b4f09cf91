#include "app/playback/orbit_camera.h"

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>

namespace tallow::app {

namespace {
// In double: small steps of a camera far from the origin must not lose the target's precision.
using dvec3 = glm::dvec3;

/// `v` turned by `angle` about the unit `axis` (Rodrigues' rotation formula).
dvec3 rotate(const dvec3& v, double angle, const dvec3& axis) {
  const double c = std::cos(angle), s = std::sin(angle);
  return v * c + glm::cross(axis, v) * s + axis * glm::dot(axis, v) * (1.0 - c);
}
}  // namespace

void orbitCamera(sss::Camera& camera, double yawRad, double pitchRad) {
  const dvec3 target(camera.target);
  const dvec3 up = glm::normalize(dvec3(camera.up));
  dvec3 offset = dvec3(camera.position) - target;
  const double distance = glm::length(offset);
  if (!(distance > 0.0)) return;
  offset = rotate(offset, yawRad, up);
  // Pitch: the angle from the up vector, kept inside [margin, 180° − margin].
  const double margin = glm::radians(kPitchMarginDeg);
  const double polar = std::acos(std::clamp(glm::dot(offset / distance, up), -1.0, 1.0));
  const double newPolar = std::clamp(polar - pitchRad, margin, glm::pi<double>() - margin);
  dvec3 right = glm::cross(up, offset);
  if (glm::length(right) < 1e-12 * distance) right = glm::cross(up, std::abs(up.x) < 0.9 ? dvec3(1, 0, 0) : dvec3(0, 0, 1));
  offset = rotate(offset, newPolar - polar, glm::normalize(right));
  camera.position = glm::vec3(target + offset);
}

double viewHeightAtTarget(const sss::Camera& camera) {
  if (camera.orthographic) return camera.orthoHeight;
  const double distance = glm::length(dvec3(camera.position) - dvec3(camera.target));
  return 2.0 * distance * std::tan(glm::radians(double(camera.fovYDeg)) / 2.0);
}

void panCamera(sss::Camera& camera, double dx, double dy) {
  const dvec3 forward = dvec3(camera.target) - dvec3(camera.position);
  if (!(glm::length(forward) > 0.0)) return;
  const dvec3 right = glm::cross(forward, dvec3(camera.up));
  if (!(glm::length(right) > 0.0)) return;
  const dvec3 r = glm::normalize(right);
  const dvec3 u = glm::normalize(glm::cross(r, forward));
  const double h = viewHeightAtTarget(camera);
  // The scene moves with the mouse: the camera moves the other way.
  const dvec3 shift = -(dx * h) * r - (dy * h) * u;
  camera.position = glm::vec3(dvec3(camera.position) + shift);
  camera.target = glm::vec3(dvec3(camera.target) + shift);
}

void zoomCamera(sss::Camera& camera, double factor) {
  if (!(factor > 0.0) || !std::isfinite(factor)) return;
  if (camera.orthographic) {
    camera.orthoHeight = static_cast<float>(std::max(camera.orthoHeight * factor, kMinDistance));
    return;
  }
  const dvec3 target(camera.target);
  const dvec3 offset = dvec3(camera.position) - target;
  const double distance = glm::length(offset);
  if (!(distance > 0.0)) return;
  const double next = std::max(distance * factor, kMinDistance);
  camera.position = glm::vec3(target + offset * (next / distance));
}

}  // namespace tallow::app
