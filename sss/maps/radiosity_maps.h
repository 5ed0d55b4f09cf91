#pragma once
// Directional subsurface scattering by scattered radiosity maps (Dal Corso, Frisvad, Mosegaard and
// Bærentzen 2017, "the paper"), steps 1 and 2 of its Fig. 3, and what step 3 (Algorithm 1, in
// shaders/surface.frag) needs to read them:
//   1. light G-buffers: per directional light an orthographic view fitted to the translucent
//      objects, per point light a cube; world position, normal and object tag per texel, all
//      lights in one layered (instanced) pass;
//   2. K scattered radiosity maps: orthographic views from Halton directions on the translucent
//      objects' bounding sphere, one layered depth pre-pass, then the estimator of Eq. 9 per
//      visible texel with depth writes off, accumulated by additive blending over F frames while
//      light and geometry stay still (progressive), with mipmaps.
// The passes that run them, and what restarts the accumulation, are in sss/maps/maps_method.h.
// Opaque objects are drawn into the light G-buffers as occluders (tag 0) but get no maps.
#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "gpu/gl_objects.h"
#include "gpu/program.h"
#include "gpu/shader_library.h"
#include "sss/render_settings.h"
#include "sss/scene.h"
#include "sss/scene_geometry.h"
#include "sss/translucent_slots.h"

namespace tallow::sss {

/// At most this many translucent objects (material slots) and lights of each kind per scene.
inline constexpr int kMaxTranslucentObjects = kMaxTranslucentSlots;
inline constexpr int kMaxSssDirectionalLights = 32;
inline constexpr int kMaxSssPointLights = 8;

/// One map's camera: direction from the bounding sphere's centre toward the camera, and
/// world → [0,1]³ (texture coordinates, depth).
struct MapView {
  glm::vec3 direction{0.0f, 0.0f, 1.0f};
  glm::mat4 viewProjection{1.0f};
  glm::mat4 toTexture{1.0f};
};

/// The K map views around the sphere (centre, radius): Halton directions (radical inverses in
/// bases 2 and 3 of k + 1, area-uniform on the sphere, as the paper's §3.2), orthographic, the
/// frustum enclosing the sphere.
std::vector<MapView> radiosityMapViews(int k, const glm::vec3& centre, float radius);
/// The same for listed directions (unit, from the centre toward each camera).
std::vector<MapView> radiosityMapViews(const std::vector<glm::vec3>& directions, const glm::vec3& centre, float radius);
/// K of a frame: the scene's listed map directions, else sss.maps (auto, not yet replaced by the
/// renderer's choice: kAutoMapsMax, the most it may choose).
int mapCount(const Scene& scene, const RenderSettings& settings);

/// Draws the translucent scene objects (slots[objectIndex] ≥ 0) with `program` — maps/layered.vert
/// (+ layered.geom: layeredProgram), uniforms uModel, uNormalMatrix, uSlot — once into each of `instances`
/// layers whose view-projections `layerViews` holds (std430 mat4 per layer, binding 4).
void drawTranslucentLayered(gpu::Program& program, const SceneGeometry& geometry, const std::vector<int>& slots,
                            const gpu::Buffer& layerViews, int instances);

/// The per-slot material arrays of shaders/maps/gather.glsl (uSigmaA, uSigmaS, uG [mm⁻¹], uEta), from
/// the materials of the scene objects by their translucent slot (slots[objectIndex], −1: opaque).
void setSlotMaterialUniforms(gpu::Program& program, const Scene& scene, const std::vector<int>& slots);

/// The translucent objects' bounding sphere in world units (centre, radius); radius 0 when none.
struct BoundingSphere {
  glm::vec3 centre{0.0f};
  float radius = 0.0f;
};
BoundingSphere translucentBounds(const Scene& scene, const SceneGeometry& geometry);

/// "Pearling" (the paper's §5): where the mean free path of the estimator's samples, 1/σ_tr, is
/// shorter than a light G-buffer texel, most samples of a texel look up the same G-buffer entry and
/// the result breaks into beads. One entry per translucent object and colour band where it happens.
struct PearlingWarning {
  std::string object;
  int band = 0;
  double meanFreePathMm = 0.0;  ///< 1/σ_tr of the band
  double texelMm = 0.0;         ///< world size of one directional light G-buffer texel
};
std::vector<PearlingWarning> pearlingWarnings(const Scene& scene, float sphereRadius, int lightMapSize);
/// The light G-buffer size the renderer uses: sss.light_map_size (auto: autoLightMapSize), or with
/// sss.light_map_auto the smallest power of two at least that large whose texel is ≤ the shortest
/// 1/σ_tr of the translucent objects, capped at `maxSize`.
int effectiveLightMapSize(const Scene& scene, const RenderSettings& settings, float sphereRadius, int maxSize);

/// What step 2 does with the maps this frame.
enum class MapsUpdate {
  Accumulate,  ///< nothing moved: N more samples added to every texel (after a reuse, the still
               ///< starts: its count and seeds start over while the kept frames fade out)
  Restart,     ///< new views, the maps emptied (the paper, whenever light or geometry change)
  Reuse,       ///< the geometry or a light moved: each texel keeps, trims or resets its sum by
               ///< sss.history (maps/history.comp), then N samples; a restart when it cannot
  Resize,      ///< K alone changed, nothing moved, sss.history > 0: the first min(K, K') maps keep their sums (the
               ///< Halton directions are nested), the new ones start empty; the count starts over
               ///< so that the new maps get sss.frames frames; a restart when the views do not hold
};

/// Bytes of the history's list of covered texels for K maps of size² (maps/covered_texels.glsl):
/// a 16-byte header and 4 bytes a texel; 0 when the texels outnumber 2^32 (no list: every texel).
std::size_t coveredTexelBytes(int size, int k);

class RadiosityMaps {
 public:
  explicit RadiosityMaps(const gpu::ShaderLibrary& shaders);

