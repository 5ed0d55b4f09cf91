// SSLPV on llvmpipe (issue 8): flux conservation of the GPU propagation, the analytic slab against
// the dipole's total reflectance and against an independent laterally reduced recursion, the
// voxelised medium against the shared procedural, the frame plan's reuse of the grids, finiteness
// on hard cases, and the limits.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "gpu/gl_context.h"
#include "sss/maps/radiosity_maps.h"
#include "sss/peers/sslpv.h"
#include "sss/peers/sslpv_math.h"
#include "sss/scene_geometry.h"
#include "support/dipole_totals.h"
#include "support/render_support.h"
#include "support/run_tallow.h"
#include "support/slab_recursion.h"
#include "support/temp_dir.h"

namespace tallow {
namespace {

namespace sh = sss::sslpv_glsl;
using test::centreMean;
using test::fresnelT;
using test::PresetSession;
constexpr double kPi = 3.14159265358979323846;

bool allFinite(const gpu::Image& image) {
  return std::all_of(image.pixels.begin(), image.pixels.end(), [](const glm::vec4& p) {
    return std::isfinite(p.r) && std::isfinite(p.g) && std::isfinite(p.b) && p.r >= 0 && p.g >= 0 && p.b >= 0;
  });
}

bool ran(const sss::FrameTimings& t, const std::string& prefix) {
  return std::any_of(t.passes.begin(), t.passes.end(), [&](const auto& p) { return p.name.rfind(prefix, 0) == 0; });
}

// --- Propagation -----------------------------------------------------------------------------------

/// ∫ y_lm dω over the pyramid of one face of a unit cube seen from its centre (the face toward +e):
/// (y00 · 2π/3, √(3/4π) e ∫ ω·e dω), the second by a 400 × 400 quadrature of the face, where
/// dω = cos θ dA/r² and ω·e = cos θ. What a cell sends to the neighbour behind that face.
glm::dvec4 facePyramid(int axis, int sign) {
  constexpr int n = 400;
  double cosine = 0.0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double x = -0.5 + (i + 0.5) / n, y = -0.5 + (j + 0.5) / n, r2 = 0.25 + x * x + y * y;
      cosine += 0.25 / (r2 * r2) / (n * n);  // cos²θ/r² dA with cos θ = 0.5/r
    }
  glm::dvec3 e(0.0);
  e[axis] = sign;
  const double b = std::sqrt(3.0 / (4.0 * kPi)) * cosine;
  return {0.5 / std::sqrt(kPi) * 2.0 * kPi / 3.0, b * e.y, b * e.z, b * e.x};
}

TEST(Sslpv, PropagationConservesFluxUpToWhatLeavesTheGrid) {
  // A non-absorbing, non-scattering grid (σ_t = 0, σ'_s = 0) with random coefficients in every
  // cell: after one step the total flux Σ 2√π c00 is the flux before minus exactly what the
  // boundary cells sent out of the grid, each outward face's ∫_pyramid I dω (computed here from
  // the face's geometry, not from the propagation matrices).
  auto context = gpu::GlContext::create(gpu::ContextOptions{});
  const gpu::ShaderLibrary shaders;
  constexpr int n = 8;
  sss::SslpvMedium medium(shaders);
  medium.fillUniform(n, glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(0.0f));
  sss::SslpvPropagation propagation(shaders);
  propagation.resize(n);
  propagation.clear();
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<glm::vec4> cells(n * n * n);
  for (auto& c : cells) c = glm::vec4(2.0f + u(rng), u(rng), u(rng), u(rng));  // positive flux, any band 1
  propagation.upload(0, cells);
  const auto fluxOf = [](const std::vector<glm::vec4>& g) {
    double f = 0.0;
    for (const auto& c : g) f += 2.0 * std::sqrt(kPi) * c[0];
    return f;
  };
  double outflow = 0.0;
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const glm::ivec3 p(x, y, z);
        const glm::dvec4 c(cells[static_cast<std::size_t>((z * n + y) * n + x)]);
        for (int axis = 0; axis < 3; ++axis)
          for (int sign = -1; sign <= 1; sign += 2)
            if (p[axis] + sign < 0 || p[axis] + sign >= n) outflow += glm::dot(facePyramid(axis, sign), c);
      }
  const double before = fluxOf(cells);
  propagation.propagate(1, 0, 1.0f, medium);
  const double after = fluxOf(propagation.download(propagation.current()[0]));
  std::printf("[ sslpv ] flux before %.6f, after %.6f, out of the grid %.6f (%.2f%%)\n", before, after, outflow,
              100.0 * outflow / before);
  // Float sums of 512 cells × 6 matrix products: ~10⁻⁶ relative; the face quadrature ~10⁻⁶.
  EXPECT_NEAR(after, before - outflow, 2e-5 * before);
  EXPECT_GT(outflow, 0.1 * before);  // the check has something to account for
  // The first step is not accumulated when skip = 1; the accumulation of 3 steps, skip 1, is the
  // sum of steps 2 and 3 run one by one.
  propagation.clear();
  propagation.upload(0, cells);
  propagation.propagate(1, 0, 1.0f, medium);
  const auto step1 = propagation.download(propagation.current()[0]);
  propagation.propagate(1, 0, 1.0f, medium);
  const auto step2 = propagation.download(propagation.current()[0]);
  propagation.propagate(1, 0, 1.0f, medium);
  const auto step3 = propagation.download(propagation.current()[0]);
  propagation.clear();
  propagation.upload(0, cells);
  propagation.propagate(3, 1, 1.0f, medium);
  const auto acc = propagation.download(propagation.accumulation()[0]);
  for (std::size_t i = 0; i < acc.size(); i += 37)
    for (int k = 0; k < 4; ++k) EXPECT_NEAR(acc[i][k], step2[i][k] + step3[i][k], 1e-5f) << i;
}

