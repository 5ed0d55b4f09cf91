#pragma once
// One frame as a plan of passes: only the passes this scene needs run (no point-light cube maps
// without a point light that casts shadows, no shadow maps with shadows off…). plan() says which
// and why (`--explain`); render() runs them and times each on the GPU.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "gpu/gl_objects.h"
#include "gpu/gpu_timer.h"
#include "gpu/image.h"
#include "gpu/shader_library.h"
#include "sss/display_pass.h"
#include "sss/field_objects.h"
#include "sss/maps/radiosity_maps.h"
#include "sss/maps/virtual_point_lights.h"
#include "sss/peers/image_space.h"
#include "sss/render_settings.h"
#include "sss/scene.h"
#include "sss/scene_geometry.h"
#include "sss/shadow_pass.h"
#include "sss/surface_pass.h"

namespace tallow::sss {

struct PlannedPass {
  std::string name;    ///< as in stats.json: "shadow.directional", "surface", …
  std::string reason;  ///< why this scene needs it
};

/// Visible pixels of translucent objects shaded from the radiosity maps, and those no map sees
/// (Algorithm 1's n = 0: they get B = 0).
struct MapCoverage {
  std::size_t translucentPixels = 0, unseenPixels = 0;
  double unseenShare() const { return translucentPixels ? double(unseenPixels) / double(translucentPixels) : 0.0; }
};

struct FrameTimings {
  std::vector<gpu::PassTiming> passes;  ///< GPU ms per pass that ran
  double gpuTotalMs = 0.0;
};

/// Checks settings and scene against the limits of the renderer and of the current GL context;
/// throws std::invalid_argument with one line (e.g. a shadow map larger than GL_MAX_TEXTURE_SIZE).
void checkLimits(const Scene& scene, const RenderSettings& settings);

class Renderer {
 public:
  /// Compiles the passes and uploads the scene's shapes. Needs a current GL 4.5 context.
  Renderer(const gpu::ShaderLibrary& shaders, const Scene& scene, const RenderSettings& settings);

  /// The passes of a first frame (field objects are always sampled and extracted then).
  static std::vector<PlannedPass> plan(const Scene& scene, const RenderSettings& settings);
  /// The passes render(scene, settings, timeS) runs now: "field.sample" and "field.extract" only
  /// when a field object must be isosurfaced again (t or field.res changed since the last frame).
  std::vector<PlannedPass> planFrame(const Scene& scene, const RenderSettings& settings, double timeS) const;

  /// Renders the frame at time `timeS` into the HDR target (settings.width × settings.height).
  /// `scene` must have the same objects as at construction; transforms and parameters may change.
  FrameTimings render(const Scene& scene, const RenderSettings& settings, double timeS);
  /// Tone maps the last frame into framebuffer `target` (0 = window) of the given size.
  void display(GLuint target, int width, int height, const gpu::ToneMapSettings& toneMap);

  gpu::Image readRadiance() const;  ///< the last frame, linear, top row first
  /// Coverage of the last frame by the radiosity maps (reads the frame back: for stats and tests).
  MapCoverage mapCoverage() const;
  /// Per pixel of the last frame (top row first): 1 where the camera sees an opaque surface (a
  /// receiver of the VPLs' light), 0 elsewhere. Reads the frame back.
  std::vector<std::uint8_t> receiverMask() const;
  const gpu::Texture& radiance() const { return radiance_; }
  /// The camera target's coverage (Algorithm 1: r translucent, g seen by a map, b opaque) and depth
  /// attachments of the last frame, for the view window's debug views.
  const gpu::Texture& coverage() const { return coverage_; }
  const gpu::Texture& depth() const { return depth_; }
  /// Meshes, primitives and the last extraction of every field object; the field count reads a
  /// transform-feedback query, which waits for the GPU (a stall): call it for stats, not per frame.
  std::size_t triangleCount() const { return geometry_.triangleCount() + fields_->triangleCount(); }
  std::size_t gpuBytes() const;  ///< render targets, shadow maps, meshes, field extraction buffers, maps
  /// The radiosity maps, once a frame has used them (null before, or with another method).
  const RadiosityMaps* radiosityMaps() const { return maps_.get(); }
  const SceneGeometry& geometry() const { return geometry_; }
  /// The image-space method's passes, once a frame has used them (null before, or with another method).
  const ImageSpaceSss* imageSpace() const { return imageSpace_.get(); }
  /// The VPLs of the last frame that had them (null before, or when the scene needs none).
  const VirtualPointLights* virtualPointLights() const { return vpls_.get(); }
  /// SSLPV's grids, once a frame has used them (null before, or with another method).
  const Sslpv* sslpv() const { return sslpv_.get(); }
  /// Forgets what the progressive methods have accumulated, keeping every allocation: the next
  /// frame restarts the radiosity maps (as a change of their state key does) and the no-cache
  /// seeds and the image-space accumulation. For `tallow bench`, which times the frames after a
  /// warm-up frame.
  void restartAccumulation();

 private:
  void ensureTargets(int width, int height);
  /// What the radiosity maps depend on at time t (RadiosityMaps::stateKey).
  std::string mapKey(const Scene& scene, const RenderSettings& settings, double timeS) const;
  /// planFrame with the maps' state key already computed.
  std::vector<PlannedPass> planFrame(const Scene& scene, const RenderSettings& settings, double timeS,
                                     const std::string& mapStateKey) const;

  /// What SSLPV's medium grid depends on at time t (Sslpv::mediumKey, with the restarts).
  std::string sslpvMediumKey(const Scene& scene, const RenderSettings& settings, double timeS) const;

  /// What the VPLs depend on beyond the maps (vpl.* settings), with the maps' state key.
  static std::string vplKey(const RenderSettings& settings, const std::string& mapStateKey);

  SceneGeometry geometry_;
  std::unique_ptr<FieldObjects> fields_;
  const gpu::ShaderLibrary& shaders_;
  std::unique_ptr<RadiosityMaps> maps_;  ///< created on the first frame that needs it
  std::unique_ptr<VirtualPointLights> vpls_;  ///< created on the first frame that needs them
  std::unique_ptr<ImageSpaceSss> imageSpace_;  ///< created on the first frame that needs it
  std::unique_ptr<Sslpv> sslpv_;         ///< created on the first frame that needs it
  std::string vplKey_;                   ///< vplKey() of the last VPL pass
  int vplFrame_ = 0;                     ///< frames with VPLs: seeds the directions when not stable
  int noCacheFrame_ = 0;                 ///< seeds of the no-cache gather, one estimate per frame
  int accumulation_ = 0;                 ///< restartAccumulation() calls: part of the maps' state key
  ShadowPass shadows_;
  SurfacePass surface_;
  DisplayPass display_;
  gpu::GpuTimer timer_;
  gpu::Texture radiance_, coverage_, depth_;
  gpu::Framebuffer target_;
};

}  // namespace tallow::sss
