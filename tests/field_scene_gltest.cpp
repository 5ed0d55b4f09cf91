// Field objects in scenes (issue 4, points 2, 3, 6): the blob and candle presets render headless,
// animate, repeat after the blob's period, isosurface only when t changes, and "field" errors in a
// preset are located at file:line:col.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numeric>
#include <string>
#include <vector>

#include "app/config/input_error.h"
#include "app/config/preset.h"
#include "app/config/setup.h"
#include "geometry/blob_field.h"
#include "geometry/candle_field.h"
#include "gpu/gl_context.h"
#include "sss/field_objects.h"
#include "sss/field_source.h"
#include "sss/renderer.h"
#include "support/render_support.h"

namespace tallow {
namespace {

constexpr int kWidth = 96, kHeight = 64;

bool hasPass(const std::vector<sss::PlannedPass>& plan, const std::string& name) {
  return std::any_of(plan.begin(), plan.end(), [&](const sss::PlannedPass& p) { return p.name == name; });
}
bool hasTiming(const sss::FrameTimings& t, const std::string& name) {
  return std::any_of(t.passes.begin(), t.passes.end(), [&](const gpu::PassTiming& p) { return p.name == name; });
}

/// The settings of one preset loaded at a small size with a coarse lattice.
std::vector<std::string> fieldSceneSets(int res = 32) {
  return {"render.width=" + std::to_string(kWidth), "render.height=" + std::to_string(kHeight),
          "field.res=" + std::to_string(res),
          // Small radiosity maps, converged after one frame: a frame that changes nothing
          // then draws exactly the same image (only step 3 runs).
          "sss.maps=6", "sss.samples=4", "sss.map_size=128", "sss.light_map_size=128", "sss.frames=1",
          // Every frame at the pixel centres (a still's average is StillAverage.*'s).
          "render.aa=1"};
}

/// Renders the frame at t, expecting no GL error; returns its linear radiance.
gpu::Image render(test::PresetSession& s, double t, sss::FrameTimings* timings = nullptr) {
  const sss::FrameTimings ft = s.renderFrame(t);
  if (timings) *timings = ft;
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  return s.renderer().readRadiance();
}

void expectFinite(const gpu::Image& image) {
  ASSERT_EQ(image.width, kWidth);
  ASSERT_EQ(image.height, kHeight);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      for (int c = 0; c < 4; ++c) ASSERT_TRUE(std::isfinite(image.at(x, y)[c])) << x << ", " << y;
}

/// Pixels in the box [x0, x1) × [y0, y1) whose radiance differs by more than one 8-bit level.
int differingPixels(const gpu::Image& a, const gpu::Image& b, int x0, int y0, int x1, int y1) {
  int n = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      const glm::vec4 d = glm::abs(a.at(x, y) - b.at(x, y));
      n += std::max(d.r, std::max(d.g, d.b)) > 1.0f / 255.0f ? 1 : 0;
    }
  return n;
}

TEST(FieldSceneGL, BlobPresetRendersFiniteAndCountsExtractedTriangles) {
  test::PresetSession s("blob", fieldSceneSets());
  const std::size_t before = s.renderer().triangleCount();  // meshes only: nothing extracted yet
  const gpu::Image image = render(s, 0.0);
  expectFinite(image);
  const std::size_t after = s.renderer().triangleCount();
  std::printf("[ field ] blob at 32^3: %zu extracted triangles\n", after - before);
  EXPECT_GT(after, before + 100);
}

TEST(FieldSceneGL, AMeshThatOutgrowsItsBuffersIsGrownAndDrawnAgain) {
  // Issue 38: transform-feedback overflow on the render path. The blob's extractor is given room
  // for 64 vertices; the frame at t = 1 cuts its mesh. A capture waits for the counts after the
  // frame (Renderer::repairGeometry: grown, to be drawn again); a window's next frame looks at them
  // without waiting and draws everything again. Either way the frame after is the whole mesh, the
  // triangles of a renderer that never overflowed.
  test::PresetSession fresh("blob", fieldSceneSets());
  const gpu::Image whole = render(fresh, 1.0);
  const std::size_t triangles = fresh.renderer().fieldObjects().triangleCount();
  ASSERT_GT(triangles, 1000u);
  for (const bool wait : {true, false}) {
    test::PresetSession s("blob", fieldSceneSets());
    render(s, 0.0);
    s.renderer().mutableFieldObjects()->setVertexCapacity(64);
    render(s, 1.0);
    EXPECT_LE(s.renderer().fieldObjects().triangleCount(), 3u * 64u) << "the mesh was cut";
    if (wait) {
      EXPECT_TRUE(s.renderer().repairGeometry());
    } else {
      glFinish();  // the counts are in; render() looks at them without waiting
    }
    const gpu::Image again = render(s, 1.0);
    EXPECT_EQ(s.renderer().fieldObjects().triangleCount(), triangles) << (wait ? "capture" : "window");
    EXPECT_FALSE(s.renderer().repairGeometry()) << "the grown buffers held the frame drawn again";
    EXPECT_EQ(differingPixels(again, whole, 0, 0, kWidth, kHeight), 0) << (wait ? "capture" : "window");
  }
}

TEST(FieldSceneGL, CandlePresetRendersFiniteWithTheLightAtTheFlame) {
  std::vector<std::string> sets = fieldSceneSets();
  sets.push_back("flame.flicker=0");  // a steady flame: its emission centre is the field's flame point
  test::PresetSession s("candle", sets);
  const gpu::Image image = render(s, 0.0);
  expectFinite(image);
  EXPECT_GT(s.renderer().triangleCount(), 100u);
  // The point light of the preset follows the flame of the candle: at its emission centre, which for
  // a steady flame is wickExposed + flameLift above the pool's surface (CandleParams; within a tenth of
  // a millimetre, geometry/candle_flame.h), and comes down as the candle burns.
  const sss::Scene& scene = s.scene();
  const auto light = std::find_if(scene.lights.begin(), scene.lights.end(),
                                  [](const sss::Light& l) { return l.kind == sss::LightKind::Point; });
  ASSERT_NE(light, scene.lights.end());
  ASSERT_EQ(light->follow, 0);
  const geometry::CandleParams params = sss::candleParams(scene.objects[0].field);
  const double end = params.durationS;
  const std::size_t index = static_cast<std::size_t>(light - scene.lights.begin());
  const glm::dvec3 start(sss::sceneAtTime(scene, 0.0).lights[index].position);
  const glm::dvec3 burnt(sss::sceneAtTime(scene, end).lights[index].position);
  const glm::dvec3 position(scene.objects[0].transform.position);
  std::printf("[ field ] candle flame at t = 0: (%.5f, %.5f, %.5f), at t = %g: y = %.5f\n", start.x, start.y, start.z,
              end, burnt.y);
  constexpr double kCentre = 1e-4;
  const double lift = params.wickExposed + params.flameLift;
  EXPECT_NEAR(start.y - position.y, geometry::CandleField(0.0, params).poolY() + lift, kCentre);
  EXPECT_NEAR(burnt.y - position.y, geometry::CandleField(end, params).poolY() + lift, kCentre);
  constexpr double kFloat = 1e-6;  // light positions are floats (an ulp at 0.1 m is 7e-9)
  EXPECT_GT(start.y - burnt.y, 0.005) << "the flame comes down with the burning candle";
  EXPECT_NEAR(start.x, position.x, kFloat);
  EXPECT_NEAR(burnt.z, position.z, kFloat);
  // The candle changes as it burns: frames at the start and the end differ.
  const gpu::Image late = render(s, scene.objects[0].field.candleDurationS);
  expectFinite(late);
  EXPECT_GT(differingPixels(image, late, 0, 0, kWidth, kHeight), 20);
}

TEST(FieldSceneGL, BlobAnimatesAndRepeatsAfterItsPeriod) {
  // The maps restart at every change (sss.history=0), so that a frame depends on its time alone and
  // not on the frames before it.
  std::vector<std::string> sets = fieldSceneSets();
  sets.push_back("sss.history=0");
  test::PresetSession s("blob", sets);
  // The whole blob repeats after the least common multiple of its paths' periods.
  const geometry::BlobParams params;
  double period = 1.0;
  for (double p : params.period) period = std::lcm(static_cast<long long>(period), static_cast<long long>(p));
  ASSERT_EQ(period, 5005.0);
  // The blob sits at the camera target, the centre of the image; at t = 0 its four blobs form one
  // ball there, at t = 2 s they have moved apart by about the ball's radius, so the centre half of
  // the image (the blob spans about a third of the view height) changes.
  const int x0 = kWidth / 4, x1 = 3 * kWidth / 4, y0 = kHeight / 4, y1 = 3 * kHeight / 4;
  const gpu::Image a = render(s, 1.0);
  const gpu::Image b = render(s, 3.0);
  const gpu::Image c = render(s, 1.0 + period);
  const int moved = differingPixels(a, b, x0, y0, x1, y1);
  const int repeated = differingPixels(a, c, 0, 0, kWidth, kHeight);
  std::printf("[ field ] blob: %d pixels differ between t = 1 and 3 s, %d between t = 1 and 1 + %g s\n", moved,
              repeated, period);
  EXPECT_GT(moved, 50);
  EXPECT_EQ(repeated, 0);
}

TEST(FieldSceneGL, FieldPassesRunOnlyWhenTheTimeOrResolutionChanges) {
  test::PresetSession s("blob", fieldSceneSets());
  EXPECT_TRUE(hasPass(sss::Renderer::plan(s.scene(), s.settings()), "field.extract"));
  EXPECT_TRUE(hasPass(s.renderer().planFrame(s.scene(), s.settings(), 0.5), "field.sample"));
  EXPECT_TRUE(hasPass(s.renderer().planFrame(s.scene(), s.settings(), 0.5), "field.extract"));
  sss::FrameTimings first, second, third;
  const gpu::Image a = render(s, 0.5, &first);
  EXPECT_TRUE(hasTiming(first, "field.sample"));
  EXPECT_TRUE(hasTiming(first, "field.extract"));
  EXPECT_FALSE(hasPass(s.renderer().planFrame(s.scene(), s.settings(), 0.5), "field.extract"));
  EXPECT_FALSE(hasPass(s.renderer().planFrame(s.scene(), s.settings(), 0.5), "field.sample"));
  const gpu::Image b = render(s, 0.5, &second);
  EXPECT_FALSE(hasTiming(second, "field.extract"));
  EXPECT_TRUE(hasTiming(second, "surface"));
  // The translucent blob's maps were computed in the first frame and are converged (sss.frames = 1).
  EXPECT_TRUE(hasTiming(first, "sss.maps"));
  EXPECT_FALSE(hasTiming(second, "sss.maps"));
  EXPECT_FALSE(hasTiming(second, "sss.light_gbuffer"));
  EXPECT_EQ(differingPixels(a, b, 0, 0, kWidth, kHeight), 0) << "the cached extraction is drawn again";
  EXPECT_TRUE(hasPass(s.renderer().planFrame(s.scene(), s.settings(), 0.75), "field.extract"));
  sss::RenderSettings finer = s.settings();
  finer.fieldRes = 48;
  EXPECT_TRUE(hasPass(s.renderer().planFrame(s.scene(), finer, 0.5), "field.extract"));
  s.renderer().render(s.scene(), finer, 0.5);
  EXPECT_FALSE(hasPass(s.renderer().planFrame(s.scene(), finer, 0.5), "field.extract"));
  // The other extraction path is a new extractor: extracted again, once.
  finer.fieldExtraction = finer.fieldExtraction == geometry::ExtractionPath::Compute
                              ? geometry::ExtractionPath::GeometryShader
                              : geometry::ExtractionPath::Compute;
  EXPECT_TRUE(hasPass(s.renderer().planFrame(s.scene(), finer, 0.5), "field.extract"));
  s.renderer().render(s.scene(), finer, 0.5);
  EXPECT_FALSE(hasPass(s.renderer().planFrame(s.scene(), finer, 0.5), "field.extract"));
}

TEST(FieldSceneGL, MeshFieldRendersTheBunnyThroughTheLevelSetPath) {
  const std::string path = ::testing::TempDir() + "tallow_bunny_field.json";
  {
    std::ofstream out(path);
    out << R"({"camera": {"position": [0, 0.06, 0.3], "target": [0, 0.05, 0]},
  "lights": [{"type": "directional", "direction": [0, 1, 1], "irradiance": [3, 3, 3]}],
  "objects": [{"field": {"type": "mesh", "mesh": "data:bunny.ply"}, "scale": 0.1}]})";
  }
  test::PresetSession s(path, fieldSceneSets());
  EXPECT_EQ(s.scene().objects[0].shape, sss::ShapeKind::Field);
  const gpu::Image image = render(s, 0.0);
  expectFinite(image);
  EXPECT_GT(s.renderer().triangleCount(), 100u);
  int lit = 0;  // the bunny (about a third of the view) against a black background
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) lit += image.at(x, y).g > 0.05f ? 1 : 0;
  EXPECT_GT(lit, 200);
  // A mesh field does not depend on time: no new extraction at another t.
  EXPECT_FALSE(hasPass(s.renderer().planFrame(s.scene(), s.settings(), 1.0), "field.extract"));
}