// --- Injection -------------------------------------------------------------------------------------

/// Total flux Σ 2√π c00 per band of the grid right after injection into the slab of `s`.
glm::dvec3 injectedFlux(PresetSession& s, int injectSize) {
  const gpu::ShaderLibrary shaders;
  sss::RenderSettings settings = s.settings();
  settings.sss.lightMapSize = injectSize;
  sss::SceneGeometry geometry(s.scene());
  sss::RadiosityMaps gbuffers(shaders);
  gbuffers.renderLightGBuffers(s.scene(), settings, geometry);
  geometry::Aabb box;
  box.extend({-0.1f, 0.0f, -0.1f});
  box.extend({0.1f, 0.05f, 0.1f});
  const sss::SslpvGrid grid = sss::fitSslpvGrid(box, 32);
  sss::SslpvPropagation propagation(shaders);
  propagation.resize(grid.size);
  propagation.clear();
  sss::SslpvInjection(shaders).inject(s.scene(), settings, gbuffers, grid, propagation.current());
  glm::dvec3 flux(0.0);
  for (int b = 0; b < 3; ++b)
    for (const glm::vec4& c : propagation.download(propagation.current()[static_cast<std::size_t>(b)]))
      flux[b] += 2.0 * std::sqrt(kPi) * c[0];
  return flux;
}

TEST(Sslpv, InjectionCarriesTheTransmittedFluxOfDirectionalAndPointLights) {
  // §3.1 on the slab's top face (0.2 × 0.2 m at y = 0.05). Directional light straight down,
  // E = 1 W/m²: Σ_p T Φ_p = F_t(0°) E A. A point light of 1 W/sr 0.1 m above the face's centre:
  // Σ_p T Φ_p = ∫_face F_t(θ) cos θ / r² dA (quadrature here, 1000 × 1000). Texels whose centre
  // falls on the face stand for it: the edge texels make ~texel × perimeter / area ≈ 0.3% (1024²,
  // directional) and the cube's texel solid-angle approximation ~10⁻⁴; 0.5% covers both.
  PresetSession s("slab", {"render.width=16", "render.height=16", "method=sslpv"});
  const double eta = s.scene().objects[0].material.eta;
  const glm::dvec3 directional = injectedFlux(s, 1024);
  const double expectedDirectional = test::normalTransmittance(eta) * 1.0 * 0.2 * 0.2;
  sss::Light& light = s.scene().lights[0];
  light.kind = sss::LightKind::Point;
  light.position = {0.0f, 0.15f, 0.0f};
  light.intensity = glm::vec3(1.0f);
  const glm::dvec3 point = injectedFlux(s, 512);
  double expectedPoint = 0.0;
  constexpr int n = 1000;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double x = -0.1 + 0.2 * (i + 0.5) / n, z = -0.1 + 0.2 * (j + 0.5) / n, h = 0.1;
      const double r2 = x * x + z * z + h * h, cosTheta = h / std::sqrt(r2);
      expectedPoint += fresnelT(cosTheta, eta) * cosTheta / r2 * (0.04 / (n * n));
    }
  for (int b = 0; b < 3; ++b) {
    std::printf("[ sslpv ] injected band %d: directional %.6f W (expected %.6f), point %.6f W (expected %.6f)\n", b,
                directional[b], expectedDirectional, point[b], expectedPoint);
    EXPECT_NEAR(directional[b] / expectedDirectional, 1.0, 0.005);
    EXPECT_NEAR(point[b] / expectedPoint, 1.0, 0.005);
  }
}

