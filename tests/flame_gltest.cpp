// The candle's visible flame (issues 16 and 35): drawn after the surface, brighter than any wax, kept
// out of everything the light transport reads, as bright in total as its point light, coloured and
// soft-edged as the issue measures it.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cmath>

#include <nlohmann/json.hpp>

#include <fstream>

#include "gpu/image_io.h"
#include "sss/field_source.h"
#include "sss/flame_pass.h"
#include "support/render_support.h"
#include "support/run_tallow.h"
#include "support/temp_dir.h"

namespace tallow {
namespace {

double luminance(const glm::vec4& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

TEST(Flame, IsDrawnOverThePictureAndOutshinesTheWax) {
  test::PresetSession session("candle", {"render.width=96", "render.height=54", "field.res=48", "sss.maps=4",
                                         "sss.samples=2", "sss.frames=1", "sss.map_size=64", "sss.light_map_size=64",
                                         "vpl.count=0", "flame.exposure_ev=0", "render.aa=1", "render.bloom=0",
                                         "render.local_exposure=0"});
  const double t = 12.0;
  session.render(t);
  const gpu::Image with = session.render(t);  // converged maps
  const std::vector<std::uint8_t> wax = session.renderer().translucentMask();
  session.settings().flame = false;
  sss::FrameTimings timings;
  const gpu::Image without = session.render(t, &timings);
  // Turning the flame off reruns nothing but the camera pass: the flame is in no map or G-buffer.
  ASSERT_EQ(timings.passes.size(), 1u);
  EXPECT_EQ(timings.passes[0].name, "surface");
  double flameMax = 0.0, waxMax = 0.0;
  int flamePixels = 0;
  for (std::size_t i = 0; i < with.pixels.size(); ++i) {
    const double added = luminance(with.pixels[i]) - luminance(without.pixels[i]);
    EXPECT_GE(added, -1e-6) << "pixel " << i << ": the flame only adds light";
    if (added > 0.0) {
      ++flamePixels;
      flameMax = std::max(flameMax, luminance(with.pixels[i]));
    }
    if (wax[i]) waxMax = std::max(waxMax, luminance(without.pixels[i]));
  }
  EXPECT_GT(flamePixels, 3) << "the flame stands above the rim, in view";
  EXPECT_LT(flamePixels, static_cast<int>(with.pixels.size()) / 50) << "a flame, not a glow over the picture";
  ASSERT_GT(waxMax, 0.0);
  // HDR well above the wax at its own exposure 0: its flux is the light's intensity (0.006 W/sr over
  // ~1 cm²) against wax lit from millimetres away.
  EXPECT_GT(flameMax, 3.0 * waxMax) << "flame " << flameMax << ", brightest wax " << waxMax;
}

/// A session on the candle at t = 0 (a flat top: the whole flame above the wax) seen from the side by
/// an orthographic camera, the flame steady.
test::PresetSession sideView(int width, int height, double viewHeight) {
  test::PresetSession s("candle", {"render.width=" + std::to_string(width), "render.height=" + std::to_string(height),
                                   "field.res=48", "method=albedo", "vpl.count=0", "flame.flicker=0",
                                   "flame.exposure_ev=0"});
  sss::Camera& camera = s.scene().camera;
  camera.orthographic = true;
  camera.orthoHeight = static_cast<float>(viewHeight);
  camera.position = {0.0f, 0.08f, 0.3f};
  camera.target = {0.0f, 0.08f, 0.0f};
  return s;
}

TEST(Flame, SendsTheCameraItsLightsIntensity) {
  // The drawn flame's radiance summed over its pixels (orthographic: each pixel a known area) is its
  // flux, which must be the point light's intensity band by band: the GPU's rasterised profile
  // (shaders/flame.frag) against the CPU's quadrature of the same lines (geometry::flameEmission).
  constexpr int kSize = 240;
  constexpr double kView = 0.04;  // metres: 6 mm wide pixels of 0.17 mm
  test::PresetSession s = sideView(kSize, kSize, kView);
  const gpu::Image with = s.render(0.0);
  s.settings().flame = false;
  const gpu::Image without = s.render(0.0);
  glm::dvec3 sum(0.0);
  for (std::size_t i = 0; i < with.pixels.size(); ++i) sum += glm::dvec3(with.pixels[i] - without.pixels[i]);
  const double pixelArea = (kView / kSize) * (kView / kSize);
  const glm::dvec3 flux = sum * pixelArea;
  const glm::dvec3 light(sss::sceneAtTime(s.scene(), 0.0).lights[0].intensity);
  std::printf("[ flame   ] drawn flux (%.6f, %.6f, %.6f) W/sr, the light's intensity (%.6f, %.6f, %.6f)\n", flux.x,
              flux.y, flux.z, light.x, light.y, light.z);
  // The pixels sample the soft edge finely (measured: agreement to 1e-5; a profile stretched by 3%
  // misses by 2.9%): within 0.5% per band that carries
  // light (blue carries almost none at these temperatures).
  EXPECT_NEAR(flux.x / light.x, 1.0, 0.005);
  EXPECT_NEAR(flux.y / light.y, 1.0, 0.005);
}

/// sRGB of a display value in [0, 1] as HSV saturation.
double saturation(const std::array<double, 3>& c) {
  const double hi = std::max({c[0], c[1], c[2]}), lo = std::min({c[0], c[1], c[2]});
  return hi > 0.0 ? (hi - lo) / hi : 0.0;
}

TEST(Flame, IsColouredAndSoftEdgedAsTheIssueMeasures) {
  // Issue 35's bar at 640×360 on the preset as it is: of the flame's own pixels (those it brightens
  // by more than 0.25 in the displayed picture) at most 40% are white and their median saturation is
  // at least 0.25; and at least 15% of the pixels it brightens by more than 0.1 are soft edge (between
  // 20% and 80% of its brightest). Before, 93% were (255, 255, 255) with a hard edge.
  // The preset's own light, exposures and method, small maps converged in one frame (so that the two
  // renders differ by the flame alone).
  test::PresetSession s("candle", {"render.width=640", "render.height=360", "field.res=64", "sss.maps=4",
                                   "sss.samples=2", "sss.frames=1", "sss.map_size=128", "sss.light_map_size=128",
                                   "vpl.count=0"});
  const double t = s.scene().startS;
  const gpu::Image with = s.render(t);
  s.settings().flame = false;
  const gpu::Image without = s.render(t);
  const std::vector<std::uint8_t> on = gpu::toneMappedRgb8(with, s.settings().toneMap);
  const std::vector<std::uint8_t> off = gpu::toneMappedRgb8(without, s.settings().toneMap);
  std::vector<double> brighten(with.pixels.size());
  double brightest = 0.0;
  for (std::size_t i = 0; i < brighten.size(); ++i) {
    double d = 0.0;
    for (int c = 0; c < 3; ++c) d = std::max(d, (on[3 * i + c] - off[3 * i + c]) / 255.0);
    brighten[i] = d;
    brightest = std::max(brightest, d);
  }
  int own = 0, white = 0, lit = 0, soft = 0;
  std::vector<double> saturations;
  for (std::size_t i = 0; i < brighten.size(); ++i) {
    if (brighten[i] > 0.1) {
      ++lit;
      soft += brighten[i] >= 0.2 * brightest && brighten[i] <= 0.8 * brightest ? 1 : 0;
    }
    if (brighten[i] <= 0.25) continue;
    ++own;
    const std::array<double, 3> c{on[3 * i] / 255.0, on[3 * i + 1] / 255.0, on[3 * i + 2] / 255.0};
    white += c[0] >= 0.98 && c[1] >= 0.98 && c[2] >= 0.98 ? 1 : 0;
    saturations.push_back(saturation(c));
  }
  ASSERT_GT(own, 20) << "the flame is in view";
  std::nth_element(saturations.begin(), saturations.begin() + saturations.size() / 2, saturations.end());
  const double median = saturations[saturations.size() / 2];
  std::printf("[ flame   ] 640x360: %d own pixels, %.1f%% white, median saturation %.2f; %d lit, %.1f%% soft edge\n", own,
              100.0 * white / own, median, lit, 100.0 * soft / lit);
  EXPECT_LE(white, 0.4 * own);
  EXPECT_GE(median, 0.25);
  EXPECT_GE(soft, 0.15 * lit);
}

TEST(Flame, ACaptureRecordsTheLightFlickeringWithTheFlame) {
  // The issue's bar from a capture: over 0.5 s the point light's intensity varies by at least 1% or
  // its position sways at least 0.1 mm off its burn-down line, recorded in stats.json per frame.
  test::TempDir dir;
  const auto r = test::runTallow({"capture", "--preset", "candle", "--size", "32x18", "--set", "method=albedo",
                                  "--set", "vpl.count=0", "--frames", "16", "--fps", "30", "--out",
                                  (dir.path() / "o").string()});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  std::ifstream in(dir.path() / "o" / "stats.json");
  const nlohmann::json stats = nlohmann::json::parse(in);
  double lo = 1e30, hi = 0.0, sway = 0.0;
  for (const nlohmann::json& f : stats["frames"]) {
    const nlohmann::json& i = f["point_light_intensities"][0];
    const double y = 0.2126 * i[0].get<double>() + 0.7152 * i[1].get<double>() + 0.0722 * i[2].get<double>();
    lo = std::min(lo, y);
    hi = std::max(hi, y);
    const nlohmann::json& p = f["point_lights"][0];
    sway = std::max(sway, std::hypot(p[0].get<double>(), p[2].get<double>()));  // the candle stands on the axis
  }
  std::printf("[ flame   ] capture of 0.5 s: intensity varies %.2f%%, sways %.3f mm\n", 100.0 * (hi / lo - 1.0),
              sway * 1e3);
  EXPECT_TRUE(hi / lo - 1.0 >= 0.01 || sway >= 0.0001);
  EXPECT_GE(hi / lo - 1.0, 0.01);
}

}  // namespace
}  // namespace tallow