TEST(FieldSceneGL, StaticScenesPlanNoFieldPasses) {
  app::SceneOptions options;
  options.preset = "bunny";
  const app::LoadedScene loaded = app::loadScene(options);
  const auto plan = sss::Renderer::plan(loaded.config.scene, loaded.config.render);
  EXPECT_FALSE(hasPass(plan, "field.sample"));
  EXPECT_FALSE(hasPass(plan, "field.extract"));
}

// --- Preset errors --------------------------------------------------------------------------------

/// The error of a preset with `object` on line 4 and `lights` (if any) at the start of line 2.
std::string presetError(const std::string& object, const std::string& lights = "") {
  const std::string text = "{\n  " + lights + "\"camera\": {\"position\": [0, 0, 1], \"target\": [0, 0, 0]},\n  \"objects\": [\n    " +
                           object + "\n  ]\n}\n";
  const sss::MaterialTable materials = sss::MaterialTable::parse(
      "name,source,sigma_s_r,sigma_s_g,sigma_s_b,sigma_a_r,sigma_a_g,sigma_a_b,g_r,g_g,g_b,eta,unit\n"
      "Marble,Jensen et al. 2001,2.19,2.62,3,0.0021,0.0041,0.0071,0,0,0,1.5,mm^-1\n",
      "inline.csv");
  try {
    app::parsePreset(text, "p.json", "/presets", materials, "/data");
  } catch (const app::InputError& e) {
    return e.what();
  }
  return "";
}

