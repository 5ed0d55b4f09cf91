#include "sss/peers/sslpv_method.h"

#include "sss/peers/sslpv.h"

namespace tallow::sss {
namespace {

Sslpv& sslpv(FrameContext& context) { return context.modules.obtain<Sslpv>(context.shaders); }

}  // namespace

std::string SslpvVoxelizePass::reason(const FrameState& state) const {
  return Sslpv::describeVoxelize(state.scene, state.settings);
}

PassIo SslpvVoxelizePass::io(const FrameState&) const {
  // "accumulation": a restart (bench) recomputes the method from its first pass, as a first frame does.
  return {{resource::kGeometry, "scene.shapes", "scene.materials", "sslpv.grid", "accumulation"},
          {resource::kSslpvMedium},
          {}};
}

void SslpvVoxelizePass::run(FrameContext& context, bool) {
  sslpv(context).voxelize(context.scene(), context.settings(), context.geometry);
}

std::string SslpvLightGBufferPass::reason(const FrameState& state) const {
  return Sslpv::describeLightGBuffer(state.scene, state.settings);
}

PassIo SslpvLightGBufferPass::io(const FrameState&) const {
  return {{resource::kGeometry, resource::kSslpvMedium, "scene.shapes", "scene.light_placement", "sslpv.inject_size"},
          {resource::kSslpvLightGBuffers},
          {}};
}

void SslpvLightGBufferPass::run(FrameContext& context, bool) {
  sslpv(context).renderLightGBuffers(context.scene(), context.settings(), context.geometry);
}

std::string SslpvInjectPass::reason(const FrameState& state) const { return Sslpv::describeInject(state.settings); }

PassIo SslpvInjectPass::io(const FrameState&) const {
  // The propagation consumes the injected grid in place (ping-pong), so a propagation with other
  // steps needs a fresh injection: this pass reads what the propagation reads too.
  return {{resource::kSslpvLightGBuffers, resource::kSslpvMedium, "scene.light_placement", "scene.light_intensity",
           "scene.materials", "sslpv.inject_size", "sslpv.steps", "sslpv.skip"},
          {resource::kSslpvInjection},
          {}};
}

void SslpvInjectPass::run(FrameContext& context, bool) { sslpv(context).inject(context.scene(), context.settings()); }

std::string SslpvPropagatePass::reason(const FrameState& state) const {
  return Sslpv::describePropagate(state.settings);
}

PassIo SslpvPropagatePass::io(const FrameState&) const {
  return {{resource::kSslpvInjection, resource::kSslpvMedium, "sslpv.steps", "sslpv.skip"},
          {resource::kSslpvAccumulation},
          {}};
}

void SslpvPropagatePass::run(FrameContext& context, bool) { sslpv(context).propagate(context.settings()); }

void SslpvMethod::checkLimits(const FrameState& state) const { Sslpv::checkLimits(state.scene, state.settings); }

std::vector<Pass*> SslpvMethod::passes(const FrameState& state) {
  if (!anyTranslucent(state.scene)) return {};
  return {&voxelize_, &gbuffer_, &inject_, &propagate_};
}

bool SslpvMethod::shadesTranslucent(const FrameState& state) const { return anyTranslucent(state.scene); }

void SslpvMethod::addMemory(const Scene& scene, const RenderSettings& settings, const BudgetSizes&,
                            FrameMemory& m) const {
  if (!Sslpv::applies(scene, settings)) return;
  const SslpvSettings& v = settings.sslpv;
  int directional = 0, point = 0;
  for (const Light& l : scene.lights) (l.kind == LightKind::Directional ? directional : point)++;
  m.add("SSLPV grids", "sslpv.grid=" + std::to_string(v.grid) + "³", Sslpv::gridBytes(v.grid, translucentObjectCount(scene)));
  m.add("SSLPV light G-buffers", squareText("sslpv.inject_size", v.injectSize),
        lightGBufferBytes(directional, point, v.injectSize));
}

std::string SslpvMethod::describeShading(const FrameState&) const {
  return "translucent ones from the SSLPV accumulation grid (area light of Eqs. 5-7 after the SH rotation of Eq. 6)";
}

PassIo SslpvMethod::surfaceIo(const FrameState&) const {
  return {{resource::kSslpvAccumulation, resource::kSslpvMedium, "sslpv.exitance"}, {}, {}};
}

void SslpvMethod::bindSurface(gpu::Program& p, const FrameContext& context, GLuint firstUnit) const {
  const Sslpv* grids = context.modules.find<Sslpv>();
  if (grids && shadesTranslucent(context.state))
    grids->setLookupUniforms(p, context.settings(), firstUnit);
  else
    Sslpv::setLookupOff(p, firstUnit);
}

}  // namespace tallow::sss
