#include "sss/renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <stdexcept>

#include "gpu/gl_limits.h"
#include "gpu/glsl_shared.h"
#include "gpu/readback.h"
#include "sss/field_objects.h"
#include "sss/field_source.h"
#include "sss/shadow_pass.h"
#include "sss/surface_pass.h"
#include "sss/memory_budget.h"
#include "sss/pixel_jitter.h"

namespace tallow::glsl {
#include "shaders/common/coverage_masks.glsl"
}  // namespace tallow::glsl

namespace tallow::sss {
namespace {

/// CPU time this thread has used, in ms (POSIX CLOCK_THREAD_CPUTIME_ID; 0 where it is missing).
double threadCpuMs() {
  timespec ts{};
  if (clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts) != 0) return 0.0;
  return 1e3 * static_cast<double>(ts.tv_sec) + 1e-6 * static_cast<double>(ts.tv_nsec);
}

}  // namespace

void checkLimits(const Scene& scene, const RenderSettings& settings) {
  int dirCount = 0, pointCount = 0;
  for (const Light& l : scene.lights) (l.kind == LightKind::Directional ? dirCount : pointCount)++;
  if (dirCount > kMaxDirectionalLights)
    throw std::invalid_argument("the scene has " + std::to_string(dirCount) + " directional lights; at most " +
                                std::to_string(kMaxDirectionalLights) + " are supported");
  if (pointCount > kMaxPointLights)
    throw std::invalid_argument("the scene has " + std::to_string(pointCount) + " point lights; at most " +
                                std::to_string(kMaxPointLights) + " are supported");
  const gpu::GlLimits& limits = gpu::glLimits();
  const GLint maxTexture = limits.maxTextureSize, maxLayers = limits.maxArrayTextureLayers;
  const GLint* maxViewport = limits.maxViewportDims;
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
  // Every method's limits, whichever is selected: a preset is refused the same way for all of them.
  const FrameState state{scene, settings, 0.0, 0};
  for (const auto& method : makeTranslucencyMethods()) method->checkLimits(state);
  checkMemoryBudget(scene, settings);  // after the per-method limits, which name a single setting
}

Renderer::Renderer(const gpu::ShaderLibrary& shaders, const Scene& scene, const RenderSettings& settings)
    : shaders_(shaders), geometry_(scene), display_(shaders) {
  modules_.obtain<FieldObjects>(shaders, scene);
  modules_.obtain<ShadowPass>(shaders);
  SurfacePass& surface = modules_.obtain<SurfacePass>(shaders);
  checkLimits(scene, settings);
  target_.ensure(settings.width, settings.height);
  if (scene.environment) surface.setEnvironment(*scene.environment);
}

Renderer::~Renderer() = default;

std::vector<PlannedPass> Renderer::plan(const Scene& scene, const RenderSettings& settings) {
  FramePlan plan;
  return plan.describe(FrameState{scene, settings, 0.0, 0});
}

Renderer::Due Renderer::due(const Pass& pass, const FrameState& state, const PassIo& io,
                            const std::map<std::string, Stamp>& resources) const {
  const auto record = records_.find(&pass);
  if (forget_ || record == records_.end()) return Due::Changed;
  Fingerprint inputs;
  bool newData = false;
  for (const std::string& name : io.reads) {
    if (isInput(name)) {
      inputs << inputFingerprint(name, state);
      continue;
    }
    const auto now = resources.find(name);
    const Stamp stamp = now == resources.end() ? Stamp{} : now->second;
    const auto then = record->second.seen.find(name);
    const Stamp seen = then == record->second.seen.end() ? Stamp{} : then->second;
    if (stamp.epoch != seen.epoch) return Due::Changed;
    newData |= stamp.version != seen.version;
  }
  if (inputs.value() != record->second.inputs) return Due::Changed;
  return newData || pass.runsAgain(state) ? Due::Again : Due::No;
}

