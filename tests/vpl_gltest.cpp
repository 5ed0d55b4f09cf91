// Virtual point lights (issue 7, point 5): the areas they stand for, their total flux against a
// dense estimate, one VPL's irradiance on a receiver against the disc formula computed here, a
// receiver that sees the light only through the VPLs, the backlit placement, and finiteness.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "gpu/image_error.h"
#include "sss/bssrdf/bssrdf.h"
#include "sss/maps/virtual_point_lights.h"
#include "sss/reference/reference_integrator.h"
#include "support/render_support.h"
#include "support/temp_dir.h"

namespace tallow {
namespace {

using test::PresetSession;
constexpr double kPi = 3.14159265358979323846;

/// A marble cube of edge `edge` whose centre is `lift` above a grey floor, lit by a directional
/// light from `toLight`; an orthographic camera straight down showing `view` metres square.
nlohmann::json cubeScene(double edge, double lift, const std::vector<double>& toLight, double view) {
  return {{"name", "vpl-cube"},
          {"description", "a marble cube above a floor, seen from above"},
          {"camera",
           {{"type", "orthographic"}, {"position", {0, 1, 0}}, {"target", {0, 0, 0}}, {"up", {0, 0, -1}},
            {"height", view}}},
          {"lights", {{{"type", "directional"}, {"direction", toLight}, {"irradiance", {1, 1, 1}}, {"shadows", true}}}},
          {"objects",
           {{{"name", "cube"}, {"shape", "box"}, {"size", {1, 1, 1}}, {"scale", edge}, {"material", "Marble"},
             {"albedo", {0.8, 0.8, 0.8}}, {"position", {0, lift, 0}}},
            {{"name", "floor"}, {"shape", "plane"}, {"size", {1, 1}}, {"albedo", {0.5, 0.5, 0.5}}, {"position", {0, 0, 0}}}}},
          {"ambient", {0, 0, 0}},
          {"background", {0, 0, 0}},
          {"animation", {{"duration_s", 0}, {"loop", true}}}};
}

std::string write(const test::TempDir& dir, const std::string& name, const nlohmann::json& preset) {
  const auto path = dir.path() / (name + ".json");
  std::ofstream(path) << preset.dump(2);
  return path.string();
}

const std::vector<std::string> kCheapMaps = {"sss.maps=6", "sss.samples=4", "sss.map_size=64", "sss.light_map_size=128",
                                             "sss.frames=1"};

std::vector<std::string> with(std::vector<std::string> sets, const std::vector<std::string>& more) {
  sets.insert(sets.end(), more.begin(), more.end());
  return sets;
}

TEST(Vpl, SolidAngleAreasAddUpToTheSurfaceArea) {
  // Directions uniform on the sphere around the box centre c meet the surface with density
  // cos α / (4π d² N) per unit area, so A_v = 4π d² / (N cos α) adds up to the surface's area: 6a²
  // for a cube (cos α ≥ 1/√3 there, above the shader's cap of 0.1).
  test::TempDir dir;
  const double a = 0.04;
  const std::string preset = write(dir, "cube", cubeScene(a, 0.05, {0.3, 1, 0.2}, 0.2));
  PresetSession s(preset, with(kCheapMaps, {"render.width=16", "render.height=16", "vpl.count=4096",
                                            "vpl.placement=all", "vpl.cube_size=256"}));
  s.render();
  const sss::VirtualPointLights* vpls = s.renderer().module<sss::VirtualPointLights>();
  ASSERT_NE(vpls, nullptr);
  const std::vector<sss::VplRecord> records = vpls->read();
  ASSERT_EQ(records.size(), 4096u);
  const glm::vec3 c = vpls->centre();
  EXPECT_NEAR(c.y, 0.05, 1e-6);
  double area = 0.0;
  for (const sss::VplRecord& r : records) {
    ASSERT_GT(r.position.w, 0.0f) << "every direction meets the closed cube";
    area += r.normal.w;
    const glm::vec3 d = glm::vec3(r.position) - c;
    const float face = std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)});
    EXPECT_NEAR(face, a / 2, a / 200) << "on the cube's surface";
    const glm::vec3 n(r.normal);
    EXPECT_GT(std::max({std::abs(n.x), std::abs(n.y), std::abs(n.z)}), 0.999f) << "a face normal";
    EXPECT_GT(glm::dot(n, d), 0.0f) << "pointing outward";
  }
  std::printf("[ vpl ] sum of A_v = %.6g m^2, 6a^2 = %.6g m^2 (ratio %.5f)\n", area, 6 * a * a, area / (6 * a * a));
  EXPECT_NEAR(area / (6 * a * a), 1.0, 0.01);

  // The cells' parts: 3 × 3 squares of each VPL's cell of solid angle 4π/N, their solid angles adding
  // up to the cell's, so their areas too add up to the surface's.
  double partArea = 0.0;
  for (const sss::VplRecord& r : vpls->readParts()) {
    ASSERT_GT(r.position.w, 0.0f) << "every part's direction meets the closed cube";
    partArea += r.normal.w;
    const glm::vec3 d = glm::vec3(r.position) - c;
    EXPECT_NEAR(std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)}), a / 2, a / 200) << "on the cube's surface";
  }
  std::printf("[ vpl ] sum of the parts' areas = %.6g m^2 (ratio %.5f)\n", partArea, partArea / (6 * a * a));
  EXPECT_NEAR(partArea / (6 * a * a), 1.0, 0.01);

  // The paper's Eq. 16 weight: A_box / N each.
  s.settings().vpl.area = sss::VplArea::BoundingBox;
  s.render();
  for (const sss::VplRecord& r : s.renderer().module<sss::VirtualPointLights>()->read())
    EXPECT_NEAR(r.normal.w, 6 * a * a / 4096, 1e-4 * 6 * a * a / 4096);
}

