// The image-space method on llvmpipe (issue 8, docs/image-space.md): the analytic slab at normal
// and oblique light, rejection and renormalisation next to a lid (another object, or a depth step
// of the same one), the GPU's sample pattern
// against the C++ instantiation of the same lines, the progressive plan, opaque receivers left
// unchanged, finiteness on hard cases, and the command line (bad values, --explain, stats.json).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "geometry/ply_writer.h"
#include "geometry/primitives.h"
#include "gpu/glsl_shared.h"
#include "sss/peers/image_space.h"
#include "support/dipole_totals.h"
#include "support/render_support.h"
#include "support/run_tallow.h"
#include "support/temp_dir.h"

// The pattern's shared lines in float, as the GPU runs them.
namespace tallow::image_space_gltest_f32 {
using namespace glm;
using uint = std::uint32_t;
using real = float;
using real2 = glm::vec2;
using real3 = glm::vec3;
#include "sss/bssrdf/bssrdf_models.inc"
#include "shaders/maps/estimator.glsl"
#include "shaders/maps/dipole_sampling.glsl"
#include "shaders/peers/image_space/sampling.glsl"
}  // namespace tallow::image_space_gltest_f32

namespace tallow {
namespace {

using test::centreMean;
using test::fresnelT;
using test::PresetSession;
constexpr double kPi = 3.14159265358979323846;

// Every frame at the pixel centres: these tests measure the estimator frame by frame (render.aa's
// still average is StillAverage.*'s).
const std::vector<std::string> kSlabImageSpace = {"render.width=48", "render.height=48", "method=image-space",
                                                  "image_space.samples=32", "image_space.frames=8", "render.aa=1"};

std::vector<std::string> with(std::vector<std::string> sets, const std::vector<std::string>& more) {
  sets.insert(sets.end(), more.begin(), more.end());
  return sets;
}

// --- The analytic slab ---------------------------------------------------------------------------

TEST(ImageSpace, SlabMatchesTheStandardDipoleTotal) {
  // presets/slab.json: marble lit at normal incidence by E = 1 W/m², seen straight down by an
  // orthographic camera. Far from the edges B = ∫ R_d E F_t(0) dA = F_t(0) E R_d,total (Jensen et
  // al. 2001's total) and L = F_t(0)/π · B. The disc (8 mean free paths of the red band, 68 mm)
  // reaches past the slab's edge (40 mm from the centre square), where samples find no surface:
  // the R_d mass beyond 40 mm is < 0.1% in every band. Every pixel of one place in the 4×4 tile
  // draws the same samples on this uniform slab, so the centre mean has the noise of one pixel's
  // T² N F = 16 × 32 × 8 samples: measured 1.0% per frame of 16 × 16 samples (64 frames, all three
  // bands, mean 1.000 ± 0.001), hence 0.25% here; 1% is 4 standard errors.
  PresetSession s("slab", kSlabImageSpace);
  gpu::Image image;
  for (int f = 0; f < 8; ++f) image = s.render();
  const sss::Material& m = s.scene().objects[0].material;
  const double ft = test::normalTransmittance(m.eta);
  for (int c = 0; c < 3; ++c) {
    const double expected = ft * ft * test::jensenTotalRd(m.sigma_a[c], m.sigma_s[c], m.g[c], m.eta) / kPi;
    const double ratio = centreMean(image, c) / expected;
    std::printf("[ image-space ] slab band %d: L / (F_t² E R_d/π) = %.5f\n", c, ratio);
    EXPECT_NEAR(ratio, 1.0, 0.01) << "band " << c;
  }
}

TEST(ImageSpace, SlabLitObliquelyTransmitsECosThetaFt) {
  // Light 60° from the normal: the G-buffer's irradiance is E cos θ F_t(θ) (Eq. 5), so
  // L = F_t(0)/π · E cos θ F_t(θ) R_d,total; the same tolerance as at normal incidence.
  const double cosTheta = 0.5;
  PresetSession s("slab", with(kSlabImageSpace, {"light.direction=0.8660254,0.5,0"}));
  gpu::Image image;
  for (int f = 0; f < 8; ++f) image = s.render();
  const sss::Material& m = s.scene().objects[0].material;
  for (int c = 0; c < 3; ++c) {
    const double expected = test::normalTransmittance(m.eta) / kPi * cosTheta * fresnelT(cosTheta, m.eta) *
                            test::jensenTotalRd(m.sigma_a[c], m.sigma_s[c], m.g[c], m.eta);
    const double ratio = centreMean(image, c) / expected;
    std::printf("[ image-space ] 60° slab band %d: L / (F_t(0) cos θ F_t(θ) E R_d/π) = %.5f\n", c, ratio);
    EXPECT_NEAR(ratio, 1.0, 0.01) << "band " << c;
  }
}

// --- Rejection and renormalisation ------------------------------------------------------------------

/// Share of ∫_disc R_d dA (band c, disc of 8 mean free paths of the red band) on the part of the
/// disc with u > −δ (u along the image's x axis, δ ≥ 0 in mm), by Simpson on 20000 intervals:
/// beyond r = δ the angles |φ − π| < acos(δ/r) are cut off.
double visibleShare(const sss::Material& m, int c, double deltaMm) {
  const double mfp = 1.0 / std::sqrt(3.0 * m.sigma_a[0] * (m.sigma_a[0] + m.sigma_s[0] * (1.0 - m.g[0])));
  const double R = 8.0 * mfp;
  const int n = 20000;
  double visible = 0.0, total = 0.0;
  for (int i = 0; i <= n; ++i) {
    const double r = R * i / n, w = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
    const double f = test::jensenRd(r, m.sigma_a[c], m.sigma_s[c], m.g[c], m.eta) * r;
    const double angle = r <= deltaMm ? 2.0 * kPi : 2.0 * kPi - 2.0 * std::acos(deltaMm / r);
    visible += w * f * angle;
    total += w * f * 2.0 * kPi;
  }
  return visible / total;
}

/// The slab preset with a lid that hides x < −0.04 m from the camera: an opaque box, or a second
/// box in the slab's own mesh (a depth discontinuity of one object).
std::string slabWithLid(const test::TempDir& dir, bool sameObject) {
  std::ifstream in(std::string(TALLOW_TEST_SOURCE_DIR) + "/presets/slab.json");
  nlohmann::json preset = nlohmann::json::parse(in);
  preset["name"] = "slab-lid";
  if (sameObject) {
    // The slab [−0.1, 0.1] × [0, 0.05] × [−0.1, 0.1] and the lid [−0.16, −0.04] × [0.19, 0.2] ×
    // [−0.15, 0.15] as one mesh; placed by its bounding box (largest extent 0.3 m, bottom centre at
    // x = −0.03), which gives back these coordinates.
    geometry::TriangleMesh mesh;
    for (const auto& [centre, size] : {std::pair{glm::vec3(0.0f, 0.025f, 0.0f), glm::vec3(0.2f, 0.05f, 0.2f)},
                                       std::pair{glm::vec3(-0.1f, 0.195f, 0.0f), glm::vec3(0.12f, 0.01f, 0.3f)}}) {
      const geometry::TriangleMesh box = geometry::makeBox();
      const auto base = static_cast<std::uint32_t>(mesh.positions.size());
      for (std::size_t i = 0; i < box.positions.size(); ++i) {
        mesh.positions.push_back(centre + box.positions[i] * size);
        mesh.normals.push_back(box.normals[i]);
      }
      for (const auto& t : box.triangles) mesh.triangles.push_back({base + t[0], base + t[1], base + t[2]});
    }
    geometry::writePly(dir.path() / "stepped.ply", mesh);
    preset["objects"][0] = {{"name", "stepped"}, {"mesh", (dir.path() / "stepped.ply").string()},
                            {"material", "Marble"}, {"albedo", {0.8, 0.8, 0.8}}, {"position", {-0.03, 0.0, 0.0}},
                            {"scale", 0.3}};
  } else {
    preset["objects"].push_back({{"name", "lid"}, {"shape", "box"}, {"size", {0.12, 0.01, 0.3}},
                                 {"albedo", {0.5, 0.5, 0.5}}, {"position", {-0.1, 0.195, 0.0}}});
  }
  const auto path = dir.path() / "slab-lid.json";
  std::ofstream(path) << preset.dump(2);
  return path.string();
}

TEST(ImageSpace, SamplesOnAnotherObjectOrAcrossADepthStepAreRejected) {
  // A lid hides x < −0.04 m of the slab from the camera (shadows off: the slab stays uniformly lit
  // at normal incidence). The orthographic view spans 0.24 m over 48 pixels from x = −0.12, so
  // columns < 16 show the lid and the lid's edge is a pixel edge: a sample of x_o is rejected
  // exactly when its u along x is below −δ, δ = the distance of x_o to that edge. Expected, per
  // pixel of columns 16 and 17 (δ = 2.5 and 7.5 mm): with renormalize off, B = F_t E ∫ R_d over the
  // visible part of the disc, i.e. the open slab's value times visibleShare(δ), averaged over the
  // columns of the pixel's combination window that show the slab (columns c − 1 … c + 2); with
  // renormalize on, exactly the open slab's value F_t E ∫_disc R_d (on a flat, uniformly lit
  // surface each valid sample's R_d E w equals ∫_disc R_d times its coverage weight). Both for an
  // opaque lid (another object) and for a lid in the slab's own mesh, 0.14 m above it (the same
  // translucent slot: only the depth test rejects). Samples accepted on either lid would add
  // nothing to B (the opaque lid has no irradiance, the far one R_d ≈ 0) but would count as
  // covered: the renormalised value would drop to the "off" value, 2–5% low, so the 0.1% bound on
  // it (float rounding) is what detects a missing rejection. Tolerance off: 1.5%, 4 standard errors
  // of the 16-row mean of 32 samples × 16 sets × 8 frames.
  for (const bool sameObject : {false, true}) {
    test::TempDir dir;
    const std::string preset = slabWithLid(dir, sameObject);
    gpu::Image images[2];
    for (const bool renormalize : {false, true}) {
      PresetSession s(preset, {"render.width=48", "render.height=48", "method=image-space", "render.shadows=false",
                               "image_space.samples=32", "image_space.frames=8", "render.aa=1",
                               std::string("image_space.renormalize=") + (renormalize ? "true" : "false")});
      for (int f = 0; f < 8; ++f) images[renormalize] = s.render();
    }
    const sss::Material& m = PresetSession(preset).scene().objects[0].material;
    const double ft = test::normalTransmittance(m.eta);
    for (int c = 0; c < 3; ++c) {
      const double open = ft * ft * test::jensenTotalRd(m.sigma_a[c], m.sigma_s[c], m.g[c], m.eta) / kPi;
      for (int column : {16, 17}) {
        double expected = 0.0;
        int columns = 0;
        for (int q = column - 1; q <= column + 2; ++q)
          if (q >= 16) {
            expected += visibleShare(m, c, (q - 16 + 0.5) * 5.0);
            ++columns;
          }
        expected /= columns;
        double off = 0.0, on = 0.0;
        for (int y = 16; y < 32; ++y) {
          off += images[0].at(column, y)[c] / open / 16.0;
          on += images[1].at(column, y)[c] / open / 16.0;
        }
        std::printf("[ image-space ] %s lid, column %d, band %d: off %.4f (expected %.4f), on %.5f (expected 1)\n",
                    sameObject ? "same-object" : "opaque", column, c, off, expected, on);
        EXPECT_NEAR(off / expected, 1.0, 0.015) << "column " << column << " band " << c;
        EXPECT_NEAR(on, 1.0, 1e-3) << "column " << column << " band " << c;
      }
    }
  }
}

// --- The GPU runs the shared lines -------------------------------------------------------------------

TEST(ImageSpace, GpuPatternIsTheSharedCodesPattern) {
  // After one frame the pattern buffer holds the frame's entries (slot, set, sample); the same
  // function compiled as C++ in float, with the same inputs, gives them to float rounding: the
  // GPU's exp, log and sqrt differ from the C library's in the last bits, and Newton's method then
  // stops within a few ulps of the same root (relative 10⁻⁴ on offsets and weights, 10⁻⁴ of the
  // largest weight absolutely, where a weight is small).
  PresetSession s("slab", with(kSlabImageSpace, {"image_space.tile=2", "image_space.samples=12",
                                                 "image_space.uniform_share=0.25"}));
  s.render();
  const sss::ImageSpaceSss* is = s.renderer().module<sss::ImageSpaceSss>();
  ASSERT_NE(is, nullptr);
  const int sets = 4, samples = 12, nUniform = 3;
  std::vector<sss::ImageSpacePatternRecord> records(static_cast<std::size_t>(sets * samples));
  ASSERT_EQ(is->pattern().size(), records.size() * sizeof(sss::ImageSpacePatternRecord));
  is->pattern().download(0, is->pattern().size(), records.data());
  namespace sh = image_space_gltest_f32;
  const sss::Material& m = s.scene().objects[0].material;
  const auto k = [&](int c) { return sh::bssrdfCoefficients(m.sigma_a[c], m.sigma_s[c], m.g[c], m.eta); };
  double largest = 0.0;
  for (const auto& r : records) largest = std::max(largest, double(r.weight));
  for (int set = 0; set < sets; ++set)
    for (int j = 0; j < samples; ++j) {
      const auto& gpu = records[static_cast<std::size_t>(set * samples + j)];
      const sh::IsPatternEntry cpu =
          sh::isPatternEntry(k(0), k(1), k(2), 8.0f, j, samples, nUniform, std::uint32_t(set), 0u);
      const double r = glm::length(cpu.offset);
      EXPECT_NEAR(gpu.offsetX, cpu.offset.x, 1e-4 * r + 1e-6) << set << ' ' << j;
      EXPECT_NEAR(gpu.offsetY, cpu.offset.y, 1e-4 * r + 1e-6) << set << ' ' << j;
      EXPECT_NEAR(gpu.weight, cpu.weight, 1e-4 * cpu.weight + 1e-4 * largest) << set << ' ' << j;
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(gpu.coverage[c], cpu.coverage[c], 1e-4 + 1e-4 * cpu.coverage[c]);
    }
}

// --- The plan ----------------------------------------------------------------------------------------

bool ran(const sss::FrameTimings& t, const std::string& name) {
  return std::any_of(t.passes.begin(), t.passes.end(), [&](const gpu::PassTiming& p) { return p.name == name; });
}

TEST(ImageSpace, AccumulatesThenStopsAndRestartsWhenTheCameraMoves) {
  PresetSession s("slab", with(kSlabImageSpace, {"image_space.frames=2"}));
  sss::FrameTimings t;
  s.render(0.0, &t);
  EXPECT_TRUE(ran(t, "image_space.gbuffer") && ran(t, "image_space.scatter") && ran(t, "image_space.combine"));
  EXPECT_FALSE(ran(t, "sss.light_gbuffer")) << "no radiosity-map pass for image-space";
  const gpu::Image second = s.render(0.0, &t);
  EXPECT_FALSE(ran(t, "image_space.gbuffer")) << "the G-buffer holds for the accumulation";
  EXPECT_TRUE(ran(t, "image_space.scatter"));
  EXPECT_EQ(s.renderer().module<sss::ImageSpaceSss>()->frames(), 2);
  const gpu::Image converged = s.render(0.0, &t);
  EXPECT_FALSE(ran(t, "image_space.scatter")) << "converged: only the surface pass";
  EXPECT_TRUE(ran(t, "surface"));
  EXPECT_EQ(second.pixels, converged.pixels) << "a converged frame shows the accumulation unchanged";
  s.scene().camera.position.x += 0.01f;
  s.render(0.0, &t);
  EXPECT_TRUE(ran(t, "image_space.gbuffer")) << "a moved camera restarts";
  EXPECT_EQ(s.renderer().module<sss::ImageSpaceSss>()->frames(), 1);
  EXPECT_GT(s.renderer().gpuBytes(), s.renderer().module<sss::ImageSpaceSss>()->bytes());
  EXPECT_GE(s.renderer().module<sss::ImageSpaceSss>()->bytes(), std::size_t{48 * 48 * (16 * 6 + 8 + 4)});
}

// --- Receivers and hard cases ------------------------------------------------------------------------

TEST(ImageSpace, OpaqueReceiversAreShadedAsByTheOtherMethods) {
  // The bunny on its floor: every floor pixel is the same Lambertian shading as with the radiosity
  // maps (no VPLs): the method changes translucent pixels only.
  const std::vector<std::string> sets = {"render.width=48", "render.height=36", "image_space.frames=1",
                                         "sss.maps=2", "sss.map_size=32", "sss.frames=1", "vpl.count=0"};
  PresetSession a("bunny", with(sets, {"method=image-space"}));
  PresetSession b("bunny", with(sets, {"method=radiosity-maps"}));
  const gpu::Image ia = a.render(), ib = b.render();
  const std::vector<std::uint8_t> receivers = a.renderer().receiverMask();
  int compared = 0;
  for (std::size_t i = 0; i < receivers.size(); ++i) {
    if (!receivers[i]) continue;
    ++compared;
    EXPECT_EQ(ia.pixels[i], ib.pixels[i]) << "pixel " << i;
  }
  EXPECT_GT(compared, 100);
}

TEST(ImageSpace, HardCasesStayFinite) {
  // No absorption (Spectralon: σ_a = 0, σ_tr bounded below), a low-albedo medium (Ketchup's red),
  // a bunny 10⁻⁴ m and 100 m across, a grazing camera, all uniform or no uniform samples, one pixel
  // tiles, a tight depth ratio: every pixel finite and non-negative.
  const std::vector<std::vector<std::string>> cases = {
      {"material=Spectralon"}, {"material=Ketchup"}, {"scale=0.0001"}, {"scale=100"},
      {"camera.position=0.3,0.002,0.0"}, {"image_space.uniform_share=1"}, {"image_space.uniform_share=0"},
      {"image_space.tile=1", "image_space.depth_ratio=0.01", "image_space.jacobian=false"},
      {"image_space.radius=64", "image_space.renormalize=true"}};
  for (const auto& c : cases) {
    PresetSession s("bunny", with({"render.width=32", "render.height=24", "method=image-space",
                                   "image_space.samples=8", "image_space.frames=1"},
                                  c));
    const gpu::Image image = s.render();
    for (const glm::vec4& p : image.pixels)
      ASSERT_TRUE(std::isfinite(p.r) && std::isfinite(p.g) && std::isfinite(p.b) && p.r >= 0 && p.g >= 0 && p.b >= 0)
          << c.front();
  }
}

// --- The command line --------------------------------------------------------------------------------

TEST(ImageSpace, BadValuesAreRefusedWithOneLine) {
  test::TempDir dir;
  const auto out = dir.path() / "o";
  for (const auto& [set, expected] : std::vector<std::pair<std::string, std::string>>{
           {"image_space.samples=0", "image_space.samples: 0 is out of range [1, 1024]"},
           {"image_space.tile=9", "image_space.tile: 9 is out of range [1, 8]"},
           {"image_space.uniform_share=1.5", "image_space.uniform_share: 1.5 is out of range [0, 1]"},
           {"image_space.radius=0", "image_space.radius: 0 is out of range [0.5, 64]"},
           {"image_space.frames=0", "image_space.frames: 0 is out of range [1, 1048576]"},
           {"image_space.depth_ratio=-1", "image_space.depth_ratio: -1 is out of range [0.01, 100]"},
           {"image_space.jacobian=maybe", "image_space.jacobian"},
           {"method=image_space", "did you mean \"image-space\""}}) {
    const auto r = test::runTallow({"capture", "--preset", "slab", "--size", "16x16", "--set", set, "--out", out.string()});
    EXPECT_NE(r.exitCode, 0) << set;
    EXPECT_EQ(test::lineCount(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(expected), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out)) << set;
  }
}

TEST(ImageSpace, ExplainListsThePassesAndStatsTimeThem) {
  test::TempDir dir;
  const auto out = dir.path() / "o";
  const auto r = test::runTallow({"capture", "--preset", "slab", "--size", "24x24", "--explain", "--set",
                                  "method=image-space", "--set", "image_space.frames=2", "--frames", "3", "--out",
                                  out.string()});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  for (const char* pass : {"image_space.gbuffer", "image_space.scatter", "image_space.combine"})
    EXPECT_NE(r.out.find(std::string("pass ") + pass), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("sss.light_gbuffer"), std::string::npos) << r.out;
  std::ifstream in(out / "stats.json");
  const auto stats = nlohmann::json::parse(in);
  const auto& frames = stats["frames"];
  ASSERT_EQ(frames.size(), 3u);
  EXPECT_TRUE(frames[0]["gpu_ms"].contains("image_space.gbuffer")) << frames[0].dump();
  EXPECT_TRUE(frames[1]["gpu_ms"].contains("image_space.scatter")) << frames[1].dump();
  EXPECT_FALSE(frames[1]["gpu_ms"].contains("image_space.gbuffer")) << frames[1].dump();
  EXPECT_FALSE(frames[2]["gpu_ms"].contains("image_space.scatter")) << frames[2].dump();
  EXPECT_EQ(stats["parameters"]["method"], "image-space");
}

}  // namespace
}  // namespace tallow

