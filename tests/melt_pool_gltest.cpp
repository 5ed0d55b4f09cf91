// The candle's melt pool on the GPU (issue 35, point 2): the light G-buffer tags the liquid where the
// CPU's classification (the same shared lines, in double) says so; the pool's material changes the
// pool's pixels and nothing else, and the same material in the pool's slot changes nothing at all;
// the pool mirrors the flame where a plane mirror puts its image.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "geometry/candle_field.h"
#include "sss/field_source.h"
#include "sss/maps/radiosity_maps.h"
#include "sss/renderer.h"
#include "sss/translucent_slots.h"
#include "support/render_support.h"

namespace tallow {
namespace {

constexpr double kT = 16.0;

double luminance(const glm::vec4& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

std::vector<glm::vec4> readCubeArray(const gpu::Texture& t) {
  std::vector<glm::vec4> texels(static_cast<std::size_t>(t.width()) * t.height() * t.depth() * 6);
  glGetTextureImage(t.id(), 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(texels.size() * sizeof(glm::vec4)), texels.data());
  return texels;
}

TEST(MeltPool, LightGBufferTagsTheLiquidAsTheCpuDoes) {
  test::PresetSession s("candle", {"render.width=48", "render.height=27", "field.res=96", "sss.maps=2",
                                   "sss.samples=1", "sss.frames=1", "sss.map_size=32", "sss.light_map_size=256",
                                   "vpl.count=0"});
  s.render(kT);
  const sss::RadiosityMaps* maps = s.renderer().module<sss::RadiosityMaps>();
  ASSERT_NE(maps, nullptr);
  ASSERT_EQ(maps->slotTable().count, 2);
  const int liquidTag = maps->slotTable().liquidSlot[0] + 1;
  const std::vector<glm::vec4> position = readCubeArray(maps->pointPositions());
  const std::vector<glm::vec4> normal = readCubeArray(maps->pointNormals());
  const glm::vec4 region = sss::sceneAtTime(s.scene(), kT).objects[0].liquidRegion;  // the candle at the origin
  int liquid = 0, wax = 0, disagree = 0;
  for (std::size_t i = 0; i < position.size(); ++i) {
    const int tag = static_cast<int>(position[i].w + 0.5f);
    if (tag == 0) continue;
    const bool cpu = sss::liquidSurfaceContains(glm::dvec3(glm::vec3(position[i])), glm::dvec3(glm::vec3(normal[i])), region);
    (tag == liquidTag ? liquid : wax)++;
    if (cpu != (tag == liquidTag)) ++disagree;
  }
  std::printf("[ pool    ] light G-buffer at t = %.0f s: %d liquid texels, %d wax, %d disagree with the CPU\n", kT,
              liquid, wax, disagree);
  EXPECT_GT(liquid, 5000) << "the flame looks down on the pool";
  EXPECT_GT(wax, 5000);
  EXPECT_LE(disagree, liquid / 1000) << "only float rounding at the region's edges";
}

/// The candle seen straight down (orthographic, `size`² pixels over `view` metres), no flame, a
/// steady light; pixel (x, y) sees world (x, z) on the axis's plane.
test::PresetSession topView(int size, double view) {
  test::PresetSession s("candle", {"render.width=" + std::to_string(size), "render.height=" + std::to_string(size),
                                   "field.res=96", "sss.maps=6", "sss.samples=4", "sss.frames=2", "sss.map_size=128",
                                   "sss.light_map_size=256", "vpl.count=0", "render.flame=false", "flame.flicker=0"});
  sss::Camera& c = s.scene().camera;
  c.orthographic = true;
  c.orthoHeight = static_cast<float>(view);
  c.position = {0.0f, 0.2f, 0.0f};
  c.target = {0.0f, 0.0f, 0.0f};
  c.up = {0.0f, 0.0f, 1.0f};
  return s;
}

TEST(MeltPool, ItsMaterialShadesThePoolAndNothingElse) {
  constexpr int kSize = 96;
  constexpr double kView = 0.046;
  test::PresetSession s = topView(kSize, kView);
  const gpu::Image pool = s.render(kT);
  const sss::Material liquid = *s.scene().objects[0].liquidMaterial;
  s.scene().objects[0].liquidMaterial = s.scene().objects[0].material;  // the wax's own in the pool's slot
  const gpu::Image same = s.render(kT);
  s.scene().objects[0].liquidMaterial.reset();
  const gpu::Image none = s.render(kT);
  const geometry::CandleField field(kT, sss::candleParams(s.scene().objects[0].field));
  const double poolR = field.poolRadius(), rimInner = field.cupRadius(), outer = sss::candleParams(s.scene().objects[0].field).radius;
  // Image x grows with world −x or +x depending on the up vector; rho is symmetric either way.
  double poolWith = 0, poolWithout = 0, rimWith = 0, rimWithout = 0, maxSame = 0;
  int poolPixels = 0, rimPixels = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const double wx = ((x + 0.5) / kSize - 0.5) * kView, wz = ((y + 0.5) / kSize - 0.5) * kView;
      const double rho = std::hypot(wx, wz);
      const std::size_t i = static_cast<std::size_t>(y) * kSize + static_cast<std::size_t>(x);
      maxSame = std::max(maxSame, std::abs(luminance(same.pixels[i]) - luminance(none.pixels[i])));
      if (rho > 0.003 && rho < 0.8 * poolR) {
        poolWith += luminance(pool.pixels[i]);
        poolWithout += luminance(none.pixels[i]);
        ++poolPixels;
      } else if (rho > rimInner + 0.0007 && rho < outer - 0.0007) {
        rimWith += luminance(pool.pixels[i]);
        rimWithout += luminance(none.pixels[i]);
        ++rimPixels;
      }
    }
  std::printf("[ pool    ] seen from above at t = %.0f s: pool %d px %.4g with its material, %.4g without (%.2fx); "
              "rim top %d px %.4g vs %.4g; the wax's material in the pool's slot: largest change %.3g\n",
              kT, poolPixels, poolWith / poolPixels, poolWithout / poolPixels, poolWith / poolWithout, rimPixels,
              rimWith / rimPixels, rimWithout / rimPixels, maxSame);
  ASSERT_GT(poolPixels, 500);
  ASSERT_GT(rimPixels, 100);
  EXPECT_LT(poolWith / poolWithout, 0.8) << "clear liquid returns less light than milky wax (σ_s a tenth)";
  EXPECT_NEAR(rimWith / rimWithout, 1.0, 0.03) << "the rim exits through wax either way";
  EXPECT_LT(maxSame, 1e-6) << "the pool's slot with the wax's material is the wax";
  (void)liquid;
}

TEST(MeltPool, MirrorsTheFlameWhereAPlaneMirrorPutsItsImage) {
  // Looking steeply into the cup, specular on against off: the difference on the pool is the flame's
  // reflection (and a little of the ambient sky's). Its luminance-weighted centre on the pool's plane
  // is where the line from the camera to the flame's mirror image (its emission centre reflected in
  // y = pool) crosses the plane — geometry of a plane mirror, not the shader's.
  constexpr int kW = 160, kH = 90;
  test::PresetSession s("candle", {"render.width=160", "render.height=90", "field.res=96", "sss.maps=4",
                                   "sss.samples=2", "sss.frames=1", "sss.map_size=64", "sss.light_map_size=128",
                                   "vpl.count=0", "flame.flicker=0"});
  sss::Camera& c = s.scene().camera;
  c.position = {0.0f, 0.135f, -0.036f};
  c.target = {0.0f, 0.037f, 0.0f};
  c.fovYDeg = 25.0f;
  const gpu::Image on = s.render(kT);
  s.settings().specular = false;
  const gpu::Image off = s.render(kT);
  const sss::Scene scene = sss::sceneAtTime(s.scene(), kT);
  const float poolY = scene.objects[0].liquidRegion.x, poolR = scene.objects[0].liquidRegion.y;
  const glm::dvec3 flame(scene.lights[0].position);
  const glm::dvec3 image(flame.x, 2.0 * poolY - flame.y, flame.z);
  const glm::dvec3 eye(c.position);
  const double along = (poolY - eye.y) / (image.y - eye.y);
  const glm::dvec3 expected = eye + along * (image - eye);
  const glm::dmat4 view = glm::lookAt(eye, glm::dvec3(c.target), glm::dvec3(c.up));
  const glm::dmat4 projection = glm::perspective(glm::radians(double(c.fovYDeg)), double(kW) / kH, 0.01, 1.0);
  const glm::dmat4 toWorld = glm::inverse(projection * view);
  glm::dvec3 weighted(0.0);
  double total = 0.0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const glm::dvec4 far = toWorld * glm::dvec4(2.0 * (x + 0.5) / kW - 1.0, 1.0 - 2.0 * (y + 0.5) / kH, 1.0, 1.0);
      const glm::dvec3 dir = glm::normalize(glm::dvec3(far) / far.w - eye);
      const glm::dvec3 onPlane = eye + ((poolY - eye.y) / dir.y) * dir;
      if (std::hypot(onPlane.x, onPlane.z) > 0.7 * poolR) continue;  // the pool, not its meniscus
      const std::size_t i = static_cast<std::size_t>(y) * kW + static_cast<std::size_t>(x);
      const double added = luminance(on.pixels[i]) - luminance(off.pixels[i]);
      if (added < 0.02) continue;  // the sky's faint reflection everywhere
      weighted += added * onPlane;
      total += added;
    }
  ASSERT_GT(total, 0.0) << "no reflection on the pool";
  const glm::dvec3 centre = weighted / total;
  std::printf("[ pool    ] the flame's reflection: centre (%.2f, %.2f) mm on the pool, a plane mirror puts it at "
              "(%.2f, %.2f) mm; %.3g summed\n",
              centre.x * 1e3, centre.z * 1e3, expected.x * 1e3, expected.z * 1e3, total);
  EXPECT_LT(glm::length(glm::dvec2(centre.x - expected.x, centre.z - expected.z)), 0.0015);
}

TEST(MeltPool, ThePuddleBehindTheWaxDoesNotMirrorTheFlame) {
  // The default camera's view of the puddle at the candle's foot, narrowed to 6 degrees so that the
  // flame is out of the picture: drawing the flame or not may change nothing there. A mirrored ray
  // from the puddle's curved edge meets the flame's sheet through the wax; before the mirror was
  // weighted by the flame's light's shadow map, 3 puddle pixels took the flame's reflection here
  // (0.04 in luminance at most; two orange dots on the default picture at 480x270).
  auto render = [](bool flame) {
    test::PresetSession s("candle", {"render.width=160", "render.height=90", "render.aa=1", "render.bloom=0",
                                     "vpl.count=0", "flame.flicker=0", "sss.maps=8", "sss.map_size=128",
                                     "camera.target=0.0103,0.002,-0.025", "camera.fov_deg=6",
                                     flame ? "render.flame=true" : "render.flame=false"});
    return s.render(kT);
  };
  const gpu::Image on = render(true), off = render(false);
  ASSERT_EQ(on.pixels.size(), off.pixels.size());
  int changed = 0;
  double largest = 0.0;
  for (std::size_t i = 0; i < on.pixels.size(); ++i) {
    const double d = std::abs(luminance(on.pixels[i]) - luminance(off.pixels[i]));
    largest = std::max(largest, d);
    changed += d > 1e-4 ? 1 : 0;
  }
  std::printf("[ pool    ] the puddle with the flame drawn and not: %d pixels differ, %.3g at most\n", changed, largest);
  EXPECT_EQ(changed, 0) << "the puddle mirrors the flame through the wax";
}

}  // namespace
}  // namespace tallow
