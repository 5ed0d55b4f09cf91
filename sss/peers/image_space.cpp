#include "sss/peers/image_space.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "gpu/gl_limits.h"
#include "sss/light_uniforms.h"
#include "sss/maps/radiosity_maps.h"

namespace tallow::sss {
namespace {

constexpr GLuint kPatternBinding = 7;  // shaders/peers/image_space/pattern.comp, scatter.frag
constexpr int kPatternGroupSize = 64;                               // pattern.comp's local size

int translucentCount(const Scene& scene) {
  return static_cast<int>(
      std::count_if(scene.objects.begin(), scene.objects.end(), [](const SceneObject& o) { return o.translucent; }));
}

int uniformSamples(const ImageSpaceSettings& s) {
  return std::clamp(static_cast<int>(std::lround(static_cast<double>(s.uniformShare) * s.samples)), 0, s.samples);
}

std::string formatted(float v) {
  std::ostringstream o;
  o << v;
  return o.str();
}

std::size_t patternBytes(int slots, const ImageSpaceSettings& s) {
  return static_cast<std::size_t>(std::max(slots, 1)) * static_cast<std::size_t>(s.tile * s.tile) *
         static_cast<std::size_t>(s.samples) * sizeof(ImageSpacePatternRecord);
}

/// GL state of the passes, back to the defaults at the end of the scope.
struct PassState {
  ~PassState() {
    glDisable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    glBindVertexArray(0);
    glUseProgram(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
  }
};

}  // namespace

static_assert(sizeof(ImageSpacePatternRecord) == 32, "std430 layout of IsPatternGpu: two vec4");

ImageSpaceSss::ImageSpaceSss(const gpu::ShaderLibrary& shaders)
    : gbuffer_(shaders),
      patternProgram_(shaders, {{{GL_COMPUTE_SHADER, "peers/image_space/pattern.comp"}}}),
      scatterProgram_(shaders, {{{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, "peers/image_space/scatter.frag"}}}),
      combineProgram_(shaders, {{{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, "peers/image_space/combine.frag"}}}) {}

bool ImageSpaceSss::applies(const Scene& scene, const RenderSettings& settings) {
  return settings.sss.method == SssMethod::ImageSpace && translucentCount(scene) > 0;
}

void ImageSpaceSss::checkLimits(const Scene& scene, const RenderSettings& settings) {
  if (!applies(scene, settings)) return;
  const int translucent = translucentCount(scene);
  if (translucent > kMaxTranslucentObjects)
    throw std::invalid_argument("the scene has " + std::to_string(translucent) + " translucent objects; the image-space "
                                "method holds at most " + std::to_string(kMaxTranslucentObjects));
  const GLint maxBlock = gpu::glLimits().maxShaderStorageBlockSize;
  const std::size_t bytes = patternBytes(translucent, settings.imageSpace);
  if (bytes > static_cast<std::size_t>(maxBlock))
    throw std::invalid_argument("image_space.samples × image_space.tile²: the sample pattern needs " +
                                std::to_string(bytes) + " bytes, over this GPU's GL_MAX_SHADER_STORAGE_BLOCK_SIZE of " +
                                std::to_string(maxBlock));
}

std::string ImageSpaceSss::describe(const Scene& scene, const RenderSettings& settings, const std::string& pass) {
  const ImageSpaceSettings& s = settings.imageSpace;
  if (pass == "image_space.gbuffer")
    return "the camera's view of every object: position, normal and E F_t from " + std::to_string(scene.lights.size()) +
           " light(s) with their shadows, per pixel of the " + std::to_string(translucentCount(scene)) +
           " translucent object(s) (once per accumulation)";
  if (pass == "image_space.scatter") {
    const int u = uniformSamples(s);
    return std::to_string(s.samples) + " samples per pixel on its tangent plane (" + std::to_string(s.samples - u) +
           " exact importance samples of the standard dipole's R_d, the colour bands in turn, " + std::to_string(u) +
           " uniform, balance heuristic) within " + formatted(s.radius) +
           " mean free paths, projected into the image; " + std::to_string(s.tile * s.tile) +
           " interleaved sample sets (tile " + std::to_string(s.tile) + "x" + std::to_string(s.tile) + ")";
  }
  return "geometry-aware mean over each pixel's " + std::to_string(s.tile) + "x" + std::to_string(s.tile) +
         " window, accumulated until " + std::to_string(s.frames) + " frames; B " +
         (s.renormalize ? "divided by the sampled share of R_d on visible surface" : "over the visible surface");
}

void ImageSpaceSss::ensureTargets(int width, int height) {
  if (sum_.id() && sum_.width() == width && sum_.height() == height) return;
  sum_ = screenTexture(GL_RGBA32F, width, height);
  coverage_ = screenTexture(GL_RGBA32F, width, height);
  accumSum_ = screenTexture(GL_RGBA32F, width, height);
  accumCoverage_ = screenTexture(GL_RGBA32F, width, height);
  scatterTarget_ = gpu::Framebuffer();
  scatterTarget_.attachColor(0, sum_);
  scatterTarget_.attachColor(1, coverage_);
  scatterTarget_.setDrawBuffers(2);
  scatterTarget_.checkComplete("image-space scatter target");
  accumTarget_ = gpu::Framebuffer();
  accumTarget_.attachColor(0, accumSum_);
  accumTarget_.attachColor(1, accumCoverage_);
  accumTarget_.setDrawBuffers(2);
  accumTarget_.checkComplete("image-space accumulation");
}

void ImageSpaceSss::restart() {
  frames_ = 0;
  if (!accumSum_.id()) return;  // nothing accumulated yet (renderGBuffer allocates the targets)
  const float zero[4] = {0, 0, 0, 0};
  for (GLint i = 0; i < 2; ++i) glClearNamedFramebufferfv(accumTarget_.id(), GL_COLOR, i, zero);
}

void ImageSpaceSss::renderGBuffer(const Scene& scene, const RenderSettings& settings, const SceneGeometry& geometry,
                                  const CameraView& camera, const ShadowPass& shadows) {
  gbuffer_.render(scene, settings, geometry, camera, shadows);
  ensureTargets(settings.width, settings.height);
}

void ImageSpaceSss::scatter(const Scene& scene, const RenderSettings& settings, const CameraView& camera) {
  const ImageSpaceSettings& s = settings.imageSpace;
  const std::vector<int>& slotOf = gbuffer_.slots();
  const int slots = std::max(1, static_cast<int>(std::count_if(slotOf.begin(), slotOf.end(), [](int v) { return v >= 0; })));
  const int sets = s.tile * s.tile;
  const std::size_t bytes = patternBytes(slots, s);
  if (pattern_.size() != bytes) pattern_ = gpu::Buffer(bytes);

  // The frame's pattern (the shared lines of shaders/peers/image_space/sampling.glsl on the GPU).
  gpu::Program& pattern = patternProgram_;
  setSlotMaterialUniforms(pattern, scene, slotOf);
  pattern.set("uSlots", slots);
  pattern.set("uSets", sets);
  pattern.set("uSamples", s.samples);
  pattern.set("uUniformSamples", uniformSamples(s));
  pattern.set("uFrame", frames_);
  pattern.set("uRadiusMfp", s.radius);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPatternBinding, pattern_.id());
  pattern.use();
  const int entries = slots * sets * s.samples;
  glDispatchCompute(static_cast<GLuint>((entries + kPatternGroupSize - 1) / kPatternGroupSize), 1, 1);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);