namespace tallow {
namespace {

TEST(ImageSpace, BenchTimesItsAccumulationAndMeasuresItsError) {
  // tallow bench with image-space beside albedo on the slab (8x6): the image-space row accumulates
  // image_space.frames = 3 frames, then shows 2 converged ones (5 in all); its scatter pass is timed;
  // and the scattered light brings it closer to the reference than albedo, which has none.
  test::TempDir dir;
  const auto ref = dir.path() / "ref.exr";
  const auto r0 = test::runTallow({"reference", "--preset", "slab", "--size", "8x6", "--spp", "2", "--out", ref.string()});
  ASSERT_EQ(r0.exitCode, 0) << r0.err;
  const auto out = dir.path() / "bench";
  const auto r = test::runTallow({"bench", "--preset", "slab", "--size", "8x6", "--methods", "image-space,albedo", "--set",
                                  "image_space.frames=3", "--set", "render.shadow_map_size=256", "--sweep",
                                  "image_space.samples=8,16", "--reference", ref.string(), "--out", out.string()});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  std::ifstream in(out / "bench.json");
  const auto bench = nlohmann::json::parse(in);
  double imageSpaceError = 0.0, albedoError = 0.0;
  int imageSpaceRows = 0;
  for (const auto& row : bench["rows"]) {
    if (row["method"] == "image-space") {
      ++imageSpaceRows;
      EXPECT_EQ(row["frames"], 5);
      EXPECT_EQ(row["converged_frames"], 2);
      EXPECT_TRUE(row["median_accumulating_wall_ms"].is_number());
      EXPECT_TRUE(row["gpu_ms_median"]["image_space.scatter"].is_number());
      imageSpaceError = std::max(imageSpaceError, row["last_rel_rmse"].get<double>());
    } else {
      albedoError = row["last_rel_rmse"].get<double>();
    }
  }
  EXPECT_EQ(imageSpaceRows, 2) << "image_space.* sweeps are method knobs sharing the one reference";
  EXPECT_LT(imageSpaceError, albedoError);
}

}  // namespace
}  // namespace tallow