// --- The analytic slab -----------------------------------------------------------------------------

/// The camera's radiance F_t(0°)/π · π L_i (Eq. 7 about +y) on the slab by the test's laterally
/// reduced recursion (support/slab_recursion.h), per band.
glm::dvec3 slabRecursion(const sss::Material& m, double eta, double cellM, int layers, int steps, int skip,
                         double capCos) {
  const double ft = test::normalTransmittance(eta);
  glm::dvec3 out(0.0);
  for (int band = 0; band < 3; ++band) {
    const test::SlabRecursion r = test::slabRecursion(m.sigma_a[band], m.sigma_s[band], m.g[band],
                                                      ft * cellM * cellM, cellM * 1000.0, layers, steps, skip);
    const glm::vec4 cn = sh::sslpvRotateToNormal(glm::vec4(r.top), glm::vec3(0, 1, 0));
    out[band] = ft / kPi * kPi *
                sh::sslpvAreaLightRadiance(cn, static_cast<float>(cellM * cellM), static_cast<float>(capCos));
  }
  return out;
}

TEST(Sslpv, SlabAgainstTheDipoleTotalAndTheReducedRecursion) {
  // presets/slab.json: marble, 0.2 × 0.05 × 0.2 m, lit straight down by E = 1 W/m², camera straight
  // down. The 32³ grid has 6.25 mm cells whose planes hold the slab's faces: 8 layers.
  for (const std::string exitance : {"hemisphere", "face"}) {
    PresetSession s("slab", {"render.width=48", "render.height=48", "method=sslpv", "sslpv.grid=32",
                             "sslpv.inject_size=1024", "sslpv.exitance=" + exitance});
    const gpu::Image image = s.render();
    const sss::Material& m = s.scene().objects[0].material;
    const sss::SslpvSettings& p = s.settings().sslpv;
    const glm::dvec3 recursion =
        slabRecursion(m, m.eta, 0.00625, 8, p.steps, p.skip, exitance == "face" ? 2.0 / 3.0 : 0.0);
    const double ft = test::normalTransmittance(m.eta);
    for (int c = 0; c < 3; ++c) {
      const double measured = centreMean(image, c);
      const double dipole = ft * ft * test::jensenTotalRd(m.sigma_a[c], m.sigma_s[c], m.g[c], m.eta) / kPi;
      std::printf("[ sslpv ] slab %s band %d: L = %.5f, recursion %.5f (ratio %.4f), F_t² E R_d/π = %.5f (ratio %.3f)\n",
                  exitance.c_str(), c, measured, recursion[c], measured / recursion[c], dipole, measured / dipole);
      // The GPU's 3D grid against the test's 1D recursion: the same model, written twice. The
      // injection lands 22.3 texels of 1024² per cell on average, so cells get 22² or 23² texels
      // (±4.5%) in a pattern the centre square (10 × 10 cells) averages to < 1%.
      EXPECT_NEAR(measured / recursion[c], 1.0, 0.01) << "band " << c;
      // Against the dipole, SSLPV's own error: with the paper's skip of 2 steps the hemisphere
      // reaches 0.71, 0.36, 0.15 and the face cap a third of that. Marble's σ_tr ΔX is 0.73, 1.05
      // and 1.58 in these 6.25 mm cells, so most of R_d leaves within a cell or two of entry, in
      // the steps the paper does not accumulate; the shorter the diffusion length, the more is
      // lost (docs/sslpv.md). The recursion above accounts for these figures to 10⁻⁴; here only
      // their envelope: some light in every band, less than R_d, and ordered r > g > b.
      EXPECT_GT(measured / dipole, exitance == "face" ? 0.02 : 0.1) << "band " << c;
      EXPECT_LT(measured / dipole, 1.0) << "band " << c;
      if (c > 0) {
        EXPECT_LT(measured, centreMean(image, c - 1)) << "band " << c;
      }
    }
  }
}

