#include "sss/renderer.h"

#include <algorithm>
#include <stdexcept>

#include "gpu/readback.h"
#include "sss/field_source.h"
#include "sss/memory_budget.h"

namespace tallow::sss {

void checkLimits(const Scene& scene, const RenderSettings& settings) {
  int dirCount = 0, pointCount = 0;
  for (const Light& l : scene.lights) (l.kind == LightKind::Directional ? dirCount : pointCount)++;
  if (dirCount > kMaxDirectionalLights)
    throw std::invalid_argument("the scene has " + std::to_string(dirCount) + " directional lights; at most " +
                                std::to_string(kMaxDirectionalLights) + " are supported");
  if (pointCount > kMaxPointLights)
    throw std::invalid_argument("the scene has " + std::to_string(pointCount) + " point lights; at most " +
                                std::to_string(kMaxPointLights) + " are supported");
  GLint maxTexture = 0, maxLayers = 0, maxViewport[2] = {0, 0};
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTexture);
  glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &maxLayers);
  glGetIntegerv(GL_MAX_VIEWPORT_DIMS, maxViewport);
  if (settings.shadowMapSize > maxTexture)
    throw std::invalid_argument("render.shadow_map_size: " + std::to_string(settings.shadowMapSize) +
                                " exceeds this GPU's GL_MAX_TEXTURE_SIZE of " + std::to_string(maxTexture));
  if (settings.width > maxTexture || settings.height > maxTexture || settings.width > maxViewport[0] ||
      settings.height > maxViewport[1])
    throw std::invalid_argument("render size " + std::to_string(settings.width) + "x" +
                                std::to_string(settings.height) + " exceeds this GPU's limit of " +
                                std::to_string(std::min(maxTexture, maxViewport[0])) + " pixels per side");
  if (6 * pointCount > maxLayers)
    throw std::invalid_argument("too many point lights for this GPU's GL_MAX_ARRAY_TEXTURE_LAYERS");
  RadiosityMaps::checkLimits(scene, settings);
  VirtualPointLights::checkLimits(scene, settings);
  ImageSpaceSss::checkLimits(scene, settings);
  Sslpv::checkLimits(scene, settings);
  checkMemoryBudget(scene, settings);  // after the per-method limits, which name a single setting
}

Renderer::Renderer(const gpu::ShaderLibrary& shaders, const Scene& scene, const RenderSettings& settings)
    : geometry_(scene), fields_(std::make_unique<FieldObjects>(shaders, scene)), shaders_(shaders), shadows_(shaders),
      surface_(shaders), display_(shaders) {
  checkLimits(scene, settings);
  ensureTargets(settings.width, settings.height);
  if (scene.environment) surface_.setEnvironment(*scene.environment);
}

