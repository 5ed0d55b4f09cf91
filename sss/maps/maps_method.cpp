#include "sss/maps/maps_method.h"

#include <algorithm>

#include "sss/maps/map_count.h"
#include "sss/maps/radiosity_maps.h"
#include "sss/maps/virtual_point_lights.h"

namespace tallow::sss {
namespace {

int countLights(const Scene& scene, LightKind kind) {
  int n = 0;
  for (const Light& l : scene.lights) n += l.kind == kind ? 1 : 0;
  return n;
}

/// What the gather (maps/gather.glsl) reads beyond the light G-buffers: the lights' radiometry and
/// placement, the materials, the model and its sampling options. The maps' pass and the no-cache
/// camera pass both run it.
std::vector<std::string> gatherReads() {
  return {resource::kLightGBuffers, "scene.light_placement", "scene.light_intensity", "scene.materials", "sss.model",
          "sss.samples", "sss.stereographic", "sss.point_share", "sss.projected_area", "sss.texel_plane"};
}

void append(std::vector<std::string>& to, const std::vector<std::string>& from) {
  to.insert(to.end(), from.begin(), from.end());
}

RadiosityMaps& maps(FrameContext& context) { return context.modules.obtain<RadiosityMaps>(context.shaders); }

/// The light G-buffers the gather reads (the maps' and no-cache's).
void addLightGBuffers(const Scene& scene, const RenderSettings& settings, const BudgetSizes& sizes, FrameMemory& m) {
  if (!RadiosityMaps::needsLightGBuffers(scene, settings)) return;
  const int directional = countLights(scene, LightKind::Directional), point = countLights(scene, LightKind::Point);
  const auto [size, text] = budgetSize("sss.light_map_size", sizes.lightMapSize, settings.sss.lightMapSize);
  m.add("light G-buffers", std::to_string(directional) + " directional and " + std::to_string(point) + " point light(s) at " + text,
        lightGBufferBytes(directional, point, size));
}

/// A size setting as --explain prints it: the texels, or "auto" (chosen when the pass runs).
std::string sizeText(int size) { return size == kAuto ? std::string("auto") : std::to_string(size); }

}  // namespace

// --- sss.light_gbuffer ----------------------------------------------------------------------------

std::string LightGBufferPass::reason(const FrameState& state) const {
  return std::to_string(countLights(state.scene, LightKind::Directional)) + " directional (orthographic layer) and " +
         std::to_string(countLights(state.scene, LightKind::Point)) + " point (cube) light G-buffer(s), " +
         sizeText(state.settings.sss.lightMapSize) + "^2, one layered pass each kind";
}

PassIo LightGBufferPass::io(const FrameState&) const {
  // The materials set the size when sss.light_map_auto fits it to the shortest 1/σ_tr; "accumulation"
  // makes a restart of the progressive methods (bench) redraw it, as their first frame does.
  return {{resource::kGeometry, "scene.shapes", "scene.light_placement", "scene.materials", "sss.light_map_size",
           "sss.light_map_auto", "accumulation"},
          {resource::kLightGBuffers},
          {}};
}

void LightGBufferPass::run(FrameContext& context, bool /*changed*/) {
  maps(context).renderLightGBuffers(context.scene(), context.settings(), context.geometry);
}

// --- sss.maps -------------------------------------------------------------------------------------

std::string RadiosityMapsPass::reason(const FrameState& state) const {
  const SssSettings& s = state.settings.sss;
  const std::string k = state.scene.mapDirections.empty() && s.maps == kAuto
                            ? "auto (from their coverage, at most " + std::to_string(kAutoMapsMax) + ")"
                            : std::to_string(mapCount(state.scene, state.settings));
  return k + (state.scene.mapDirections.empty() ? " (Halton)" : " (listed in the preset)") + " scattered radiosity maps of " +
         sizeText(s.mapSize) + "^2: depth pre-pass, then " + std::to_string(s.samples) +
         " samples per texel and colour band (" + std::string(bssrdfModelName(s.model)) +
         " dipole), accumulated until " + std::to_string(s.frames) + " frames";
}

PassIo RadiosityMapsPass::io(const FrameState&) const {
  PassIo io{{resource::kGeometry, "scene.shapes", "scene.map_directions", "sss.maps", "sss.map_size", "sss.gather",
             "sss.history", "sss.history_move", "sss.history_rescale", "accumulation"},
            {resource::kRadiosityMaps},
            {"sss.frames"}};
  append(io.reads, gatherReads());
  return io;
}

bool RadiosityMapsPass::runsAgain(const FrameState& state) const {
  // A history kept through motion leaves the estimate in the still that follows (issue 38), also
  // when it holds sss.frames frames already (sss.frames ≤ sss.history).
  return frames_ < state.settings.sss.frames || stillPending_;
}

void RadiosityMapsPass::run(FrameContext& context, bool changed) {
  // What may change without a restart when sss.history > 0: the geometry and the light G-buffers
  // (resources, not inputs), the time, where the lights are (a candle's flame moves with it) and how
  // bright they are (the flame's flicker changes its light's flux every frame: restarting on it kept
  // the melting candle's maps at one frame, its history never used); the kept history is rescaled to
  // the new light (sss.history_rescale), as for a light that moves.
  // Any other input (materials, K, the estimator's settings, a bench's restart) restarts the maps,
  // and so does Renderer::invalidate (as if nothing had run); so does a change of sss.history or
  // sss.history_move themselves, like any setting of the maps.
  // A change of K alone (sss.maps=auto's choice, or the user's) in a frame where nothing moved keeps
  // the maps that stay: the Halton directions are nested (MapsUpdate::Resize).
  Fingerprint key, keyBesideK, motion;
  for (const std::string& name : io(context.state).reads) {
    if (!isInput(name)) continue;
    if (name == "time" || name == "scene.light_placement" || name == "scene.light_intensity") {
      motion << inputFingerprint(name, context.state);
      continue;
    }
    key << inputFingerprint(name, context.state);
    if (name != "sss.maps") keyBesideK << inputFingerprint(name, context.state);
  }
  const bool sameSettings = key.value() == restartKey_;
  const bool onlyK = !sameSettings && keyBesideK.value() == restartKeyBesideK_ && motion.value() == motionKey_;
  restartKey_ = key.value();
  restartKeyBesideK_ = keyBesideK.value();
  motionKey_ = motion.value();
  // sss.history = 0 is the paper's restart at every change, a change of K among them.
  const bool keep = !context.invalidated && context.settings().sss.history > 0;
  MapsUpdate update = MapsUpdate::Accumulate;
  if (changed)
    update = keep && onlyK ? MapsUpdate::Resize : keep && sameSettings ? MapsUpdate::Reuse : MapsUpdate::Restart;
  RadiosityMaps& m = maps(context);
  m.renderMaps(context.scene(), context.settings(), context.geometry, update);
  frames_ = m.frames();
  stillPending_ = m.stillPending();
}

// --- vpl --------------------------------------------------------------------------------------------

std::string VplPass::reason(const FrameState& state) const {
  return VirtualPointLights::describe(state.scene, state.settings);
}

PassIo VplPass::io(const FrameState&) const {
  // B(x_v) comes from Algorithm 1 over the maps (sss.bias, sss.comb, sss.view_weight); placement
  // auto looks for point lights inside the translucent objects' box; A_v needs the shapes.
  return {{resource::kRadiosityMaps, resource::kGeometry, "scene.shapes", "scene.materials", "scene.light_placement",
           "sss.bias", "sss.comb", "sss.view_weight", "vpl.count", "vpl.cube_size", "vpl.placement", "vpl.area",
           "vpl.stable", "vpl.shadows", "vpl.shadow_clusters", "vpl.shadow_size"},
          {resource::kVpls},
          {}};
}

void VplPass::run(FrameContext& context, bool /*changed*/) {
  auto& vpls = context.modules.obtain<VirtualPointLights>(context.shaders);
  vpls.render(context.scene(), context.settings(), context.geometry, *context.modules.find<RadiosityMaps>(), frame_++,
              context.countMapCoverage);
}

// --- vpl.receivers ----------------------------------------------------------------------------------

std::string VplReceiversPass::reason(const FrameState& state) const {
  return "the " + std::to_string(state.settings.vpl.count) +
         " VPLs' emergent light on every opaque pixel (Eq. 15), in compute over the camera pass's receivers";
}

PassIo VplReceiversPass::io(const FrameState&) const {
  // Added to each new picture of the camera pass (kCamera: it reruns whenever that does), from this
  // frame's VPLs; the VPL shadows' normal offset follows the lights' (render.pcf_radius, shadow_bias).
  return {{resource::kCamera, resource::kVpls, "render.pcf_radius", "render.shadow_bias"}, {}, {}};
}

void VplReceiversPass::run(FrameContext& context, bool /*changed*/) {
  if (VirtualPointLights* vpls = context.modules.find<VirtualPointLights>())
    vpls->lightReceivers(context.target, context.settings());
}

// --- the methods ------------------------------------------------------------------------------------

void RadiosityMapsMethod::checkLimits(const FrameState& state) const {
  RadiosityMaps::checkLimits(state.scene, state.settings);
  VirtualPointLights::checkLimits(state.scene, state.settings);
}

std::vector<Pass*> RadiosityMapsMethod::passes(const FrameState& state) {
  if (!anyTranslucent(state.scene)) return {};
  std::vector<Pass*> p{gbuffer_.get(), &maps_};
  if (VirtualPointLights::applies(state.scene, state.settings)) p.push_back(&vpl_);
  return p;
}

bool RadiosityMapsMethod::shadesTranslucent(const FrameState& state) const { return anyTranslucent(state.scene); }

bool RadiosityMapsMethod::choosesMapCount(const FrameState& state) const {
  return state.settings.sss.maps == kAuto && state.scene.mapDirections.empty() &&
         RadiosityMaps::applies(state.scene, state.settings);
}

bool RadiosityMapsMethod::countsVplCoverage(const FrameState& state) const {
  return VirtualPointLights::applies(state.scene, state.settings);
}

std::string RadiosityMapsMethod::surfaceShader() const {
  return VirtualPointLights::computeReceivers() ? "maps/surface_algorithm1.glsl"
                                                : "maps/surface_algorithm1_vpl_fragment.glsl";
}

std::vector<Pass*> RadiosityMapsMethod::afterCamera(const FrameState& state) {
  if (!anyTranslucent(state.scene) || !VirtualPointLights::computeReceivers() ||
      !VirtualPointLights::applies(state.scene, state.settings))
    return {};
  return {&vplReceivers_};
}

void RadiosityMapsMethod::addMemory(const Scene& scene, const RenderSettings& settings, const BudgetSizes& sizes,
                                    FrameMemory& m) const {
  addLightGBuffers(scene, settings, sizes, m);
  const SssSettings& s = settings.sss;
  if (RadiosityMaps::applies(scene, settings)) {
    const int k = mapCount(scene, settings);
    const auto [size, text] = budgetSize("sss.map_size", sizes.mapSize, s.mapSize);
    const std::string count = s.maps == kAuto && scene.mapDirections.empty()
                                  ? "sss.maps=auto (at most " + std::to_string(k) + ")"
                                  : "sss.maps=" + std::to_string(k);
    m.add("radiosity maps", count + " × " + text, radiosityMapBytes(k, size, s.computeGather, s.history > 0));
  }
  if (VirtualPointLights::applies(scene, settings)) {
    const VplSettings& v = settings.vpl;
    m.add("VPLs", "vpl.count=" + std::to_string(v.count) + ", " + squareText("vpl.cube_size", v.cubeSize), vplBytes(v));
    m.add("VPL shadow maps",
          "vpl.shadow_clusters=" + std::to_string(v.shadowClusters) + " × " + squareText("vpl.shadow_size", v.shadowSize),
          vplShadowBytes(v));
  }
}

void NoCacheMethod::addMemory(const Scene& scene, const RenderSettings& settings, const BudgetSizes& sizes,
                              FrameMemory& m) const {
  addLightGBuffers(scene, settings, sizes, m);
}

std::string RadiosityMapsMethod::describeShading(const FrameState&) const {
  return "translucent ones from the radiosity maps (Algorithm 1, Eq. 5)";
}

PassIo RadiosityMapsMethod::surfaceIo(const FrameState& state) const {
  PassIo io{{resource::kRadiosityMaps, "sss.bias", "sss.comb", "sss.view_weight"}, {}, {}};
  if (VirtualPointLights::applies(state.scene, state.settings)) io.reads.push_back(resource::kVpls);
  return io;
}

void RadiosityMapsMethod::bindSurface(gpu::Program& p, const FrameContext& context, GLuint firstUnit) const {
  const GLuint mapsUnit = firstUnit, depthUnit = firstUnit + 1, vplShadowUnit = firstUnit + 2;
  const RadiosityMaps* maps = context.modules.find<RadiosityMaps>();
  if (maps && shadesTranslucent(context.state)) {
    maps->setAlgorithm1Uniforms(p, context.settings(), mapsUnit, depthUnit, true, false);
  } else {
    p.set("uMaps", static_cast<int>(mapsUnit));
    p.set("uMapDepth", static_cast<int>(depthUnit));
    p.set("uMapCount", 0);
  }
  const bool vpls = VirtualPointLights::applies(context.scene(), context.settings());
  VirtualPointLights::setReceiverUniforms(p, vpls ? context.modules.find<VirtualPointLights>() : nullptr,
                                          vplShadowUnit);
}

double RadiosityMapsMethod::stillWeight(const FrameContext& context) const {
  const RadiosityMaps* maps = context.modules.find<RadiosityMaps>();
  return maps ? std::max(1.0, static_cast<double>(maps->frames())) : 1.0;
}

std::vector<Pass*> NoCacheMethod::passes(const FrameState& state) {
  if (!anyTranslucent(state.scene)) return {};
  return {gbuffer_.get()};
}

bool NoCacheMethod::shadesTranslucent(const FrameState& state) const { return anyTranslucent(state.scene); }

std::string NoCacheMethod::describeShading(const FrameState& state) const {
  return "translucent ones by the gather per pixel against the light G-buffers (no-cache: " +
         std::to_string(state.settings.sss.samples) + " samples per pixel and band, a new estimate every frame)";
}

PassIo NoCacheMethod::surfaceIo(const FrameState&) const {
  // A restart of the accumulation (bench) starts the frames' seeds over.
  PassIo io{{"accumulation"}, {}, {}};
  append(io.reads, gatherReads());
  return io;
}

void NoCacheMethod::bindSurface(gpu::Program& p, const FrameContext& context, GLuint firstUnit) const {
  // The gather's samplers on their own units even when there is nothing to gather: a sampler left on
  // unit 0 would clash with the shadow map's type there and void every draw.
  p.set("uSssDirPosition", static_cast<int>(firstUnit));
  p.set("uSssDirNormal", static_cast<int>(firstUnit + 1));
  p.set("uSssPointGPosition", static_cast<int>(firstUnit + 2));
  p.set("uSssPointGNormal", static_cast<int>(firstUnit + 3));
  const RadiosityMaps* maps = context.modules.find<RadiosityMaps>();
  if (maps && shadesTranslucent(context.state))
    maps->setGatherUniforms(p, context.scene(), context.settings(), firstUnit, context.cameraFrame);
}

}  // namespace tallow::sss
