// The scattered radiosity maps on llvmpipe (issue 5, point 8): the analytic slab, the GPU estimator
// against its CPU instantiation with the same random numbers, progressive convergence, the
// stereographic correction, coverage, finiteness on hard cases, and the GPU limits.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "geometry/ply_writer.h"
#include "geometry/primitives.h"
#include "gpu/gl_objects.h"
#include "gpu/image_error.h"
#include "sss/maps/radiosity_estimator.h"
#include "sss/maps/radiosity_maps.h"
#include "support/dipole_totals.h"
#include "support/error_of.h"
#include "support/render_support.h"
#include "support/run_tallow.h"
#include "support/temp_dir.h"

namespace tallow {
namespace {

using test::centreMean;
using test::fresnelT;
using test::PresetSession;

/// Level 0 of every layer of a 2D array texture (RGBA32F), layer-major.
std::vector<glm::vec4> readLayers(const gpu::Texture& t) {
  std::vector<glm::vec4> texels(static_cast<std::size_t>(t.width()) * t.height() * t.depth());
  glGetTextureImage(t.id(), 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(texels.size() * sizeof(glm::vec4)),
                    texels.data());
  return texels;
}

// --- The analytic slab ---------------------------------------------------------------------------

TEST(RadiosityMaps, SlabMatchesTheStandardDipoleTotalFarFromTheEdges) {
  // presets/slab.json: marble lit at normal incidence by E = 1 W/m², seen straight down by an
  // orthographic camera. Far from the edges the scattered radiosity of the standard dipole is
  // B = F_t(0°) E R_d (the total diffuse reflectance, Jensen et al. 2001), and the camera pass
  // returns L = F_t(0°)/π · B (Eq. 5; no ambient). The centre square is ≥ 5 cm from the edges,
  // where e^{−σ_tr·50 mm} < 0.3% of the profile is missing in every band.
  PresetSession s("slab", {"render.width=48", "render.height=48", "sss.maps=6", "sss.samples=32",
                           "sss.map_size=128", "sss.light_map_size=512", "sss.frames=64"});
  gpu::Image image;
  for (int f = 0; f < 4; ++f) image = s.render();
  const sss::Material& m = s.scene().objects[0].material;
  const double ft = test::normalTransmittance(m.eta);
  for (int c = 0; c < 3; ++c) {
    const double rd = test::jensenTotalRd(m.sigma_a[c], m.sigma_s[c], m.g[c], m.eta);
    const double expected = ft * ft * rd / 3.14159265358979;
    const double measured = centreMean(image, c);
    std::printf("[ maps ] slab band %d: L = %.5f, F_t² E R_d/π = %.5f (ratio %.4f)\n", c, measured, expected,
                measured / expected);
    EXPECT_NEAR(measured / expected, 1.0, 0.02) << "band " << c;
  }
}

TEST(RadiosityMaps, NoCacheVariantMatchesTheSlabToo) {
  // method=no-cache (the paper's Fig. 11, as translucent shadow maps): the same gather per camera
  // pixel against the light G-buffer, no maps. One frame, N = 64 per pixel and band; the centre
  // square's mean has the same expectation F_t² E R_d/π.
  PresetSession s("slab", {"render.width=48", "render.height=48", "method=no-cache", "sss.samples=64",
                           "sss.light_map_size=512"});
  sss::FrameTimings t;
  const gpu::Image image = s.render(0.0, &t);
  EXPECT_FALSE(std::any_of(t.passes.begin(), t.passes.end(), [](const auto& p) { return p.name == "sss.maps"; }));
  EXPECT_TRUE(std::any_of(t.passes.begin(), t.passes.end(), [](const auto& p) { return p.name == "sss.light_gbuffer"; }));
  const sss::Material& m = s.scene().objects[0].material;
  const double ft = test::normalTransmittance(m.eta);
  for (int c = 0; c < 3; ++c) {
    const double expected = ft * ft * test::jensenTotalRd(m.sigma_a[c], m.sigma_s[c], m.g[c], m.eta) / 3.14159265358979;
    std::printf("[ maps ] no-cache slab band %d: ratio %.4f\n", c, centreMean(image, c) / expected);
    EXPECT_NEAR(centreMean(image, c) / expected, 1.0, 0.02) << "band " << c;
  }
}

TEST(RadiosityMaps, SlabLitObliquelyKeepsLambertsCosineOnce) {
  // Light 60° from the normal: Eq. 7 gives B = E cos θ F_t(θ) R_d (the standard dipole has no
  // ω dependence), seen straight down as L = F_t(0°)/π · B. The samples lie on the light's view
  // plane, whose area element is cos θ times the surface's; with sss.projected_area the estimator
  // divides by it, and the paper's Eq. 9 as printed (off) keeps a further cos θ = 1/2. The two
  // runs use the same seeds, so their ratio is exactly 1/cos θ per texel.
  // The samples meet the light G-buffer on each texel's tangent plane (sss.texel_plane): with the
  // texel's depth instead, x_i lies up to half a texel × tan θ off the tilted slab, r never reaches
  // 0 and the peak of S_d is lost — 7–11% here, falling with the texel's square (docs).
  const double cosTheta = 0.5;
  struct Variant {
    bool projected, texelPlane;
    double tolerance;
  };
  std::vector<gpu::Image> images;
  for (const Variant v : {Variant{true, true, 0.02}, Variant{false, true, -1.0}, Variant{true, false, -1.0}}) {
    PresetSession s("slab", {"render.width=48", "render.height=48", "sss.maps=6", "sss.samples=32",
                             "sss.map_size=128", "sss.light_map_size=512", "light.direction=0.8660254,0.5,0",
                             std::string("sss.projected_area=") + (v.projected ? "true" : "false"),
                             std::string("sss.texel_plane=") + (v.texelPlane ? "true" : "false")});
    gpu::Image image;
    for (int f = 0; f < 4; ++f) image = s.render();
    images.push_back(image);
    if (!v.projected) continue;
    const sss::Material& m = s.scene().objects[0].material;
    for (int c = 0; c < 3; ++c) {
      const double rd = test::jensenTotalRd(m.sigma_a[c], m.sigma_s[c], m.g[c], m.eta);
      const double expected =
          test::normalTransmittance(m.eta) / 3.14159265358979 * cosTheta * fresnelT(cosTheta, m.eta) * rd;
      const double ratio = centreMean(image, c) / expected;
      std::printf("[ maps ] 60° slab band %d, texel plane %s: L / (F_t(0) cos θ F_t(θ) E R_d/π) = %.4f\n", c,
                  v.texelPlane ? "on " : "off", ratio);
      if (v.tolerance > 0.0) EXPECT_NEAR(ratio, 1.0, v.tolerance) << "band " << c;
      else EXPECT_LT(ratio, 0.97) << "the texel's depth loses the near field at 60°, band " << c;
    }
  }
  for (int c = 0; c < 3; ++c) {
    const double ratio = centreMean(images[0], c) / centreMean(images[1], c);
    std::printf("[ maps ] 60° slab band %d: projected / paper = %.5f\n", c, ratio);
    EXPECT_NEAR(ratio, 1.0 / cosTheta, 1e-3) << "band " << c;
  }
}

// --- The GPU estimator is the shared code ----------------------------------------------------------

/// The texel of a cube-map array layer (faces +X, −X, +Y, −Y, +Z, −Z of each cube, layer-major, as
/// glGetTextureImage returns them) that a nearest look-up along `d` reads: the face of the major axis
/// and (s, t) of the OpenGL 4.5 specification's Table 8.19 (§8.13).
std::size_t cubeTexel(const glm::dvec3& d, int size, int cube) {
  const glm::dvec3 a = glm::abs(d);
  int face;
  double sc, tc, ma;
  if (a.x >= a.y && a.x >= a.z) face = d.x >= 0 ? 0 : 1, sc = d.x >= 0 ? -d.z : d.z, tc = -d.y, ma = a.x;
  else if (a.y >= a.z) face = d.y >= 0 ? 2 : 3, sc = d.x, tc = d.y >= 0 ? d.z : -d.z, ma = a.y;
  else face = d.z >= 0 ? 4 : 5, sc = d.z >= 0 ? d.x : -d.x, tc = -d.y, ma = a.z;
  const auto texel = [&](double c) { return std::clamp(static_cast<int>(std::floor(0.5 * (c / ma + 1.0) * size)), 0, size - 1); };
  return (static_cast<std::size_t>(cube * 6 + face) * size + texel(tc)) * size + texel(sc);
}

/// After one frame of sss.gather=compute (sss.maps=1): every `stride`-th map texel that sees the
/// object, x_o and n_o from the maps' G-buffer, computed again on the CPU by the float instantiation
/// of the same loops (shaders/maps/gather_loop.glsl) with the same random streams, every light of
/// the scene, and the read-back light G-buffers looked up the way the shader does (nearest texel;
/// the cube's face by Table 8.19). Returns the relative differences per band and texel.
std::vector<double> gpuAgainstCpu(PresetSession& s, int stride) {
  s.render();
  const sss::RadiosityMaps& maps = *s.renderer().module<sss::RadiosityMaps>();
  EXPECT_EQ(maps.frames(), 1);
  const std::vector<glm::vec4> b = readLayers(maps.maps());
  const std::vector<glm::vec4> xo = readLayers(maps.mapPositions()), no = readLayers(maps.mapNormals());
  const int size = maps.maps().width();
  std::vector<glm::vec4> dirPos, dirNrm, cubePos, cubeNrm;
  int dsize = 0, csize = 0;
  const sss::RenderSettings& settings = s.settings();
  sss::ScatteredRadiosityInput in;
  in.directional = false;
  int dirIndex = 0, pointIndex = 0;
  const auto tagHits = [](float w) { return static_cast<int>(w + 0.5f) == 1; };  // slot 0's object: the only one
  for (const sss::Light& l : s.scene().lights) {
    if (l.kind == sss::LightKind::Directional) {
      EXPECT_EQ(dirIndex++, 0) << "one directional light";
      dirPos = readLayers(maps.directionalPositions());
      dirNrm = readLayers(maps.directionalNormals());
      dsize = maps.directionalPositions().width();
      in.directional = true;
      in.toLight = glm::normalize(glm::dvec3(l.direction));
      in.irradiance = glm::dvec3(l.intensity);
      in.t1 = glm::dvec3(maps.directionalTangents()[0]);
      in.t2 = glm::dvec3(maps.directionalBitangents()[0]);
    } else {
      if (cubePos.empty()) {
        cubePos = readLayers(maps.pointPositions());
        cubeNrm = readLayers(maps.pointNormals());
        csize = maps.pointPositions().width();
      }
      const int cube = pointIndex++;
      in.pointLights.push_back({glm::dvec3(l.position) * 1000.0, glm::dvec3(l.intensity),
                                [&, cube](const glm::dvec3& d) -> std::optional<sss::LightGBufferHit> {
                                  const std::size_t i = cubeTexel(d, csize, cube);
                                  if (!tagHits(cubePos[i].w)) return std::nullopt;
                                  return sss::LightGBufferHit{glm::dvec3(glm::vec3(cubePos[i])) * 1000.0,
                                                              glm::dvec3(glm::vec3(cubeNrm[i]))};
                                }});
    }
  }
  const glm::mat4 toG = dirIndex > 0 ? maps.directionalMatrices()[0] : glm::mat4(1.0f);
  const sss::LightGBufferLookup directional = [&](const glm::dvec3& xjMm) -> std::optional<sss::LightGBufferHit> {
    const glm::vec4 t = toG * glm::vec4(glm::vec3(xjMm / 1000.0), 1.0f);
    if (t.x < 0.0f || t.y < 0.0f || t.x >= 1.0f || t.y >= 1.0f) return std::nullopt;
    const auto i = static_cast<std::size_t>(static_cast<int>(t.y * dsize)) * dsize + static_cast<int>(t.x * dsize);
    if (!tagHits(dirPos[i].w)) return std::nullopt;
    return sss::LightGBufferHit{glm::dvec3(glm::vec3(dirPos[i])) * 1000.0, glm::dvec3(glm::vec3(dirNrm[i]))};
  };
  const sss::Material& m = s.scene().objects[0].material;
  in.material = {glm::dvec3(m.sigma_a), glm::dvec3(m.sigma_s), glm::dvec3(m.g), m.eta};
  in.model = settings.sss.model;
  in.samples = settings.sss.samples;
  in.stereographic = settings.sss.stereographic;
  in.projectedArea = settings.sss.projectedArea;
  in.texelPlane = settings.sss.texelPlane;
  in.pointShare = settings.sss.pointShare;
  in.map = 0;
  in.frame = 0;
  std::vector<double> differences;
  for (int y = 0; y < size; y += stride)
    for (int x = 0; x < size; x += stride) {
      const std::size_t i = static_cast<std::size_t>(y) * size + x;
      if (static_cast<int>(xo[i].w + 0.5f) != 1) continue;  // no surface of slot 0 here
      in.xo = glm::dvec3(glm::vec3(xo[i])) * 1000.0;
      in.no = glm::dvec3(glm::normalize(glm::vec3(no[i])));
      in.texelX = static_cast<std::uint32_t>(x);
      in.texelY = static_cast<std::uint32_t>(y);
      const sss::ScatteredRadiosity cpu = sss::estimateScatteredRadiosity<float>(in, directional);
      for (int c = 0; c < 3; ++c) differences.push_back(std::abs(b[i][c] - cpu.B[c]) / std::max(cpu.B[c], 1e-12));
    }
  return differences;
}

void expectAgreement(const char* name, std::vector<double> d, std::size_t atLeast) {
  ASSERT_GE(d.size(), atLeast) << name;
  std::sort(d.begin(), d.end());
  const double median = d[d.size() / 2], p99 = d[d.size() * 99 / 100];  // p99: a texel border's odd look-up
  std::printf("[ maps ] %s: %zu texel bands, relative difference median %.2e, 99th percentile %.2e, worst %.2e\n",
              name, d.size(), median, p99, d.back());
  EXPECT_LT(median, 1e-5) << name;
  EXPECT_LT(d.back(), 2e-4) << name;
}

TEST(RadiosityMaps, GpuEstimatorEqualsTheCpuInstantiationAtChosenTexels) {
  // One frame of the compute gather; each compared texel's B computed again on the CPU by the same
  // loops (gather_loop.glsl in float) with the same random streams and the read-back G-buffers:
  // the slab lit at normal incidence, lit at 60° (the projected-area division and x_i on the
  // texel's tilted plane matter there), and the paper's candle holder: a point light inside the
  // hollow cylinder (the stereographic look-up, the area ratio, the second density) with a
  // directional fill, both lights in one gather. Only the compilers' float rounding and the odd
  // look-up that lands on the other side of a texel border differ.
  const std::vector<std::string> common{"render.width=32", "render.height=32", "sss.maps=1", "sss.samples=16",
                                        "sss.map_size=64", "sss.gather=compute"};
  {
    std::vector<std::string> sets = common;
    sets.push_back("sss.light_map_size=256");
    PresetSession slab("slab", sets);
    expectAgreement("slab, normal incidence", gpuAgainstCpu(slab, 3), 60);
  }
  {
    std::vector<std::string> sets = common;
    sets.insert(sets.end(), {"sss.light_map_size=256", "light.direction=0.8660254,0.5,0"});
    PresetSession slab("slab", sets);
    expectAgreement("slab lit at 60 degrees", gpuAgainstCpu(slab, 3), 60);
  }
  {
    std::vector<std::string> sets = common;
    sets.push_back("sss.light_map_size=128");
    PresetSession holder("candle-holder", sets);
    ASSERT_EQ(holder.scene().lights.size(), 2u);
    expectAgreement("candle holder, point light inside and a directional fill", gpuAgainstCpu(holder, 2), 60);
  }
}

TEST(RadiosityMaps, FragmentAndComputeGathersGiveTheSameMaps) {
  // sss.gather=fragment is the paper's layered fragment pass; compute runs the same gather
  // (shaders/maps/gather.glsl) over the maps' rasterised G-buffer. Same x_o, n_o and seeds: the
  // same texels are shaded, with the same values up to the compilers' float rounding.
  const std::vector<std::string> common{"render.width=32", "render.height=32", "sss.maps=3", "sss.samples=4",
                                        "sss.map_size=64", "sss.light_map_size=128"};
  std::vector<std::vector<glm::vec4>> maps;
  for (const char* gather : {"sss.gather=fragment", "sss.gather=compute"}) {
    std::vector<std::string> sets = common;
    sets.push_back(gather);
    PresetSession s("bunny", sets);
    s.render();
    s.render();
    maps.push_back(readLayers(s.renderer().module<sss::RadiosityMaps>()->maps()));
  }
  ASSERT_EQ(maps[0].size(), maps[1].size());
  std::size_t shaded = 0, worstAt = 0;
  double worst = 0.0;
  for (std::size_t i = 0; i < maps[0].size(); ++i) {
    ASSERT_EQ(maps[0][i].a, maps[1][i].a) << "texel " << i << " shaded by one gather only";
    if (maps[0][i].a == 0.0f) continue;
    ++shaded;
    for (int c = 0; c < 3; ++c) {
      const double d = std::abs(maps[0][i][c] - maps[1][i][c]) / std::max(1e-6, double(std::abs(maps[0][i][c])));
      if (d > worst) {
        worst = d;
        worstAt = i;
      }
    }
  }
  std::printf("[ maps ] fragment vs compute gather: %zu texels, worst relative difference %.2e\n", shaded, worst);
  EXPECT_GT(shaded, 500u);
  EXPECT_LT(worst, 1e-4) << "texel " << worstAt;
}

// --- Progressive accumulation ------------------------------------------------------------------------

TEST(RadiosityMaps, ProgressiveErrorFallsLikeOneOverTheSquareRootOfFrames) {
  // A map texel after F frames averages F independent frames of the estimator, so against the texel
  // after R = 32 frames (which contains them) the RMS difference is σ √(1/F − 1/R): the ratio for
  // F = 1 and F = 4 is √((1 − 1/32)/(1/4 − 1/32)) = 2.10, and for F = 4 and 16, √7 = 2.65. The
  // texels, not the picture: Algorithm 1's footprint also narrows with F (shaders/maps/algorithm1.glsl), so
  // the picture's error falls faster than the maps' at first.
  constexpr int kReference = 32;
  PresetSession s("bunny", {"render.width=64", "render.height=48", "sss.maps=6", "sss.samples=2",
                            "sss.map_size=128", "sss.light_map_size=256", "sss.frames=32"});
  // Level 0 of the maps holds Σ_F (B_N, 1): B is rgb / a where a texel is covered.
  const auto meanB = [&]() {
    std::vector<glm::vec4> texels = readLayers(s.renderer().module<sss::RadiosityMaps>()->maps());
    for (glm::vec4& t : texels) t = t.a > 0.0f ? t / t.a : glm::vec4(0.0f);
    return texels;
  };
  std::vector<std::vector<glm::vec4>> at;  // after 1, 4, 16 frames
  for (int f = 1; f <= kReference; ++f) {
    s.render();
    if (f == 1 || f == 4 || f == 16) at.push_back(meanB());
  }
  const std::vector<glm::vec4> converged = meanB();
  const auto rms = [&](const std::vector<glm::vec4>& a) {
    double sum = 0.0;
    int n = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
      if (converged[i].a <= 0.0f) continue;
      for (int c = 0; c < 3; ++c) sum += std::pow(a[i][c] - converged[i][c], 2.0);
      ++n;
    }
    return std::sqrt(sum / std::max(n, 1));
  };
  const double e1 = rms(at[0]), e4 = rms(at[1]), e16 = rms(at[2]);
  std::printf("[ maps ] RMS against %d frames: F=1 %.3e, F=4 %.3e, F=16 %.3e (ratios %.2f, %.2f)\n", kReference, e1,
              e4, e16, e1 / e4, e4 / e16);
  const double r = kReference;
  // ±20%: the ratio of two RMS estimates over thousands of texels, each with its own samples.
  EXPECT_NEAR(e1 / e4, std::sqrt((1.0 - 1.0 / r) / (0.25 - 1.0 / r)), 0.2 * 2.10);
  EXPECT_NEAR(e4 / e16, std::sqrt((0.25 - 1.0 / r) / (1.0 / 16 - 1.0 / r)), 0.2 * 2.65);
  // After sss.frames frames the maps are converged: the next frame runs only step 3.
  sss::FrameTimings t;
  s.render(0.0, &t);
  EXPECT_FALSE(std::any_of(t.passes.begin(), t.passes.end(), [](const auto& p) { return p.name == "sss.maps"; }));
}

// --- Point lights: stereographic correction --------------------------------------------------------

/// Per-pixel variance of one frame's estimate, from two independent frames: Var ≈ mean (a − b)²/2.
double frameVariance(const std::vector<std::string>& sets) {
  PresetSession s("candle-holder", sets);
  const gpu::Image one = s.render();
  const gpu::Image two = s.render();  // the mean of frames 0 and 1
  double sum = 0.0;
  int n = 0;
  for (std::size_t i = 0; i < one.pixels.size(); ++i) {
    // Frame 1 alone is 2·two − one.
    for (int c = 0; c < 3; ++c) {
      const double second = 2.0 * two.pixels[i][c] - one.pixels[i][c];
      sum += 0.5 * std::pow(second - one.pixels[i][c], 2.0);
    }
    ++n;
  }
  return sum / n;
}

// A point light at the centre of a hollow marble sphere (inner radius R = 5 mm, 3 cm thick): the
// inner wall is lit at normal incidence by E = I/R² everywhere, and for the standard dipole, which
// depends on the chord r = |x_o − x_i| alone, Archimedes' dA = 2πr dr on a sphere makes
// B = F_t(0) E ∫₀^{2R} R_d(r) 2πr dr exactly (the plane's total, cut at the diameter). Seen from the
// centre, L = F_t(0)/π · B in every pixel. R is close to 1/σ_tr, so the samples' tangent plane
// and the wall differ a lot: the stereographic look-up must count dA_i/dA_j (sss.projected_area);
// the paper's Eq. 9, which leaves it out, is too bright. method=no-cache gathers per pixel, as the
// maps' cameras outside cannot see the inner wall.
TEST(RadiosityMaps, PointLightInsideAHollowSphereMatchesArchimedesIntegral) {
  const double innerMm = 5.0, outerMm = 35.0, intensity = 2.5e-5;  // W/sr → E = 1 W/m² at the wall
  geometry::TriangleMesh shell;
  for (const double radius : {outerMm, innerMm}) {
    const geometry::TriangleMesh sphere = geometry::makeSphere(160, 320);
    const auto base = static_cast<std::uint32_t>(shell.positions.size());
    const bool inner = radius == innerMm;
    for (std::size_t i = 0; i < sphere.positions.size(); ++i) {
      shell.positions.push_back(sphere.positions[i] * static_cast<float>(radius / 1000.0));
      shell.normals.push_back(inner ? -sphere.normals[i] : sphere.normals[i]);  // the solid's outward normal
    }
    for (const auto& t : sphere.triangles)
      shell.triangles.push_back(inner ? std::array<std::uint32_t, 3>{base + t[0], base + t[2], base + t[1]}
                                      : std::array<std::uint32_t, 3>{base + t[0], base + t[1], base + t[2]});
  }
  test::TempDir dir;
  geometry::writePly(dir.path() / "shell.ply", shell);
  const double outerM = outerMm / 1000.0;
  nlohmann::json preset = {
      {"name", "shell"},
      {"description", "a point light at the centre of a hollow marble sphere, seen from the centre"},
      {"camera", {{"type", "perspective"}, {"position", {0, 0, 0}}, {"target", {0, 0, 1}}, {"up", {0, 1, 0}}, {"fov_deg", 20}}},
      {"lights", {{{"type", "point"}, {"position", {0, 0, 0}}, {"intensity", {intensity, intensity, intensity}}, {"shadows", true}}}},
      {"objects", {{{"name", "shell"}, {"mesh", (dir.path() / "shell.ply").string()}, {"material", "Marble"},
                    {"albedo", {0.8, 0.8, 0.8}}, {"position", {0, -outerM, 0}}, {"scale", 2.0 * outerM}}}},
      {"ambient", {0, 0, 0}},
      {"background", {0, 0, 0}},
      {"animation", {{"duration_s", 0}, {"loop", true}}},
      {"settings", {{"sss.model", "standard"}}}};
  std::ofstream(dir.path() / "shell.json") << preset.dump(2);
  double ratios[2][3] = {};
  for (const bool projected : {true, false}) {
    PresetSession s((dir.path() / "shell.json").string(),
                    {"render.width=12", "render.height=12", "method=no-cache", "sss.samples=512", "sss.light_map_size=512",
                     "sss.stereographic=true", std::string("sss.projected_area=") + (projected ? "true" : "false")});
    const gpu::Image image = s.render();
    const sss::Material& m = s.scene().objects[0].material;
    const double E = intensity / (innerMm * innerMm * 1e-6);
    for (int c = 0; c < 3; ++c) {
      // ∫₀^{2R} R_d(r) 2πr dr by composite Simpson on 4000 intervals.
      const int n = 4000;
      const double h = 2.0 * innerMm / n;
      double integral = 0.0;
      for (int i = 0; i <= n; ++i) {
        const double r = i * h, w = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
        integral += w * test::jensenRd(r, m.sigma_a[c], m.sigma_s[c], m.g[c], m.eta) * 2.0 * 3.14159265358979 * r;
      }
      integral *= h / 3.0;
      const double ft = test::normalTransmittance(m.eta);
      const double expected = ft * ft * E * integral / 3.14159265358979;
      double sum = 0.0;
      for (const glm::vec4& p : image.pixels) sum += p[c];
      ratios[projected ? 0 : 1][c] = sum / double(image.pixels.size()) / expected;
      std::printf("[ maps ] hollow sphere band %d, %s: L / (F_t² E ∫₀^2R R_d 2πr dr/π) = %.4f (the cut keeps %.1f%% of R_d,total)\n",
                  c, projected ? "with dA_i/dA_j" : "paper's Eq. 9", ratios[projected ? 0 : 1][c],
                  100.0 * integral / test::jensenTotalRd(m.sigma_a[c], m.sigma_s[c], m.g[c], m.eta));
    }
  }
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(ratios[0][c], 1.0, 0.02) << "band " << c;
    EXPECT_GT(ratios[1][c], 1.1) << "without the area ratio the wall is too bright, band " << c;
  }
}

