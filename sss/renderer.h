#pragma once
// One frame as a plan of passes (sss/frame_plan.h): the field objects' isosurfaces, the shadow
// maps, the translucency method's passes and the camera pass. render() runs those whose declared
// inputs changed (sss/pass.h says when a pass reruns), times each on the GPU, and keeps what they
// made for the next frame; plan() and planFrame() say which passes and why (`--explain`).
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <set>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "gpu/gl_objects.h"
#include "gpu/gpu_timer.h"
#include "gpu/image.h"
#include "gpu/shader_library.h"
#include "sss/display_pass.h"
#include "sss/frame_plan.h"
#include "sss/maps/map_coverage_probe.h"
#include "sss/maps/map_count.h"
#include "sss/pass.h"
#include "sss/render_settings.h"
#include "sss/scene.h"
#include "sss/scene_geometry.h"

namespace tallow::sss {

class FieldObjects;

/// Visible pixels of translucent objects shaded from the radiosity maps, and those no map sees
/// (Algorithm 1's n = 0: they get B = 0).
struct MapCoverage {
  std::size_t translucentPixels = 0, unseenPixels = 0;
  double unseenShare() const { return translucentPixels ? double(unseenPixels) / double(translucentPixels) : 0.0; }
};

/// One frame's time per pass: the CPU clock's when render() returns, the GPU's once the timer
/// queries are read (Renderer::resolveTimings, or Renderer::latestTimings for an earlier frame).
struct FrameTimings {
  std::uint64_t frame = 0;              ///< the renderer's frame number (gpu::GpuTimer)
  std::vector<gpu::PassTiming> passes;  ///< per pass that ran, in order
  double cpuTotalMs = 0.0;
  double threadCpuTotalMs = 0.0;  ///< Σ passes' threadCpuMs
  double gpuTotalMs = std::numeric_limits<double>::quiet_NaN();  ///< NaN until resolved
  bool gpuKnown() const { return !std::isnan(gpuTotalMs); }
};

/// Per pixel of a frame (top row first): 1 where the camera sees a translucent object (and no candle
/// flame in front of it), and 1 where it sees an opaque surface (a receiver of the VPLs' light).
struct PixelMasks {
  std::vector<std::uint8_t> translucent, receivers;
};
/// The masks of a coverage image read back (Renderer::coverage()).
PixelMasks pixelMasksOf(const gpu::Image& coverage);
/// The masks of the picture shown read back when it is not the radiance (the glare's or the local
/// exposure's output, whose alpha is the coverage's code: common/coverage_masks.glsl).
PixelMasks pixelMasksOfCode(const gpu::Image& shown);

/// Checks settings and scene against the limits of the renderer and of the current GL context;
/// throws std::invalid_argument with one line (e.g. a shadow map larger than GL_MAX_TEXTURE_SIZE).
void checkLimits(const Scene& scene, const RenderSettings& settings);

class Renderer {
 public:
  /// Compiles the shared passes and uploads the scene's shapes. Needs a current GL 4.5 context.
  Renderer(const gpu::ShaderLibrary& shaders, const Scene& scene, const RenderSettings& settings);
  /// The renderer keeps a reference to the shader library: a temporary would dangle.
  Renderer(gpu::ShaderLibrary&&, const Scene&, const RenderSettings&) = delete;
  ~Renderer();

  /// The passes of a first frame, with why the scene needs each (no GL context needed).
  static std::vector<PlannedPass> plan(const Scene& scene, const RenderSettings& settings);
  /// The passes render(scene, settings, timeS) would run now: those whose declared inputs changed
  /// since they last ran, the progressive ones still accumulating, and the camera pass.
  std::vector<PlannedPass> planFrame(const Scene& scene, const RenderSettings& settings, double timeS) const;

  /// Renders the frame at time `timeS` into the HDR target (settings.width × settings.height).
  /// `scene` must have the same objects as at construction; transforms and parameters may change.
  /// Never waits for the GPU: the timings returned hold each pass's CPU time; their GPU times come
  /// from resolveTimings (after a glFinish, at no wait) or, frames later, from latestTimings.
  FrameTimings render(const Scene& scene, const RenderSettings& settings, double timeS);
  /// Fills t's GPU times from the timer ring, waiting for them when `wait`; false when they are not
  /// available (wait = false) or no longer kept (more than gpu::GpuTimer::kRing frames ago).
  bool resolveTimings(FrameTimings& t, bool wait = true) const;
  /// The newest frame whose GPU times are known, looked up without waiting (frame 0: none yet).
  const FrameTimings& latestTimings();
  /// Tone maps the last frame into framebuffer `target` (0 = window) of the given size.
  void display(GLuint target, int width, int height, const gpu::ToneMapSettings& toneMap);