// --- The medium grid -------------------------------------------------------------------------------

std::vector<glm::vec4> readGrid(const gpu::Texture& t) {
  std::vector<glm::vec4> cells(static_cast<std::size_t>(t.width()) * t.height() * t.depth());
  glGetTextureImage(t.id(), 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(cells.size() * sizeof(glm::vec4)), cells.data());
  return cells;
}

/// A preset of one translucent shape lit from above, SSLPV on a grid of `grid`³.
std::string shapePreset(const test::TempDir& dir, const std::string& object, int grid) {
  const auto path = dir.path() / "shape.json";
  std::ofstream(path) << R"({"camera": {"position": [0, 0.3, 0.4], "target": [0, 0.05, 0]},
    "lights": [{"type": "directional", "direction": [0.2, 1, 0.1], "irradiance": [1, 1, 1]}],
    "objects": [)" << object << R"(],
    "settings": {"method": "sslpv", "render.width": 16, "render.height": 16, "sslpv.grid": )" << grid
                      << R"(, "sslpv.steps": 4, "sslpv.skip": 0, "sslpv.inject_size": 32}})";
  return path.string();
}

TEST(Sslpv, VoxelisedSphereHasTheMeshVolume) {
  // The parity voxelisation of the sphere primitive (radius 5 cm, 32³ cells of 3.125 mm, 2³
  // sub-samples each): Σ over cells of the inside share × cell volume against the volume of the
  // very polyhedron drawn (divergence theorem over its triangles). A lattice of spacing h counts a
  // smooth body's volume to about (h/r)^{3/2} ≈ 0.5% here; 1% allows for it.
  test::TempDir dir;
  PresetSession s(shapePreset(dir, R"({"shape": "sphere", "scale": 0.05, "position": [0, 0.05, 0],
                                       "material": "Marble"})", 32));
  s.render();
  const auto& medium = s.renderer().module<sss::Sslpv>()->medium();
  const float cell = s.renderer().module<sss::Sslpv>()->grid().cell;
  double voxels = 0.0;
  int flagged = 0;
  for (const glm::vec4& c : readGrid(medium.scattering())) voxels += c.a;
  for (const glm::vec4& c : readGrid(medium.extinction())) flagged += c.a > 0.5f ? 1 : 0;
  voxels *= static_cast<double>(cell) * cell * cell;
  const geometry::TriangleMesh mesh = sss::SceneGeometry::shapeMesh(s.scene().objects[0]);
  double volume = 0.0;
  for (const auto& t : mesh.triangles) {
    const glm::dvec3 a(mesh.positions[t[0]]), b(mesh.positions[t[1]]), c(mesh.positions[t[2]]);
    volume += glm::dot(a, glm::cross(b, c)) / 6.0;
  }
  volume *= 0.05 * 0.05 * 0.05;  // unit sphere scaled to 5 cm
  std::printf("[ sslpv ] sphere: voxelised %.4e m³, mesh %.4e m³ (ratio %.4f), %d medium cells\n", voxels, volume,
              voxels / volume, flagged);
  EXPECT_NEAR(voxels / volume, 1.0, 0.01);
  // Medium cells are those with any inside sub-sample: at least the volume, at most it plus a shell.
  EXPECT_GE(flagged * static_cast<double>(cell) * cell * cell, volume);
}