std::vector<PlannedPass> Renderer::plan(const Scene& scene, const RenderSettings& settings) {
  std::vector<PlannedPass> passes;
  if (FieldObjects::any(scene)) {
    int n = 0;
    for (const SceneObject& o : scene.objects) n += o.shape == ShapeKind::Field ? 1 : 0;
    passes.push_back({"field.sample", std::to_string(n) + " field object(s) at a new time: sampled on the CPU on a " +
                                          std::to_string(settings.fieldRes) + "^3 lattice and uploaded"});
    passes.push_back({"field.extract", "GPU dual contouring (surface nets) of the uploaded lattice(s) into "
                                       "transform-feedback buffers"});
  }
  int dirShadowed = 0, pointShadowed = 0;
  for (const Light& l : scene.lights)
    if (l.castsShadows) (l.kind == LightKind::Directional ? dirShadowed : pointShadowed)++;
  if (ShadowPass::needsDirectional(scene, settings))
    passes.push_back({"shadow.directional", std::to_string(dirShadowed) +
                                                " directional light(s) cast shadows: one orthographic depth layer each"});
  if (ShadowPass::needsPoint(scene, settings))
    passes.push_back({"shadow.point", std::to_string(pointShadowed) +
                                          " point light(s) cast shadows: one depth cube each (6 faces)"});
  const bool maps = RadiosityMaps::applies(scene, settings);
  const bool noCache = settings.sss.method == SssMethod::NoCache && RadiosityMaps::needsLightGBuffers(scene, settings);
  if (maps || noCache) {
    int dir = 0, point = 0;
    for (const Light& l : scene.lights) (l.kind == LightKind::Directional ? dir : point)++;
    const SssSettings& s = settings.sss;
    passes.push_back({"sss.light_gbuffer", std::to_string(dir) + " directional (orthographic layer) and " +
                                               std::to_string(point) + " point (cube) light G-buffer(s), " +
                                               std::to_string(s.lightMapSize) + "^2, one layered pass each kind"});
    if (maps)
      passes.push_back({"sss.maps", std::to_string(mapCount(scene, settings)) +
                                      (scene.mapDirections.empty() ? " (Halton)" : " (listed in the preset)") +
                                      " scattered radiosity maps of " + std::to_string(s.mapSize) +
                                      "^2: depth pre-pass, then " + std::to_string(s.samples) +
                                      " samples per texel and colour band (" + std::string(bssrdfModelName(s.model)) +
                                      " dipole), accumulated until " + std::to_string(s.frames) + " frames"});
  }
  const bool imageSpace = ImageSpaceSss::applies(scene, settings);
  if (imageSpace)
    for (const char* name : {"image_space.gbuffer", "image_space.scatter", "image_space.combine"})
      passes.push_back({name, ImageSpaceSss::describe(scene, settings, name)});
  const bool sslpv = Sslpv::applies(scene, settings);
  if (sslpv) {
    passes.push_back({"sslpv.voxelize", Sslpv::describeVoxelize(scene, settings)});
    passes.push_back({"sslpv.light_gbuffer", Sslpv::describeLightGBuffer(scene, settings)});
    passes.push_back({"sslpv.inject", Sslpv::describeInject(settings)});
    passes.push_back({"sslpv.propagate", Sslpv::describePropagate(settings)});
  }
  if (VirtualPointLights::applies(scene, settings))
    passes.push_back({"vpl", VirtualPointLights::describe(scene, settings)});
  passes.push_back({"surface", std::to_string(scene.objects.size()) + " object(s): " +
                                   (sslpv ? "translucent ones from the SSLPV accumulation grid (area light of Eqs. 5-7 "
                                            "after the SH rotation of Eq. 6), opaque ones Lambertian"
                                    : maps ? "translucent ones from the radiosity maps (Algorithm 1, Eq. 5), opaque "
                                                "ones Lambertian"
                                    : imageSpace ? "translucent ones from the image-space estimate at their pixel (L = F_t/pi "
                                                   "B, standard dipole), opaque ones Lambertian"
                                    : noCache ? "translucent ones by the gather per pixel against the light G-buffers "
                                                "(no-cache: " + std::to_string(settings.sss.samples) +
                                                    " samples per pixel and band, a new estimate every frame), opaque "
                                                    "ones Lambertian"
                                              : "Lambertian with direct light, shadows and ambient (method albedo: "
                                                "translucent objects use their albedo)") +
                                   " with direct light, shadows and ambient"});
  return passes;
}

std::vector<PlannedPass> Renderer::planFrame(const Scene& scene, const RenderSettings& settings,
                                             double timeS) const {
  return planFrame(scene, settings, timeS, mapKey(scene, settings, timeS));
}

std::vector<PlannedPass> Renderer::planFrame(const Scene& scene, const RenderSettings& settings, double timeS,
                                             const std::string& mapStateKey) const {
  std::vector<PlannedPass> passes = plan(scene, settings);
  if (!fields_->stale(timeS, settings.fieldRes))
    std::erase_if(passes, [](const PlannedPass& p) { return p.name.rfind("field.", 0) == 0; });
  // Converged: nothing the maps depend on changed and F reached sss.frames; only step 3 runs.
  if (maps_ && RadiosityMaps::applies(scene, settings) && !maps_->needsUpdate(mapStateKey, settings))
    std::erase_if(passes, [](const PlannedPass& p) { return p.name.rfind("sss.", 0) == 0; });
  // The image-space accumulation: its G-buffer once per accumulation, nothing once it is complete.
  if (imageSpace_ && ImageSpaceSss::applies(scene, settings)) {
    const std::string imageSpaceKey = ImageSpaceSss::stateKey(mapStateKey, scene, settings);
    if (!imageSpace_->needsUpdate(imageSpaceKey, settings))
      std::erase_if(passes, [](const PlannedPass& p) { return p.name.rfind("image_space.", 0) == 0; });
    else if (!imageSpace_->needsGBuffer(imageSpaceKey))
      std::erase_if(passes, [](const PlannedPass& p) { return p.name == "image_space.gbuffer"; });
  }
  // The VPLs read the maps and the geometry: nothing to redo while both hold, unless the directions
  // change every frame.
  if (vpls_ && vpls_->count() == settings.vpl.count && settings.vpl.stable && fields_ &&
      !fields_->stale(timeS, settings.fieldRes) && maps_ && !maps_->needsUpdate(mapStateKey, settings) &&
      vplKey_ == vplKey(settings, mapStateKey))
    std::erase_if(passes, [](const PlannedPass& p) { return p.name == "vpl"; });
  // SSLPV is deterministic: while its inputs hold, its grids are what a recomputation would give.
  if (sslpv_ && Sslpv::applies(scene, settings)) {
    const std::string medium = sslpvMediumKey(scene, settings, timeS);
    const bool mediumStale = sslpv_->mediumStale(medium);
    if (!mediumStale) std::erase_if(passes, [](const PlannedPass& p) { return p.name == "sslpv.voxelize"; });
    if (!mediumStale && !sslpv_->lightStale(Sslpv::lightKey(scene, settings, medium)))
      std::erase_if(passes, [](const PlannedPass& p) { return p.name.rfind("sslpv.", 0) == 0; });
  }
  return passes;
}