TEST(RadiosityMaps, StereographicCorrectionLowersTheVarianceInsideTheCandleHolder) {
  // The paper's Fig. 4: a point light surrounded by the object. Planar sampling of the cube-map
  // G-buffer reaches only the hemisphere around x_o; the stereographic correction (Eqs. 13–14)
  // reaches the whole cube, and the estimate is less noisy — with the paper's Eq. 9 as printed and
  // with each sample weighted by dA_i/dA_j (sss.projected_area), which takes most of the planar
  // look-up's noise away too (its far samples land close to the light with a large 1/d²).
  for (const bool projected : {false, true}) {
    // The paper's comparison: Eq. 12 alone (no second density, which is drawn about the light
    // whatever the look-up and would blur what the correction itself changes).
    const std::vector<std::string> common{"render.width=64", "render.height=48", "sss.maps=6", "sss.samples=4",
                                          "sss.map_size=128", "sss.light_map_size=128", "render.shadows=false",
                                          "sss.point_share=0",
                                          std::string("sss.projected_area=") + (projected ? "true" : "false")};
    std::vector<std::string> stereo = common, planar = common;
    stereo.push_back("sss.stereographic=true");
    planar.push_back("sss.stereographic=false");
    const double vs = frameVariance(stereo), vp = frameVariance(planar);
    std::printf("[ maps ] candle holder, %s: per-frame pixel variance stereographic %.3e, planar %.3e\n",
                projected ? "with dA_i/dA_j" : "paper's Eq. 9", vs, vp);
    EXPECT_LT(vs, vp);
  }
}

