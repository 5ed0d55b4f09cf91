#pragma once
// A pass of the frame plan (Filament's frame graph and Mitsuba's parameters_changed, in small): it
// says why the scene needs it, declares what it reads — frame inputs (sss/frame_inputs.h) and
// resources other passes write — and what it writes, and runs. The renderer (sss/renderer.h) runs a
// planned pass when
//   - it never ran, or an input it reads changed, or a resource it reads was rewritten from scratch
//     (the writer's epoch moved): run(context, /*changed=*/true), a restart;
//   - a resource it reads got new content without a restart (a progressive writer added a frame;
//     the version moved): run(context, false);
//   - it wants another frame for itself (runsAgain: a progressive accumulation that is not complete,
//     or the camera pass, which draws every frame): run(context, false);
// and skips it otherwise. Nothing else decides what is stale: a parameter a pass reads but does not
// declare is caught by tests/frame_invalidation_gltest.cpp.
#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <typeindex>
#include <unordered_map>
#include <vector>

#include "gpu/gl_objects.h"
#include "gpu/shader_library.h"
#include "sss/frame_inputs.h"
#include "sss/scene_geometry.h"
#include "sss/view_setup.h"

namespace tallow::sss {

class TranslucencyMethod;

/// Resources: what passes write and read, by name (the --explain of docs/architecture.md).
namespace resource {
inline constexpr const char* kFieldLattice = "field.lattice";  ///< field objects sampled at t
inline constexpr const char* kGeometry = "geometry";           ///< field objects' extracted triangles
inline constexpr const char* kShadowDirectional = "shadow_maps.directional";
inline constexpr const char* kShadowPoint = "shadow_maps.point";
inline constexpr const char* kCamera = "camera";  ///< the camera target: radiance, coverage, depth
}  // namespace resource

/// What a pass reads and writes, by name. `reads` holds frame inputs (inputNames()) and resources
/// (names another pass writes); `paces` holds inputs that only decide how many frames a progressive
/// pass accumulates (sss.frames): a change lets it run again, without a restart.
struct PassIo {
  std::vector<std::string> reads;
  std::vector<std::string> writes;
  std::vector<std::string> paces;
};

/// GPU state that outlives a frame and is shared by passes (the radiosity maps' textures, the
/// shadow maps, …), one object per type, made on first use.
class ModuleStore {
 public:
  /// The module of type T, made with T(args…) the first time.
  template <typename T, typename... Args>
  T& obtain(Args&&... args) {
    auto it = modules_.find(typeid(T));
    if (it == modules_.end()) {
      auto module = std::make_shared<T>(std::forward<Args>(args)...);
      Entry e{module, nullptr};
      if constexpr (requires(const T& t) { t.bytes(); }) e.bytes = [m = module.get()] { return m->bytes(); };
      it = modules_.emplace(typeid(T), std::move(e)).first;
    }
    return *static_cast<T*>(it->second.module.get());
  }
  /// The module of type T if it was made, else null.
  template <typename T>
  T* find() const {
    const auto it = modules_.find(typeid(T));
    return it == modules_.end() ? nullptr : static_cast<T*>(it->second.module.get());
  }
  /// GPU memory of every module that counts its own (a bytes() member).
  std::size_t bytes() const {
    std::size_t n = 0;
    for (const auto& [type, e] : modules_) n += e.bytes ? e.bytes() : 0;
    return n;
  }

 private:
  struct Entry {
    std::shared_ptr<void> module;
    std::function<std::size_t()> bytes;
  };
  std::unordered_map<std::type_index, Entry> modules_;
};

/// The camera's render target: linear radiance, Algorithm 1's coverage (r translucent, g seen by a
/// map, b opaque), sss.maps=auto's per-pixel coverage bins (shaders/surface.frag oCoverageBins), the
/// translucent part of the radiance (rgb: F_t/π·B, a: 1 where a translucent surface is drawn; the
/// still's average weights it by the estimate's samples, sss/still_average.h) and depth.
struct CameraTarget {
  gpu::Texture radiance, coverage, coverageBins, translucent, depth;
  /// The opaque receivers' G-buffer the camera pass leaves for the passes that light them after it
  /// (the VPLs' emergent light, sss/maps/virtual_point_lights.h): receiver xyz = world point's float
  /// bits, w = its unit normal (common/octahedral.glsl), integers so that no bit changes; receiverAlbedo rgb = ρ, a = 1 on an opaque
  /// receiver (cleared to 0 each frame).
  gpu::Texture receiver, receiverAlbedo;
  gpu::Framebuffer framebuffer;
  /// (Re)allocates for width × height; keeps the textures when the size is unchanged.
  void ensure(int width, int height);
  std::size_t bytes() const {
    return radiance.bytes() + coverage.bytes() + coverageBins.bytes() + translucent.bytes() + depth.bytes() +
           receiver.bytes() + receiverAlbedo.bytes();
  }
};

/// Everything a pass's run() may use.
struct FrameContext {
  const FrameState& state;
  const gpu::ShaderLibrary& shaders;
  SceneGeometry& geometry;
  ModuleStore& modules;
  CameraTarget& target;
  const TranslucencyMethod& method;  ///< the frame's method (the camera pass asks it to shade)
  /// Frames the camera pass drew since the accumulation began: seeds the no-cache gather.
  int cameraFrame = 0;
  /// Renderer::invalidate() before this frame: every pass runs as if it never ran (no history kept).
  bool invalidated = false;
  /// sss.maps=auto: Algorithm 1's callers count which map first sees each point into the buffer the
  /// renderer bound (sss/maps/map_coverage_probe.h).
  bool countMapCoverage = false;
  /// render.aa: this frame's place in the still (0: the still starts, nothing is averaged yet) and
  /// the camera's sub-pixel offset for it, in pixels (sss/pixel_jitter.h; (0, 0) at stillFrame 0).
  int stillFrame = 0;
  glm::vec2 cameraJitter{0.0f};
  /// The picture shown as the frame's passes leave it: the camera target's radiance, then each
  /// afterPicture pass's output (the glare, the local exposure) in turn.
  const gpu::Texture* shown = &target.radiance;
  const Scene& scene() const { return state.scene; }
  const RenderSettings& settings() const { return state.settings; }
  /// The scene camera for the target's aspect ratio, fitted to the geometry's bounds, moved by
  /// cameraJitter (every pass that draws for the camera target sees the same sub-pixel offset).
  CameraView camera() const;
};

class Pass {
 public:
  virtual ~Pass() = default;
  /// As in stats.json and `--explain`: "shadow.directional", "sss.maps", "surface", …
  virtual std::string name() const = 0;
  /// Why this scene needs the pass, for `--explain` (no GL: also called before any context).
  virtual std::string reason(const FrameState& state) const = 0;
  virtual PassIo io(const FrameState& state) const = 0;
  /// True when the pass wants to run although nothing it reads changed (see the file comment).
  virtual bool runsAgain(const FrameState& /*state*/) const { return false; }
  /// True for a progressive pass whose runs on unchanged inputs refine an estimate (the maps'
  /// accumulation): Renderer::holdRefinement skips those runs while the user moves something.
  virtual bool refines() const { return false; }
  /// True for a pass that only makes the picture shown from the finished picture (the glare): its
  /// changed inputs do not restart a still's average (render.aa).
  virtual bool afterPicture() const { return false; }
  /// Runs the pass; `changed`: an input or a resource's epoch changed since its last run (or it
  /// never ran, or the renderer forgot everything): progressive passes restart.
  virtual void run(FrameContext& context, bool changed) = 0;
};

}  // namespace tallow::sss
