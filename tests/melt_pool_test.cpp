// The candle's melt pool as a material (issue 35, point 2), without GL: which surface points are
// liquid (shaders/materials/liquid_surface.glsl, shared with the GPU), the slots that give the pool
// its own material, the preset key, and the flame the pool mirrors (shaders/flame/flame_mirror.glsl).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <string>

#include "app/config/input_error.h"
#include "app/config/preset.h"
#include "geometry/candle_field.h"
#include "geometry/cpu_mesher.h"
#include "sss/field_source.h"
#include "sss/flame_pass.h"
#include "sss/translucent_slots.h"

namespace tallow {
namespace {

namespace fs = std::filesystem;
const fs::path kDataDir = TALLOW_TEST_DATA_DIR;
const fs::path kPresetDir = fs::path(TALLOW_TEST_SOURCE_DIR) / "presets";

const app::Config& candlePreset() {
  static const sss::MaterialTable materials = sss::MaterialTable::load(kDataDir / "materials.csv");
  static const app::Config c = app::loadPreset(kPresetDir / "candle.json", materials, kDataDir);
  return c;
}

TEST(LiquidSurface, IsTheFlatPoolAndItsMeniscusFacingUp) {
  const glm::vec4 region(0.040f, 0.015f, 0.0008f, 0.0003f);  // pool at y = 40 mm, 15 mm wide
  const glm::dvec3 up(0, 1, 0), side(1, 0, 0);
  EXPECT_TRUE(sss::liquidSurfaceContains({0.005, 0.040, 0.003}, up, region));
  EXPECT_TRUE(sss::liquidSurfaceContains({0.0, 0.0402, -0.0149}, up, region)) << "within the tolerance";
  EXPECT_TRUE(sss::liquidSurfaceContains({0.0145, 0.0405, 0.0}, glm::normalize(glm::dvec3(-1, 1, 0)), region))
      << "the meniscus, its normal 45° from up";
  EXPECT_FALSE(sss::liquidSurfaceContains({0.005, 0.0395, 0.0}, up, region)) << "below the surface: wax";
  EXPECT_FALSE(sss::liquidSurfaceContains({0.005, 0.0412, 0.0}, up, region)) << "above the meniscus";
  EXPECT_FALSE(sss::liquidSurfaceContains({0.016, 0.040, 0.0}, up, region)) << "beyond the radius";
  EXPECT_FALSE(sss::liquidSurfaceContains({0.001, 0.0402, 0.0}, side, region)) << "the wick's side";
  EXPECT_FALSE(sss::liquidSurfaceContains({0.001, 0.040, 0.0}, -up, region)) << "facing down";
  EXPECT_FALSE(sss::liquidSurfaceContains({0.005, 0.040, 0.0}, up, glm::vec4(0.040f, 0.0f, 0.0008f, 0.0003f)))
      << "radius 0: no pool";
}

TEST(LiquidSurface, TheCandlesMeshHasAPoolOfTheModelsArea) {
  // The candle preset at t = 14 s meshed as `tallow mesh` does (CPU path, 128³): the liquid
  // triangles' area is the model's (analytic, not the mesh's): the flat disc inside the meniscus,
  // less the wick's cross-section, plus the meniscus — a fillet of radius m swept about the axis,
  // from flat (φ = 0) to where its normal is LIQUID_MIN_UP = 0.25 from horizontal (cos φ = 0.25):
  // 2π m [(r − m) φ + m (1 − cos φ)].
  const sss::Scene scene = sss::sceneAtTime(candlePreset().scene, 14.0);
  const sss::SceneObject& candle = scene.objects[0];
  ASSERT_TRUE(candle.liquidMaterial);
  const geometry::CandleField field(14.0, sss::candleParams(candle.field));
  ASSERT_GT(field.poolRadius(), 0.012);
  EXPECT_FLOAT_EQ(candle.liquidRegion.x, static_cast<float>(field.poolY()));
  EXPECT_FLOAT_EQ(candle.liquidRegion.y, static_cast<float>(field.poolRadius()));
  const sss::FieldSource source(candle);
  const geometry::TriangleMesh mesh = geometry::meshOnCpu(source.sample(14.0, 128), *source.at(14.0));
  double liquidArea = 0.0, farthest = 0.0;
  glm::dvec3 areaNormal(0.0);
  int liquidTriangles = 0;
  for (const auto& tri : mesh.triangles) {
    const glm::dvec3 a(mesh.positions[tri[0]]), b(mesh.positions[tri[1]]), c(mesh.positions[tri[2]]);
    const glm::dvec3 cross = glm::cross(b - a, c - a);
    const glm::dvec3 centre = (a + b + c) / 3.0;
    if (!sss::liquidSurfaceContains(centre, cross, candle.liquidRegion)) continue;
    ++liquidTriangles;
    liquidArea += 0.5 * glm::length(cross);
    areaNormal += 0.5 * cross;
    farthest = std::max(farthest, std::abs(centre.y - field.poolY()));
  }
  const double r = field.poolRadius(), wick = sss::candleParams(candle.field).wickRadius;
  const double m = geometry::CandleField::meniscus(), phi = std::acos(0.25);
  const double disc = std::numbers::pi * ((r - m) * (r - m) - wick * wick) +
                      2.0 * std::numbers::pi * m * ((r - m) * phi + m * (1.0 - std::cos(phi)));
  std::printf("[ pool    ] t = 14 s: %d liquid triangles, %.1f mm² (model %.1f mm²), farthest %.3f mm off the plane\n",
              liquidTriangles, liquidArea * 1e6, disc * 1e6, farthest * 1e3);
  EXPECT_NEAR(liquidArea / disc, 1.0, 0.02);
  // Flat and facing up: the area-weighted normal of what is called liquid is the axis.
  EXPECT_GT(glm::normalize(areaNormal).y, 0.999);
}

TEST(LiquidSurface, NoPoolBeforeTheWaxMelts) {
  const sss::Scene scene = sss::sceneAtTime(candlePreset().scene, 0.0);
  EXPECT_EQ(scene.objects[0].liquidRegion.y, 0.0f);
  EXPECT_EQ(&sss::materialAt(scene.objects[0], {0.0, 0.065, 0.005}, {0.0, 1.0, 0.0}), &scene.objects[0].material);
}

TEST(TranslucentSlots, APoolTakesTheSlotAfterItsCandle) {
  const sss::Scene scene = sss::sceneAtTime(candlePreset().scene, 16.0);
  const sss::SlotTable t = sss::translucentSlotTable(scene);
  ASSERT_EQ(t.count, 2);
  EXPECT_EQ(t.objectSlot[0], 0);
  EXPECT_EQ(t.objectSlot[1], -1) << "the table is opaque";
  EXPECT_EQ(t.slotObject[0], 0);
  EXPECT_EQ(t.slotObject[1], 0) << "the pool is the candle's";
  EXPECT_EQ(t.liquidSlot[0], 1);
  EXPECT_EQ(t.liquidSlot[1], 1);
  EXPECT_EQ(t.material[1].sigma_s, scene.objects[0].liquidMaterial->sigma_s);
  EXPECT_EQ(t.material[0].sigma_s, scene.objects[0].material.sigma_s);
  EXPECT_EQ(t.slotObject[2], -1);
  const glm::dvec3 onPool(0.004, scene.objects[0].liquidRegion.x, 0.0);
  EXPECT_EQ(&sss::materialAt(scene.objects[0], onPool, {0, 1, 0}), &*scene.objects[0].liquidMaterial);
  // Eight translucent objects fit; a pool beside them does not.
  sss::Scene many = scene;
  for (int i = 0; i < 7; ++i) {
    sss::SceneObject s;
    s.shape = sss::ShapeKind::Sphere;
    s.translucent = true;
    s.material = scene.objects[0].material;
    many.objects.push_back(s);
  }
  try {
    sss::translucentSlotTable(many);
    FAIL() << "nine slots";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("need 9 material slots"), std::string::npos) << e.what();
  }
  many.objects[0].liquidMaterial.reset();
  EXPECT_EQ(sss::translucentSlotTable(many).count, 8);
}

/// A point of the drawn flame's sheet as flame.vert places it for a camera at `viewer`.
glm::dvec3 sheetPoint(const sss::FlameSheet& f, const glm::dvec3& viewer, double x, double v) {
  const glm::dvec3 base(f.base), up(f.up);
  const glm::dvec3 centre = base + 0.4 * double(f.height) * up;
  const glm::dvec3 side = glm::normalize(glm::cross(up, glm::normalize(viewer - centre)));
  return base + v * double(f.height) * up + v * v * glm::dvec3(f.sway) + x * double(f.halfWidth) * side;
}

TEST(FlameMirror, ARayToAPointOfTheSheetSeesThatPoint) {
  // From a pool point, the ray toward the point (x, v) of the sheet as flame.vert would draw it for
  // a viewer there sees flameProfile(x, v): flame_mirror.glsl's plane and coordinates against the
  // vertex shader's formula. A steady flame (no sway): the sheet is then exactly the mirror's plane.
  sss::Scene steady = candlePreset().scene;
  steady.flameFlicker = 0.0;
  const sss::Scene scene = sss::sceneAtTime(steady, 16.0);
  sss::RenderSettings settings;
  const std::vector<sss::FlameSheet> flames = sss::flameSheets(scene, 16.0, settings);
  ASSERT_EQ(flames.size(), 1u);
  const sss::FlameSheet& f = flames[0];
  EXPECT_GT(f.height, 0.005f);
  EXPECT_GT(f.radianceScale, 0.0f);
  const glm::dvec3 origin(0.003, scene.objects[0].liquidRegion.x, -0.009);
  for (const auto& [x, v] : {std::pair{0.0, 0.3}, {0.4, 0.5}, {-0.7, 0.2}, {0.2, 0.8}}) {
    const glm::dvec3 target = sheetPoint(f, origin, x, v);
    const glm::dvec3 seen = sss::flameSeenAlong(origin, glm::normalize(target - origin), f);
    const glm::dvec3 expected = geometry::flameProfileAt(x, v);
    EXPECT_NEAR(seen.x, expected.x, 1e-6 * expected.x) << "x " << x << ", v " << v;
    EXPECT_NEAR(seen.y, expected.y, 1e-6 * expected.x) << "x " << x << ", v " << v;
    EXPECT_GT(seen.x, 0.0);
  }
  // Away from the flame, above its tip, beside it: nothing.
  EXPECT_EQ(sss::flameSeenAlong(origin, {0.0, 0.0, -1.0}, f), glm::dvec3(0.0));
  const glm::dvec3 aboveTip = sheetPoint(f, origin, 0.0, 1.3);
  EXPECT_EQ(sss::flameSeenAlong(origin, glm::normalize(aboveTip - origin), f), glm::dvec3(0.0));
  const glm::dvec3 beside = sheetPoint(f, origin, 2.0, 0.4);
  EXPECT_EQ(sss::flameSeenAlong(origin, glm::normalize(beside - origin), f), glm::dvec3(0.0));
}

TEST(PoolMaterial, BelongsToATranslucentCandle) {
  static const sss::MaterialTable materials = sss::MaterialTable::load(kDataDir / "materials.csv");
  const auto errorOf = [](const std::string& object) {
    const std::string text = "{\n  \"camera\": {\"position\": [0, 0.1, 0.3], \"target\": [0, 0.05, 0]},\n"
                             "  \"objects\": [\n    " + object + "\n  ]\n}\n";
    try {
      app::parsePreset(text, "p.json", "/presets", materials, kDataDir);
    } catch (const app::InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(errorOf(R"({"shape": "sphere", "material": "Marble", "pool_material": "Marble"})"),
            "p.json:4:47: \"pool_material\" is the liquid of a candle's melt pool; this object is not a candle field");
  EXPECT_EQ(errorOf(R"({"field": {"type": "candle"}, "pool_material": "Marble"})"),
            "p.json:4:35: \"pool_material\" needs a translucent candle; give the object a \"material\" first");
  const std::string bad = errorOf(R"({"field": {"type": "candle"}, "material": "Marble", "pool_material": {"from": "Marble", "sigma_t": 1}})");
  EXPECT_NE(bad.find("p.json:4:"), std::string::npos) << bad;
  EXPECT_NE(bad.find("sigma_t"), std::string::npos) << bad;
  EXPECT_EQ(errorOf(R"({"field": {"type": "candle"}, "material": "Marble", "pool_material": "Marble"})"), "");
}

}  // namespace
}  // namespace tallow
