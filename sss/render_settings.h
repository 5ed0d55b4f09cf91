#pragma once
// Every tunable of the renderer, one field each. The names, ranges, defaults and help live in one
// place only, the parameter registry (app/config/params.cpp); this struct just holds the values.
#include "geometry/extraction_path.h"
#include "geometry/vertex_placement.h"
#include "gpu/tonemap.h"
#include "sss/bssrdf/bssrdf.h"

namespace tallow::sss {

/// How translucent objects are shaded (parameter `method`).
enum class SssMethod {
  RadiosityMaps,  ///< scattered radiosity maps (Dal Corso et al. 2017, issue 5)
  Albedo,         ///< no subsurface transport: Lambertian with the object's albedo (a baseline)
  NoCache,        ///< the gather per camera pixel against the light G-buffers, no maps (paper Fig. 11)
  ImageSpace,     ///< local subsurface scattering in image space (Mertens et al. 2003; issue 8, docs/image-space.md)
  Sslpv,          ///< subsurface light propagation volumes (Børlum et al. 2011, docs/sslpv.md)
  Burley,         ///< the engines' screen-space diffusion profile (Christensen and Burley 2015; docs/burley.md)
};

/// An int setting's "auto" (sss.map_size, sss.light_map_size, sss.maps): the renderer chooses the
/// value from the scene (sss/maps/map_resolution.h, sss/maps/map_count.h).
constexpr int kAuto = 0;

/// The scattered radiosity maps of Dal Corso et al. (sss.* parameters).
struct SssSettings {
  SssMethod method = SssMethod::RadiosityMaps;       ///< method
  BssrdfModel model = BssrdfModel::Directional;      ///< sss.model
  int maps = 16;              ///< sss.maps: K, the scattered radiosity maps (directions; kAuto: chosen)
  int samples = 8;            ///< sss.samples: N, samples per texel, map, frame and colour band
  int mapSize = 512;          ///< sss.map_size [texels] of each scattered radiosity map (kAuto: chosen)
  int lightMapSize = 512;     ///< sss.light_map_size [texels] of each light G-buffer (kAuto: chosen)
  float bias = 0.0f;          ///< sss.bias: ε_bias [× the translucent objects' bounding radius]
  float comb = 0.0f;          ///< sss.comb: ε_comb [× the translucent objects' bounding radius]
  float viewWeight = 0.0f;    ///< sss.view_weight: p of Algorithm 1's per-map weight cos^p θ (0: the paper)
  int frames = 0;             ///< sss.frames: accumulated frames after which the maps are converged
  /// sss.history: when the geometry or the lights move, each map texel whose surface point and
  /// normal still hold keeps at most this many frames of its accumulated estimate (the rest is
  /// reset), rescaled to follow the light (sss.history_rescale); 0 restarts the maps (the paper).
  /// shaders/maps/history.glsl, issue 17; measured in docs/RESULTS.md.
  int history = 8;
  /// sss.history_move: how far a texel's surface point may move for it to keep its history, in
  /// units of the shortest diffusion length 1/σ_tr of the translucent materials.
  float historyMove = 0.5f;
  /// sss.history_rescale: the footprint, in shortest diffusion lengths, over which a kept history
  /// is rescaled to this frame's estimate band by band, so that it follows a light that moves
  /// while the surface holds (shaders/maps/history.glsl, sssHistoryRescale); 0: kept as it was.
  float historyRescale = 1.0f;
  bool stereographic = true;  ///< sss.stereographic: Eqs. 13–14 for point lights inside objects
  /// sss.point_share: the share of point-light samples drawn from the stereographic density about
  /// the light instead of Eq. 12 (shaders/maps/estimator.glsl, issue 17); 0: Eq. 12 alone (the
  /// paper). 0.25 takes the candle's lower-wall bias from −12.7% to −0.3% (docs/radiosity-maps.md).
  float pointShare = 0.25f;
  bool lightMapAuto = false;  ///< sss.light_map_auto: raise the light map size against pearling
  bool computeGather = true;  ///< sss.gather: false = the paper's fragment pass, true = compute pass
  bool projectedArea = true;  ///< sss.projected_area: the sampling plane's Jacobian (false: the paper's Eq. 9)
  bool texelPlane = true;     ///< sss.texel_plane: x_i on the light G-buffer texel's tangent plane (false: its depth)
};

/// Where the virtual point lights stand (vpl.placement).
enum class VplPlacement {
  Auto,     ///< backlit when a point light is surrounded (inside the translucent objects' bounds), else all
  All,      ///< every VPL the outermost-surface cube map gives
  Backlit,  ///< only VPLs facing away from every surrounded point light (the paper's §3.4)
};

/// How much surface each VPL stands for (vpl.area).
enum class VplArea {
  SolidAngle,   ///< A_v = 4π d_v² / (N_vpl cos α_v): the cube map's sampling density, exact on average
  BoundingBox,  ///< A_v = A_box / N_vpl: the paper's Eq. 16 with the bounding box's area
};

/// Upper bound of vpl.count (the parameter's range; the receiver loop's cost grows with it).
inline constexpr int kMaxVpls = 4096;
/// Upper bound of vpl.shadow_clusters (the receiver shader's uniform arrays).
inline constexpr int kMaxVplShadowClusters = 64;

/// Transport of emergent light by virtual point lights (the paper's §3.4, Eqs. 15–16; vpl.*).
struct VplSettings {
  int count = 0;                 ///< vpl.count: N_vpl; 0 = no VPLs
  int cubeSize = 128;            ///< vpl.cube_size [texels]: face of the outermost-surface cube map
  VplPlacement placement = VplPlacement::Auto;  ///< vpl.placement
  VplArea area = VplArea::SolidAngle;           ///< vpl.area
  bool stable = true;            ///< vpl.stable: the same directions every frame (false: new ones each frame)
  bool shadows = false;          ///< vpl.shadows: receivers' visibility of the VPLs (clustered cube shadow maps)
  int shadowClusters = 64;       ///< vpl.shadow_clusters: C, cube shadow maps shared by the VPLs of a cluster
  int shadowSize = 64;           ///< vpl.shadow_size [texels]: face of each cluster's cube shadow map
};

/// Upper bounds of image_space.tile and image_space.samples (the parameters' ranges; the sample
/// pattern's size grows with both).
inline constexpr int kImageSpaceMaxTile = 8;
inline constexpr int kImageSpaceMaxSamples = 1024;

/// Local subsurface scattering in image space (image_space.*; docs/image-space.md).
struct ImageSpaceSettings {
  int samples = 16;            ///< image_space.samples: N per pixel and frame, shared by the colour bands
  float uniformShare = 0.25f;  ///< image_space.uniform_share: of N, uniform on the disc (combined sampling)
  int tile = 4;                ///< image_space.tile: T, interleaved sampling with T² sample sets
  float radius = 8.0f;         ///< image_space.radius [mean free paths 1/σ_tr of the longest band]
  int frames = 32;             ///< image_space.frames: accumulated frames while nothing changes
  float depthRatio = 1.0f;     ///< image_space.depth_ratio: rejection of samples off x_o's tangent plane
  bool jacobian = true;        ///< image_space.jacobian: dA_p/dA_p' of the tangent plane's projection
  bool renormalize = false;    ///< image_space.renormalize: divide by the sampled share of R_d on valid surface
};

inline constexpr int kBurleyMaxSamples = 256;

/// How burley.scatter applies the profile (burley.kernel).
enum class BurleyKernel {
  Disc,       ///< importance-sampled discs facing the camera (Unreal's Burley SSS)
  Separable,  ///< a horizontal then a vertical 1D pass (Jimenez et al. 2015's structure)
};

/// The engines' screen-space diffusion profile (burley.*; docs/burley.md).
struct BurleySettings {
  int samples = 32;           ///< burley.samples: N per translucent pixel and frame (separable: taps per pass)
  bool transmission = true;   ///< burley.transmission: light through thin parts from the shadow maps
  BurleyKernel kernel = BurleyKernel::Disc;  ///< burley.kernel
};

/// Which flux of a cell's point light SSLPV's area light carries out of the surface (sslpv.exitance).
enum class SslpvExitance {
  Hemisphere,  ///< all of the hemisphere about the normal (the paper's Eq. 5)
  Face,        ///< the cap of one cube face's solid angle, 2π/3 sr (what the propagation passes on)
};

/// Subsurface light propagation volumes (Børlum et al. 2011; sslpv.*).
struct SslpvSettings {
  int grid = 32;         ///< sslpv.grid: LPV cells per axis
  int steps = 32;        ///< sslpv.steps: propagation steps
  int skip = 2;          ///< sslpv.skip: first steps left out of the accumulation grid
  int injectSize = 256;  ///< sslpv.inject_size [texels]: light G-buffers injected from
  SslpvExitance exitance = SslpvExitance::Hemisphere;  ///< sslpv.exitance
};

struct RenderSettings {
  int width = 0;              ///< render.width [px]
  int height = 0;             ///< render.height [px]
  bool shadows = false;       ///< render.shadows
  int shadowMapSize = 0;      ///< render.shadow_map_size [texels]
  float shadowBias = 0.0f;    ///< render.shadow_bias [shadow-map texels along the normal]
  int pcfRadius = 0;          ///< render.pcf_radius [texels]
  int fieldRes = 0;           ///< field.res [lattice samples per axis]
  geometry::VertexPlacement fieldPlacement = geometry::kDefaultPlacement;  ///< field.placement
  /// field.evaluate: true (gpu) fills the blob's, the candle's and melting meshes' lattices on the
  /// GPU from t; false (cpu) samples every field on the CPU and uploads it, normals from the lattice
  /// (the path before issue 16, kept to measure against).
  bool fieldOnGpu = true;
  /// field.extraction: the stages of dual contouring's vertex and quad passes (geometry shaders with
  /// transform feedback, the paper's, or compute shaders).
  geometry::ExtractionPath fieldExtraction = geometry::kDefaultExtraction;
  bool specular = true;       ///< render.specular: Fresnel reflection of the environment on translucent objects
  bool flame = true;          ///< render.flame: the visible flame of a burning candle (sss/flame_pass.h)
  /// flame.exposure_ev: the drawn flame's own exposure, stops (sss/flame_pass.h: a global exposure set
  /// for the lit wax shows a flame white; the eye, adapting locally, sees it coloured).
  float flameExposureEv = -2.5f;
  gpu::ToneMapSettings toneMap;  ///< render.tonemap, render.exposure_ev
  /// render.aa: sub-pixel positions a still cycles through while its frames are averaged
  /// (sss/still_average.h); 1 draws every frame at the pixel centres and averages nothing.
  int aaSamples = 1;
  /// render.bloom: the share of the picture's light the glare PSF spreads in the picture shown
  /// (sss/bloom.h); 0: off.
  float bloom = 0.0f;
  /// render.local_exposure: the share of each region's distance below mid grey (in stops of its
  /// edge-aware mean) that the picture shown lifts (sss/local_exposure.h); 0: off.
  float localExposure = 0.0f;
  SssSettings sss;
  VplSettings vpl;
  ImageSpaceSettings imageSpace;
  SslpvSettings sslpv;
  BurleySettings burley;
};

}  // namespace tallow::sss
