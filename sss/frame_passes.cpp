#include "sss/frame_passes.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "sss/bloom.h"
#include "sss/local_exposure.h"
#include "sss/field_objects.h"
#include "sss/field_source.h"
#include "sss/shadow_pass.h"
#include "sss/still_average.h"
#include "sss/surface_pass.h"
#include "sss/translucency_method.h"

namespace tallow::sss {
namespace {

int fieldCount(const Scene& scene) {
  return static_cast<int>(std::count_if(scene.objects.begin(), scene.objects.end(),
                                        [](const SceneObject& o) { return o.shape == ShapeKind::Field; }));
}

bool anyAnimatedField(const Scene& scene) {
  return std::any_of(scene.objects.begin(), scene.objects.end(),
                     [](const SceneObject& o) { return o.shape == ShapeKind::Field && fieldAnimated(o.field); });
}

int shadowedLights(const Scene& scene, LightKind kind) {
  return static_cast<int>(std::count_if(scene.lights.begin(), scene.lights.end(),
                                        [&](const Light& l) { return l.castsShadows && l.kind == kind; }));
}

/// What a shadow pass reads: the shapes that cast and receive, where the lights are, the map size.
PassIo shadowIo(const char* written) {
  return {{resource::kGeometry, "scene.shapes", "scene.light_placement", "render.shadows", "render.shadow_map_size"},
          {written},
          {}};
}

}  // namespace

// --- fields ---------------------------------------------------------------------------------------

bool FieldSamplePass::needed(const FrameState& state) const { return fieldCount(state.scene) > 0; }

std::string FieldSamplePass::reason(const FrameState& state) const {
  // Blob, candle and melting meshes: evaluated on the GPU from uniforms at t (a melting mesh also
  // reads its static grids), unless field.evaluate=cpu; a still mesh is sampled on the CPU.
  const auto onGpu = std::count_if(state.scene.objects.begin(), state.scene.objects.end(), [&](const SceneObject& o) {
    return state.settings.fieldOnGpu && o.shape == ShapeKind::Field && fieldAnimated(o.field);
  });
  const std::string lattice = std::to_string(state.settings.fieldRes) + "^3 lattice";
  const auto cpu = fieldCount(state.scene) - onGpu;
  std::string out = std::to_string(fieldCount(state.scene)) + " field object(s) at a new time:";
  if (onGpu > 0)
    out.append(" ").append(std::to_string(onGpu)).append(" evaluated on the GPU on a ").append(lattice)
        .append(" (uniforms only)");
  if (onGpu > 0 && cpu > 0) out.append(";");
  if (cpu > 0)
    out.append(" ").append(std::to_string(cpu)).append(" sampled on the CPU on a ").append(lattice).append(" and uploaded");
  return out;
}

PassIo FieldSamplePass::io(const FrameState& state) const {
  // The fields' shapes are fixed when the renderer is made (FieldObjects); only t and the lattice
  // resolution change what is sampled. The extractor, made here, holds the vertex placement. A field
  // that does not move does not read t.
  PassIo io{{"field.res", "field.placement", "field.evaluate", "field.extraction"}, {resource::kFieldLattice}, {}};
  if (anyAnimatedField(state.scene)) io.reads.push_back("time");
  return io;
}

void FieldSamplePass::run(FrameContext& context, bool /*changed*/) {
  context.modules.find<FieldObjects>()->sample(context.state.timeS, fieldMeshingOf(context.settings()),
                                               context.geometry);
  context.geometry.update(context.scene());
}

bool FieldExtractPass::needed(const FrameState& state) const { return fieldCount(state.scene) > 0; }

std::string FieldExtractPass::reason(const FrameState& state) const {
  return std::string("GPU dual contouring (vertices at the ") +
         (state.settings.fieldPlacement == geometry::VertexPlacement::Qef ? "tangent planes' quadric minimum"
                                                                          : "edge crossings' mass point") +
         ") of the field lattice(s), " +
         (state.settings.fieldExtraction == geometry::ExtractionPath::Compute
              ? "by compute shaders into buffers drawn indirectly"
              : "by geometry shaders into transform-feedback buffers");
}

PassIo FieldExtractPass::io(const FrameState&) const { return {{resource::kFieldLattice}, {resource::kGeometry}, {}}; }

void FieldExtractPass::run(FrameContext& context, bool /*changed*/) { context.modules.find<FieldObjects>()->extract(); }

// --- shadow maps ----------------------------------------------------------------------------------

bool DirectionalShadowPass::needed(const FrameState& state) const {
  return ShadowPass::needsDirectional(state.scene, state.settings);
}

std::string DirectionalShadowPass::reason(const FrameState& state) const {
  return std::to_string(shadowedLights(state.scene, LightKind::Directional)) +
         " directional light(s) cast shadows: one orthographic depth layer each";
}

PassIo DirectionalShadowPass::io(const FrameState&) const { return shadowIo(resource::kShadowDirectional); }

void DirectionalShadowPass::run(FrameContext& context, bool /*changed*/) {
  context.modules.find<ShadowPass>()->renderDirectional(context.scene(), context.settings(), context.geometry);
}

bool PointShadowPass::needed(const FrameState& state) const { return ShadowPass::needsPoint(state.scene, state.settings); }

std::string PointShadowPass::reason(const FrameState& state) const {
  return std::to_string(shadowedLights(state.scene, LightKind::Point)) +
         " point light(s) cast shadows: one depth cube each (6 faces)";
}

PassIo PointShadowPass::io(const FrameState&) const { return shadowIo(resource::kShadowPoint); }

void PointShadowPass::run(FrameContext& context, bool /*changed*/) {
  context.modules.find<ShadowPass>()->renderPoint(context.scene(), context.settings(), context.geometry);
}

// --- the camera pass --------------------------------------------------------------------------------

std::string CameraPass::reason(const FrameState& state) const {
  const std::string translucent =
      !method_->shadesTranslucent(state)
          ? "Lambertian with direct light, shadows and ambient (method albedo: translucent objects use their albedo)"
          : method_->describeShading(state) + ", opaque ones Lambertian";
  return std::to_string(state.scene.objects.size()) + " object(s): " + translucent +
         " with direct light, shadows and ambient";
}

PassIo CameraPass::io(const FrameState& state) const {
  PassIo io{{resource::kGeometry, resource::kShadowDirectional, resource::kShadowPoint, "scene.shapes", "scene.albedo",
             "scene.materials", "scene.light_placement", "scene.light_intensity", "scene.camera", "scene.environment",
             "scene.ambient", "scene.background", "render.width", "render.height", "render.shadows",
             "render.shadow_bias", "render.pcf_radius", "render.specular", "render.flame", "flame.exposure_ev", "method"},
            {resource::kCamera},
            {}};
  const PassIo m = method_->surfaceIo(state);
  io.reads.insert(io.reads.end(), m.reads.begin(), m.reads.end());
  return io;
}

void CameraPass::run(FrameContext& context, bool /*changed*/) {
  if (context.state.accumulation != accumulation_) {  // Renderer::restartAccumulation: the seeds start over
    accumulation_ = context.state.accumulation;
    frame_ = 0;
  }
  const CameraTarget& t = context.target;
  const glm::vec4 clear(context.scene().background, 1.0f);
  glClearNamedFramebufferfv(t.framebuffer.id(), GL_COLOR, 0, &clear.x);
  const glm::vec4 none(0.0f);
  glClearNamedFramebufferfv(t.framebuffer.id(), GL_COLOR, 1, &none.x);
  const glm::uvec4 noBins(0u);
  glClearNamedFramebufferuiv(t.framebuffer.id(), GL_COLOR, 2, &noBins.x);
  glClearNamedFramebufferfv(t.framebuffer.id(), GL_COLOR, 3, &none.x);
  glClearNamedFramebufferfv(t.framebuffer.id(), GL_COLOR, 5, &none.x);  // no receiver (4 is read only where 5 says)
  const float one = 1.0f;
  glClearNamedFramebufferfv(t.framebuffer.id(), GL_DEPTH, 0, &one);
  context.cameraFrame = frame_++;
  context.modules.find<SurfacePass>()->render(context);
}

// --- the picture shown: glare, then local adaptation ------------------------------------------------

namespace {

/// "key = share: what" for the reason of a pass whose parameter is a share.
std::string shareReason(const char* key, float share, const char* what) {
  char value[32];
  std::snprintf(value, sizeof value, "%g", double(share));
  return std::string(key) + " = " + value + ": " + what;
}

/// The picture shown through `Effect` (Bloom, LocalExposure: apply(picture, share, exposure scale,
/// coverage) and output()), which becomes the picture shown, its alpha the coverage's code
/// (common/coverage_masks.glsl).
template <class Effect>
void showThrough(FrameContext& context, float share) {
  Effect& effect = context.modules.obtain<Effect>(context.shaders);
  effect.apply(*context.shown, share, std::exp2(context.settings().toneMap.exposureEv), &context.target.coverage);
  context.shown = &effect.output();
}

}  // namespace


std::string BloomPass::reason(const FrameState& state) const {
  return shareReason("render.bloom", state.settings.bloom,
                     "that share of the light above white spread by a glare PSF (1/r² over 2 to 64 pixels, flux "
                     "kept) into the picture shown; the radiance (EXR) unchanged");
}

PassIo BloomPass::io(const FrameState&) const {
  // It also reads render.exposure_ev (white is where the exposure puts it), a display-only input
  // that no pass declares: the pass runs after every camera pass (runsAgain) and so always sees
  // the exposure of its frame.
  return {{resource::kCamera, "render.bloom"}, {}, {}};
}

void BloomPass::run(FrameContext& context, bool /*changed*/) { showThrough<Bloom>(context, context.settings().bloom); }

std::string LocalExposurePass::reason(const FrameState& state) const {
  return shareReason("render.local_exposure", state.settings.localExposure,
                     "the picture shown with each region's edge-aware mean log luminance (a bilateral grid) that "
                     "share nearer mid grey where it is darker; the radiance (EXR) unchanged");
}

PassIo LocalExposurePass::io(const FrameState&) const {
  // Like the glare, it reads render.exposure_ev (mid grey is where the exposure puts it) and runs
  // after every camera pass (runsAgain), so it always sees its frame's exposure.
  return {{resource::kCamera, "render.local_exposure"}, {}, {}};
}

void LocalExposurePass::run(FrameContext& context, bool /*changed*/) {
  showThrough<LocalExposure>(context, context.settings().localExposure);
}

// --- the still's average ----------------------------------------------------------------------------

std::string StillAveragePass::reason(const FrameState& state) const {
  return "render.aa = " + std::to_string(state.settings.aaSamples) +
         ": while nothing changes, each frame drawn at the next sub-pixel position and averaged into the "
         "picture (anti-aliased edges; the translucent estimate weighted by its samples where it is drawn)";
}

PassIo StillAveragePass::io(const FrameState&) const { return {{resource::kCamera, "render.aa"}, {}, {}}; }

void StillAveragePass::run(FrameContext& context, bool /*changed*/) {
  context.modules.obtain<StillAverage>(context.shaders)
      .add(context.target.radiance, context.target.translucent, context.method.stillWeight(context),
           context.stillFrame == 0);
}

}  // namespace tallow::sss