std::string Renderer::sslpvMediumKey(const Scene& scene, const RenderSettings& settings, double timeS) const {
  return Sslpv::mediumKey(scene, settings, fields_->animated() ? timeS : 0.0) + "|restart " +
         std::to_string(accumulation_);
}

std::string Renderer::mapKey(const Scene& scene, const RenderSettings& settings, double timeS) const {
  return RadiosityMaps::stateKey(scene, settings, fields_->animated() ? timeS : 0.0) + "|restart " +
         std::to_string(accumulation_);
}

std::string Renderer::vplKey(const RenderSettings& settings, const std::string& mapStateKey) {
  const VplSettings& v = settings.vpl;
  return mapStateKey + "|vpl " + std::to_string(v.count) + ',' + std::to_string(v.cubeSize) + ',' +
         std::to_string(static_cast<int>(v.placement)) + ',' + std::to_string(static_cast<int>(v.area)) + ',' +
         std::to_string(v.stable) + ',' + std::to_string(v.shadows) + ',' + std::to_string(v.shadowClusters) + ',' +
         std::to_string(v.shadowSize);
}

void Renderer::restartAccumulation() {
  ++accumulation_;
  noCacheFrame_ = 0;
}

void Renderer::ensureTargets(int width, int height) {
  if (radiance_.id() && radiance_.width() == width && radiance_.height() == height) return;
  radiance_ = gpu::Texture::create2D(GL_RGBA32F, width, height);
  radiance_.setFilter(GL_NEAREST, GL_NEAREST);
  depth_ = gpu::Texture::create2D(GL_DEPTH_COMPONENT32F, width, height);
  coverage_ = gpu::Texture::create2D(GL_RGBA8, width, height);
  coverage_.setFilter(GL_NEAREST, GL_NEAREST);
  target_ = gpu::Framebuffer();
  target_.attachColor(0, radiance_);
  target_.attachColor(1, coverage_);
  target_.attachDepth(depth_);
  target_.setDrawBuffers(2);
  target_.checkComplete("camera target");
}

