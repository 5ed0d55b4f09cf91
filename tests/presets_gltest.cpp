// Every shipped preset (presets/*.json) loads and renders: `tallow capture` at a small size exits 0
// and writes an EXR of finite values. And the two presets whose geometry other tests and
// benchmarks rely on are what DESIGN.md says: `slab` is the analytic flat case (one directional
// light at normal incidence, an orthographic camera looking straight down), `candle-holder` has
// its point light strictly inside the hollow shape's cavity.
#include <gtest/gtest.h>

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "app/config/setup.h"
#include "gpu/image_io.h"
#include "sss/bssrdf/bssrdf.h"
#include "sss/maps/virtual_point_lights.h"
#include "sss/scene_geometry.h"
#include "support/render_support.h"
#include "support/run_tallow.h"
#include "support/temp_dir.h"

namespace tallow {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> shippedPresets() {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(fs::path(TALLOW_TEST_SOURCE_DIR) / "presets"))
    if (entry.path().extension() == ".json") names.push_back(entry.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

app::LoadedScene load(const std::string& preset) {
  app::SceneOptions options;
  options.preset = (fs::path(TALLOW_TEST_SOURCE_DIR) / "presets" / (preset + ".json")).string();
  return app::loadScene(options);
}

TEST(Presets, TheOnesTestsAndBenchmarksNameAreShipped) {
  const std::vector<std::string> names = shippedPresets();
  for (const char* name : {"bunny", "blob", "blob-chocolate", "candle", "candle-holder", "slab"})
    EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
}

TEST(Presets, EveryShippedPresetCapturesFiniteFrames) {
  // Small maps and a coarse field lattice keep this quick on llvmpipe; the preset's own scene,
  // lights and settings are all still read and rendered.
  const std::vector<std::string> small = {"--set", "sss.maps=4",         "--set", "sss.samples=4",
                                          "--set", "sss.map_size=128",   "--set", "sss.light_map_size=128",
                                          "--set", "field.res=32",            "--set", "sslpv.grid=16",
                                          "--set", "sslpv.inject_size=64"};
  test::TempDir dir;
  for (const std::string& name : shippedPresets()) {
    SCOPED_TRACE(name);
    const fs::path out = dir.path() / name;
    std::vector<std::string> args = {"capture", "--preset", name, "--size", "160x90", "--out", out.string()};
    args.insert(args.end(), small.begin(), small.end());
    const auto r = test::runTallow(args);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    if (r.exitCode != 0) continue;  // and go on with the other presets
    const gpu::Image exr = gpu::readExr(out / "frame_0000.exr");
    EXPECT_EQ(exr.width, 160);
    EXPECT_EQ(exr.height, 90);
    int nonFinite = 0;
    float maxValue = 0.0f;
    for (const glm::vec4& p : exr.pixels)
      for (int c = 0; c < 4; ++c) {
        nonFinite += std::isfinite(p[c]) ? 0 : 1;
        if (std::isfinite(p[c])) maxValue = std::max(maxValue, p[c]);
      }
    EXPECT_EQ(nonFinite, 0);
    EXPECT_GT(maxValue, 0.0f);  // something is lit
  }
}

TEST(Presets, SlabIsTheAnalyticFlatCase) {
  const app::LoadedScene loaded = load("slab");
  const sss::Scene& scene = loaded.config.scene;
  ASSERT_EQ(scene.lights.size(), 1u);
  const sss::Light& light = scene.lights[0];
  EXPECT_EQ(light.kind, sss::LightKind::Directional);
  EXPECT_GT(glm::dot(light.direction, glm::vec3(0, 1, 0)), 1.0f - 1e-6f);  // normal incidence on the top face
  EXPECT_EQ(light.intensity.r, light.intensity.g);
  EXPECT_EQ(light.intensity.g, light.intensity.b);

  EXPECT_TRUE(scene.camera.orthographic);
  const glm::vec3 view = glm::normalize(scene.camera.target - scene.camera.position);
  EXPECT_GT(glm::dot(view, glm::vec3(0, -1, 0)), 1.0f - 1e-6f);  // straight down

  ASSERT_EQ(scene.objects.size(), 1u);  // nothing else to shadow or light it
  const sss::SceneObject& slab = scene.objects[0];
  EXPECT_EQ(slab.shape, sss::ShapeKind::Box);
  EXPECT_TRUE(slab.translucent);
  EXPECT_EQ(slab.transform.rotationDeg, glm::vec3(0.0f));  // top face normal = +y
  EXPECT_EQ(loaded.config.render.sss.model, sss::BssrdfModel::Standard);
  EXPECT_EQ(scene.ambient, glm::vec3(0.0f));

  // The camera looks at the middle of the top face, and that middle is far from the edges: the
  // diffusion profile has fallen by e^-5 within 5/σ_tr of a point in every band.
  const glm::vec3 size = slab.size * slab.transform.scale;
  EXPECT_NEAR(scene.camera.target.x, slab.transform.position.x, 1e-6f);
  EXPECT_NEAR(scene.camera.target.z, slab.transform.position.z, 1e-6f);
  EXPECT_GT(scene.camera.position.y, slab.transform.position.y + 0.5f * size.y);  // above the top face
  const sss::Material& m = slab.material;
  for (int band = 0; band < 3; ++band) {
    const double sigmaTr = std::sqrt(3.0 * m.sigma_a[band] * (m.sigma_a[band] + m.sigma_s[band] * (1.0 - m.g[band])));
    const double reachM = 5.0 / sigmaTr * 1e-3;  // mm → m
    EXPECT_GT(0.5 * std::min(size.x, size.z), reachM) << "band " << band;
    EXPECT_GT(size.y, reachM) << "band " << band;  // thick: little light reaches the bottom
  }
  // The whole top face is in view, with the middle half of it well clear of the frame's edges.
  EXPECT_GE(scene.camera.orthoHeight, 0.5f * size.z);
}

TEST(Presets, CandleHolderHasItsPointLightInsideTheCavity) {
  const app::LoadedScene loaded = load("candle-holder");
  const sss::Scene& scene = loaded.config.scene;
  const auto holder = std::find_if(scene.objects.begin(), scene.objects.end(), [](const sss::SceneObject& o) {
    return o.shape == sss::ShapeKind::HollowCylinder;
  });
  ASSERT_NE(holder, scene.objects.end());
  EXPECT_EQ(holder, scene.objects.begin());  // first: `material` and `scale` refer to it
  EXPECT_TRUE(holder->translucent);
  EXPECT_EQ(holder->material.name, "White Grapefruit Juice");
  const auto light = std::find_if(scene.lights.begin(), scene.lights.end(),
                                  [](const sss::Light& l) { return l.kind == sss::LightKind::Point; });
  ASSERT_NE(light, scene.lights.end());

  // The light in the shape's own frame (size units, bottom centre at the origin, axis +y).
  const glm::mat4 model = sss::SceneGeometry::modelMatrix(*holder, sss::SceneGeometry::shapeMesh(*holder).bounds());
  const glm::vec3 p(glm::inverse(model) * glm::vec4(light->position, 1.0f));
  const float inner = holder->size.x, outer = holder->size.y, height = holder->size.z;
  const float floorY = outer - inner;  // the bottom is as thick as the wall
  EXPECT_LT(std::hypot(p.x, p.z), inner);
  EXPECT_GT(p.y, floorY);
  EXPECT_LT(p.y, height);
  // Not touching: at least a tenth of the cavity's radius from the wall and the floor.
  EXPECT_LT(std::hypot(p.x, p.z), 0.9f * inner);
  EXPECT_GT(p.y, floorY + 0.1f * inner);

  // A floor under it, and a camera from the side and a little above the rim.
  const auto floorPlane = std::find_if(scene.objects.begin(), scene.objects.end(),
                                       [](const sss::SceneObject& o) { return o.shape == sss::ShapeKind::Plane; });
  ASSERT_NE(floorPlane, scene.objects.end());
  EXPECT_LE(floorPlane->transform.position.y, holder->transform.position.y);
  const glm::vec3 eye(glm::inverse(model) * glm::vec4(scene.camera.position, 1.0f));
  EXPECT_GT(std::hypot(eye.x, eye.z), outer);
  EXPECT_GT(eye.y, height);
}

TEST(Presets, CandleIsAFlameInsideWaxLightingTheTable) {
  // Issue 7, point 3: the melting candle, its flame a point light surrounded by wax (stereographic
  // correction on), glycerine soap scaled to approximate wax (§4), VPLs lighting the table, and no
  // other light but a faint ambient; the default preset.
  EXPECT_EQ(app::defaultPresetName(), "candle");
  const std::vector<std::string> small = {"render.width=80", "render.height=60", "sss.maps=6", "sss.samples=4",
                                          "sss.map_size=128", "sss.light_map_size=128", "field.res=48"};
  test::PresetSession with("candle", small);
  const sss::Scene& scene = with.scene();
  ASSERT_EQ(scene.lights.size(), 1u);
  EXPECT_EQ(scene.lights[0].kind, sss::LightKind::Point);
  EXPECT_GE(scene.lights[0].follow, 0);
  EXPECT_TRUE(with.settings().sss.stereographic);
  EXPECT_EQ(with.settings().vpl.count, 80);
  EXPECT_EQ(scene.objects[0].material.name, "Glycerine Soap x20");
  EXPECT_GT(scene.startS, 0.0f) << "shown once the top has melted into a cup";
  const gpu::Image lit = with.render(scene.startS);
  EXPECT_EQ(sss::VirtualPointLights::placement(scene, with.settings(), with.renderer().geometry()),
            sss::VplPlacement::Backlit) << "the flame is inside the wax's bounding box at t = start_s";
  test::PresetSession without("candle", [&] {
    auto s = small;
    s.push_back("vpl.count=0");
    return s;
  }());
  const gpu::Image dark = without.render(scene.startS);
  // The table in front of the candle (the bottom rows): lit by the VPLs, far brighter than by the
  // ambient alone.
  double litSum = 0.0, darkSum = 0.0;
  for (int y = 52; y < 60; ++y)
    for (int x = 0; x < 80; ++x) {
      ASSERT_TRUE(std::isfinite(lit.at(x, y).r));
      litSum += lit.at(x, y).r;
      darkSum += dark.at(x, y).r;
    }
  std::printf("[ presets ] candle: the table in front with VPLs %.4g, without %.4g\n", litSum, darkSum);
  EXPECT_GT(litSum, 3.0 * darkSum);
}

}  // namespace
}  // namespace tallow