// --- Coverage, finiteness, limits -----------------------------------------------------------------

TEST(RadiosityMaps, SixteenMapsSeeAlmostEveryVisiblePixelOfTheBunny) {
  // The paper's guideline (§5): K = 16 covers simple models. Share of the bunny's visible pixels
  // that no map sees (Algorithm 1's n = 0): at most 0.5%.
  PresetSession s("bunny", {"render.width=240", "render.height=135", "sss.maps=16", "sss.samples=1",
                            "sss.map_size=256", "sss.light_map_size=128"});
  s.render();
  const sss::MapCoverage c = s.renderer().mapCoverage();
  std::printf("[ maps ] bunny K=16: %zu of %zu translucent pixels unseen (%.3f%%)\n", c.unseenPixels,
              c.translucentPixels, 100.0 * c.unseenShare());
  EXPECT_GT(c.translucentPixels, 1000u);
  EXPECT_LE(c.unseenShare(), 0.005);
}

TEST(RadiosityMaps, ViewWeightKeepsCoverageAndAUniformB) {
  // sss.view_weight p weights each map by cos^p θ and normalises by the weights' sum: (a) every
  // pixel some map sees keeps a B (the same pixels are unseen for p = 0 and p = 4); (b) where B is
  // the same in every map — the slab's top under normal light, seen by K maps at various θ — the
  // weighted mean is that B for any p (same seeds: the maps are identical, only step 3 differs).
  std::vector<sss::MapCoverage> coverage;
  for (const char* p : {"sss.view_weight=0", "sss.view_weight=4"}) {
    PresetSession s("bunny", {"render.width=160", "render.height=90", "sss.maps=4", "sss.samples=1",
                              "sss.map_size=128", "sss.light_map_size=128", p});
    s.render();
    coverage.push_back(s.renderer().mapCoverage());
  }
  EXPECT_GT(coverage[0].unseenPixels, 0u) << "K = 4 should leave some pixels unseen, or (a) tests nothing";
  EXPECT_EQ(coverage[0].unseenPixels, coverage[1].unseenPixels);
  EXPECT_EQ(coverage[0].translucentPixels, coverage[1].translucentPixels);
  std::vector<gpu::Image> images;
  for (const char* p : {"sss.view_weight=0", "sss.view_weight=4"}) {
    PresetSession s("slab", {"render.width=32", "render.height=32", "sss.maps=6", "sss.samples=32", "sss.map_size=128",
                             "sss.light_map_size=256", p});
    for (int f = 0; f < 4; ++f) s.render();
    images.push_back(s.render());
  }
  for (int c = 0; c < 3; ++c) {
    const double ratio = centreMean(images[1], c) / centreMean(images[0], c);
    std::printf("[ maps ] slab band %d: B with cos^4 weights / equal weights = %.4f\n", c, ratio);
    EXPECT_NEAR(ratio, 1.0, 0.01) << "band " << c;
  }
}