  gpu::Image readRadiance() const;  ///< the last frame, linear, top row first
  /// The picture shown of the last frame (what display() tone-maps, PNGs and videos are made of):
  /// the radiance with render.bloom's glare and render.local_exposure's adaptation where they are
  /// on, the radiance itself otherwise.
  gpu::Image readShown() const;
  /// Whether the picture shown is the radiance itself (no pass after the camera's changes it), so
  /// that a caller holding readRadiance()'s image need not read the frame twice.
  bool showsRadiance() const { return &shown() == &target_.radiance; }
  /// Coverage of the last frame by the radiosity maps (reads the frame back: for stats and tests).
  MapCoverage mapCoverage() const;
  /// Per pixel of the last frame (top row first): 1 where the camera sees an opaque surface (a
  /// receiver of the VPLs' light), 0 elsewhere. Reads the frame back.
  std::vector<std::uint8_t> receiverMask() const;
  /// Per pixel of the last frame: 1 where the camera sees a translucent object (and no candle flame
  /// in front of it). Reads the frame back.
  std::vector<std::uint8_t> translucentMask() const;
  /// Both masks from one read-back of the coverage target.
  PixelMasks pixelMasks() const;
  /// The texture the picture shown is in: the radiance, or the last afterPicture pass's output.
  const gpu::Texture& shownTexture() const { return shown(); }
  const gpu::Texture& radiance() const { return target_.radiance; }
  /// The camera target's coverage (Algorithm 1: r translucent, g seen by a map, b opaque) and depth
  /// attachments of the last frame, for the view window's debug views.
  const gpu::Texture& coverage() const { return target_.coverage; }
  const gpu::Texture& depth() const { return target_.depth; }
  /// Meshes, primitives and the last extraction of every field object; the field count reads a
  /// transform-feedback query, which waits for the GPU (a stall): call it for stats, not per frame.
  std::size_t triangleCount() const;
  /// triangleCount without a wait (the window's panel): nullopt while an extraction is on the GPU.
  std::optional<std::size_t> triangleCountIfAvailable() const;
  std::size_t gpuBytes() const;  ///< render targets, shadow maps, meshes, field extraction buffers, maps
  /// A method's GPU state (sss::RadiosityMaps, whose light G-buffers serve no-cache too;
  /// ImageSpaceSss, VirtualPointLights, Sslpv, …), once a frame has used it; null before. The
  /// renderer names no method: the caller names the module it looks at (the type must be complete).
  template <typename T>
  const T* module() const {
    return modules_.find<T>();
  }
  const SceneGeometry& geometry() const { return geometry_; }
  /// The scene's field objects (their extractors and the melting meshes' static grids on the GPU).
  const FieldObjects& fieldObjects() const;
  FieldObjects* mutableFieldObjects();
  /// After a frame, waits for its field extractions' counts: true when a mesh overflowed its
  /// buffers, which are grown (FieldObjects::growOverflowed); the frame, cut, must be rendered
  /// again. render() itself checks the last frame's without waiting and then redraws everything.
  bool repairGeometry();
  /// sss.maps=auto with a method that chooses K (TranslucencyMethod::choosesMapCount): the K the next
  /// frame uses (sss/maps/map_count.h), from the coverage read back so far; std::nullopt where
  /// nothing is chosen (a fixed K, listed map directions, a method without maps).
  std::optional<int> chosenMapCount(const Scene& scene, const RenderSettings& settings) const;
  /// The newest coverage counts read back for sss.maps=auto (none before the first arrives).
  const std::optional<MapCoverageCounts>& lastMapCoverage() const { return lastMapCoverage_; }
  /// Forgets what the progressive methods have accumulated, keeping every allocation: the next
  /// frame reruns every pass that reads the input "accumulation" (the methods' first passes, so the
  /// passes after them too) and restarts the no-cache seeds. For `tallow bench`, which times the
  /// frames after a warm-up frame.
  void restartAccumulation();
  /// Forgets what every pass made and what the renderer chose from earlier frames (sss.maps=auto's
  /// K and the coverage it measured): the next frame is drawn as a new renderer draws its first.
  void invalidate();
  /// The next frame skips these passes (by name), keeping what they last wrote, whatever their
  /// inputs say (one that never ran runs: it has nothing to keep): tests/frame_invalidation_gltest.cpp
  /// observes which passes a change needs.
  void hold(std::set<std::string> passes) { held_ = std::move(passes); }
  /// The next frame is a preview (the view window while the camera or a slider moves, issue 40):
  /// it skips the runs of refining passes (Pass::refines) whose inputs did not change — more
  /// accumulation of the same estimate — and keeps what they hold; a changed input still runs them.
  /// The frames after it refine again. The default candle at 320x180 on llvmpipe: the maps' 4 s of a
  /// 5 s frame skipped.
  void holdRefinement() { holdRefinement_ = true; }