  // The estimate per pixel.
  gpu::Program& p = scatterProgram_;
  setSlotMaterialUniforms(p, scene, slotOf);
  p.set("uPosition", 0);
  p.set("uNormal", 1);
  p.set("uIrradiance", 2);
  gbuffer_.positions().bind(0);
  gbuffer_.normals().bind(1);
  gbuffer_.irradiance().bind(2);
  setCameraUniforms(p, camera);
  // A pixel's world size: per metre of distance (perspective) or in metres (orthographic).
  const float height = static_cast<float>(settings.height);
  p.set("uPixelScale", camera.orthographic ? scene.camera.orthoHeight / height
                                           : 2.0f * std::tan(glm::radians(scene.camera.fovYDeg) / 2.0f) / height);
  p.set("uTile", s.tile);
  p.set("uSamples", s.samples);
  p.set("uDepthRatio", s.depthRatio);
  p.set("uJacobian", s.jacobian ? 1 : 0);
  PassState state;
  scatterTarget_.bind();
  glViewport(0, 0, settings.width, settings.height);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  p.use();
  emptyVao_.bind();
  glDrawArrays(GL_TRIANGLES, 0, 3);
}

void ImageSpaceSss::combine(const RenderSettings& settings) {
  gpu::Program& p = combineProgram_;
  p.set("uSum", 0);
  p.set("uCoverage", 1);
  p.set("uPosition", 2);
  p.set("uNormal", 3);
  p.set("uTile", settings.imageSpace.tile);
  sum_.bind(0);
  coverage_.bind(1);
  gbuffer_.positions().bind(2);
  gbuffer_.normals().bind(3);
  PassState state;
  accumTarget_.bind();
  glViewport(0, 0, settings.width, settings.height);
  glDisable(GL_DEPTH_TEST);
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE);
  p.use();
  emptyVao_.bind();
  glDrawArrays(GL_TRIANGLES, 0, 3);
  ++frames_;
}

void ImageSpaceSss::setSurfaceUniforms(gpu::Program& p, const ImageSpaceSss* self, const RenderSettings& settings,
                                       GLuint firstUnit) {
  p.set("uImageSpaceSum", static_cast<int>(firstUnit));
  p.set("uImageSpaceCoverage", static_cast<int>(firstUnit + 1));
  p.set("uImageSpaceRenormalize", settings.imageSpace.renormalize ? 1 : 0);
  if (!self) return;
  self->accumSum_.bind(firstUnit);
  self->accumCoverage_.bind(firstUnit + 1);
}

std::size_t ImageSpaceSss::bytes() const {
  return gbuffer_.bytes() + sum_.bytes() + coverage_.bytes() +
         accumSum_.bytes() + accumCoverage_.bytes() + pattern_.size();
}

}  // namespace tallow::sss