std::vector<std::pair<Pass*, Renderer::Due>> Renderer::schedule(const FrameState& state,
                                                                std::map<std::string, Stamp>& resources) const {
  std::vector<std::pair<Pass*, Due>> out;
  for (Pass* pass : plan_.passes(state)) {
    if (held_.count(pass->name()) && records_.count(pass)) continue;  // a pass that never ran has nothing to keep
    const PassIo io = pass->io(state);
    const Due d = due(*pass, state, io, resources);
    if (d == Due::No) continue;
    if (holdRefinement_ && d == Due::Again && pass->refines()) continue;
    out.emplace_back(pass, d);
    for (const std::string& w : io.writes) {
      Stamp& s = resources[w];
      ++s.version;
      if (d == Due::Changed) ++s.epoch;
    }
  }
  return out;
}

bool Renderer::choosesMapCount(const Scene& scene, const RenderSettings& settings) const {
  const FrameState state{scene, settings, 0.0, 0};
  return plan_.method(state).choosesMapCount(state);
}

std::optional<int> Renderer::chosenMapCount(const Scene& scene, const RenderSettings& settings) const {
  if (!choosesMapCount(scene, settings)) return std::nullopt;
  return mapCountChooser_.k();
}

RenderSettings Renderer::withChosenMaps(const Scene& scene, const RenderSettings& settings) const {
  RenderSettings s = settings;
  if (choosesMapCount(scene, settings)) s.sss.maps = mapCountChooser_.k();
  return s;
}

void Renderer::takeMapCoverage(const Scene& scene, const RenderSettings& settings) {
  std::optional<MapCoverageCounts> counts = coverageProbe_.poll();
  if (!counts) return;
  // The VPL pass runs only when the maps change: its last counts at this K stand for the frames after.
  if (counts->vpls) {
    vplCoverage_ = counts->vpls;
    vplCoverageMaps_ = counts->maps;
  } else if (const FrameState state{scene, settings, 0.0, 0};
             vplCoverage_ && vplCoverageMaps_ == counts->maps && plan_.method(state).countsVplCoverage(state)) {
    counts->vpls = vplCoverage_;
  }
  mapCountChooser_.update(*counts);
  lastMapCoverage_ = std::move(counts);
}

std::vector<PlannedPass> Renderer::planFrame(const Scene& sceneAsLoaded, const RenderSettings& userSettings,
                                             double timeS) const {
  const Scene scene = sceneAtTime(sceneAsLoaded, timeS);
  const RenderSettings settings = withChosenMaps(scene, userSettings);
  const FrameState state{scene, settings, timeS, accumulation_};
  std::map<std::string, Stamp> resources = resources_;
  std::vector<PlannedPass> out;
  for (const auto& [pass, d] : schedule(state, resources))
    out.push_back({pass->name(), pass->reason(state), pass->io(state)});
  return out;
}

