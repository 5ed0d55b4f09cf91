// The engines' diffusion profile as a peer (`method=burley`, issue 41, docs/burley.md) on llvmpipe:
// the analytic slab (the profile carries the standard dipole's total), edges not darkened (the
// weights renormalised over the samples on the object, as engines do), light through a thin slab
// from behind (the shadow map's thickness through the profile's transmittance), every preset, and
// the bench beside the other methods.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "sss/peers/burley_profile.h"
#include "support/dipole_totals.h"
#include "support/render_support.h"
#include "support/run_tallow.h"
#include "support/temp_dir.h"

namespace tallow {
namespace {

using test::centreMean;
using test::PresetSession;
constexpr double kPi = 3.14159265358979323846;

// presets/slab.json (marble, E = 1 W/m² straight down, an orthographic camera straight down; the
// 0.2 m slab fills 40 of the 48 pixels), one frame at the pixel centres.
const std::vector<std::string> kSlabBurley = {"render.width=48", "render.height=48", "method=burley", "render.aa=1"};

std::vector<std::string> with(std::vector<std::string> sets, const std::vector<std::string>& more) {
  sets.insert(sets.end(), more.begin(), more.end());
  return sets;
}

/// The slab's centre shows L = F_t(0)²/π E R_d,total per band, to float rounding (2e-3).
void expectTheDipoleTotal(PresetSession&& s) {
  const gpu::Image image = s.render();
  const sss::Material& m = s.scene().objects[0].material;
  const double ft = test::normalTransmittance(m.eta);
  for (int c = 0; c < 3; ++c) {
    const double expected = ft * ft * test::jensenTotalRd(m.sigma_a[c], m.sigma_s[c], m.g[c], m.eta) / kPi;
    EXPECT_NEAR(centreMean(image, c) / expected, 1.0, 2e-3) << "band " << c;
  }
}

TEST(Burley, SlabMatchesTheStandardDipoleTotal) {
  // Under uniform irradiance every sample sees the same E, so the renormalised estimate is exactly
  // A E F_t(0) with A the standard dipole's total (Jensen et al. 2001): L = F_t(0)²/π E R_d,total,
  // the image-space peer's analytic value, to float rounding (no light from behind: no transmission).
  expectTheDipoleTotal(PresetSession("slab", kSlabBurley));
}

TEST(Burley, TheSeparableKernelGivesTheSlabTheSameTotal) {
  // burley.kernel=separable: each pass's weights sum to 1 and follow the surface at the edges, so
  // uniform E gives A E F_t(0) again, to float rounding.
  expectTheDipoleTotal(PresetSession("slab", with(kSlabBurley, {"burley.kernel=separable"})));
}

TEST(Burley, EdgesAreNotDarkened) {
  // The slab's outermost pixels lose about half their samples off the edge; engines renormalise the
  // weights over the samples that count, so those pixels keep the centre's radiance (an estimate
  // without it, the sum over N samples, would show them about half as bright).
  PresetSession s("slab", kSlabBurley);
  const gpu::Image image = s.render();
  int edge = 0;
  for (int x = 0; x < image.width && !edge; ++x)
    if (image.at(x, image.height / 2)[1] > 0.0f) edge = x;
  ASSERT_GT(edge, 0) << "the slab is in the picture";
  for (int c = 0; c < 3; ++c) {
    double sum = 0.0;
    int n = 0;
    for (int y = image.height / 4; y < 3 * image.height / 4; ++y, ++n)
      sum += image.at(edge, y)[c] + image.at(image.width - 1 - edge, y)[c];
    const double ratio = sum / (2 * n) / centreMean(image, c);
    std::printf("[ burley  ] band %d: edge column / centre = %.5f\n", c, ratio);
    EXPECT_NEAR(ratio, 1.0, 5e-3) << "band " << c;
  }
}

TEST(Burley, AThinSlabLitFromBehindTransmitsTheProfilesMassBeyondItsThickness) {
  // The slab lit from below (light.direction 0,−1,0), seen from above: no light on the top face, so
  // all of L is the transmitted light F_t(0)/π · E F_t(0) T(t) with t the 50 mm between the top face
  // and the first surface the light's shadow map sees (the bottom face). A medium of long mean free
  // path (σ_a 0.01, σ_s 0.05 mm⁻¹: d ≈ 11 mm) lets a measurable share through. T's form is tested
  // against quadrature in BurleyProfile.*; this checks the thickness read from the shadow map
  // (about 3% of L per mm, so 1% is a third of a millimetre).
  PresetSession s("slab", with(kSlabBurley, {"light.direction=0,-1,0", "material.sigma_a=0.01,0.012,0.014",
                                             "material.sigma_s=0.05,0.05,0.05"}));
  const gpu::Image image = s.render();
  const sss::Material& m = s.scene().objects[0].material;
  const double ft = test::normalTransmittance(m.eta);
  const auto bands = sss::burleyBands(m);
  for (int c = 0; c < 3; ++c) {
    const double expected = ft * ft / kPi * sss::burleyTransmittance(50.0, bands[static_cast<std::size_t>(c)]);
    const double ratio = centreMean(image, c) / expected;
    std::printf("[ burley  ] band %d: transmitted L / (F_t² T(50 mm)/π) = %.5f (T = %.4f)\n", c, ratio,
                sss::burleyTransmittance(50.0, bands[static_cast<std::size_t>(c)]));
    EXPECT_NEAR(ratio, 1.0, 0.01) << "band " << c;
  }
  // And without transmission nothing reaches the top face.
  s.settings().burley.transmission = false;
  EXPECT_EQ(centreMean(s.render(), 1), 0.0);
}

TEST(Burley, APointLightBelowTheSlabTransmitsThroughItsCubeThickness) {
  // The same thin medium lit by a point light 0.2 m below the slab's bottom face (light.type=point,
  // I = 1 W/sr), seen from above: at the centre pixel the top face (0.25 m from the light) gets
  // F_t(0)/π · (I / d²) F_t(0) T(t) with t the 50 mm the light's cube shadow map sees through
  // (its stored depth turned back into a distance). Within 1%, as the directional case.
  PresetSession s("slab", with(kSlabBurley, {"light.type=point", "light.position=0,-0.2,0", "light.intensity=1,1,1",
                                             "material.sigma_a=0.01,0.012,0.014", "material.sigma_s=0.05,0.05,0.05"}));
  const gpu::Image image = s.render();
  const sss::Material& m = s.scene().objects[0].material;
  const double ft = test::normalTransmittance(m.eta);
  const auto bands = sss::burleyBands(m);
  // The centre pixel's point: half a pixel (2.5 mm) from the axis in x and z; its distance and cosine.
  const double h = 0.25, off = 0.24 / 48 * 0.5, d2 = h * h + 2 * off * off, cosine = h / std::sqrt(d2);
  for (int c = 0; c < 3; ++c) {
    const double thickness = 50.0 / cosine;  // along the ray, through the 50 mm slab
    const double expected = ft / kPi * (cosine / d2) * test::fresnelT(cosine, m.eta) *
                            sss::burleyTransmittance(thickness, bands[static_cast<std::size_t>(c)]);
    const double ratio = image.at(image.width / 2, image.height / 2)[c] / expected;
    std::printf("[ burley  ] point light, band %d: transmitted L / expected = %.5f\n", c, ratio);
    EXPECT_NEAR(ratio, 1.0, 0.01) << "band " << c;
  }
}

TEST(Burley, AMaterialInOpenPbrTermsShowsItsColourOnTheSlab) {
  // Issue 42, point 3: the slab's marble replaced by {"subsurface_color": [0.6, 0.35, 0.1],
  // "subsurface_radius_mm": 2, "subsurface_radius_scale": [1, 0.5, 0.25], "eta": 1.4}. The colour is
  // the standard dipole's total of the σ it becomes, which is the profile's A: L = F_t(0)² E c/π per
  // band, the colour itself, exactly (uniform E).
  test::TempDir dir;
  std::ifstream in(std::string(TALLOW_TEST_SOURCE_DIR) + "/presets/slab.json");
  nlohmann::json preset = nlohmann::json::parse(in);
  preset["objects"][0]["material"] = {{"subsurface_color", {0.6, 0.35, 0.1}},
                                      {"subsurface_radius_mm", 2.0},
                                      {"subsurface_radius_scale", {1.0, 0.5, 0.25}},
                                      {"eta", 1.4}};
  const auto file = dir.path() / "openpbr_slab.json";
  std::ofstream(file) << preset.dump(2);
  PresetSession s(file.string(), kSlabBurley);
  const gpu::Image image = s.render();
  const double ft = test::normalTransmittance(1.4);
  const double color[3] = {0.6, 0.35, 0.1};
  for (int c = 0; c < 3; ++c) {
    const double ratio = centreMean(image, c) / (ft * ft * color[c] / kPi);
    std::printf("[ burley  ] OpenPBR material, band %d: L / (F_t(0)² E c/π) = %.5f\n", c, ratio);
    EXPECT_NEAR(ratio, 1.0, 2e-3) << "band " << c;
  }
}

TEST(Burley, RunsOnEveryPreset) {
  // Each preset of presets/ captured with method=burley at a small size: exit 0 and a finite frame.
  test::TempDir dir;
  int presets = 0;
  for (const auto& e : std::filesystem::directory_iterator(std::string(TALLOW_TEST_SOURCE_DIR) + "/presets")) {
    if (e.path().extension() != ".json") continue;
    ++presets;
    const std::string name = e.path().stem().string();
    const auto out = dir.path() / name;
    const auto r = test::runTallow({"capture", "--preset", name, "--size", "48x27", "--set", "method=burley", "--set",
                                    "render.shadow_map_size=256", "--out", out.string()});
    ASSERT_EQ(r.exitCode, 0) << name << ": " << r.err;
    std::ifstream in(out / "stats.json");
    const auto stats = nlohmann::json::parse(in);
    EXPECT_EQ(stats["frames"][0]["pixels"]["non_finite"], 0) << name;
  }
  EXPECT_GE(presets, 10);
}

TEST(Burley, BenchTimesItBesideTheOthersAndMeasuresItsError) {
  // tallow bench with burley beside albedo on the slab (8x6) against a reference: its two passes
  // are timed, and the profile's scattered light brings it closer to the reference than albedo's
  // Lambertian surface (measured 0.663 against 0.711).
  test::TempDir dir;
  const auto ref = dir.path() / "ref.exr";
  const auto r0 = test::runTallow({"reference", "--preset", "slab", "--size", "8x6", "--spp", "2", "--out", ref.string()});
  ASSERT_EQ(r0.exitCode, 0) << r0.err;
  const auto out = dir.path() / "bench";
  const auto r = test::runTallow({"bench", "--preset", "slab", "--size", "8x6", "--methods", "burley,albedo", "--set",
                                  "render.shadow_map_size=256", "--reference", ref.string(), "--out", out.string()});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  std::ifstream in(out / "bench.json");
  const auto bench = nlohmann::json::parse(in);
  double burleyError = -1.0, albedoError = -1.0;
  for (const auto& row : bench["rows"]) {
    if (row["method"] == "burley") {
      burleyError = row["last_rel_rmse"].get<double>();
      EXPECT_TRUE(row["gpu_ms_median"]["burley.gbuffer"].is_number());
      EXPECT_TRUE(row["gpu_ms_median"]["burley.scatter"].is_number());
    } else {
      albedoError = row["last_rel_rmse"].get<double>();
    }
  }
  ASSERT_GE(burleyError, 0.0);
  EXPECT_LT(burleyError, albedoError);
}

}  // namespace
}  // namespace tallow