 private:
  /// A resource's counts: `epoch` moves when its writer restarted (ran with changed inputs),
  /// `version` at every write.
  struct Stamp {
    std::uint64_t epoch = 0, version = 0;
    bool operator==(const Stamp&) const = default;
  };
  struct PassRecord {
    std::uint64_t inputs = 0;             ///< fingerprint of the inputs it read at its last run
    std::map<std::string, Stamp> seen;    ///< the resources it read, as they were then
  };
  enum class Due { No, Changed, Again };
  /// Whether `pass` runs in `state`, given the resources' stamps `resources`.
  Due due(const Pass& pass, const FrameState& state, const PassIo& io,
          const std::map<std::string, Stamp>& resources) const;
  /// The due passes of the frame in `state` in order, advancing `resources` as running them would.
  std::vector<std::pair<Pass*, Due>> schedule(const FrameState& state, std::map<std::string, Stamp>& resources) const;

  /// sss.maps=auto with a method that draws maps (TranslucencyMethod::choosesMapCount).
  bool choosesMapCount(const Scene& scene, const RenderSettings& settings) const;
  /// `settings` with sss.maps=auto replaced by the chosen K (what the passes and their inputs see).
  RenderSettings withChosenMaps(const Scene& scene, const RenderSettings& settings) const;
  /// Takes the newest coverage counts the GPU has finished (no wait) into the K chooser.
  void takeMapCoverage(const Scene& scene, const RenderSettings& settings);

  const gpu::ShaderLibrary& shaders_;
  SceneGeometry geometry_;
  ModuleStore modules_;
  mutable FramePlan plan_;  ///< mutable: listing the plan points the camera pass at the frame's method
  std::unordered_map<const Pass*, PassRecord> records_;
  std::map<std::string, Stamp> resources_;
  /// The last frame's picture shown (FrameContext::shown): the radiance, or the output of its last
  /// afterPicture pass (the glare, the local exposure); null before the first frame.
  const gpu::Texture* shown_ = nullptr;
  /// The texture display() tone-maps: shown_, or the radiance before the first frame.
  const gpu::Texture& shown() const;
  int stillFrame_ = 0;    ///< render.aa: frames since the still began (FrameContext::stillFrame)
  int accumulation_ = 0;  ///< restartAccumulation() calls: the input "accumulation"
  bool forget_ = false;   ///< invalidate(): every pass of the next frame runs as changed
  std::set<std::string> held_;  ///< hold(): passes the next frame skips
  bool holdRefinement_ = false;  ///< holdRefinement(): the next frame skips refining passes' Again
  DisplayPass display_;
  /// The coverage target (r translucent, g seen by a map, b opaque, a halved under the flame).
  gpu::Image readCoverage() const;
  gpu::GpuTimer timer_;
  std::vector<FrameTimings> pending_;  ///< rendered frames whose GPU times are not read yet (≤ kRing)
  FrameTimings latest_;                ///< the newest with GPU times
  CameraTarget target_;
  MapCountChooser mapCountChooser_;
  MapCoverageProbe coverageProbe_;
  std::optional<CoverageHistogram> vplCoverage_;  ///< the VPLs' counts, measured at vplCoverageMaps_
  int vplCoverageMaps_ = 0;
  std::optional<MapCoverageCounts> lastMapCoverage_;
};

}  // namespace tallow::sss
