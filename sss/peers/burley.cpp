#include "sss/peers/burley.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "sss/light_uniforms.h"
#include "sss/maps/radiosity_maps.h"
#include "sss/memory_budget.h"
#include "sss/peers/burley_profile.h"
#include "sss/shadow_pass.h"

namespace tallow::sss {
namespace {

// scatter.comp's units: its G-buffer, the shadow maps as receivers compare them (lights.glsl needs
// them bound) and the same maps read as depths for the thickness.
constexpr GLuint kPositionUnit = 0, kNormalUnit = 1, kIrradianceUnit = 2;
constexpr GLuint kDirShadowUnit = 3, kPointShadowUnit = 4, kDirDepthUnit = 5, kPointDepthUnit = 6;
constexpr GLuint kRadiosityImage = 0;
constexpr GLuint kTapsBinding = 8;  // separable.comp's Taps
constexpr int kTapStride = kBurleyMaxSamples / 2 + 1;  // taps per slot in the buffer (K ≤ samples / 2)
constexpr int kGroupSize = 8;  // scatter.comp's local size, both axes

BurleySss& burley(FrameContext& context) { return context.modules.obtain<BurleySss>(context.shaders); }

}  // namespace

BurleySss::BurleySss(const gpu::ShaderLibrary& shaders)
    : gbuffer_(shaders),
      scatterProgram_(shaders, {{{GL_COMPUTE_SHADER, "peers/burley/scatter.comp"}}}),
      separableProgram_(shaders, {{{GL_COMPUTE_SHADER, "peers/burley/separable.comp"}}}) {
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
  const std::string transmission =
      settings.burley.transmission ? "; light through thin parts from the shadow maps' thickness" : "";
  if (settings.burley.kernel == BurleyKernel::Separable)
    return "Christensen and Burley's normalised diffusion profile (A and d per band from the material) as a "
           "horizontal then a vertical pass of " + std::to_string(2 * std::max(1, settings.burley.samples / 2) + 1) +
           " taps, each the profile's mass in its strip, following the surface" + transmission;
  return std::to_string(settings.burley.samples) +
         " samples per translucent pixel of Christensen and Burley's normalised diffusion profile (A and d per band "
         "from the material), on a disc facing the camera, renormalised over the samples on the same object" +
         transmission + "; a new rotation on each of a still's " + std::to_string(settings.aaSamples) +
         " frame(s) (render.aa)";
}

std::size_t BurleySss::bytesFor(int width, int height, BurleyKernel kernel) {
  const std::size_t separable = kernel == BurleyKernel::Separable
                                    ? screenTextureBytes(GL_RGBA32F, width, height) +
                                          static_cast<std::size_t>(kMaxTranslucentObjects * kTapStride) * 4 * sizeof(float)
                                    : 0;
  return CameraIrradianceGBuffer::bytesFor(width, height) + screenTextureBytes(GL_RGBA32F, width, height) + separable;
}

void BurleySss::ensureTarget(gpu::Texture& texture, int width, int height) {
  if (!texture.id() || texture.width() != width || texture.height() != height)
    texture = screenTexture(GL_RGBA32F, width, height);
}

void BurleySss::updateTaps(const Scene& scene, const RenderSettings& settings) {
  const int halfTaps = std::max(1, settings.burley.samples / 2);
  std::vector<float> key{static_cast<float>(halfTaps)};
  std::vector<const Material*> materials(kMaxTranslucentObjects, nullptr);
  const std::vector<int>& slots = gbuffer_.slots();
  for (std::size_t i = 0; i < scene.objects.size() && i < slots.size(); ++i) {
    if (slots[i] < 0) continue;
    const Material& m = scene.objects[i].material;
    materials[static_cast<std::size_t>(slots[i])] = &m;
    key.insert(key.end(), {static_cast<float>(slots[i]), m.sigma_a.x, m.sigma_a.y, m.sigma_a.z, m.sigma_s.x,
                           m.sigma_s.y, m.sigma_s.z, m.g.x, m.g.y, m.g.z, m.eta});
  }
  if (key == tapsKey_ && taps_.size()) return;
  std::vector<float> data(static_cast<std::size_t>(kMaxTranslucentObjects * kTapStride) * 4, 0.0f);
  for (int slot = 0; slot < kMaxTranslucentObjects; ++slot) {
    const Material* m = materials[static_cast<std::size_t>(slot)];
    if (!m) continue;
    const std::vector<BurleyTap> taps = burleySeparableTaps(burleyBands(*m), halfTaps);
    for (std::size_t k = 0; k < taps.size(); ++k) {
      float* e = &data[(static_cast<std::size_t>(slot * kTapStride) + k) * 4];
      for (int c = 0; c < 3; ++c) e[c] = static_cast<float>(taps[k].weight[static_cast<std::size_t>(c)]);
      e[3] = static_cast<float>(taps[k].offset);
    }
  }
  taps_.assign(data.size() * sizeof(float), data.data());  // made once, then uploaded in place
  tapsKey_ = std::move(key);
}

void BurleySss::renderGBuffer(const Scene& scene, const RenderSettings& settings, const SceneGeometry& geometry,
                              const CameraView& camera, const ShadowPass& shadows) {
  gbuffer_.render(scene, settings, geometry, camera, shadows);
}

void BurleySss::scatter(const Scene& scene, const RenderSettings& settings, const CameraView& camera,
                        const ShadowPass& shadows, int frame) {
  ensureTarget(radiosity_, settings.width, settings.height);
  const bool separable = settings.burley.kernel == BurleyKernel::Separable;
  if (separable) {
    ensureTarget(intermediate_, settings.width, settings.height);
    updateTaps(scene, settings);
  }
  gpu::Program& p = separable ? separableProgram_ : scatterProgram_;
  // transmission.glsl's uniforms, shared by both kernels.
  setSlotMaterialUniforms(p, scene, gbuffer_.slots());
  setLightUniforms(p, scene, settings, shadows, kDirShadowUnit, kPointShadowUnit);
  setCameraUniforms(p, camera);
  p.set("uPosition", static_cast<int>(kPositionUnit));
  p.set("uNormal", static_cast<int>(kNormalUnit));
  p.set("uDirShadowDepth", static_cast<int>(kDirDepthUnit));
  p.set("uPointShadowDepth", static_cast<int>(kPointDepthUnit));
  gbuffer_.positions().bind(kPositionUnit);
  gbuffer_.normals().bind(kNormalUnit);
  shadows.bind(kDirDepthUnit, kPointDepthUnit);
  depthValues_.bind(kDirDepthUnit);
  depthValues_.bind(kPointDepthUnit);
  // A pixel's world size: per metre of distance (perspective) or in metres (orthographic).
  const float height = static_cast<float>(settings.height);
  p.set("uPixelScale", camera.orthographic ? scene.camera.orthoHeight / height
                                           : 2.0f * std::tan(glm::radians(scene.camera.fovYDeg) / 2.0f) / height);
  p.set("uTransmission", settings.burley.transmission ? 1 : 0);
  const GLuint groupsX = static_cast<GLuint>((settings.width + kGroupSize - 1) / kGroupSize);
  const GLuint groupsY = static_cast<GLuint>((settings.height + kGroupSize - 1) / kGroupSize);
  p.use();
  if (!separable) {
    p.set("uIrradiance", static_cast<int>(kIrradianceUnit));
    gbuffer_.irradiance().bind(kIrradianceUnit);
    p.set("uSamples", settings.burley.samples);
    p.set("uFrame", frame);
    glBindImageTexture(kRadiosityImage, radiosity_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glDispatchCompute(groupsX, groupsY, 1);
  } else {
    p.set("uInput", static_cast<int>(kIrradianceUnit));
    p.set("uHalfTaps", std::max(1, settings.burley.samples / 2));
    p.set("uTapStride", kTapStride);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kTapsBinding, taps_.id());
    // Along x from the irradiance into the intermediate target, then along y from it into B.
    p.set("uPass", 0);
    gbuffer_.irradiance().bind(kIrradianceUnit);
    glBindImageTexture(kRadiosityImage, intermediate_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glDispatchCompute(groupsX, groupsY, 1);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    p.set("uPass", 1);
    intermediate_.bind(kIrradianceUnit);
    glBindImageTexture(kRadiosityImage, radiosity_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glDispatchCompute(groupsX, groupsY, 1);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kTapsBinding, 0);
  }
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
           "render.shadows", "render.aa", "burley.samples", "burley.transmission", "burley.kernel"},
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
        BurleySss::bytesFor(settings.width, settings.height, settings.burley.kernel));
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