  /// True when the scene has translucent objects and `settings` selects the radiosity maps.
  static bool applies(const Scene& scene, const RenderSettings& settings);
  /// True when the frame needs the light G-buffers: radiosity maps or no-cache, with translucent objects.
  static bool needsLightGBuffers(const Scene& scene, const RenderSettings& settings);
  /// Throws std::invalid_argument naming the limit when K or the map sizes exceed what this GPU
  /// holds (GL_MAX_ARRAY_TEXTURE_LAYERS, GL_MAX_TEXTURE_SIZE; memory: sss/memory_budget.h), or
  /// when the scene has more translucent objects or lights than the passes hold.
  static void checkLimits(const Scene& scene, const RenderSettings& settings);
  /// Tests compare the history passes over the listed texels with those over every texel: false
  /// makes later frames dispatch over every texel.
  static void allowCompactedHistory(bool allow);

  /// Step 1 (pass sss.light_gbuffer): the translucent slots, the objects' bounding sphere, the light
  /// G-buffers' size and textures, then every light's G-buffer drawn.
  void renderLightGBuffers(const Scene& scene, const RenderSettings& settings, const SceneGeometry& geometry);
  /// Step 2 (pass sss.maps): on a restart, the K views and the maps' depth (or G-buffer) anew and
  /// the accumulation emptied; on a reuse (sss.history > 0; a restart when the objects' bounding
  /// sphere left the views' or nothing was accumulated), the maps' G-buffer anew and each texel's
  /// history kept where its surface point and normal hold; then one frame of N samples added to
  /// every map. The first accumulating frame after a reuse starts a still: frames() and the seeds
  /// start over at 0 and what the maps held then fades out linearly over sss.frames frames
  /// (maps/history_fade.comp), so that once the still has sss.frames frames the maps hold exactly
  /// what a restart at the pause would have accumulated (issue 38). Needs the light G-buffers of
  /// renderLightGBuffers.
  void renderMaps(const Scene& scene, const RenderSettings& settings, const SceneGeometry& geometry,
                  MapsUpdate update);

