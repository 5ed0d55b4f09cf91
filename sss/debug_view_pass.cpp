#include "sss/debug_view_pass.h"

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "sss/maps/radiosity_maps.h"
#include "sss/maps/virtual_point_lights.h"
#include "sss/view_setup.h"

namespace tallow::sss {

namespace {

// shaders/debug/texture_view.frag's modes.
enum TextureMode { kGBufferPosition = 0, kGBufferNormal = 1, kMap = 2, kCoverage = 3, kDifference = 4 };

/// Restores what the overlays change, whatever path leaves the pass.
struct OverlayState {
  OverlayState() {
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
  }
  ~OverlayState() {
    glDisable(GL_BLEND);
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    glDisable(GL_PROGRAM_POINT_SIZE);
    glBindVertexArray(0);
    glUseProgram(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
  }
};

/// Largest VPL disc on screen, pixels; the brightest VPL gets it, the others by the square root of
/// their share of its power (disc area ∝ power).
constexpr float kMaxVplPixels = 14.0f;
constexpr float kMinVplPixels = 3.0f;
constexpr glm::vec3 kWireColour{0.95f, 0.85f, 0.2f};

}  // namespace

DebugViewPass::DebugViewPass(const gpu::ShaderLibrary& shaders)
    : textureProgram_(shaders, {{{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, "debug/texture_view.frag"}}}),
      overlayProgram_(shaders, {{{GL_VERTEX_SHADER, "debug/overlay.vert"}, {GL_FRAGMENT_SHADER, "debug/overlay.frag"}}}) {}

void DebugViewPass::setReference(const gpu::Image& reference) {
  reference_ = gpu::Texture::create2D(GL_RGBA32F, reference.width, reference.height);
  reference_.setFilter(GL_NEAREST, GL_NEAREST);
  // Files store the top row first; GL's row 0 is the bottom.
  std::vector<glm::vec4> rows(reference.pixels.size());
  for (int y = 0; y < reference.height; ++y)
    std::copy_n(reference.pixels.begin() + static_cast<std::ptrdiff_t>(y) * reference.width, reference.width,
                rows.begin() + static_cast<std::ptrdiff_t>(reference.height - 1 - y) * reference.width);
  glTextureSubImage2D(reference_.id(), 0, 0, 0, reference.width, reference.height, GL_RGBA, GL_FLOAT, rows.data());
}

std::optional<DebugViewPass::LightLayer> DebugViewPass::lightLayer(const Scene& scene, int light) {
  if (light < 0 || light >= static_cast<int>(scene.lights.size())) return std::nullopt;
  LightLayer out;
  out.cube = scene.lights[static_cast<std::size_t>(light)].kind == LightKind::Point;
  // The G-buffers hold the lights of each kind in scene order (RadiosityMaps::renderLightGBuffers).
  for (int i = 0; i < light; ++i) out.layer += (scene.lights[static_cast<std::size_t>(i)].kind == LightKind::Point) == out.cube;
  return out;
}

std::string DebugViewPass::render(const DebugView& view, Renderer& renderer, const Scene& scene,
                                  const RenderSettings& settings, GLuint target, int width, int height,
                                  int coveredLeft) {
  const bool overlay = view.kind == DebugViewKind::Final || view.kind == DebugViewKind::Wireframe ||
                       view.kind == DebugViewKind::Vpl;
  std::string note;
  if (!overlay) {
    glBindFramebuffer(GL_FRAMEBUFFER, target);
    glViewport(0, 0, width, height);
    note = drawTexture(view, renderer, scene, settings, width, height, coveredLeft);
    if (note.empty()) return "";
  }
  // The final image, and the overlays over it.
  renderer.display(target, width, height, settings.toneMap);
  if (!overlay) return note;
  glBindFramebuffer(GL_FRAMEBUFFER, target);
  glViewport(0, 0, width, height);
  if (view.kind == DebugViewKind::Wireframe) drawWireframe(renderer, scene, width, height);
  if (view.kind == DebugViewKind::Vpl) note = drawVpls(renderer, scene, settings, width, height);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  return note;
}

std::string DebugViewPass::drawTexture(const DebugView& view, const Renderer& renderer, const Scene& scene,
                                       const RenderSettings& settings, int width, int height, int coveredLeft) {
  gpu::Program& p = textureProgram_;
  p.set("uViewport", glm::vec2(width, height));
  // Beside the panel while a third of the window is left; over all of it otherwise.
  p.set("uLeft", coveredLeft < 2 * width / 3 ? static_cast<float>(std::max(coveredLeft, 0)) : 0.0f);
  p.set("uExposureScale", std::exp2(settings.toneMap.exposureEv + view.exposureEv));
  p.set("uToneMap", static_cast<int>(settings.toneMap.op));
  p.set("uSquare", 0);
  p.set("uCube", 0);
  const RadiosityMaps* maps = renderer.module<sss::RadiosityMaps>();
  const bool gbuffer = view.kind == DebugViewKind::GBufferPosition || view.kind == DebugViewKind::GBufferNormal;
  if (gbuffer) {
    if (!maps || !RadiosityMaps::needsLightGBuffers(scene, settings))
      return "no light G-buffers: the method uses none (method radiosity-maps or no-cache) or nothing is translucent";
    const auto layer = lightLayer(scene, view.light);
    if (!layer)
      return "light " + std::to_string(view.light) + " does not exist (the scene has " +
             std::to_string(scene.lights.size()) + ")";
    const bool normal = view.kind == DebugViewKind::GBufferNormal;
    p.set("uMode", normal ? kGBufferNormal : kGBufferPosition);
    p.set("uSquare", 1);
    p.set("uCube", layer->cube ? 1 : 0);
    p.set("uLayer", layer->layer);
    p.set("uFace", std::clamp(view.layer, 0, 5));
    p.set("uCentre", maps->sphere().centre);
    p.set("uRadius", std::max(maps->sphere().radius, 1e-6f));
    if (layer->cube) {
      maps->pointPositions().bind(1);
      maps->pointNormals().bind(5);
    } else {
      maps->directionalPositions().bind(0);
      maps->directionalNormals().bind(4);
    }
  } else if (view.kind == DebugViewKind::Map) {
    if (!maps || !RadiosityMaps::applies(scene, settings) || !maps->maps().id())
      return "no scattered radiosity maps: method is not radiosity-maps or nothing is translucent";
    const int k = maps->maps().depth();
    if (view.layer >= k) return "map " + std::to_string(view.layer) + " does not exist (K = " + std::to_string(k) + ")";
    p.set("uMode", kMap);
    p.set("uSquare", 1);
    p.set("uLayer", view.layer);
    // The maps hold Σ B over F frames; B / π is the radiance scale of the image.
    p.set("uMapScale", 1.0f / (glm::pi<float>() * static_cast<float>(std::max(maps->frames(), 1))));
    maps->maps().bind(0);
  } else if (view.kind == DebugViewKind::Coverage) {
    p.set("uMode", kCoverage);
    renderer.coverage().bind(2);
  } else {  // Difference
    if (!hasReference()) return "no reference image (give one with --reference REF.exr)";
    if (reference_.width() != width || reference_.height() != height)
      return "the reference is " + std::to_string(reference_.width()) + "x" + std::to_string(reference_.height()) +
             ", the image " + std::to_string(width) + "x" + std::to_string(height);
    p.set("uMode", kDifference);
    renderer.radiance().bind(2);
    reference_.bind(3);
  }
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  p.use();
  emptyVao_.bind();
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  glUseProgram(0);
  for (GLuint unit = 0; unit < 6; ++unit) glBindTextureUnit(unit, 0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  return "";
}

void DebugViewPass::drawWireframe(const Renderer& renderer, const Scene& scene, int width, int height) {
  OverlayState state;
  const float aspect = static_cast<float>(width) / static_cast<float>(height);
  const CameraView camera = cameraView(scene.camera, aspect, renderer.geometry().worldBounds());
  gpu::Program& p = overlayProgram_;
  p.set("uViewProjection", camera.viewProjection);
  p.set("uPoints", 0);
  p.set("uLineColor", kWireColour);
  renderer.depth().bind(0);
  glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
  p.use();
  for (const DrawItem& item : renderer.geometry().items()) {
    p.set("uModel", item.model);
    item.draw();
  }
  glBindTextureUnit(0, 0);
}

std::string DebugViewPass::drawVpls(const Renderer& renderer, const Scene& scene, const RenderSettings& settings,
                                    int width, int height) {
  const VirtualPointLights* vpls = renderer.module<sss::VirtualPointLights>();
  if (!vpls || !VirtualPointLights::applies(scene, settings))
    return "no VPLs in this frame (vpl.count > 0, method radiosity-maps and an opaque receiver are needed)";
  // Position and colour per active VPL; its power is ∝ B/π · A_v (record radiance × area).
  struct Point {
    glm::vec3 position;
    glm::vec4 colour;  ///< rgb, a: size in pixels
  };
  const std::vector<VplRecord> records = vpls->read();
  std::vector<Point> points;
  float maxPower = 0.0f;
  for (const VplRecord& r : records) {
    if (r.position.w <= 0.0f) continue;
    const float power = glm::dot(glm::vec3(r.radiance), glm::vec3(0.2126f, 0.7152f, 0.0722f)) * r.normal.w;
    maxPower = std::max(maxPower, power);
    points.push_back({glm::vec3(r.position), glm::vec4(glm::vec3(r.radiance), power)});
  }
  for (Point& pt : points) {
    const glm::vec3 c = pt.colour;
    const float peak = std::max({c.r, c.g, c.b, 1e-30f});
    const float share = maxPower > 0.0f ? std::sqrt(pt.colour.a / maxPower) : 0.0f;
    // Hue of the VPL's light at full brightness; size by power.
    pt.colour = glm::vec4(c / peak, kMinVplPixels + (kMaxVplPixels - kMinVplPixels) * share);
  }
  if (points.empty()) return "no active VPLs (none stands on backlit surface)";
  const std::size_t bytes = points.size() * sizeof(Point);
  if (points_.size() < bytes) {
    points_ = gpu::Buffer(bytes);
    pointsVao_ = gpu::VertexArray();
    pointsVao_.setAttribute(0, points_, offsetof(Point, position), sizeof(Point), 3);
    pointsVao_.setAttribute(1, points_, offsetof(Point, colour), sizeof(Point), 4);
  }
  points_.upload(0, bytes, points.data());

  OverlayState state;
  glEnable(GL_PROGRAM_POINT_SIZE);
  const float aspect = static_cast<float>(width) / static_cast<float>(height);
  const CameraView camera = cameraView(scene.camera, aspect, renderer.geometry().worldBounds());
  gpu::Program& p = overlayProgram_;
  p.set("uViewProjection", camera.viewProjection);
  p.set("uModel", glm::mat4(1.0f));
  p.set("uPoints", 1);
  renderer.depth().bind(0);
  p.use();
  pointsVao_.bind();
  glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(points.size()));
  glBindTextureUnit(0, 0);
  return "";
}

}  // namespace tallow::sss