/// The per-pixel gather's B on a backlit object's rim against the maps' after the first frame and
/// after 16 (the rim's pixels chosen on an independent estimate), as ratios of their sums.
struct RimRatios { std::size_t pixels; double first, accumulated; };
RimRatios backlitRimRatios(const std::string& preset, const std::vector<std::string>& scene) {
  auto with = [&](std::initializer_list<const char*> extra) {
    std::vector<std::string> sets = scene;
    sets.insert(sets.end(), extra.begin(), extra.end());
    return sets;
  };
  // Two independent per-pixel estimates (frames 0 and 1 draw different samples): one picks the rim's
  // pixels, the other measures them, so the choice does not favour pixels whose estimate fell low.
  PresetSession gather(preset, with({"method=no-cache", "sss.samples=256"}));
  const gpu::Image pick = gather.render();
  const gpu::Image truth = gather.render();
  const std::vector<std::uint8_t> wax = gather.renderer().translucentMask();
  auto grey = [](const glm::vec4& p) { return (double(p.r) + p.g + p.b) / 3.0; };
  std::vector<std::size_t> rim;
  for (std::size_t i = 0; i < pick.pixels.size(); ++i) {
    const double v = grey(pick.pixels[i]);
    if (wax[i] != 0 && v > 5e-4 && v < 4e-2) rim.push_back(i);
  }
  auto rimRatio = [&](const gpu::Image& image) {
    double sum = 0.0, ref = 0.0;
    for (std::size_t i : rim) {
      sum += grey(image.pixels[i]);
      ref += grey(truth.pixels[i]);
    }
    return sum / ref;
  };
  PresetSession maps(preset, with({"sss.maps=8", "sss.samples=8", "sss.map_size=256", "sss.frames=16"}));
  const double first = rimRatio(maps.render());
  gpu::Image image;
  for (int f = 1; f < 16; ++f) image = maps.render();
  return {rim.size(), first, rimRatio(image)};
}

