#include "sss/peers/burley.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "sss/light_uniforms.h"
#include "sss/maps/radiosity_maps.h"
#include "sss/memory_budget.h"
#include "sss/shadow_pass.h"

namespace tallow::sss {
namespace {

// scatter.comp's units: its G-buffer, the shadow maps as receivers compare them (lights.glsl needs
// them bound) and the same maps read as depths for the thickness.
constexpr GLuint kPositionUnit = 0, kNormalUnit = 1, kIrradianceUnit = 2;
constexpr GLuint kDirShadowUnit = 3, kPointShadowUnit = 4, kDirDepthUnit = 5, kPointDepthUnit = 6;
constexpr GLuint kRadiosityImage = 0;
constexpr int kGroupSize = 8;  // scatter.comp's local size, both axes

BurleySss& burley(FrameContext& context) { return context.modules.obtain<BurleySss>(context.shaders); }

std::size_t screenBytes(GLenum format, int width, int height) {
  return gpu::Texture::bytesFor(GL_TEXTURE_2D, format, width, height, 1, 1);
}

}  // namespace

BurleySss::BurleySss(const gpu::ShaderLibrary& shaders)
    : gbuffer_(shaders), scatterProgram_(shaders, {{{GL_COMPUTE_SHADER, "peers/burley/scatter.comp"}}}) {
  depthValues_.set(GL_TEXTURE_COMPARE_MODE, GL_NONE);
  depthValues_.set(GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  depthValues_.set(GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  depthValues_.set(GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  depthValues_.set(GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

bool BurleySss::applies(const Scene& scene, const RenderSettings& settings) {
  return settings.sss.method == SssMethod::Burley && translucentObjectCount(scene) > 0;
}

void BurleySss::checkLimits(const Scene& scene, const RenderSettings& settings) {
  if (!applies(scene, settings)) return;
  const int translucent = translucentObjectCount(scene);
  if (translucent > kMaxTranslucentObjects)
    throw std::invalid_argument("the scene has " + std::to_string(translucent) +
                                " translucent objects; method burley holds at most " +
                                std::to_string(kMaxTranslucentObjects));
}

std::string BurleySss::describe(const Scene& scene, const RenderSettings& settings, const std::string& pass) {
  if (pass == "burley.gbuffer")
    return "the camera's view of every object: position, normal and E F_t from " + std::to_string(scene.lights.size()) +
           " light(s) with their shadows, per pixel of the " + std::to_string(translucentObjectCount(scene)) +
           " translucent object(s)";
  return std::to_string(settings.burley.samples) +
         " samples per translucent pixel of Christensen and Burley's normalised diffusion profile (A and d per band "
         "from the material), on a disc facing the camera, renormalised over the samples on the same object" +
         (settings.burley.transmission ? "; light through thin parts from the shadow maps' thickness" : "") +
         "; a new rotation on each of a still's " + std::to_string(settings.aaSamples) + " frame(s) (render.aa)";
}

std::size_t BurleySss::bytesFor(int width, int height) {
  return CameraIrradianceGBuffer::bytesFor(width, height) + screenBytes(GL_RGBA32F, width, height);
}

void BurleySss::renderGBuffer(const Scene& scene, const RenderSettings& settings, const SceneGeometry& geometry,
                              const CameraView& camera, const ShadowPass& shadows) {
  gbuffer_.render(scene, settings, geometry, camera, shadows);
}

void BurleySss::scatter(const Scene& scene, const RenderSettings& settings, const CameraView& camera,
                        const ShadowPass& shadows, int frame) {
  if (!radiosity_.id() || radiosity_.width() != settings.width || radiosity_.height() != settings.height) {
    radiosity_ = gpu::Texture::create2D(GL_RGBA32F, settings.width, settings.height);
    radiosity_.setFilter(GL_NEAREST, GL_NEAREST);
    radiosity_.setWrap(GL_CLAMP_TO_EDGE);
  }
  gpu::Program& p = scatterProgram_;
  setSlotMaterialUniforms(p, scene, gbuffer_.slots());
  setLightUniforms(p, scene, settings, shadows, kDirShadowUnit, kPointShadowUnit);
  setCameraUniforms(p, camera);
  p.set("uPosition", static_cast<int>(kPositionUnit));
  p.set("uNormal", static_cast<int>(kNormalUnit));
  p.set("uIrradiance", static_cast<int>(kIrradianceUnit));
  p.set("uDirShadowDepth", static_cast<int>(kDirDepthUnit));
  p.set("uPointShadowDepth", static_cast<int>(kPointDepthUnit));
  gbuffer_.positions().bind(kPositionUnit);
  gbuffer_.normals().bind(kNormalUnit);
  gbuffer_.irradiance().bind(kIrradianceUnit);
  shadows.bind(kDirDepthUnit, kPointDepthUnit);
  depthValues_.bind(kDirDepthUnit);
  depthValues_.bind(kPointDepthUnit);
  // A pixel's world size: per metre of distance (perspective) or in metres (orthographic).
  const float height = static_cast<float>(settings.height);
  p.set("uPixelScale", camera.orthographic ? scene.camera.orthoHeight / height
                                           : 2.0f * std::tan(glm::radians(scene.camera.fovYDeg) / 2.0f) / height);
  p.set("uSamples", settings.burley.samples);
  p.set("uFrame", frame);
  p.set("uTransmission", settings.burley.transmission ? 1 : 0);
  glBindImageTexture(kRadiosityImage, radiosity_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  p.use();
  glDispatchCompute(static_cast<GLuint>((settings.width + kGroupSize - 1) / kGroupSize),
                    static_cast<GLuint>((settings.height + kGroupSize - 1) / kGroupSize), 1);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
  // No state leaks: the units sample their textures by their own parameters again.
  gpu::Sampler::unbind(kDirDepthUnit);
  gpu::Sampler::unbind(kPointDepthUnit);
  glBindImageTexture(kRadiosityImage, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  glUseProgram(0);
}

void BurleySss::setSurfaceUniforms(gpu::Program& p, const BurleySss* self, GLuint unit) {
  p.set("uBurleyRadiosity", static_cast<int>(unit));
  if (self && self->radiosity_.id()) self->radiosity_.bind(unit);
}

std::string BurleyGBufferPass::reason(const FrameState& state) const {
  return BurleySss::describe(state.scene, state.settings, name());
}

PassIo BurleyGBufferPass::io(const FrameState&) const {
  // As image_space.gbuffer: E F_t with the lights' shadows (lights.glsl).
  return {{resource::kGeometry, resource::kShadowDirectional, resource::kShadowPoint, "scene.shapes",
           "scene.materials", "scene.light_placement", "scene.light_intensity", "scene.camera", "render.width",
           "render.height", "render.shadows", "render.shadow_bias", "render.pcf_radius", "accumulation"},
          {resource::kBurleyGBuffer},
          {}};
}

void BurleyGBufferPass::run(FrameContext& context, bool) {
  burley(context).renderGBuffer(context.scene(), context.settings(), context.geometry, context.camera(),
                                *context.modules.find<ShadowPass>());
}

std::string BurleyScatterPass::reason(const FrameState& state) const {
  return BurleySss::describe(state.scene, state.settings, name());
}

PassIo BurleyScatterPass::io(const FrameState&) const {
  // The thickness reads the shadow maps and the lights (the transmitted light's irradiance);
  // render.aa sets how many rotations a still gets: a change starts them again from the first, so
  // that a frame never depends on the rotations an earlier render.aa left behind.
  return {{resource::kBurleyGBuffer, resource::kShadowDirectional, resource::kShadowPoint, "scene.materials",
           "scene.light_placement", "scene.light_intensity", "scene.camera", "render.width", "render.height",
           "render.shadows", "render.aa", "burley.samples", "burley.transmission"},
          {resource::kBurleyRadiosity},
          {}};
}

void BurleyScatterPass::run(FrameContext& context, bool changed) {
  if (changed) frames_ = 0;
  burley(context).scatter(context.scene(), context.settings(), context.camera(), *context.modules.find<ShadowPass>(),
                          frames_);
  ++frames_;
}

void BurleyMethod::checkLimits(const FrameState& state) const { BurleySss::checkLimits(state.scene, state.settings); }

std::vector<Pass*> BurleyMethod::passes(const FrameState& state) {
  if (!anyTranslucent(state.scene)) return {};
  return {&gbuffer_, &scatter_};
}

bool BurleyMethod::shadesTranslucent(const FrameState& state) const { return anyTranslucent(state.scene); }

void BurleyMethod::addMemory(const Scene& scene, const RenderSettings& settings, const BudgetSizes&,
                             FrameMemory& m) const {
  if (!BurleySss::applies(scene, settings)) return;
  m.add("burley buffers",
        "render.width × render.height=" + std::to_string(settings.width) + "x" + std::to_string(settings.height),
        BurleySss::bytesFor(settings.width, settings.height));
}

std::string BurleyMethod::describeShading(const FrameState&) const {
  return "translucent ones from the diffusion profile's radiosity at their pixel (L = F_t/pi B, Christensen and "
         "Burley 2015)";
}

PassIo BurleyMethod::surfaceIo(const FrameState&) const { return {{resource::kBurleyRadiosity}, {}, {}}; }

void BurleyMethod::bindSurface(gpu::Program& p, const FrameContext& context, GLuint firstUnit) const {
  const BurleySss* b = context.modules.find<BurleySss>();
  BurleySss::setSurfaceUniforms(p, shadesTranslucent(context.state) ? b : nullptr, firstUnit);
}

}  // namespace tallow::sss