TEST(Vpl, FluxMatchesADenseEstimateWithinSamplingError) {
  // Φ = Σ_v B(x_v) A_v estimates ∫ B dA over the outermost surface. With N = 4096 directions the
  // estimate is dense; each direction alone gives Y_v = N B_v A_v, whose spread over the dense
  // set bounds the error of an N = 80 estimate (σ = sd(Y)/√80; Halton directions do better).
  test::TempDir dir;
  const std::string preset = write(dir, "cube", cubeScene(0.04, 0.05, {0.5, 0.8, 0.3}, 0.2));
  const auto flux = [&](int n, std::vector<double>* perDirection) {
    PresetSession s(preset, with(kCheapMaps, {"render.width=16", "render.height=16", "vpl.count=" + std::to_string(n),
                                              "vpl.placement=all", "sss.frames=1", "sss.samples=16"}));
    s.render();
    glm::dvec3 sum(0.0);
    for (const sss::VplRecord& r : s.renderer().module<sss::VirtualPointLights>()->read()) {
      const glm::dvec3 b = kPi * glm::dvec3(glm::vec3(r.radiance));  // B = π (B/π)
      sum += b * static_cast<double>(r.normal.w);
      if (perDirection) perDirection->push_back(n * (b.x + b.y + b.z) * r.normal.w);
    }
    return sum;
  };
  std::vector<double> y;
  const glm::dvec3 dense = flux(4096, &y);
  const glm::dvec3 sparse = flux(80, nullptr);
  double mean = 0.0, var = 0.0;
  for (double v : y) mean += v / y.size();
  for (double v : y) var += (v - mean) * (v - mean) / (y.size() - 1);
  const double sigma = std::sqrt(var / 80.0);
  const double denseTotal = dense.x + dense.y + dense.z, sparseTotal = sparse.x + sparse.y + sparse.z;
  std::printf("[ vpl ] flux, all bands: N=80 %.6g W, N=4096 %.6g W, sampling error of N=80 %.3g W (%.1f%%)\n",
              sparseTotal, denseTotal, sigma, 100 * sigma / denseTotal);
  ASSERT_GT(denseTotal, 0.0);
  EXPECT_LT(sigma / denseTotal, 0.25) << "the bound below would say nothing";
  EXPECT_LE(std::abs(sparseTotal - denseTotal), 3.0 * sigma);
  // And the dense mean of Y is the dense flux itself (the same numbers, a consistency check).
  EXPECT_NEAR(mean / denseTotal, 1.0, 1e-3);
}