TEST(RadiosityMaps, AFootprintReachingASurfaceNearerTheMapIsNotAveragedOver) {
  // The bunny lit from behind: near its silhouette the light crosses little marble, and B falls
  // tenfold within a pixel. The per-pixel gather (method=no-cache: the same estimator at x_o itself)
  // takes B at the pixel's centre, as the reference does. Maps that see the rim past the bunny's body
  // have footprints reaching onto the body, nearer the map, whose B a filtered look-up would average
  // in: Algorithm 1 tests the footprint's corners against the map's depth and takes such look-ups from
  // level-0 texels (shaders/maps/algorithm1.glsl). The rim's first frame read 1.375 when no tap was
  // tested, 1.281 with the four taps around x_o tested, 1.140 with the footprint's corners too. Those
  // texels are each tested within a slack of x_o's depth (ε_bias and the depth the surface's own
  // slope spans over two texels; nearer and farther surfaces left out, which the taps' filtered
  // look-ups had averaged in): 1.054 after 1 frame, 1.071 after 16 (1.113 with the filtered taps,
  // 1.124 testing only the nearer side). What the mip filter still averages on one surface, the F^(-1/4)
  // narrowing of the footprint takes away as frames accumulate (1.054 -> 1.071 after 16 frames here;
  // a backlit sphere's rim, where no look-up is an edge, reads 1.05 from the first frame: the cap at
  // half a diffusion length already bounds the footprint there).
  // Every frame at the pixel centres (render.aa=1): the per-pixel gather is the truth at each centre.
  const RimRatios r = backlitRimRatios("bunny", {"light.direction=0,0.5,-0.87", "ambient=0,0,0", "render.width=80",
                                                 "render.height=60", "sss.light_map_size=1024", "render.aa=1"});
  std::printf("[ maps ] backlit bunny's rim, %zu pixels: maps / per-pixel gather %.3f after 1 frame, %.3f after 16\n",
              r.pixels, r.first, r.accumulated);
  ASSERT_GE(r.pixels, 40u) << "the backlit rim should span some pixels";
  EXPECT_LT(r.first, 1.2) << "the first frame's footprints should not average the body's B into the rim";
  EXPECT_LT(r.accumulated, r.first + 0.02) << "accumulating should not raise the rim";
  EXPECT_LT(std::abs(r.accumulated - 1.0), 0.10) << "the edge look-ups should take only texels of x_o's surface";
}

void expectFiniteMaps(PresetSession& s, const std::string& what) {
  const gpu::Image image = s.render();
  for (const glm::vec4& p : image.pixels)
    for (int c = 0; c < 3; ++c) ASSERT_TRUE(std::isfinite(p[c]) && p[c] >= 0.0f) << what << ": pixel " << p[c];
  ASSERT_NE(s.renderer().module<sss::RadiosityMaps>(), nullptr) << what;
  for (const glm::vec4& t : readLayers(s.renderer().module<sss::RadiosityMaps>()->maps()))
    for (int c = 0; c < 4; ++c) ASSERT_TRUE(std::isfinite(t[c])) << what << ": map texel " << t[c];
}

TEST(RadiosityMaps, NoNanOrInfOnTheHardCases) {
  const std::vector<std::string> small{"render.width=48", "render.height=32", "sss.maps=4", "sss.samples=4",
                                       "sss.map_size=64", "sss.light_map_size=128"};
  const auto with = [&](std::vector<std::string> extra) {
    extra.insert(extra.begin(), small.begin(), small.end());
    return extra;
  };
  struct Case {
    std::string preset, what;
    std::vector<std::string> sets;
  };
  const std::vector<Case> cases{
      {"bunny", "1 cm bunny", with({"scale=0.01"})},
      {"bunny", "1 m bunny", with({"scale=1"})},
      {"bunny", "grazing light", with({"light.direction=1,0.001,0"})},
      {"bunny", "backlit", with({"light.direction=0,-1,0"})},
      {"bunny", "low albedo (ketchup)", with({"material=Ketchup"})},
      {"bunny", "photon beam diffusion", with({"sss.model=pbd"})},
      {"candle-holder", "light inside, planar sampling", with({"sss.stereographic=false"})},
      {"candle-holder", "light inside", with({})},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    PresetSession s(c.preset, c.sets);
    expectFiniteMaps(s, c.what);
  }
}

nlohmann::json captureStats(const test::TempDir& dir, const std::vector<std::string>& extra, std::string* err = nullptr) {
  std::vector<std::string> args{"capture", "--preset", "bunny", "--size", "48x32", "--set", "sss.maps=2",
                                "--set", "sss.samples=1", "--set", "sss.map_size=32", "--out", (dir.path() / "out").string()};
  args.insert(args.end(), extra.begin(), extra.end());
  const auto r = test::runTallow(args);
  EXPECT_EQ(r.exitCode, 0) << r.err;
  if (err) *err = r.err;
  std::ifstream in(dir.path() / "out" / "stats.json");
  return nlohmann::json::parse(in);
}