FrameTimings Renderer::render(const Scene& sceneAsLoaded, const RenderSettings& settings, double timeS) {
  // Lights that follow a candle's flame move with t; everything else is the scene as loaded.
  const bool follows = std::any_of(sceneAsLoaded.lights.begin(), sceneAsLoaded.lights.end(),
                                   [](const Light& l) { return l.follow >= 0; });
  const Scene timed = follows ? sceneAtTime(sceneAsLoaded, timeS) : Scene{};
  const Scene& scene = follows ? timed : sceneAsLoaded;
  checkLimits(scene, settings);
  ensureTargets(settings.width, settings.height);
  geometry_.update(scene);
  timer_.beginFrame();
  shadows_.reset(scene.lights.size());
  const std::string key = mapKey(scene, settings, timeS);  // once: the plan and the G-buffer pass share it
  const float aspect = static_cast<float>(settings.width) / static_cast<float>(settings.height);
  for (const PlannedPass& pass : planFrame(scene, settings, timeS, key)) {
    gpu::GpuScope scope(timer_, pass.name);
    if (pass.name == "field.sample") {
      fields_->sample(timeS, settings.fieldRes, geometry_);
      geometry_.update(scene);
    } else if (pass.name == "field.extract") {
      fields_->extract();
    } else if (pass.name == "shadow.directional") {
      shadows_.renderDirectional(scene, settings, geometry_);
    } else if (pass.name == "shadow.point") {
      shadows_.renderPoint(scene, settings, geometry_);
    } else if (pass.name == "sss.light_gbuffer") {
      if (!maps_) maps_ = std::make_unique<RadiosityMaps>(shaders_);
      maps_->renderLightGBuffers(scene, settings, geometry_, key);
    } else if (pass.name == "sss.maps") {
      maps_->renderMaps(scene, settings, geometry_);
    } else if (pass.name == "sslpv.voxelize") {
      if (!sslpv_) sslpv_ = std::make_unique<Sslpv>(shaders_);
      sslpv_->voxelize(scene, settings, geometry_, sslpvMediumKey(scene, settings, timeS));
    } else if (pass.name == "sslpv.light_gbuffer") {
      sslpv_->renderLightGBuffers(scene, settings, geometry_,
                                  Sslpv::lightKey(scene, settings, sslpvMediumKey(scene, settings, timeS)));
    } else if (pass.name == "sslpv.inject") {
      sslpv_->inject(scene, settings);
    } else if (pass.name == "sslpv.propagate") {
      sslpv_->propagate(settings);
    } else if (pass.name == "vpl") {
      if (!vpls_) vpls_ = std::make_unique<VirtualPointLights>(shaders_);
      vpls_->render(scene, settings, geometry_, *maps_, vplFrame_++);
      vplKey_ = vplKey(settings, key);
    } else if (pass.name == "image_space.gbuffer") {
      if (!imageSpace_) imageSpace_ = std::make_unique<ImageSpaceSss>(shaders_);
      imageSpace_->renderGBuffer(scene, settings, geometry_, cameraView(scene.camera, aspect, geometry_.worldBounds()),
                                 shadows_, ImageSpaceSss::stateKey(key, scene, settings));
    } else if (pass.name == "image_space.scatter") {
      imageSpace_->scatter(scene, settings, cameraView(scene.camera, aspect, geometry_.worldBounds()));
    } else if (pass.name == "image_space.combine") {
      imageSpace_->combine(settings);
    } else if (pass.name == "surface") {
      const glm::vec4 clear(scene.background, 1.0f);
      glClearNamedFramebufferfv(target_.id(), GL_COLOR, 0, &clear.x);
      const glm::vec4 none(0.0f);
      glClearNamedFramebufferfv(target_.id(), GL_COLOR, 1, &none.x);
      const float one = 1.0f;
      glClearNamedFramebufferfv(target_.id(), GL_DEPTH, 0, &one);
      const CameraView camera = cameraView(scene.camera, aspect, geometry_.worldBounds());
      // The frame's method: which pass's output shades the translucent objects.
      TranslucentSource source;
      if (maps_ && RadiosityMaps::applies(scene, settings)) source.maps = maps_.get();
      if (maps_ && settings.sss.method == SssMethod::NoCache && RadiosityMaps::needsLightGBuffers(scene, settings))
        source.noCache = maps_.get();
      if (imageSpace_ && ImageSpaceSss::applies(scene, settings)) source.imageSpace = imageSpace_.get();
      if (sslpv_ && Sslpv::applies(scene, settings)) source.sslpv = sslpv_.get();
      const VirtualPointLights* vpls = vpls_ && VirtualPointLights::applies(scene, settings) ? vpls_.get() : nullptr;
      surface_.render(scene, settings, geometry_, camera, shadows_, source, vpls, noCacheFrame_++, target_,
                      settings.width, settings.height);
    }
  }
  FrameTimings t;
  t.passes = timer_.collect();
  for (const auto& p : t.passes) t.gpuTotalMs += p.gpuMs;
  return t;
}

void Renderer::display(GLuint target, int width, int height, const gpu::ToneMapSettings& toneMap) {
  display_.render(radiance_, target, width, height, toneMap);
}

gpu::Image Renderer::readRadiance() const { return gpu::readColor(target_, 0, radiance_.width(), radiance_.height()); }

MapCoverage Renderer::mapCoverage() const {
  const gpu::Image c = gpu::readColor(target_, 1, coverage_.width(), coverage_.height());
  MapCoverage m;
  for (const glm::vec4& p : c.pixels) {
    if (p.r < 0.5f) continue;
    ++m.translucentPixels;
    if (p.g < 0.5f) ++m.unseenPixels;
  }
  return m;
}

std::vector<std::uint8_t> Renderer::receiverMask() const {
  const gpu::Image c = gpu::readColor(target_, 1, coverage_.width(), coverage_.height());
  std::vector<std::uint8_t> mask(c.pixels.size());
  for (std::size_t i = 0; i < mask.size(); ++i) mask[i] = c.pixels[i].b > 0.5f ? 1 : 0;
  return mask;
}

std::size_t Renderer::gpuBytes() const {
  return radiance_.bytes() + coverage_.bytes() + depth_.bytes() + shadows_.bytes() + geometry_.bytes() + fields_->bytes() +
         (maps_ ? maps_->bytes() : 0) + (vpls_ ? vpls_->bytes() : 0) + (imageSpace_ ? imageSpace_->bytes() : 0) +
         (sslpv_ ? sslpv_->bytes() : 0);
}

}  // namespace tallow::sss