FrameTimings Renderer::render(const Scene& sceneAsLoaded, const RenderSettings& userSettings, double timeS) {
  // Lights that follow a candle's flame move with t; everything else is the scene as loaded.
  const Scene scene = sceneAtTime(sceneAsLoaded, timeS);
  checkLimits(scene, userSettings);  // sss.maps=auto: as many maps as auto may choose
  const bool countCoverage = choosesMapCount(scene, userSettings);
  if (countCoverage) takeMapCoverage(scene, userSettings);
  const RenderSettings settings = withChosenMaps(scene, userSettings);
  target_.ensure(settings.width, settings.height);
  // A field's mesh cut by its transform-feedback buffers in an earlier frame: grown, extracted again,
  // and everything after it drawn anew (issue 38); no wait: counts not in yet are looked at later.
  if (FieldObjects* fields = modules_.find<FieldObjects>(); fields && fields->growOverflowed(false)) forget_ = true;
  geometry_.update(scene);
  FrameTimings t;
  t.frame = timer_.beginFrame();
  const FrameState state{scene, settings, timeS, accumulation_};
  FrameContext context{state, shaders_, geometry_, modules_, target_, plan_.method(state)};
  context.invalidated = forget_;
  context.countMapCoverage = countCoverage && coverageProbe_.begin(settings.sss.maps);
  std::map<std::string, Stamp> before = resources_;
  const std::vector<std::pair<Pass*, Due>> due = schedule(state, resources_);
  // render.aa: a frame in which no pass runs with changed inputs continues the still (the same
  // picture, more samples); its camera moves to the next sub-pixel position. Otherwise the still
  // restarts at the pixel centres.
  const bool still = !forget_ && std::none_of(due.begin(), due.end(), [](const auto& p) {
    return p.second == Due::Changed && !p.first->afterPicture();
  });
  stillFrame_ = still ? stillFrame_ + 1 : 0;
  context.stillFrame = stillFrame_;
  if (settings.aaSamples > 1)
    context.cameraJitter = glm::vec2(pixelJitter(static_cast<unsigned>(stillFrame_ % settings.aaSamples)));
  for (const auto& [pass, d] : due) {
    {
      const auto start = std::chrono::steady_clock::now();
      const double threadStart = threadCpuMs();
      gpu::GpuScope scope(timer_, pass->name());
      pass->run(context, d == Due::Changed);
      gpu::PassTiming timing;
      timing.name = pass->name();
      // The thread's clock is read inside the wall clock's interval: a thread cannot use more CPU
      // time than passes, and the figures say so (FrameTimingsRenderer).
      timing.threadCpuMs = threadCpuMs() - threadStart;
      timing.cpuMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
      t.cpuTotalMs += timing.cpuMs;
      t.threadCpuTotalMs += timing.threadCpuMs;
      t.passes.push_back(std::move(timing));
    }
    // What it read, as it was when it ran: the stamps of this frame's writers before it (the
    // schedule already counted this frame's writes; a pass reads only what runs before it).
    const PassIo io = pass->io(state);
    PassRecord& record = records_[pass];
    Fingerprint inputs;
    record.seen.clear();
    for (const std::string& name : io.reads) {
      if (isInput(name)) inputs << inputFingerprint(name, state);
      else record.seen[name] = before.count(name) ? before[name] : Stamp{};
    }
    record.inputs = inputs.value();
    for (const std::string& w : io.writes) before[w] = resources_[w];
  }
  forget_ = false;
  held_.clear();
  holdRefinement_ = false;
  shown_ = context.shown;
  if (context.countMapCoverage) coverageProbe_.end();
  // No wait here: this frame's GPU times are read later (resolveTimings, latestTimings).
  pending_.push_back(t);
  if (pending_.size() > gpu::GpuTimer::kRing) pending_.erase(pending_.begin());
  return t;
}

bool Renderer::resolveTimings(FrameTimings& t, bool wait) const {
  if (t.gpuKnown()) return true;
  const auto ms = timer_.times(t.frame, wait);
  if (!ms || ms->size() != t.passes.size()) return false;
  t.gpuTotalMs = 0.0;
  for (std::size_t i = 0; i < ms->size(); ++i) {
    t.passes[i].gpuMs = (*ms)[i];
    t.gpuTotalMs += (*ms)[i];
  }
  // Available with the times (GpuTimer::times looked at both); none where the driver cannot count.
  if (const auto counts = timer_.counts(t.frame, wait); counts && counts->size() == t.passes.size())
    for (std::size_t i = 0; i < counts->size(); ++i) t.passes[i].counts = (*counts)[i];
  return true;
}

const FrameTimings& Renderer::latestTimings() {
  // Newest first: the first frame the GPU has finished is the one to show; older ones go.
  for (auto it = pending_.rbegin(); it != pending_.rend(); ++it)
    if (resolveTimings(*it, false)) {
      latest_ = *it;
      pending_.erase(pending_.begin(), it.base());
      break;
    }
  return latest_;
}