  /// F, frames accumulated in the maps since the last restart or the start of a still (after a
  /// reuse, at most sss.history; per texel, the maps' alpha holds its own count, with the fading
  /// frames' share while a still after motion starts)
  int frames() const { return frames_; }
  /// The last frame kept a history (a reuse while something moved): the next frame in which nothing
  /// moves starts the still that fades it out, whatever sss.frames says is accumulated.
  bool stillPending() const { return lastUpdate_ == MapsUpdate::Reuse && frames_ > 0; }
  int lightMapSize() const { return lightMapSize_; }  ///< the light G-buffers' size in use
  int mapSize() const { return mapSize_; }  ///< the maps' size in use (sss.map_size, or what auto chose)
  const std::vector<MapView>& views() const { return views_; }
  /// The K views as shaders/maps/algorithm1.glsl's MapViewGpu array (std430: world → [0,1]³,
  /// direction, depth units per metre), built once per accumulation with the views.
  const gpu::Buffer& cameraViews() const { return cameraViews_; }
  BoundingSphere sphere() const { return sphere_; }
  /// The maps (RGBA32F 2D array with mipmaps: Σ of B_N over F frames) and their depth (2D array).
  const gpu::Texture& maps() const { return maps_; }
  const gpu::Texture& mapDepth() const { return mapDepth_; }
  const gpu::Texture& directionalPositions() const { return dirPosition_; }
  /// The point lights' G-buffers: one cube per point light (scene order of the point lights).
  const gpu::Texture& pointPositions() const { return pointPosition_; }
  const gpu::Texture& pointNormals() const { return pointNormal_; }
  /// The maps' G-buffer (sss.gather=compute or a history): x_o [m] with its slot + 1, and n_o.
  const gpu::Texture& mapPositions() const { return mapPosition_; }
  const gpu::Texture& mapNormals() const { return mapNormal_; }
  std::size_t bytes() const;
  /// Everything gather.glsl reads (lights, G-buffers on texture units firstUnit … firstUnit + 3,
  /// materials, model, N, the frame seed), for a program that includes it: the map passes, and
  /// the camera pass of the no-cache method.
  void setGatherUniforms(gpu::Program& program, const Scene& scene, const RenderSettings& settings, GLuint firstUnit,
                         int frame) const;
  /// Everything shaders/maps/algorithm1.glsl reads (the K views on its storage binding, K, F, ε_bias,
  /// ε_comb, the view weight; the maps and their depth on texture units mapsUnit and depthUnit),
  /// for a program that includes it: the camera pass and the VPL pass. `pixelLookups`: the caller
  /// passes a pixel's footprint (the camera pass), which is then filtered over at most half the
  /// shortest 1/σ_tr (maxMapFootprint); the VPL pass passes a VPL's patch and averages over all of it.
  /// `countVplCoverage`: the VPL pass counts sss.maps=auto's VPL histogram (maps/coverage_counts.glsl;
  /// only when MapCoverageProbe bound a buffer). The camera's pixels are counted by SurfacePass after
  /// the camera pass, from the pixels that stay visible.
  void setAlgorithm1Uniforms(gpu::Program& program, const RenderSettings& settings, GLuint mapsUnit,
                             GLuint depthUnit, bool pixelLookups, bool countVplCoverage) const;
  /// Translucent slot of each scene object (−1 for opaque), valid after renderLightGBuffers.
  const std::vector<int>& slots() const { return slotTable_.objectSlot; }
  /// The frame's slots with their materials and liquid parts (valid after renderLightGBuffers).
  const SlotTable& slotTable() const { return slotTable_; }
  /// The directional light G-buffers (tests): normals, and per directional light (scene order of
  /// the directional lights) world → [0,1]³ and the sampling plane's basis.
  const gpu::Texture& directionalNormals() const { return dirNormal_; }
  const std::vector<glm::mat4>& directionalMatrices() const { return dirMatrices_; }
  const std::vector<glm::vec3>& directionalTangents() const { return dirTangent_; }
  const std::vector<glm::vec3>& directionalBitangents() const { return dirBitangent_; }

