#pragma once
// Transport of emergent light (the radiosity-maps paper's §3.4, Eqs. 15–16): virtual point lights
// (VPLs) on the translucent objects' outermost surface light the opaque receivers.
//   1. The translucent objects are drawn into a cube map from the centre c of their bounding box,
//      keeping the farthest surface from c in each direction (depth test GREATER): world position
//      and normal per texel (the paper's "outermost surface").
//   2. A compute pass reads it at a fixed set of N_vpl directions (Halton, the same every frame
//      unless vpl.stable is off) and gives each VPL its position x_v, normal n_v, the scattered
//      radiosity B(x_v) from Algorithm 1 and the area A_v it stands for.
//   3. The surface pass adds, on every opaque receiver, the VPLs' irradiance with a bounded
//      geometry term (shaders/maps/vpl_receiver.glsl).
// Formulas and choices: docs/vpl.md.
#include <glm/glm.hpp>

#include <string>
#include <vector>

#include "gpu/gl_objects.h"
#include "gpu/program.h"
#include "gpu/shader_library.h"
#include "sss/maps/radiosity_maps.h"
#include "sss/render_settings.h"
#include "sss/scene.h"
#include "sss/scene_geometry.h"
#include "sss/shadow_pass.h"

namespace tallow::sss {

struct CameraTarget;

/// One VPL as the GPU holds it (std430, shaders/maps/vpl_receiver.glsl's VplGpu).
struct VplRecord {
  glm::vec4 position{0.0f};  ///< x_v; w: η of its object (0: inactive, no surface or not backlit)
  glm::vec4 normal{0.0f};    ///< n_v (unit); w: A_v [m²], the surface it stands for
  glm::vec4 radiance{0.0f};  ///< rgb: B(x_v)/π [W/(m²·sr)], the radiance before Fresnel; w: its shadow cluster
};

/// The parts each VPL's cell is split into for receivers near it, records of the same layout
/// (shaders/maps/vpl_record.glsl's VPL_PARTS).
constexpr int kVplParts = 9;

/// The N_vpl directions from the bounding box's centre: Halton directions `first` … `first` + count − 1
/// (area-uniform on the sphere; the maps' directions are the same sequence from 0).
std::vector<glm::vec3> vplDirections(int count, int first);

/// The N_vpl stable directions (vpl.stable): a spherical Fibonacci lattice, the same every frame.
std::vector<glm::vec3> stableVplDirections(int count);

/// The shadow cluster of each direction: the nearest of `clusters` Halton directions (fixed, so a
/// VPL keeps its cluster from frame to frame).
std::vector<int> vplClusters(const std::vector<glm::vec3>& directions, int clusters);

/// One cluster's shadow camera: its active VPL nearest the mean of their positions (on the surface,
/// unlike the mean), lifted by `margin` along that VPL's normal. `valid` false when the cluster has
/// no active VPL.
struct VplClusterCamera {
  glm::vec3 position{0.0f};
  bool valid = false;
};
std::vector<VplClusterCamera> vplClusterCameras(const std::vector<VplRecord>& records, int clusters, float margin);

/// Point lights inside the box (min, max) of the translucent objects: the "surrounded" sources
/// of the paper's §3.4, for which VPLs stand on backlit surface only (placement auto).
std::vector<glm::vec3> surroundedLights(const Scene& scene, const glm::vec3& boxMin, const glm::vec3& boxMax);

class VirtualPointLights {
 public:
  explicit VirtualPointLights(const gpu::ShaderLibrary& shaders);

  /// True when vpl.count > 0, the radiosity maps shade the translucent objects (B comes from
  /// Algorithm 1) and the scene has an opaque object to receive the light.
  static bool applies(const Scene& scene, const RenderSettings& settings);
  /// Throws std::invalid_argument (one line) when vpl.cube_size exceeds the GPU's cube-map limit
  /// or N_vpl records exceed its shader-storage block size.
  static void checkLimits(const Scene& scene, const RenderSettings& settings);
  /// The placement `settings` and `scene` resolve to, and why (for the plan).
  static VplPlacement placement(const Scene& scene, const RenderSettings& settings, const SceneGeometry& geometry);
  static std::string describe(const Scene& scene, const RenderSettings& settings);

  /// Steps 1 and 2 for this frame; `maps` must hold this frame's maps. `frame` seeds the
  /// directions when vpl.stable is off. `countCoverage`: the VPLs' coverage by the maps goes to
  /// sss.maps=auto's counts (section 1; the frame's MapCoverageProbe buffer is bound).
  void render(const Scene& scene, const RenderSettings& settings, const SceneGeometry& geometry,
              const RadiosityMaps& maps, int frame, bool countCoverage = false);
  /// Binds the VPL buffer and sets uVplCount (0 when `lights` is null) and the VPL shadow uniforms
  /// on a program that includes maps/vpl_receiver.glsl; the cluster cube shadow maps (or a lit dummy)
  /// go on texture unit `shadowUnit`.
  static void setReceiverUniforms(gpu::Program& program, const VirtualPointLights* lights, GLuint shadowUnit);
  /// Adds the VPLs' emergent light ρ/π · E_vpl (Eq. 15) to every opaque receiver pixel of `target`'s
  /// radiance, by a compute pass over the receivers' G-buffer the camera pass left
  /// (shaders/maps/vpl_receivers.comp, one invocation per pixel).
  void lightReceivers(const CameraTarget& target, const RenderSettings& settings);
  /// Whether the receivers are lit by lightReceivers (the default) or in the camera pass's fragment
  /// shader (the path before; tests compare the two). Process-wide; a renderer made after a change
  /// compiles its camera pass accordingly.
  static bool computeReceivers();
  static void allowComputeReceivers(bool allow);

  int count() const { return count_; }
  glm::vec3 centre() const { return centre_; }
  float boxArea() const { return boxArea_; }
  /// The records of the last render (reads the GPU buffer: tests and stats).
  std::vector<VplRecord> read() const;
  /// The parts of each VPL's cell (maps/vpl_record.glsl's VPL_PARTS per VPL, in VPL order).
  std::vector<VplRecord> readParts() const;
  std::size_t bytes() const;

 private:
  gpu::Program cubeProgram_, compute_, receivers_;
  gpu::Texture cubePosition_, cubeNormal_, cubeDepth_;
  gpu::Buffer records_, parts_, directions_, faceViews_;
  gpu::TargetFramebuffer cubeTarget_;  ///< the outermost-surface cube's G-buffer
  ShadowPass shadows_;                       ///< the clusters' cube shadow maps, as point lights
  std::vector<glm::vec3> clusterCentre_;     ///< per cluster: its shadow camera
  std::vector<float> clusterRange_;          ///< per cluster: distance stored as depth 1 (0: no cluster)
  std::vector<int> clusterCube_;             ///< per cluster: its cube in the shadow pass's array
  bool shadowed_ = false;
  int count_ = 0, directionsFirst_ = -1, directionsClusters_ = 0;
  glm::vec3 centre_{0.0f};
  float boxArea_ = 0.0f;
};

}  // namespace tallow::sss