/// A VPL's irradiance at p (normal n) as a point: F_t (B/π) A cos θ_v cos θ_r / (d² + A/π).
glm::dvec3 pointIrradiance(const sss::VplRecord& r, const glm::dvec3& p, const glm::dvec3& n) {
  const glm::dvec3 toP = p - glm::dvec3(glm::vec3(r.position));
  const double d2 = glm::dot(toP, toP);
  const glm::dvec3 u = toP / std::sqrt(d2);
  const double cosV = glm::dot(glm::dvec3(glm::vec3(r.normal)), u), cosR = -glm::dot(n, u);
  if (cosV <= 0 || cosR <= 0) return glm::dvec3(0.0);
  const double area = r.normal.w;
  return sss::fresnelTransmittance(cosV, r.position.w) * glm::dvec3(glm::vec3(r.radiance)) * area * cosV * cosR /
         (d2 + area / kPi);
}

/// The same VPL as the patch it stands for (vpl_receiver.glsl): the rectangle of area A in its
/// tangent plane, 1/cos α longer along the surface's tilt away from the centre c, of radiance
/// F_t(θ_v at its centre) B/π, its irradiance at p integrated numerically (a 256² midpoint grid of
/// the point kernel cos θ cos θ_r / d², the part below p's horizon left out) — a second way to the
/// polygon formula the shader evaluates.
glm::dvec3 patchIrradiance(const sss::VplRecord& r, const glm::dvec3& c, const glm::dvec3& p, const glm::dvec3& n) {
  const glm::dvec3 x(glm::vec3(r.position)), nv(glm::vec3(r.normal));
  const glm::dvec3 toP = p - x;
  const double cosV = glm::dot(nv, glm::normalize(toP));
  if (cosV <= 0) return glm::dvec3(0.0);
  const glm::dvec3 rc = x - c;
  const glm::dvec3 tilt = rc - glm::dot(rc, nv) * nv;
  const double cosAlpha = std::max(std::abs(glm::dot(nv, glm::normalize(rc))), 0.1);
  const glm::dvec3 t1 = glm::dot(tilt, tilt) > 1e-12 * glm::dot(rc, rc)
                            ? glm::normalize(tilt)
                            : glm::normalize(std::abs(nv.y) < 0.9 ? glm::cross(glm::dvec3(0, 1, 0), nv)
                                                                  : glm::cross(glm::dvec3(1, 0, 0), nv));
  const glm::dvec3 t2 = glm::cross(nv, t1);
  const double area = r.normal.w, s1 = std::sqrt(area / cosAlpha), s2 = std::sqrt(area * cosAlpha);
  constexpr int kGrid = 256;
  double sum = 0.0;
  for (int a = 0; a < kGrid; ++a)
    for (int b = 0; b < kGrid; ++b) {
      const glm::dvec3 q = x + ((a + 0.5) / kGrid - 0.5) * s1 * t1 + ((b + 0.5) / kGrid - 0.5) * s2 * t2;
      const glm::dvec3 d = p - q;
      const double d2 = glm::dot(d, d), cosR = -glm::dot(n, d) / std::sqrt(d2);
      if (cosR <= 0) continue;
      sum += glm::dot(nv, d) / std::sqrt(d2) * cosR / d2;
    }
  return sss::fresnelTransmittance(cosV, r.position.w) * glm::dvec3(glm::vec3(r.radiance)) * (sum * area / (double(kGrid) * kGrid));
}

