#pragma once
// The scene's lights and their shadow maps as shaders/common/lights.glsl reads them, and the camera
// as the passes that shade what it sees read it (the surface pass, the image-space passes).
#include <cstddef>

#include "gpu/program.h"
#include "sss/render_settings.h"
#include "sss/scene.h"
#include "sss/shadow_pass.h"
#include "sss/view_setup.h"

namespace tallow::sss {

/// The index among common/lights.glsl's point lights (uPointPosition…) of scene.lights[light], a point
/// light: setLightUniforms numbers them in scene order.
int pointLightUniformIndex(const Scene& scene, std::size_t light);

/// Sets lights.glsl's uniforms on `program` (light arrays, shadow layers and matrices, PCF radius,
/// bias) and binds the shadow maps to `directionalShadowUnit` and `pointShadowUnit`.
void setLightUniforms(gpu::Program& program, const Scene& scene, const RenderSettings& settings,
                      const ShadowPass& shadows, GLuint directionalShadowUnit, GLuint pointShadowUnit);

/// Sets uViewProjection, uCameraPosition, uCameraForward and uCameraOrthographic from `camera`.
void setCameraUniforms(gpu::Program& program, const CameraView& camera);

}  // namespace tallow::sss