TEST(RadiosityMaps, PearlingIsReportedAndAutoModeRaisesTheLightMap) {
  // Ketchup's green band has 1/σ_tr = 0.58 mm (σ_a = 0.97, σ_s' = 0.07 mm⁻¹, Eq. 10); a 64² light
  // G-buffer over the 0.1 m bunny's bounding sphere (diameter ≈ 0.16 m) has 2.5 mm texels.
  test::TempDir a, b;
  std::string err;
  const auto low = captureStats(a, {"--set", "material=Ketchup", "--set", "sss.light_map_size=64"}, &err);
  ASSERT_TRUE(low["sss"]["pearling"].is_array());
  EXPECT_GE(low["sss"]["pearling"].size(), 2u);
  EXPECT_NE(err.find("pearling"), std::string::npos);
  const auto raised = captureStats(b, {"--set", "material=Ketchup", "--set", "sss.light_map_size=64", "--set",
                                       "sss.light_map_auto=true"});
  EXPECT_TRUE(raised["sss"]["pearling"].empty());
  const int size = raised["sss"]["light_map_size"].get<int>();
  const double texelMm = low["sss"]["pearling"][0]["light_texel_mm"].get<double>() * 64.0 / size;
  EXPECT_LE(texelMm, 0.394 * 1.0001);       // the shortest 1/σ_tr (blue band)
  EXPECT_GT(texelMm * 2.0, 0.394);          // and the smallest power of two that does it
}

TEST(RadiosityMaps, PointLightInsideWithPlanarSamplingIsAWarningNotAnError) {
  test::TempDir dir;
  const auto r = test::runTallow({"capture", "--preset", "candle-holder", "--size", "48x32", "--set", "sss.maps=2",
                                  "--set", "sss.samples=1", "--set", "sss.map_size=32", "--set",
                                  "sss.stereographic=false", "--out", (dir.path() / "out").string()});
  EXPECT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("warning: a point light lies inside"), std::string::npos) << r.err;
}