/// vpl_receiver.glsl's blends: a record's point beyond `far` sides (√A), its patch or parts within `near`.
double patchShare(const sss::VplRecord& r, const glm::dvec3& p, double near = 2.0, double far = 4.0) {
  const double sides = glm::length(p - glm::dvec3(glm::vec3(r.position))) / std::sqrt(double(r.normal.w));
  const double t = std::clamp((sides - near) / (far - near), 0.0, 1.0);
  return 1.0 - t * t * (3.0 - 2.0 * t);
}

TEST(Vpl, VplsLightTheFloorAsPointsFarAndThroughTheirCellsPartsNear) {
  // The floor's radiance with VPLs minus without is ρ/π Σ_v E_v: beyond 3 sides (√A_v) of a VPL E_v
  // is its point's F_t (B_v/π) A_v cos θ_v cos θ_r / (d² + A_v/π); within 1.5 sides the sum over the
  // 3 × 3 parts of its cell, each in turn its point far and the patch it stands for near (the patch by
  // numerical integration, its blend from 4 to 2 of its sides); between the two a smoothstep blend
  // (no VPL shadows). Evaluated here from the records at every floor pixel's world position.
  test::TempDir dir;
  const double view = 0.2, a = 0.04;
  const std::string preset = write(dir, "cube", cubeScene(a, 0.03, {0.4, 0.8, 0.2}, view));
  const int w = 40, h = 40;
  const std::vector<std::string> base = with(kCheapMaps, {"render.width=40", "render.height=40", "vpl.placement=all"});
  PresetSession off(preset, with(base, {"vpl.count=0"}));
  PresetSession on(preset, with(base, {"vpl.count=3"}));
  const gpu::Image without = off.render(), withVpls = on.render();
  const std::vector<sss::VplRecord> records = on.renderer().module<sss::VirtualPointLights>()->read();
  const std::vector<sss::VplRecord> parts = on.renderer().module<sss::VirtualPointLights>()->readParts();
  constexpr std::size_t kParts = sss::kVplParts;
  ASSERT_EQ(parts.size(), kParts * records.size());
  const glm::dvec3 centre(on.renderer().module<sss::VirtualPointLights>()->centre());
  int compared = 0, lit = 0, near = 0, patches = 0;
  double worst = 0.0, worstOfPeak = 0.0;
  struct Value { int i, j, c; double expected, measured; };
  std::vector<Value> values;
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      const double x = ((i + 0.5) / w - 0.5) * view, z = ((j + 0.5) / h - 0.5) * view;
      if (std::abs(x) < a / 2 + view / w && std::abs(z) < a / 2 + view / h) continue;  // under the cube
      const glm::dvec3 p(x, 0.0, z), n(0, 1, 0);
      glm::dvec3 e(0.0);
      for (std::size_t v = 0; v < records.size(); ++v) {
        const sss::VplRecord& r = records[v];
        if (r.position.w <= 0.0f) continue;
        const double share = patchShare(r, p, 1.5, 3.0);
        if (share < 1) e += (1.0 - share) * pointIrradiance(r, p, n);
        if (share <= 0) continue;
        ++near;
        for (std::size_t k = 0; k < kParts; ++k) {
          const sss::VplRecord& q = parts[kParts * v + k];
          if (q.position.w <= 0.0f) continue;
          const double patch = patchShare(q, p);
          if (patch < 1) e += share * (1.0 - patch) * pointIrradiance(q, p, n);
          if (patch > 0) {
            ++patches;
            e += share * patch * patchIrradiance(q, centre, p, n);
          }
        }
      }
      for (int c = 0; c < 3; ++c) values.push_back({i, j, c, 0.5 / kPi * e[c], withVpls.at(i, j)[c] - without.at(i, j)[c]});
    }
  // Where a patch is seen edge-on its polygon sum cancels to a tiny value, which float evaluates to
  // about 1e-5 of the brightest term; relative 0.5% elsewhere.
  double peak = 0.0;
  for (const Value& v : values) peak = std::max(peak, v.expected);
  for (const Value& v : values) {
    if (v.expected > 0) ++lit;
    worst = std::max(worst, std::abs(v.measured - v.expected) / std::max(v.expected, 1e-9));
    worstOfPeak = std::max(worstOfPeak, std::abs(v.measured - v.expected) / peak);
    EXPECT_NEAR(v.measured, v.expected, 5e-3 * v.expected + 1e-4 * peak) << "pixel " << v.i << "," << v.j << " band " << v.c;
    ++compared;
  }
  std::printf("[ vpl ] %d floor values, %d lit by the VPLs, %d pixel-VPL pairs near, %d pixel-part pairs as patches; "
              "worst relative difference %.2g, %.2g of the peak\n", compared, lit, near, patches, worst, worstOfPeak);
  EXPECT_GT(lit, compared / 4) << "the VPLs must light a good part of the floor for this to test anything";
  EXPECT_GT(near, 100) << "the VPLs must be near enough to part of the floor for this to test their parts";
  EXPECT_GT(patches, 100) << "the parts must be near enough to part of the floor for this to test their patches";
}

