#include "sss/peers/image_space_method.h"

#include <algorithm>

#include "sss/peers/image_space.h"
#include "sss/shadow_pass.h"

namespace tallow::sss {
namespace {

ImageSpaceSss& imageSpace(FrameContext& context) { return context.modules.obtain<ImageSpaceSss>(context.shaders); }

}  // namespace

std::string ImageSpaceGBufferPass::reason(const FrameState& state) const {
  return ImageSpaceSss::describe(state.scene, state.settings, name());
}

PassIo ImageSpaceGBufferPass::io(const FrameState&) const {
  // E F_t with the lights' shadows (lights.glsl: render.shadows, the bias and the PCF radius);
  // "accumulation": a restart (bench) redraws it, as a first frame does.
  return {{resource::kGeometry, resource::kShadowDirectional, resource::kShadowPoint, "scene.shapes",
           "scene.materials", "scene.light_placement", "scene.light_intensity", "scene.camera", "render.width",
           "render.height", "render.shadows", "render.shadow_bias", "render.pcf_radius", "accumulation"},
          {resource::kImageSpaceGBuffer},
          {}};
}

void ImageSpaceGBufferPass::run(FrameContext& context, bool) {
  imageSpace(context).renderGBuffer(context.scene(), context.settings(), context.geometry, context.camera(),
                                    *context.modules.find<ShadowPass>());
}

std::string ImageSpaceScatterPass::reason(const FrameState& state) const {
  return ImageSpaceSss::describe(state.scene, state.settings, name());
}

PassIo ImageSpaceScatterPass::io(const FrameState&) const {
  // image_space.tile also shapes the combine pass's window: the accumulation restarts with it.
  return {{resource::kImageSpaceGBuffer, "scene.materials", "scene.camera", "render.width", "render.height",
           "image_space.samples", "image_space.uniform_share", "image_space.tile", "image_space.radius",
           "image_space.depth_ratio", "image_space.jacobian"},
          {resource::kImageSpaceEstimate},
          {"image_space.frames"}};
}

bool ImageSpaceScatterPass::runsAgain(const FrameState& state) const {
  return frames_ < state.settings.imageSpace.frames;
}

void ImageSpaceScatterPass::run(FrameContext& context, bool changed) {
  ImageSpaceSss& is = imageSpace(context);
  if (changed) is.restart();
  frames_ = changed ? 1 : frames_ + 1;
  is.scatter(context.scene(), context.settings(), context.camera());
}

std::string ImageSpaceCombinePass::reason(const FrameState& state) const {
  return ImageSpaceSss::describe(state.scene, state.settings, name());
}

PassIo ImageSpaceCombinePass::io(const FrameState&) const {
  return {{resource::kImageSpaceEstimate, resource::kImageSpaceGBuffer, "image_space.tile"},
          {resource::kImageSpaceAccumulation},
          {}};
}

void ImageSpaceCombinePass::run(FrameContext& context, bool) { imageSpace(context).combine(context.settings()); }

void ImageSpaceMethod::checkLimits(const FrameState& state) const {
  ImageSpaceSss::checkLimits(state.scene, state.settings);
}

std::vector<Pass*> ImageSpaceMethod::passes(const FrameState& state) {
  if (!anyTranslucent(state.scene)) return {};
  return {&gbuffer_, &scatter_, &combine_};
}

bool ImageSpaceMethod::shadesTranslucent(const FrameState& state) const { return anyTranslucent(state.scene); }

void ImageSpaceMethod::addMemory(const Scene& scene, const RenderSettings& settings, const BudgetSizes&,
                                 FrameMemory& m) const {
  if (!ImageSpaceSss::applies(scene, settings)) return;
  m.add("image-space buffers",
        "render.width × render.height=" + std::to_string(settings.width) + "x" + std::to_string(settings.height),
        imageSpaceBytes(settings.width, settings.height, translucentObjectCount(scene), settings.imageSpace));
}

std::string ImageSpaceMethod::describeShading(const FrameState&) const {
  return "translucent ones from the image-space estimate at their pixel (L = F_t/pi B, standard dipole)";
}

PassIo ImageSpaceMethod::surfaceIo(const FrameState&) const {
  return {{resource::kImageSpaceAccumulation, "image_space.renormalize"}, {}, {}};
}

void ImageSpaceMethod::bindSurface(gpu::Program& p, const FrameContext& context, GLuint firstUnit) const {
  const ImageSpaceSss* is = context.modules.find<ImageSpaceSss>();
  const bool shades = shadesTranslucent(context.state);
  ImageSpaceSss::setSurfaceUniforms(p, shades ? is : nullptr, context.settings(), firstUnit);
}

double ImageSpaceMethod::stillWeight(const FrameContext& context) const {
  const ImageSpaceSss* is = context.modules.find<ImageSpaceSss>();
  return is ? std::max(1.0, static_cast<double>(is->frames())) : 1.0;
}

}  // namespace tallow::sss