TEST(Sslpv, MediumGridHoldsTheVolumesMaterialPerCell) {
  // A 0.1 m box of marble with a second, absorbing material in layers (flat, then rotated and
  // turbulent: veins), 16³ cells. Every cell's σ_t, σ'_s and g against the same computation here:
  // the box's inside (exact, from its transform), the shared volume function at the 2³ sub-samples,
  // the mean material, the shared mapping (sslpvGridExtinction, sslpvScatteringFraction).
  struct Case {
    std::string rotation, volume;
  };
  const std::string inner = R"("material": {"from": "Marble", "sigma_a": [0.2, 0.4, 0.8], "g": 0.5})";
  for (const Case& c : {Case{"[0, 0, 0]", R"("period": 0.0125, "fraction": 0.5, "axis": [0, 1, 0])"},
                        Case{"[0, 0, 30]", R"("period": 0.02, "fraction": 0.3, "axis": [1, 1, 0], "turbulence": 1.5, "seed": 9)"}}) {
    SCOPED_TRACE(c.rotation);
    test::TempDir dir;
    PresetSession s(shapePreset(dir, R"({"shape": "box", "size": [0.1, 0.1, 0.1], "position": [0, 0.05, 0],
        "rotation_deg": )" + c.rotation + R"(, "material": "Marble", "volume": {)" + inner + ", " + c.volume + "}}", 16));
    s.render();
    const sss::Sslpv& lpv = *s.renderer().module<sss::Sslpv>();
    const sss::SslpvGrid g = lpv.grid();
    const sss::SceneObject& o = s.scene().objects[0];
    const sss::MaterialVolume& v = *o.volume;
    const glm::mat4 model = sss::SceneGeometry::modelMatrix(o, geometry::Aabb{glm::vec3(-0.5f), glm::vec3(0.5f)});
    const glm::mat4 toUnitBox = glm::inverse(model);  // the box is [−½, ½]³ before its transform
    const glm::mat3 rotation = glm::mat3(model) / 0.1f;
    const auto extinction = readGrid(lpv.medium().extinction()), scattering = readGrid(lpv.medium().scattering()),
               anisotropy = readGrid(lpv.medium().anisotropy());
    int compared = 0, agree = 0;
    for (int z = 0; z < g.size; ++z)
      for (int y = 0; y < g.size; ++y)
        for (int x = 0; x < g.size; ++x) {
          glm::vec3 sa(0.0f), ss(0.0f), gg(0.0f);
          int inside = 0;
          for (int k = 0; k < 8; ++k) {
            const glm::vec3 sub = g.origin + (glm::vec3(2 * x + (k & 1), 2 * y + ((k >> 1) & 1), 2 * z + ((k >> 2) & 1)) +
                                              0.5f) * (0.5f * g.cell);
            const glm::vec3 unit(toUnitBox * glm::vec4(sub, 1.0f));
            if (glm::any(glm::greaterThan(glm::abs(unit), glm::vec3(0.5f)))) continue;
            const glm::vec3 p = glm::transpose(rotation) * (sub - o.transform.position);  // the object's frame
            const float w = sh::sslpvVolumeWeight(p, v.axis, v.period, v.fraction, v.turbulence, v.seed);
            sa += glm::mix(o.material.sigma_a, v.material.sigma_a, w);
            ss += glm::mix(o.material.sigma_s, v.material.sigma_s, w);
            gg += glm::mix(o.material.g, v.material.g, w);
            ++inside;
          }
          const std::size_t i = static_cast<std::size_t>((z * g.size + y) * g.size + x);
          if (inside == 0 && extinction[i].a == 0.0f) continue;
          ++compared;
          bool same = inside > 0 && extinction[i].a == 1.0f && scattering[i].a == inside / 8.0f;
          for (int b = 0; same && b < 3; ++b) {
            const float n = static_cast<float>(inside);
            const float st = sh::sslpvGridExtinction(sa[b] / n, ss[b] / n, gg[b] / n, g.cellMm());
            const float sp = sh::sslpvScatteringFraction(ss[b] / n, g.cellMm());
            same = std::abs(extinction[i][b] - st) <= 1e-4f * st && std::abs(scattering[i][b] - sp) <= 1e-4f * sp &&
                   std::abs(anisotropy[i][b] - gg[b] / n) <= 1e-5f;
          }
          agree += same ? 1 : 0;
        }
    std::printf("[ sslpv ] medium %s: %d of %d cells agree\n", c.rotation.c_str(), agree, compared);
    // A sub-sample within float rounding of a face may fall on either side: 1% of cells may differ.
    EXPECT_GE(agree, compared * 99 / 100);
    EXPECT_GT(compared, 16 * 16 * 16 / 4);
  }
}

// --- Plan, reuse and determinism -------------------------------------------------------------------