/// presets/candle-holder.json without its directional fill: the point light inside the cup is
/// the only light, and the table cannot see it.
std::string hiddenLightPreset(const test::TempDir& dir) {
  std::ifstream in(std::string(TALLOW_TEST_SOURCE_DIR) + "/presets/candle-holder.json");
  nlohmann::json p = nlohmann::json::parse(in);
  p["lights"] = nlohmann::json::array({p["lights"][0]});
  p["ambient"] = {0, 0, 0};
  p["background"] = {0, 0, 0};
  return write(dir, "hidden", p);
}

bool allFinite(const gpu::Image& image) {
  for (const glm::vec4& px : image.pixels)
    if (!std::isfinite(px.r) || !std::isfinite(px.g) || !std::isfinite(px.b)) return false;
  return true;
}

TEST(Vpl, AHiddenLightReachesTheTableOnlyThroughTheVpls) {
  test::TempDir dir;
  const std::string preset = hiddenLightPreset(dir);
  const std::vector<std::string> base = with(kCheapMaps, {"render.width=64", "render.height=48"});
  PresetSession off(preset, with(base, {"vpl.count=0"}));
  PresetSession on(preset, with(base, {"vpl.count=80"}));
  const gpu::Image dark = off.render(), lit = on.render();
  ASSERT_TRUE(allFinite(dark));
  ASSERT_TRUE(allFinite(lit));
  // The bottom rows show only the table in front of the holder (presets/candle-holder.json's camera).
  double darkMax = 0.0, litSum = 0.0;
  int litPixels = 0;
  for (int j = 40; j < 48; ++j)
    for (int i = 0; i < 64; ++i) {
      darkMax = std::max(darkMax, static_cast<double>(dark.at(i, j).r));
      litSum += lit.at(i, j).r;
      litPixels += lit.at(i, j).r > 0.0f ? 1 : 0;
    }
  std::printf("[ vpl ] table in front: max without VPLs %.3g, mean with %.3g, %d of %d pixels lit\n", darkMax,
              litSum / (8 * 64), litPixels, 8 * 64);
  EXPECT_EQ(darkMax, 0.0) << "the table sees the flame directly: the scene does not test what it should";
  EXPECT_GT(litPixels, 8 * 64 * 9 / 10);
  // The light is surrounded, so placement auto puts VPLs on backlit surface only.
  const sss::VirtualPointLights* vpls = on.renderer().module<sss::VirtualPointLights>();
  const glm::vec3 flame = on.scene().lights[0].position;
  int active = 0;
  for (const sss::VplRecord& r : vpls->read()) {
    if (r.position.w <= 0.0f) continue;
    ++active;
    EXPECT_LE(glm::dot(glm::vec3(r.normal), flame - glm::vec3(r.position)), 0.0f) << "a VPL on lit surface";
    EXPECT_TRUE(std::isfinite(r.radiance.r) && std::isfinite(r.normal.w));
  }
  EXPECT_GT(active, 40);
  EXPECT_EQ(sss::VirtualPointLights::placement(on.scene(), on.settings(), on.renderer().geometry()),
            sss::VplPlacement::Backlit);
}