TEST(RadiosityMaps, MapDirectionsListedInThePresetReplaceHalton) {
  // "map_directions" in a preset: the maps look from exactly those directions (normalised), K is
  // their count whatever sss.maps says, and an empty list is refused with file:line:col.
  test::TempDir dir;
  std::ifstream in(std::string(TALLOW_TEST_SOURCE_DIR) + "/presets/slab.json");
  std::string json((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto at = json.rfind('}');
  const auto listed = dir.write("listed.json", json.substr(0, at) + ", \"map_directions\": [[0, 2, 0], [1, 1, 0]]}\n");
  PresetSession s(listed.string(), {"render.width=16", "render.height=16", "sss.maps=9", "sss.samples=1",
                                    "sss.map_size=32", "sss.light_map_size=64"});
  s.render();
  const auto& views = s.renderer().module<sss::RadiosityMaps>()->views();
  ASSERT_EQ(views.size(), 2u);
  EXPECT_NEAR(glm::distance(views[0].direction, glm::vec3(0, 1, 0)), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::distance(views[1].direction, glm::normalize(glm::vec3(1, 1, 0))), 0.0f, 1e-6f);
  EXPECT_EQ(s.renderer().module<sss::RadiosityMaps>()->maps().depth(), 2);
  const auto empty = dir.write("empty.json", json.substr(0, at) + ", \"map_directions\": []}\n");
  const auto r = test::runTallow({"capture", "--preset", empty.string(), "--out", (dir.path() / "o").string()});
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("map_directions: expected 1 to 256 directions"), std::string::npos) << r.err;
}

TEST(RadiosityMaps, SpecularTermIsTheFresnelWeightedEnvironment) {
  // The slab under a constant environment: every RGBE pixel (128, 128, 128, 129) is
  // (128 + 0.5)·2^(129 − 136) = 1.00390625 W/(m²·sr) (Ward 1991). Seen straight down, the
  // specular term is F_r(0°) L = ((η − 1)/(η + 1))² L on top of the subsurface term, which is the
  // same with render.specular off (same scene, same seeds).
  test::TempDir dir;
  std::string hdr = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 4 +X 8\n";
  for (int i = 0; i < 32; ++i) hdr += std::string{char(128), char(128), char(128), char(129)};
  dir.write("constant.hdr", hdr);
  std::ifstream in(std::string(TALLOW_TEST_SOURCE_DIR) + "/presets/slab.json");
  std::string json((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto preset = dir.write("slab-env.json", json.substr(0, json.rfind('}')) +
                                                      ", \"environment\": {\"file\": \"constant.hdr\", \"lights\": 1}}\n");
  const std::vector<std::string> small{"render.width=24", "render.height=24", "sss.maps=2", "sss.samples=2",
                                       "sss.map_size=64", "sss.light_map_size=64"};
  std::vector<std::string> on = small, off = small;
  off.push_back("render.specular=false");
  PresetSession a(preset.string(), on), b(preset.string(), off);
  const gpu::Image with = a.render(), without = b.render();
  const double eta = a.scene().objects[0].material.eta;
  const double fr = std::pow((eta - 1.0) / (eta + 1.0), 2.0), l = 1.00390625;
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(centreMean(with, c) - centreMean(without, c), fr * l, 1e-4 * fr * l) << c;
}

TEST(RadiosityMaps, MapsBeyondTheBudgetAreRefusedNamingTheLimit) {
  test::TempDir dir;
  const auto r = test::runTallow({"capture", "--preset", "bunny", "--size", "32x32", "--set", "sss.maps=256", "--set",
                                  "sss.map_size=8192", "--out", (dir.path() / "out").string()});
  EXPECT_EQ(r.exitCode, 1);
  // The GPU memory budget (sss/memory_budget.h) names the maps as the largest item, with their keys.
  EXPECT_EQ(r.err.rfind("tallow: GPU memory: the frame needs ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find("radiosity maps"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("(sss.maps=256 × sss.map_size=8192²)"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_TRUE(dir.entries().empty());
}

// --- sss.history: no restart while the geometry deforms (issue 17, point 3) ----------------------

struct MapCounts {
  float maxFrames = 0.0f;
  int covered = 0, kept = 0, fresh = 0, fractional = 0;
};

/// Level 0 alpha of every map texel: the frames its sum holds (an integer: kept whole, trimmed to
/// sss.history − 1 plus this frame, or started again).
MapCounts mapCounts(PresetSession& s, float keptAtLeast) {
  MapCounts c;
  for (const glm::vec4& t : readLayers(s.renderer().module<sss::RadiosityMaps>()->maps())) {
    if (t.a <= 0.0f) continue;
    ++c.covered;
    c.maxFrames = std::max(c.maxFrames, t.a);
    if (std::abs(t.a - std::round(t.a)) > 1e-3f) ++c.fractional;
    if (t.a >= keptAtLeast - 1e-3f) ++c.kept;
    if (std::abs(t.a - 1.0f) < 1e-3f) ++c.fresh;
  }
  return c;
}

std::vector<std::string> movingBlobSets(int history) {
  return {"render.width=48", "render.height=32", "field.res=32", "sss.maps=4", "sss.samples=1", "sss.map_size=64",
          "sss.light_map_size=64", "vpl.count=4", "sss.history=" + std::to_string(history)};
}

TEST(MapHistory, WhileTheBlobMovesTexelsKeepAtMostHistoryFramesAndResetWhereTheSurfaceChanged) {
  PresetSession s("blob", movingBlobSets(4));
  for (int f = 0; f < 6; ++f) s.render(1.0 + 0.05 * f);
  const MapCounts moving = mapCounts(s, 4.0f);
  std::printf("[ history ] blob, history 4, 6 frames 0.05 s apart: %d covered texels, %d hold 4 frames, %d restarted, "
              "max %.3f\n", moving.covered, moving.kept, moving.fresh, moving.maxFrames);
  ASSERT_GT(moving.covered, 1000);
  EXPECT_NEAR(moving.maxFrames, 4.0f, 1e-3f) << "bounded by sss.history";
  EXPECT_EQ(moving.fractional, 0) << "a kept sum is trimmed to whole frames";
  // Measured with the default sss.history_move of 0.5 (1.75 mm for skim milk's blue band): 410 of
  // 1138 texels kept at 0.05 s a frame, 879 of 1058 at 1/60 s; a texel that was reset in the
  // last three frames holds fewer than 4.
  EXPECT_GT(moving.kept, moving.covered / 5) << "much of the surface moved less than half a diffusion length";
  EXPECT_GT(moving.fresh, 0) << "the silhouettes moved: some texels started again";
  EXPECT_EQ(s.renderer().module<sss::RadiosityMaps>()->frames(), 4);

  // Still: nothing to trim; the count starts over and the 4 kept frames fade out over sss.frames
  // (issue 38): after n still frames a texel that held 4 holds n + 4 (1 − n / sss.frames).
  const int frames = s.settings().sss.frames;
  for (int n = 1; n <= 3; ++n) {
    s.render(1.25);
    EXPECT_EQ(s.renderer().module<sss::RadiosityMaps>()->frames(), n);
    const float expected = n + 4.0f * (1.0f - static_cast<float>(n) / frames);
    EXPECT_NEAR(mapCounts(s, expected).maxFrames, expected, 1e-3f) << "still frame " << n;
  }
  for (int n = 4; n <= frames; ++n) s.render(1.25);
  EXPECT_EQ(s.renderer().module<sss::RadiosityMaps>()->frames(), frames);
  EXPECT_NEAR(mapCounts(s, static_cast<float>(frames)).maxFrames, static_cast<float>(frames), 1e-3f)
      << "the kept frames are gone: sss.frames fresh frames";

  // sss.history = 0: the paper's restart at every change, one frame per texel.
  PresetSession restart("blob", movingBlobSets(0));
  for (int f = 0; f < 6; ++f) restart.render(1.0 + 0.05 * f);
  const MapCounts r = mapCounts(restart, 1.0f);
  EXPECT_NEAR(r.maxFrames, 1.0f, 1e-6f);
  EXPECT_EQ(restart.renderer().module<sss::RadiosityMaps>()->frames(), 1);
}

/// gpu::imageError's relative RMSE of a against b over the pixels of `mask` (non-zero).
double relativeRmse(const gpu::Image& a, const gpu::Image& b, const std::vector<std::uint8_t>& mask) {
  gpu::Image objects(b.width, b.height);
  for (std::size_t i = 0; i < mask.size(); ++i) objects.pixels[i].a = mask[i] ? 1.0f : 0.0f;
  return gpu::imageError(a, b, objects).relRmse;
}

/// The candle played at 4 fps for `frames` frames by two sessions alike but for sss.history (8 and 0):
/// K = 4, no VPLs, no flame drawn, render.aa=1, plus `sets`; `pause`: the last frame's time.
struct CandleAtFourFps {
  static std::vector<std::string> withHistory(std::vector<std::string> sets, int history) {
    sets.insert(sets.end(), {"render.aa=1", "sss.maps=4", "sss.light_map_size=128", "vpl.count=0",
                             "render.flame=false", "sss.history=" + std::to_string(history)});
    return sets;
  }
  CandleAtFourFps(const std::vector<std::string>& sets, int frames)
      : history("candle", withHistory(sets, 8)), restart("candle", withHistory(sets, 0)) {
    const double start = history.scene().startS;
    for (int f = 0; f < frames; ++f) {
      history.render(start + 0.25 * f);
      restart.render(start + 0.25 * f);
    }
    pause = start + 0.25 * (frames - 1);
  }
  PresetSession history, restart;
  double pause = 0.0;
};

TEST(MapHistory, AStillAfterMotionConvergesToTheHistoryFreeStill) {
  // Issue 38: the candle played at 4 fps, paused at frame 6, and left to accumulate to sss.frames:
  // with sss.history = 8 the kept, lagged frames must leave the estimate, so that the still ends
  // where the history-free still (sss.history = 0, the paper's restart) ends. The noise floor is the
  // history-free still's own change from N = 8 to N = 9 frames.
  CandleAtFourFps played({"render.width=96", "render.height=72", "field.res=64", "sss.map_size=128",
                          "sss.frames=16"},
                         6);
  PresetSession &history = played.history, &restart = played.restart;
  const int frames = history.settings().sss.frames;
  const double pause = played.pause;
  gpu::Image still, eight, nine, freeStill;
  while (history.renderer().module<sss::RadiosityMaps>()->frames() < frames) still = history.render(pause);
  while (restart.renderer().module<sss::RadiosityMaps>()->frames() < frames) {
    freeStill = restart.render(pause);
    if (restart.renderer().module<sss::RadiosityMaps>()->frames() == 8) eight = freeStill;
    if (restart.renderer().module<sss::RadiosityMaps>()->frames() == 9) nine = freeStill;
  }
  const std::vector<std::uint8_t> wax = restart.renderer().translucentMask();
  const double floor = relativeRmse(eight, nine, wax), error = relativeRmse(still, freeStill, wax);
  std::printf("[ history ] candle at 4 fps, paused at frame 6, %d frames: still after motion vs the history-free still "
              "%.4f, noise floor (history-free N = 8 vs 9) %.4f (%.2fx)\n",
              frames, error, floor, error / floor);
  ASSERT_GT(floor, 0.0);
  EXPECT_LE(error, 1.25 * floor);
  // Stronger, and the reason: the candle's maps are made for the field's fixed bounds, so both
  // sessions' views are the same; the still's count and seeds start over as the restart's do, so
  // once the kept frames are gone the maps hold the same sums up to rounding. Without the fade:
  // 0.0202 against a floor of 0.0186.
  EXPECT_LT(error, 1e-3);
}

TEST(MapHistory, AStillAfterMotionFadesTheHistoryAlsoWhenItHoldsSssFramesAlready) {
  // sss.frames ≤ sss.history: after the motion the maps may hold sss.frames frames or more of kept
  // history, so no frame would be due by the count; the still must start all the same and fade the
  // kept frames out (found by FrameInvalidation at the defaults: sss.frames = 1, history 8).
  CandleAtFourFps played({"render.width=64", "render.height=48", "field.res=48", "sss.map_size=64", "sss.frames=4"}, 8);
  PresetSession &history = played.history, &restart = played.restart;
  ASSERT_GE(history.renderer().module<sss::RadiosityMaps>()->frames(), 4) << "the motion left sss.frames frames of history";
  const double pause = played.pause;
  gpu::Image still, freeStill;
  for (int f = 0; f < 6; ++f) {
    still = history.render(pause);
    freeStill = restart.render(pause);
  }
  EXPECT_EQ(history.renderer().module<sss::RadiosityMaps>()->frames(), 4);
  const double error = relativeRmse(still, freeStill, restart.renderer().translucentMask());
  std::printf("[ history ] sss.frames = 4, history 8: the still after motion vs the history-free still %.5f\n", error);
  EXPECT_LT(error, 1e-3);
}

/// The largest frame count (alpha) of each map layer's texels.
std::vector<float> layerFrames(const gpu::Texture& maps) {
  const std::vector<glm::vec4> texels = readLayers(maps);
  const std::size_t perLayer = static_cast<std::size_t>(maps.width()) * maps.height();
  std::vector<float> most(static_cast<std::size_t>(maps.depth()), 0.0f);
  for (std::size_t i = 0; i < texels.size(); ++i) most[i / perLayer] = std::max(most[i / perLayer], texels[i].a);
  return most;
}

TEST(MapHistory, AChangeOfKKeepsTheMapsWhoseDirectionsStay) {
  // Issue 38: the Halton directions are nested, so when K alone changes (auto K's choice, or the
  // user's) the first min(K, K') maps keep their sums and only the new ones start. The count starts
  // over so that the new maps get sss.frames frames of their own.
  PresetSession s("bunny", {"render.width=64", "render.height=48", "sss.maps=8", "sss.samples=1",
                            "sss.map_size=64", "sss.light_map_size=128", "vpl.count=0", "sss.frames=32"});
  for (int f = 0; f < 4; ++f) s.render(0.0);
  const std::vector<sss::MapView> before = s.renderer().module<sss::RadiosityMaps>()->views();
  s.settings().sss.maps = 12;
  s.render(0.0);
  const sss::RadiosityMaps& maps = *s.renderer().module<sss::RadiosityMaps>();
  ASSERT_EQ(maps.views().size(), 12u);
  for (std::size_t i = 0; i < before.size(); ++i)
    EXPECT_EQ(maps.views()[i].direction, before[i].direction) << "map " << i;
  EXPECT_EQ(maps.frames(), 1);
  std::vector<float> most = layerFrames(maps.maps());
  for (int layer = 0; layer < 12; ++layer)
    EXPECT_FLOAT_EQ(most[static_cast<std::size_t>(layer)], layer < 8 ? 5.0f : 1.0f) << "map " << layer;
  // Fewer maps: the first six keep theirs.
  s.settings().sss.maps = 6;
  s.render(0.0);
  most = layerFrames(s.renderer().module<sss::RadiosityMaps>()->maps());
  ASSERT_EQ(most.size(), 6u);
  for (float m : most) EXPECT_FLOAT_EQ(m, 6.0f);
  // Anything else restarts them all.
  s.settings().sss.samples = 2;
  s.render(0.0);
  for (float m : layerFrames(s.renderer().module<sss::RadiosityMaps>()->maps())) EXPECT_FLOAT_EQ(m, 1.0f);
  // So does a change of K while a still after motion fades its kept frames out: kept maps would
  // hold what is left of them for good.
  s.render(0.0);
  s.scene().lights[0].intensity *= 0.9f;  // the light dims: a reuse (as a flame's flicker)
  s.render(0.0);
  s.render(0.0);  // the still starts, its fade with it
  s.settings().sss.maps = 8;
  s.render(0.0);
  for (float m : layerFrames(s.renderer().module<sss::RadiosityMaps>()->maps())) EXPECT_FLOAT_EQ(m, 1.0f);
}

TEST(MapHistory, ASettingThatChangesTheEstimateRestartsTheMaps) {
  PresetSession s("blob", movingBlobSets(4));
  for (int f = 0; f < 3; ++f) s.render(1.0);
  EXPECT_EQ(s.renderer().module<sss::RadiosityMaps>()->frames(), 3);
  s.settings().sss.samples = 2;  // another estimator: its history does not hold
  s.render(1.05);
  EXPECT_EQ(s.renderer().module<sss::RadiosityMaps>()->frames(), 1);
  EXPECT_NEAR(mapCounts(s, 1.0f).maxFrames, 1.0f, 1e-6f);
}

/// Σ over the map texels holding frames of their mean B (rgb / alpha), per band.
glm::dvec3 mapMeanTotal(PresetSession& s) {
  glm::dvec3 total(0.0);
  for (const glm::vec4& t : readLayers(s.renderer().module<sss::RadiosityMaps>()->maps()))
    if (t.a > 0.0f) total += glm::dvec3(t) / static_cast<double>(t.a);
  return total;
}

TEST(MapHistory, TheKeptHistoryFollowsALightThatTurnsWhileTheSurfaceHolds) {
  // The slab lit from straight above for 4 frames, then from 60° off the vertical: its top's
  // irradiance halves (cos 60°) while no surface point moves, so every texel keeps its history.
  // The maps' total is compared with a restart's under the new light (4 frames, the paper's own
  // estimate): without sss.history_rescale the kept 4 frames of the old light hold it far above;
  // with it, the history is rescaled to the new light's coarse means.
  const std::vector<std::string> sets = {"render.width=48", "render.height=32", "sss.maps=4", "sss.samples=8",
                                         "sss.map_size=64", "sss.light_map_size=64", "vpl.count=0",
                                         "sss.history=8"};
  const glm::vec3 turned(std::sin(glm::radians(60.0f)), std::cos(glm::radians(60.0f)), 0.0f);
  PresetSession restart("slab", sets);
  restart.scene().lights[0].direction = turned;
  for (int f = 0; f < 4; ++f) restart.render(0.0);
  const glm::dvec3 expected = mapMeanTotal(restart);
  for (const char* rescale : {"0", "1"}) {
    std::vector<std::string> with = sets;
    with.push_back(std::string("sss.history_rescale=") + rescale);
    PresetSession s("slab", with);
    for (int f = 0; f < 4; ++f) s.render(0.0);
    const glm::dvec3 before = mapMeanTotal(s);
    s.scene().lights[0].direction = turned;
    s.render(0.0);
    EXPECT_EQ(s.renderer().module<sss::RadiosityMaps>()->frames(), 5) << "a light that turns is not a restart with sss.history";
    const glm::dvec3 after = mapMeanTotal(s);
    for (int c = 0; c < 3; ++c) {
      const double ratio = after[c] / expected[c];
      std::printf("[ history ] slab, light turned 60°, sss.history_rescale=%s, band %d: before %.4g, after %.4g, "
                  "restart %.4g (after / restart %.3f)\n",
                  rescale, c, before[c], after[c], expected[c], ratio);
      if (std::string(rescale) == "0")
        EXPECT_GT(ratio, 1.25) << "the kept frames of the old light lag: (4 · 2 + 1) / 5 of the restart's, less the sides'";
      else
        EXPECT_NEAR(ratio, 1.0, 0.03) << "rescaled to the new light";
    }
  }
}

TEST(MapHistory, TheKeptHistoryFollowsALightWhoseBrightnessChanges) {
  // A candle's flame flickers: its light's flux changes every frame. The slab lit from above for 4
  // frames, then at 0.9 of the irradiance: no surface point moves, so every texel keeps its history
  // (a restart on the intensity kept the melting candle's maps at 1 frame, the history never used),
  // and the history is rescaled to the new light: the maps' total within 3% of a restart's at 0.9.
  const std::vector<std::string> sets = {"render.width=48", "render.height=32", "sss.maps=4", "sss.samples=8",
                                         "sss.map_size=64", "sss.light_map_size=64", "vpl.count=0",
                                         "sss.history=8"};
  PresetSession restart("slab", sets);
  restart.scene().lights[0].intensity *= 0.9f;
  for (int f = 0; f < 4; ++f) restart.render(0.0);
  const glm::dvec3 expected = mapMeanTotal(restart);
  PresetSession s("slab", sets);
  for (int f = 0; f < 4; ++f) s.render(0.0);
  s.scene().lights[0].intensity *= 0.9f;
  s.render(0.0);
  EXPECT_EQ(s.renderer().module<sss::RadiosityMaps>()->frames(), 5) << "a light that dims is not a restart with sss.history";
  const glm::dvec3 after = mapMeanTotal(s);
  for (int c = 0; c < 3; ++c) {
    std::printf("[ history ] slab, light at 0.9, band %d: after / restart %.4f\n", c, after[c] / expected[c]);
    EXPECT_NEAR(after[c] / expected[c], 1.0, 0.03) << "rescaled to the dimmer light";
  }
}

}  // namespace
}  // namespace tallow