void Renderer::restartAccumulation() { ++accumulation_; }

void Renderer::invalidate() {
  forget_ = true;
  mapCountChooser_ = MapCountChooser{};
  coverageProbe_.forget();
  vplCoverage_.reset();
  vplCoverageMaps_ = 0;
  lastMapCoverage_.reset();
}

const gpu::Texture& Renderer::shown() const { return shown_ ? *shown_ : target_.radiance; }

void Renderer::display(GLuint target, int width, int height, const gpu::ToneMapSettings& toneMap) {
  display_.render(shown(), target, width, height, toneMap);
}

gpu::Image Renderer::readShown() const {
  if (&shown() == &target_.radiance) return readRadiance();
  return gpu::readTexture(shown());
}

gpu::Image Renderer::readRadiance() const {
  // From the texture itself (glGetTextureImage): no framebuffer binding to ask for and restore.
  return gpu::readTexture(target_.radiance);
}

MapCoverage Renderer::mapCoverage() const {
  const gpu::Image c = readCoverage();
  MapCoverage m;
  for (const glm::vec4& p : c.pixels) {
    if (p.r < 0.5f) continue;
    ++m.translucentPixels;
    if (p.g < 0.5f) ++m.unseenPixels;
  }
  return m;
}

gpu::Image Renderer::readCoverage() const {
  return gpu::readTexture(target_.coverage);
}

PixelMasks Renderer::pixelMasks() const { return pixelMasksOf(readCoverage()); }

PixelMasks pixelMasksOf(const gpu::Image& c) {
  PixelMasks m;
  m.translucent.resize(c.pixels.size());
  m.receivers.resize(c.pixels.size());
  for (std::size_t i = 0; i < c.pixels.size(); ++i) {
    m.translucent[i] = glsl::seesTranslucent(c.pixels[i]) ? 1 : 0;
    m.receivers[i] = glsl::seesReceiver(c.pixels[i]) ? 1 : 0;
  }
  return m;
}

PixelMasks pixelMasksOfCode(const gpu::Image& shown) {
  PixelMasks m;
  m.translucent.resize(shown.pixels.size());
  m.receivers.resize(shown.pixels.size());
  for (std::size_t i = 0; i < shown.pixels.size(); ++i) {
    const int code = static_cast<int>(std::lround(shown.pixels[i].a));
    m.translucent[i] = (code & 1) ? 1 : 0;
    m.receivers[i] = (code & 2) ? 1 : 0;
  }
  return m;
}

std::vector<std::uint8_t> Renderer::receiverMask() const { return pixelMasks().receivers; }

std::vector<std::uint8_t> Renderer::translucentMask() const { return pixelMasks().translucent; }

std::size_t Renderer::triangleCount() const {
  if (const std::optional<std::size_t> n = triangleCountIfAvailable()) return *n;
  glFinish();  // wanted now (stats at the end of a run): after a finish every query has its result
  if (const std::optional<std::size_t> n = triangleCountIfAvailable()) return *n;
  return geometry_.triangleCount() + modules_.find<FieldObjects>()->triangleCount();
}

std::optional<std::size_t> Renderer::triangleCountIfAvailable() const {
  const std::optional<std::size_t> fields = modules_.find<FieldObjects>()->triangleCountIfAvailable();
  if (!fields) return std::nullopt;
  return geometry_.triangleCount() + *fields;
}

std::size_t Renderer::gpuBytes() const { return target_.bytes() + geometry_.bytes() + modules_.bytes(); }

const FieldObjects& Renderer::fieldObjects() const { return *modules_.find<FieldObjects>(); }

FieldObjects* Renderer::mutableFieldObjects() { return modules_.find<FieldObjects>(); }

bool Renderer::repairGeometry() {
  FieldObjects* fields = modules_.find<FieldObjects>();
  if (!fields || !fields->growOverflowed(true)) return false;
  forget_ = true;
  return true;
}


}  // namespace tallow::sss