TEST(Vpl, ConvergedFramesSkipThePassAndNothingTurnsNan) {
  // Hard cases for finiteness: the most VPLs the registry allows, a tiny cube and a huge one.
  test::TempDir dir;
  for (const double edge : {1e-4, 40.0}) {
    const std::string preset = write(dir, "cube", cubeScene(edge, edge, {0.0, 1.0, 0.0}, 4 * edge));
    PresetSession s(preset, with(kCheapMaps, {"render.width=24", "render.height=24", "vpl.count=4096", "sss.frames=1"}));
    ASSERT_TRUE(allFinite(s.render())) << "edge " << edge;
    for (const sss::VplRecord& r : s.renderer().module<sss::VirtualPointLights>()->read())
      ASSERT_TRUE(std::isfinite(r.radiance.r) && std::isfinite(r.normal.w) && std::isfinite(r.position.x));
    // Maps converged and VPLs stable: the second frame runs neither.
    for (const sss::PlannedPass& p : s.renderer().planFrame(s.scene(), s.settings(), 0.0)) EXPECT_NE(p.name, "vpl");
    s.settings().vpl.stable = false;
    bool planned = false;
    for (const sss::PlannedPass& p : s.renderer().planFrame(s.scene(), s.settings(), 0.0)) planned |= p.name == "vpl";
    EXPECT_TRUE(planned) << "new directions every frame need the pass every frame";
  }
}

TEST(Vpl, TheTableAgainstTheReferencesEmergentLight) {
  // presets/candle-holder.json: the receivers' emergent term of `tallow reference --emergent` (one
  // bounce of the light leaving the holder, with visibility) against the GPU's VPL term (the frame
  // with VPLs minus the frame without), over the receiver pixels, for N_vpl = 50, 80, 200.
  const std::vector<std::string> base = {"render.width=64", "render.height=48", "sss.map_size=256", "sss.frames=64"};
  PresetSession off("candle-holder", with(base, {"vpl.count=0"}));
  gpu::Image without;
  for (int f = 0; f < 4; ++f) without = off.render();
  sss::ReferenceSettings rs;
  rs.maxPasses = 32;
  rs.emergentLight = true;
  rs.emitterPoints = 2048;
  const sss::ReferenceResult ref = sss::renderReference(off.scene(), off.settings(), rs);
  ASSERT_GT(ref.emergentPixels, 1000);
  std::printf("[ vpl ] reference emergent term: %d receiver pixels, its own relative standard error %.2f%%\n",
              ref.emergentPixels, 100 * ref.emergentRelError);
  std::vector<double> errors;
  for (const int n : {50, 80, 200}) {
    PresetSession on("candle-holder", with(base, {"vpl.count=" + std::to_string(n)}));
    gpu::Image vpl;
    for (int f = 0; f < 4; ++f) vpl = on.render();
    ASSERT_TRUE(allFinite(vpl));
    for (std::size_t i = 0; i < vpl.pixels.size(); ++i)
      vpl.pixels[i] = glm::vec4(glm::vec3(vpl.pixels[i] - without.pixels[i]), 1.0f);
    const gpu::ImageError e = gpu::imageError(vpl, ref.emergent, ref.emergent);
    std::printf("[ vpl ] N_vpl = %3d: receivers' rel. RMSE %.1f%%, mean / reference %.3f (%zu pixels)\n", n,
                100 * e.relRmse, e.meanRatio, e.pixels);
    // The mean: the reference's noise on it is far below its per-pixel 10%; measured within 2.5%.
    EXPECT_NEAR(e.meanRatio, 1.0, 0.1) << "N_vpl " << n;
    // Measured 14.8%, 13.1%, 13.2% with the reference's ε (10%) inside, i.e. about 8% of the VPLs'
    // own; the cells' patches without parts gave 17.5%, 17.1%, 14.4%, Halton points 29%, 23%, 17%.
    EXPECT_LT(e.relRmse, 0.2) << "N_vpl " << n;
    errors.push_back(e.relRmse);
  }
  EXPECT_LT(errors.back(), errors.front()) << "more VPLs, less error";
}