TEST(Sslpv, GridsAreReusedWhileNothingChangesAndRecomputedOtherwise) {
  // render.aa=1: the same scene draws the same picture (a still's average is StillAverage.*'s).
  PresetSession s("bunny", {"render.width=48", "render.height=36", "method=sslpv", "sslpv.grid=16", "sslpv.steps=8",
                            "sslpv.inject_size=64", "render.shadow_map_size=256", "render.aa=1"});
  sss::FrameTimings t1, t2, t3, t4;
  const gpu::Image first = s.render(0.0, &t1);
  for (const char* pass : {"sslpv.voxelize", "sslpv.light_gbuffer", "sslpv.inject", "sslpv.propagate"})
    EXPECT_TRUE(ran(t1, pass)) << pass;
  // Same scene: the plan keeps only the camera pass of SSLPV, and the picture is unchanged.
  const gpu::Image second = s.render(0.0, &t2);
  EXPECT_FALSE(ran(t2, "sslpv."));
  EXPECT_EQ(first.pixels, second.pixels);
  // A forced recomputation (the bench's restart) gives the same picture bit for bit: everything
  // is deterministic, so reusing the grids is exact.
  s.renderer().restartAccumulation();
  const gpu::Image third = s.render(0.0, &t3);
  EXPECT_TRUE(ran(t3, "sslpv.voxelize"));
  EXPECT_EQ(first.pixels, third.pixels);
  // A brighter light: injection and propagation again, not the voxelisation; twice the light.
  s.scene().lights[0].intensity *= 2.0f;
  const gpu::Image fourth = s.render(0.0, &t4);
  EXPECT_FALSE(ran(t4, "sslpv.voxelize"));
  EXPECT_TRUE(ran(t4, "sslpv.propagate"));
  EXPECT_NE(first.pixels, fourth.pixels);
  EXPECT_GT(s.renderer().gpuBytes(), sss::Sslpv::gridBytes(16, 1));
}

// --- Hard cases and limits -------------------------------------------------------------------------

TEST(Sslpv, FiniteOnHardCases) {
  // Tiny and huge scale (1 cm: cells of 0.6 mm, thin against marble's 2.2 mm⁻¹ mean free path;
  // 1 m: 63 mm cells, σ_tr ΔX ≈ 7, a step keeps 0.5% of the light), low albedo, grazing and
  // backlit light, a point light inside a hollow object, the melting candle (a field).
  struct Case {
    std::string preset, what;
    std::vector<std::string> sets;
    bool lit = true;  ///< some light reaches a translucent surface
  };
  const std::vector<Case> cases{
      {"bunny", "1 cm bunny", {"scale=0.01"}},
      {"bunny", "1 m bunny", {"scale=1"}},
      {"bunny", "low albedo (ketchup)", {"material=Ketchup"}},
      {"bunny", "1 cm skin", {"material=Skin1", "scale=0.01"}},
      {"bunny", "grazing light", {"light.direction=1,0.001,0"}},
      {"bunny", "backlit (the floor hides the light)", {"light.direction=0,-1,0"}, false},
      {"candle-holder", "point light inside", {}},
      {"candle", "candle field, light in the flame", {"field.res=24"}},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    std::vector<std::string> sets = {"render.width=32", "render.height=32", "method=sslpv", "sslpv.grid=16",
                                     "sslpv.steps=12", "sslpv.inject_size=64", "render.shadow_map_size=256"};
    sets.insert(sets.end(), c.sets.begin(), c.sets.end());
    PresetSession s(c.preset, sets);
    EXPECT_TRUE(allFinite(s.render()));
    const sss::Sslpv* lpv = s.renderer().module<sss::Sslpv>();
    ASSERT_NE(lpv, nullptr);
    double flux = 0.0;
    for (const gpu::Texture& band : lpv->propagation().accumulation())
      for (const glm::vec4& cell : lpv->propagation().download(band)) {
        for (int k = 0; k < 4; ++k) ASSERT_TRUE(std::isfinite(cell[k]));
        flux += cell[0];
      }
    if (c.lit) {
      EXPECT_GT(flux, 0.0);
    }
  }
}

TEST(Sslpv, BadParametersAndGridsBeyondTheBudgetAreRefusedInOneLine) {
  struct Case {
    std::string set, expected;
  };
  for (const Case& c : {Case{"sslpv.grid=4", "sslpv.grid"}, Case{"sslpv.steps=0", "sslpv.steps"},
                        Case{"sslpv.exitance=cap", "sslpv.exitance"}, Case{"sslpv.skip=40", "sslpv.skip"},
                        Case{"sslpv.grid=512", "MiB SSLPV budget"}}) {
    test::TempDir dir;
    const auto r = test::runTallow({"capture", "--preset", "slab", "--size", "16x16", "--set", "method=sslpv", "--set",
                                    c.set, "--out", (dir.path() / "out").string()});
    EXPECT_NE(r.exitCode, 0) << c.set;
    EXPECT_EQ(test::lineCount(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(c.expected), std::string::npos) << r.err;
    EXPECT_TRUE(dir.entries().empty()) << c.set;
  }
}

}  // namespace
}  // namespace tallow