 private:
  void ensureLightTargets(int dirCount, int pointCount);
  void ensureMapTargets(int k, int size);
  void setLightUniforms(gpu::Program& program, const Scene& scene, GLuint firstUnit) const;
  bool viewsHold(const BoundingSphere& sphere) const;
  /// After the gather on a history reuse: the kept history, rescaled with sss.history_rescale, and
  /// this frame's estimate added into the maps (maps/history_merge.comp).
  void mergeHistory(const RenderSettings& settings);
  /// A still after motion: what the maps hold at its start is copied into historyFresh_'s level 0
  /// (free until the next reuse, which ends the fade); each of its first fadeFrames_ frames
  /// subtracts it / fadeFrames_ (maps/history_fade.comp).
  void startFade(int frames);
  void fade();
  /// On a history reuse: lists the texels with a surface in this or the last G-buffer into
  /// coveredTexels_ (maps/covered_texels.comp) and binds it; false (nothing listed) when not allowed
  /// or when the maps' texels outnumber 2^32.
  bool listCoveredTexels(int size, int k);
  /// A history pass over the listed texels (indirect) when `listed`, else over every texel.
  void dispatchHistory(int size, int k, bool listed) const;


  gpu::Program gbufferProgram_, depthProgram_, mapProgram_, mapGBufferProgram_, mapCompute_, historyCompute_,
      historyMerge_, historyFade_, coveredTexelsCompute_;
  /// The history passes' texels (issue 39, point 5; maps/covered_texels.glsl): a count, the indirect
  /// dispatch's groups, a texel index each. Made with the history's textures.
  gpu::Buffer coveredTexels_;
  bool compacted_ = false;  ///< this frame's history passes visit the listed texels only
  /// coveredTexels_ lists every texel where the maps hold anything (the last merge visited the
  /// listed texels, and nothing restarted since): a still's fade may visit only those.
  bool mapsListed_ = false;
  gpu::Texture dirPosition_, dirNormal_, dirDepth_;        ///< one layer per directional light
  gpu::Texture pointPosition_, pointNormal_, pointDepth_;  ///< one cube per point light
  gpu::Texture dummyDir_, dummyPoint_;                     ///< bound when a kind of light is absent
  gpu::Texture maps_, mapDepth_;
  gpu::Texture mapPosition_, mapNormal_;  ///< the maps' G-buffer (compute gather or history)
  gpu::Texture previousPosition_, previousNormal_;  ///< the last frame's (history only)
  /// On a history reuse: the kept history (mean, frames), and with sss.history_rescale this frame's
  /// mean where a history was kept; both mipmapped for the coarse ratio (maps/history_merge.comp).
  gpu::Texture historyMean_, historyFresh_;
  gpu::Buffer dirLayerViews_, pointLayerViews_;  ///< std430 mat4 per light G-buffer layer (layered program)
  // The passes' targets, made once (gpu::TargetFramebuffer): light G-buffers, the maps' G-buffer, the
  // depth pre-pass and the fragment gather's.
  gpu::TargetFramebuffer dirTarget_, pointTarget_, mapDepthTarget_, mapShadeTarget_;
  /// The map G-buffer's target per side of the history's ping-pong (mapPosition_ and
  /// previousPosition_ swap each reusing frame): each keeps its own pair attached.
  std::array<gpu::TargetFramebuffer, 2> mapGBufferTargets_;
  std::size_t mapGBufferSide_ = 0;
  gpu::Buffer mapLayerViews_;  ///< std430 mat4 per map: its view-projection (layered program)
  gpu::Buffer cameraViews_;    ///< the maps as Algorithm 1 reads them (cameraViews())
  std::vector<MapView> views_;
  std::vector<glm::mat4> dirMatrices_;  ///< world → [0,1]³ of each directional light's G-buffer
  std::vector<glm::vec3> dirTangent_, dirBitangent_;
  SlotTable slotTable_;
  BoundingSphere sphere_;
  BoundingSphere viewSphere_;  ///< the sphere views_ were made for
  int frames_ = 0;
  int seed_ = 0;  ///< frames since the last restart or still: the estimator's frame seed (never repeats on a reuse)
  MapsUpdate lastUpdate_ = MapsUpdate::Restart;
  int fadeFrames_ = 0, fadeDone_ = 0;  ///< the still's fade: over how many frames, how many done
  int lightMapSize_ = 0;
  int mapSize_ = 0;                ///< chosen at each restart (sss.map_size=auto: sss/maps/map_resolution.h)
  double shortestDiffusionMm_ = 0; ///< of the translucent materials, at the last light G-buffers
};

}  // namespace tallow::sss