TEST(Vpl, ShadowsDarkenWhatTheBlockHidesAsTheReferenceDoes) {
  // presets/candle-holder-block.json: an opaque block beside the holder hides part of the table from
  // its wall. Where the reference's emergent light is less than half the unshadowed VPL term (the
  // block's shadow), vpl.shadows must bring the VPL term most of the way to the reference; over all
  // receiver pixels it must not make the error worse (64 clusters).
  const std::vector<std::string> base = {"render.width=64", "render.height=48", "sss.map_size=256", "sss.frames=4",
                                         "vpl.shadow_clusters=64"};
  const auto term = [&](const std::vector<std::string>& sets, sss::ReferenceResult* ref) {
    PresetSession off("candle-holder-block", with(base, with(sets, {"vpl.count=0"})));
    PresetSession on("candle-holder-block", with(base, sets));
    gpu::Image dark, lit;
    for (int f = 0; f < 4; ++f) dark = off.render(), lit = on.render();
    for (std::size_t i = 0; i < lit.pixels.size(); ++i)
      lit.pixels[i] = glm::vec4(glm::vec3(lit.pixels[i] - dark.pixels[i]), 1.0f);
    if (ref) {
      sss::ReferenceSettings rs;
      rs.maxPasses = 128;
      rs.emergentLight = true;
      *ref = sss::renderReference(off.scene(), off.settings(), rs);
    }
    return lit;
  };
  sss::ReferenceResult ref;
  const gpu::Image unshadowed = term({"vpl.shadows=false"}, &ref), shadowed = term({"vpl.shadows=true"}, nullptr);
  double before = 0.0, after = 0.0;
  int hidden = 0;
  for (std::size_t i = 0; i < ref.emergent.pixels.size(); ++i) {
    if (ref.emergent.pixels[i].a < 0.5f) continue;
    const double r = glm::dot(glm::dvec3(glm::vec3(ref.emergent.pixels[i])), glm::dvec3(1.0));
    const double u = glm::dot(glm::dvec3(glm::vec3(unshadowed.pixels[i])), glm::dvec3(1.0));
    const double s = glm::dot(glm::dvec3(glm::vec3(shadowed.pixels[i])), glm::dvec3(1.0));
    if (u <= 0.0 || r >= 0.5 * u) continue;
    ++hidden;
    before += std::abs(u - r);
    after += std::abs(s - r);
  }
  const gpu::ImageError eOff = gpu::imageError(unshadowed, ref.emergent, ref.emergent);
  const gpu::ImageError eOn = gpu::imageError(shadowed, ref.emergent, ref.emergent);
  std::printf("[ vpl ] block's shadow: %d pixels, mean |VPL term - reference| %.3g without shadows, %.3g with\n",
              hidden, before / std::max(hidden, 1), after / std::max(hidden, 1));
  std::printf("[ vpl ] all receivers (reference ε %.1f%%): rel. RMSE %.1f%% -> %.1f%%, mean / reference %.3f -> %.3f\n",
              100 * ref.emergentRelError, 100 * eOff.relRmse, 100 * eOn.relRmse, eOff.meanRatio, eOn.meanRatio);
  ASSERT_GT(hidden, 50) << "the block must hide a good part of the table";
  EXPECT_LT(after, 0.5 * before);
  EXPECT_LE(eOn.relRmse, eOff.relRmse);
}

}  // namespace
}  // namespace tallow