TEST(FieldPreset, ReadsEachFieldType) {
  EXPECT_EQ(presetError(R"({"field": {"type": "blob", "scale": 0.05}})"), "");
  EXPECT_EQ(presetError(R"({"field": {"type": "candle", "duration_s": 30}})"), "");
  EXPECT_EQ(presetError(R"({"field": {"type": "mesh", "mesh": "data:bunny.ply"}, "scale": 0.1})"), "");
  EXPECT_EQ(presetError(R"({"field": {"type": "mesh", "mesh": "data:bunny.ply", "melt_s": 10}, "scale": 0.1})"), "");
}

TEST(FieldPreset, ErrorsNameFileLineColumn) {
  EXPECT_EQ(presetError(R"({"field": {"type": "blob"}, "mesh": "data:bunny.ply"})"),
            "p.json:4:6: an object has \"field\", \"mesh\" or \"shape\", only one of them");
  EXPECT_EQ(presetError(R"({"shape": "sphere", "field": {"type": "blob"}})"),
            "p.json:4:25: an object has \"field\", \"mesh\" or \"shape\", only one of them");
  EXPECT_EQ(presetError(R"({"field": {"type": "blub"}})"),
            "p.json:4:24: type: unknown value \"blub\" (did you mean \"blob\"?); choices: blob, candle, mesh");
  EXPECT_EQ(presetError(R"({"field": {"type": "candle", "scale": 2}})"),
            "p.json:4:34: unknown key \"scale\"");
  EXPECT_EQ(presetError(R"({"field": {"type": "blob"}, "scale": 2})"),
            "p.json:4:33: \"scale\" applies to mesh fields; a blob is sized by its field's \"scale\", a candle is "
            "fixed");
  EXPECT_EQ(presetError(R"({"field": {"type": "mesh"}})"), "p.json:4:15: missing \"mesh\"");
  const std::string dragon = presetError(R"({"field": {"type": "mesh", "mesh": "data:dragon.ply"}})");
  EXPECT_EQ(dragon.rfind("p.json:4:40: mesh: dragon.ply cannot be a field: Stanford's terms", 0), 0u) << dragon;
  EXPECT_NE(dragon.find("MODELS.md"), std::string::npos);
  EXPECT_EQ(presetError(R"({"field": 3})"), "p.json:4:15: field: expected an object with a \"type\"");
  EXPECT_EQ(presetError(R"({"field": {"type": "candle"}})", R"("lights": [{"type": "point", "follow": "candle", "intensity": [1, 1, 1]}],)"), "");
  EXPECT_EQ(presetError(R"({"field": {"type": "candle"}})", R"("lights": [{"type": "point", "follow": "wick", "intensity": [1, 1, 1]}],)"),
            "p.json:2:42: follow: no object is named \"wick\"");
  EXPECT_EQ(presetError(R"({"field": {"type": "blob"}})", R"("lights": [{"type": "point", "follow": "blob", "intensity": [1, 1, 1]}],)"),
            "p.json:2:42: follow: \"blob\" is not a candle field; only a candle has a flame to follow");
  EXPECT_EQ(presetError(R"({"field": {"type": "candle"}})", R"("lights": [{"type": "point", "follow": "candle", "position": [0, 0, 0], "intensity": [1, 1, 1]}],)"),
            "p.json:2:52: a light that follows a flame has no \"position\"; it sits at the flame");
  const std::string melt = presetError(R"({"field": {"type": "mesh", "mesh": "data:bunny.ply", "melt_s": -1}})");
  EXPECT_EQ(melt, "p.json:4:68: melt_s: -1 is out of range (0, 1e+06]");
  EXPECT_EQ(presetError(R"({"field": {"type": "blob", "melt_s": 5}})"), "p.json:4:32: unknown key \"melt_s\"");
}

}  // namespace
}  // namespace tallow
