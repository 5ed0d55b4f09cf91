// The CPU reference integrator (sss/reference/reference_integrator.h, `tallow reference`): the analytic slab
// within its own error bound, an honest error estimate (two seeds differ by about √2 × the
// estimated standard error), one-line refusals of bad options, and the emergent light onto the
// receivers (--emergent) against a numerical integral, with visibility, and off by default. No GL.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <vector>

#include "app/commands/reference_command.h"
#include "app/config/input_error.h"
#include "app/config/setup.h"
#include "gpu/hdr_io.h"
#include "gpu/image_io.h"
#include "sss/bssrdf/bssrdf.h"
#include "sss/reference/reference_integrator.h"
#include "support/dipole_totals.h"
#include "support/error_of.h"
#include "support/run_tallow.h"
#include "support/temp_dir.h"

namespace tallow {
namespace {

constexpr double kPi = 3.14159265358979323846;

app::LoadedScene slab(const std::string& size) {
  app::SceneOptions options;
  options.preset = "slab";
  options.size = size;
  return app::loadScene(options);
}

sss::ReferenceResult integrate(const app::LoadedScene& scene, int passes, int points, std::uint64_t seed) {
  sss::ReferenceSettings s;
  s.maxPasses = passes;
  s.pointsPerPass = points;
  s.seed = seed;
  return sss::renderReference(scene.config.scene, scene.config.render, s);
}

// (a) Far from its edges the slab under a normal directional light E is the half-space of the
// dipole: L = F_t(0)/π · B with B = F_t(0) E R_d,total (Jensen's closed form).
TEST(ReferenceIntegrator, AnalyticSlabWithinItsOwnErrorBound) {
  // 3×3 pixels 8 cm apart, all on the slab's top; the centre pixel is the slab's centre.
  const app::LoadedScene scene = slab("3x3");
  ASSERT_EQ(scene.config.render.sss.model, sss::BssrdfModel::Standard);
  const sss::ReferenceResult r = integrate(scene, 16, 1 << 20, 11);
  EXPECT_EQ(r.passes, 16);
  EXPECT_EQ(r.translucentPixels, 9);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 3; ++x) EXPECT_EQ(r.standardError.at(x, y).a, 1.0f) << "the object mask marks every pixel";
  const sss::Material& m = scene.config.scene.objects.at(0).material;
  const double E = scene.config.scene.lights.at(0).intensity.x;
  const double ft = test::normalTransmittance(m.eta);
  const glm::vec4 centre = r.radiance.at(1, 1), se = r.standardError.at(1, 1);
  for (int c = 0; c < 3; ++c) {
    const double expected = ft * ft * E * test::jensenTotalRd(m.sigma_a[c], m.sigma_s[c], m.g[c], m.eta) / kPi;
    const double bound = 3.0 * se[c] + 0.002 * expected;
    std::printf("band %d: reference %.6g +- %.3g (%.2f%%), analytic %.6g, deviation %.2f sigma\n", c, centre[c], se[c],
                100.0 * se[c] / expected, expected, (centre[c] - expected) / se[c]);
    EXPECT_GT(se[c], 0.0f);
    EXPECT_LT(se[c], 0.04 * expected) << "the bound must be tight enough to mean something";
    EXPECT_NEAR(centre[c], expected, bound) << "band " << c;
  }
}

// The slab lit at 60° from the normal: Eq. 7 over the surface gives B = F_t(60°) E cos 60° R_d,total
// for the standard dipole (which ignores the direction of incidence), so
// L = F_t(0) F_t(60°) E cos 60° R_d,total / π. (The radiosity maps' plane of Eq. 8 gives cos² instead.)
TEST(ReferenceIntegrator, ObliquelyLitSlabFollowsLambertsCosine) {
  app::LoadedScene scene = slab("3x3");
  const double theta = 60.0 * kPi / 180.0;
  scene.config.scene.lights.at(0).direction = glm::vec3(std::sin(theta), std::cos(theta), 0.0);
  const sss::ReferenceResult r = integrate(scene, 20, 1 << 20, 5);
  const sss::Material& m = scene.config.scene.objects.at(0).material;
  const glm::vec4 centre = r.radiance.at(1, 1), se = r.standardError.at(1, 1);
  for (int c = 0; c < 3; ++c) {
    const double expected = test::normalTransmittance(m.eta) * sss::fresnelTransmittance(std::cos(theta), m.eta) *
                            std::cos(theta) * test::jensenTotalRd(m.sigma_a[c], m.sigma_s[c], m.g[c], m.eta) / kPi;
    std::printf("band %d at 60 deg: reference %.6g +- %.3g, analytic %.6g\n", c, centre[c], se[c], expected);
    EXPECT_LT(se[c], 0.06 * expected);
    EXPECT_NEAR(centre[c], expected, 3.0 * se[c] + 0.002 * expected) << "band " << c;
  }
}

// A point light of intensity I at height h above the slab's centre: Eq. 7 with L = I/d² becomes, below
// the light, the radial integral B = π ∫ S_d(ρ) F_t(cos θ) I cos θ/d² 2πρ dρ, cos θ = h/d,
// d² = ρ² + h², integrated here by the midpoint rule on a fine log-spaced grid (S_d from the shared
// code: this checks the integrator's point-light geometry, inverse square and shadow rays).
TEST(ReferenceIntegrator, PointLightAboveTheSlab) {
  app::LoadedScene scene = slab("3x3");
  const double h = 0.02, I = 0.5;  // metres, W/sr
  sss::Light& light = scene.config.scene.lights.at(0);
  light.kind = sss::LightKind::Point;
  light.position = glm::vec3(0.0f, 0.05f + static_cast<float>(h), 0.0f);
  light.intensity = glm::vec3(static_cast<float>(I));
  const sss::ReferenceResult r = integrate(scene, 16, 1 << 20, 3);
  const sss::Material& m = scene.config.scene.objects.at(0).material;
  const glm::vec4 centre = r.radiance.at(1, 1), se = r.standardError.at(1, 1);
  for (int c = 0; c < 3; ++c) {
    double B = 0.0;  // W/m²; lengths of S_d in mm
    const int steps = 20000;
    const double lo = std::log(1e-4), hi = std::log(300.0);  // ρ in mm
    for (int k = 0; k < steps; ++k) {
      const double a = std::exp(lo + (hi - lo) * k / steps), b = std::exp(lo + (hi - lo) * (k + 1) / steps);
      const double rho = 0.5 * (a + b);
      const double dMm = std::sqrt(rho * rho + h * h * 1e6), cosTheta = h * 1e3 / dMm;
      sss::BssrdfConfig cfg{glm::dvec3(rho, 0, 0), glm::dvec3(0, 0, 1), glm::dvec3(0, 0, 1), glm::dvec3(0.0),
                            glm::dvec3(0, 0, 1), m.sigma_a[c], m.sigma_s[c], m.g[c], m.eta};
      const double sd = sss::evaluateBssrdf<double>(sss::BssrdfModel::Standard, cfg).sdClamped;
      const double E = I * cosTheta / (dMm * dMm * 1e-6) * sss::fresnelTransmittance(cosTheta, m.eta);
      B += kPi * sd * E * 2.0 * kPi * rho * (b - a);
    }
    const double expected = test::normalTransmittance(m.eta) / kPi * B;
    std::printf("band %d point light: reference %.6g +- %.3g, numerical %.6g\n", c, centre[c], se[c], expected);
    EXPECT_LT(se[c], 0.06 * expected);
    EXPECT_NEAR(centre[c], expected, 3.0 * se[c] + 0.002 * expected) << "band " << c;
  }
}

// The specular term: with no light but a constant environment, a translucent surface seen head-on
// shows F_r(0) L_env (as surface.frag: the environment in the mirror direction).
TEST(ReferenceIntegrator, SpecularReflectionOfAConstantEnvironment) {
  test::TempDir dir;
  const std::filesystem::path file = dir.path() / "constant.hdr";
  {
    std::ofstream out(file, std::ios::binary);
    out << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 2 +X 4\n";
    for (int i = 0; i < 8; ++i) out << static_cast<char>(128) << static_cast<char>(128) << static_cast<char>(128)
                                    << static_cast<char>(129);
  }
  const float L = gpu::readHdr(file).at(0, 0).x;
  ASSERT_GT(L, 0.9f);
  app::LoadedScene scene = slab("3x3");
  scene.config.scene.lights.clear();
  sss::Environment env;
  env.file = file;
  env.scale = 2.0f;
  scene.config.scene.environment = env;
  const sss::ReferenceResult r = integrate(scene, 2, 4096, 1);
  const double eta = scene.config.scene.objects.at(0).material.eta;
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(r.radiance.at(1, 1)[c], sss::fresnelReflectance(1.0, eta) * 2.0 * L, 1e-6);
  EXPECT_EQ(r.relError, 0.0);
  scene.config.render.specular = false;
  EXPECT_EQ(integrate(scene, 2, 4096, 1).radiance.at(1, 1), glm::vec4(0, 0, 0, 1));
}

// The standard-error image's alpha is the bench's object mask: 0 where no translucent object is hit.
TEST(ReferenceIntegrator, OpaqueObjectLeavesTheObjectMaskEmpty) {
  app::LoadedScene scene = slab("3x3");
  scene.config.scene.objects.at(0).translucent = false;
  const sss::ReferenceResult r = integrate(scene, 2, 1024, 1);
  EXPECT_EQ(r.translucentPixels, 0);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 3; ++x) EXPECT_EQ(r.standardError.at(x, y).a, 0.0f);
}

// (b) Two independent runs differ per pixel by about √2 × the estimated standard error (with the
// automatic point count: enough points near every x_o for the pass estimates to be well behaved).
TEST(ReferenceIntegrator, ErrorEstimateIsHonest) {
  const app::LoadedScene scene = slab("9x9");
  const sss::ReferenceResult a = integrate(scene, 10, 0, 1);
  const sss::ReferenceResult b = integrate(scene, 10, 0, 2);
  EXPECT_GE(a.nearFieldPoints, sss::kNearFieldTarget * 0.99);
  std::vector<double> z;
  for (int y = 0; y < 9; ++y)
    for (int x = 0; x < 9; ++x)
      for (int c = 0; c < 3; ++c) {
        const double sa = a.standardError.at(x, y)[c], sb = b.standardError.at(x, y)[c];
        if (!(sa > 0.0 && sb > 0.0)) continue;
        z.push_back((a.radiance.at(x, y)[c] - b.radiance.at(x, y)[c]) / std::sqrt(sa * sa + sb * sb));
      }
  ASSERT_EQ(z.size(), 49u * 3u);
  double sum2 = 0.0;
  int within = 0;
  for (double v : z) {
    sum2 += v * v;
    within += std::abs(v) <= 3.0 ? 1 : 0;
  }
  const double rms = std::sqrt(sum2 / static_cast<double>(z.size()));
  const double share = static_cast<double>(within) / static_cast<double>(z.size());
  std::printf("RMS z %.3f, %.1f%% within 3 sigma, relative errors %.4f / %.4f\n", rms, 100.0 * share, a.relError,
              b.relError);
  EXPECT_GE(share, 0.95);
  EXPECT_GE(rms, 0.7);
  EXPECT_LE(rms, 1.4);
  EXPECT_GT(a.relError, 0.0);
  EXPECT_TRUE(std::isfinite(a.relError));
}

// The relative-error stop ends after the minimum passes once ε is reached, and ε falls with passes.
TEST(ReferenceIntegrator, StopsAtTheRequestedRelativeError) {
  const app::LoadedScene scene = slab("5x5");
  sss::ReferenceSettings s;
  s.relError = 0.2;
  s.pointsPerPass = 16384;
  s.passLimit = 200;
  const sss::ReferenceResult r = sss::renderReference(scene.config.scene, scene.config.render, s);
  std::printf("relative error %.4f after %d passes\n", r.relError, r.passes);
  EXPECT_LE(r.relError, 0.2);
  EXPECT_GE(r.passes, s.minPasses);
  EXPECT_LT(r.passes, 200);
}

// Results do not depend on the number of threads.
TEST(ReferenceIntegrator, DeterministicAcrossThreadCounts) {
  const app::LoadedScene scene = slab("5x5");
  sss::ReferenceSettings s;
  s.maxPasses = 3;
  s.pointsPerPass = 2048;
  s.threads = 1;
  const sss::ReferenceResult one = sss::renderReference(scene.config.scene, scene.config.render, s);
  s.threads = 2;
  const sss::ReferenceResult two = sss::renderReference(scene.config.scene, scene.config.render, s);
  for (std::size_t i = 0; i < one.radiance.pixels.size(); ++i) EXPECT_EQ(one.radiance.pixels[i], two.radiance.pixels[i]);
}

// (c) Bad options: one line each, from the options check and from the command line.
TEST(ReferenceIntegrator, RefusesBadOptions) {
  app::ReferenceOptions o;
  o.out = "ref.exr";
  o.spp = 0;
  EXPECT_EQ(test::errorOf<app::InputError>([&] { app::validateReferenceOptions(o); }), "--spp: must be at least 1");
  o.spp = app::kNotGiven;
  o.relError = 0.0;
  EXPECT_EQ(test::errorOf<app::InputError>([&] { app::validateReferenceOptions(o); }),
            "--rel-error: must be a positive number");
  o.relError = -0.1;
  EXPECT_EQ(test::errorOf<app::InputError>([&] { app::validateReferenceOptions(o); }),
            "--rel-error: must be a positive number");
  // A NaN given is a bad value (issue 20), not the absence of --rel-error.
  o.relError = std::nan("");
  EXPECT_EQ(test::errorOf<app::InputError>([&] { app::validateReferenceOptions(o); }),
            "--rel-error: must be a positive number");
  o.relError.reset();
  EXPECT_NE(test::errorOf<app::InputError>([&] { app::validateReferenceOptions(o); }).find("--spp S"), std::string::npos);
  sss::ReferenceSettings s;  // the library refuses too
  const app::LoadedScene scene = slab("4x4");
  s.maxPasses = 1;
  s.pointsPerPass = -1;
  EXPECT_EQ(test::errorOf<std::invalid_argument>(
                [&] { sss::renderReference(scene.config.scene, scene.config.render, s); }),
            "--points: must be 0 (automatic) or more");

  test::TempDir dir;
  const std::string out = (dir.path() / "ref.exr").string();
  for (const std::vector<std::string>& bad :
       {std::vector<std::string>{"reference", "--preset", "slab", "--spp", "0", "--out", out},
        std::vector<std::string>{"reference", "--preset", "slab", "--rel-error", "0", "--out", out},
        std::vector<std::string>{"reference", "--preset", "slab", "--rel-error", "-1", "--out", out}}) {
    const test::CommandResult r = test::runTallow(bad);
    EXPECT_NE(r.exitCode, 0);
    EXPECT_EQ(test::lineCount(r.err), 1) << r.err;
  }
  EXPECT_TRUE(dir.entries().empty());
}

// The command writes REF.exr and REF_stderr.exr with the metadata.
TEST(ReferenceIntegrator, CommandWritesImageAndStandardError) {
  test::TempDir dir;
  const std::string out = (dir.path() / "ref.exr").string();
  const test::CommandResult r = test::runTallow(
      {"reference", "--preset", "slab", "--size", "6x4", "--spp", "3", "--points", "1024", "--seed", "5", "--out", out});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const gpu::Image image = gpu::readExr(out);
  const gpu::Image se = gpu::readExr(app::standardErrorPath(out));
  EXPECT_EQ(image.width, 6);
  EXPECT_EQ(image.height, 4);
  EXPECT_EQ(se.width, 6);
  EXPECT_NE(r.out.find("3 pass(es)"), std::string::npos) << r.out;
  EXPECT_EQ(gpu::readExrStringAttributes(out).at("tallow.pixel_filter"), "box") << "the command's default";
}

// --- Emergent light (ReferenceSettings::emergentLight, `--emergent`) -----------------------------

// tests/data/emergent_sphere.json: a marble sphere over a grey ground (ρ = 0.5, ambient 0.1) lit
// straight down by 1 W/m²; 12×4 pixels of 1 cm, column i at x = (i − 5.5) cm, rows at z = ∓1.5, ∓0.5
// cm; the four pixels at x, z = ±0.5 cm see the sphere, the others the ground (none in its shadow).
app::LoadedScene emergentSphere() {
  app::SceneOptions options;
  options.preset = std::string(TALLOW_TEST_SOURCE_DIR) + "/tests/data/emergent_sphere.json";
  return app::loadScene(options);
}

sss::ReferenceResult integrateEmergent(const app::LoadedScene& scene, int passes, int points, int emitters,
                                       std::uint64_t seed) {
  sss::ReferenceSettings s;
  s.maxPasses = passes;
  s.pointsPerPass = points;
  s.seed = seed;
  s.emergentLight = emitters > 0;
  if (emitters > 0) s.emitterPoints = emitters;
  return sss::renderReference(scene.config.scene, scene.config.render, s);
}

// A small receiver (2 mm square, ρ = 0.5) 1 cm above the slab's centre, facing it, seen from below by
// a narrow perspective camera in the gap. The slab is lit at 60° so that the receiver's shadow falls
// 1.7 cm away; far from the edges its radiosity is uniform, B = F_t(60°) E cos 60° R_d,total (the
// standard dipole, as in ObliquelyLitSlabFollowsLambertsCosine), so the receiver's radiance is
// L = ρ/π · B/π · ∫_top F_t(cos θ) cos² θ / d² dA, cos θ = h/d, over the slab's 20 cm square top (the
// other faces face away), integrated here by the midpoint rule on a 0.05 mm grid. Allowance 1% for
// what the integral leaves out: the lower B within ~1 cm of the slab's edges (≈ 0.3% of the kernel's
// weight lies there) and the receiver's own shadow (≈ side²/(16π h²) ≈ 0.1%).
TEST(ReferenceIntegrator, EmergentLightOnAReceiverAboveTheSlab) {
  app::LoadedScene scene = slab("3x3");
  const double theta = 60.0 * kPi / 180.0, h = 0.01, top = 0.05, side = 0.002, rho = 0.5, half = 0.1;
  scene.config.scene.lights.at(0).direction = glm::vec3(std::sin(theta), std::cos(theta), 0.0);
  sss::SceneObject receiver;
  receiver.name = "receiver";
  receiver.shape = sss::ShapeKind::Plane;
  receiver.size = glm::vec3(side, 1.0, side);
  receiver.transform.position = glm::vec3(0.0, top + h, 0.0);
  receiver.transform.rotationDeg = glm::vec3(180.0f, 0.0f, 0.0f);  // facing down
  receiver.albedo = glm::vec3(static_cast<float>(rho));
  scene.config.scene.objects.push_back(receiver);
  sss::Camera& camera = scene.config.scene.camera;
  camera.orthographic = false;
  camera.position = glm::vec3(0.0, top + 0.5 * h, 0.0);
  camera.target = glm::vec3(0.0, top + h, 0.0);
  camera.up = glm::vec3(0.0, 0.0, -1.0);
  camera.fovYDeg = 10.0f;  // the view 0.9 mm across at the receiver: every pixel sees it
  const sss::ReferenceResult r = integrateEmergent(scene, 16, 1 << 16, 8192, 7);
  EXPECT_EQ(r.translucentPixels, 0);
  EXPECT_EQ(r.emergentPixels, 9);
  ASSERT_EQ(r.emergent.width, 3);

  const sss::Material& m = scene.config.scene.objects.at(0).material;
  double kernel = 0.0;  // ∫ F_t(cos θ) cos² θ / d² dA over the top (dimensionless; π for an infinite plane and F_t = 1)
  const int steps = 2000;
  const double dx = half / steps;
  for (int i = 0; i < steps; ++i)
    for (int k = 0; k < steps; ++k) {
      const double x = (i + 0.5) * dx, z = (k + 0.5) * dx, d2 = x * x + z * z + h * h, cosT = h / std::sqrt(d2);
      kernel += 4.0 * sss::fresnelTransmittance(cosT, m.eta) * cosT * cosT / d2 * dx * dx;
    }
  const double E = scene.config.scene.lights.at(0).intensity.x;
  const glm::vec4 centre = r.radiance.at(1, 1), se = r.standardError.at(1, 1);
  for (int c = 0; c < 3; ++c) {
    const double B = sss::fresnelTransmittance(std::cos(theta), m.eta) * E * std::cos(theta) *
                     test::jensenTotalRd(m.sigma_a[c], m.sigma_s[c], m.g[c], m.eta);
    const double expected = rho / kPi * B / kPi * kernel;
    std::printf("band %d emergent: reference %.6g +- %.3g (%.2f%%), numerical %.6g (kernel %.5f), deviation %.2f sigma\n",
                c, centre[c], se[c], 100.0 * se[c] / expected, expected, kernel, (centre[c] - expected) / se[c]);
    EXPECT_FLOAT_EQ(r.emergent.at(1, 1)[c], centre[c]) << "no direct light or ambient on the downward face";
    EXPECT_GT(se[c], 0.0f);
    EXPECT_LT(se[c], 0.05 * expected) << "the bound must be tight enough to mean something";
    EXPECT_NEAR(centre[c], expected, 3.0 * se[c] + 0.01 * expected) << "band " << c;
  }
  EXPECT_GT(r.emergentRelError, 0.0);
  EXPECT_LT(r.emergentRelError, 0.05);
}

// Visibility: a wall 4 cm high at x = 2.0…2.2 cm, beyond the sphere (radius 1 cm) and not between it
// and the light, hides the sphere from the ground behind it: there the emergent term is exactly 0.
// Every segment from the sphere to the ground at x ≤ 1.5 cm stays at x ≤ 1.5 cm, so the wall shadows
// none of it and changes none of the lit points: those pixels keep their value.
TEST(ReferenceIntegrator, EmergentLightIsBlockedByAnOccluder) {
  app::LoadedScene scene = emergentSphere();
  const sss::ReferenceResult open = integrateEmergent(scene, 4, 4096, 2048, 3);
  sss::SceneObject wall;
  wall.name = "wall";
  wall.shape = sss::ShapeKind::Box;
  wall.size = glm::vec3(0.002, 0.04, 0.2);
  wall.transform.position = glm::vec3(0.021, 0.02, 0.0);
  scene.config.scene.objects.push_back(wall);
  const sss::ReferenceResult walled = integrateEmergent(scene, 4, 4096, 2048, 3);
  ASSERT_EQ(open.translucentPixels, 4);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 12; ++x) {
      if (open.standardError.at(x, y).a > 0.0f) continue;  // the sphere
      for (int c = 0; c < 3; ++c) {
        const double before = open.emergent.at(x, y)[c], after = walled.emergent.at(x, y)[c];
        const double se = open.standardError.at(x, y)[c];
        if (x >= 8) {  // behind the wall
          EXPECT_GT(before, 5.0 * se) << "pixel " << x << "," << y << ": emergent light to block";
          EXPECT_EQ(after, 0.0) << "pixel " << x << "," << y;
        } else {
          EXPECT_NEAR(after, before, 3.0 * std::hypot(se, walled.standardError.at(x, y)[c]) + 1e-12)
              << "pixel " << x << "," << y;
        }
      }
    }
  std::printf("column 8 (behind the wall): %.4g +- %.3g without it, %.4g with it; column 3: %.4g and %.4g\n",
              open.emergent.at(8, 1).x, open.standardError.at(8, 1).x, walled.emergent.at(8, 1).x,
              open.emergent.at(3, 1).x, walled.emergent.at(3, 1).x);
}

// Off by default: the receivers get direct light and ambient only (ρ/π E + ρ ambient, none in the
// sphere's shadow), no emergent image; turning it on leaves the sphere's pixels bit for bit (its
// random streams are its own) and adds the emergent term to the receivers.
TEST(ReferenceIntegrator, EmergentLightIsOffByDefault) {
  const app::LoadedScene scene = emergentSphere();
  EXPECT_FALSE(sss::ReferenceSettings{}.emergentLight);
  const sss::ReferenceResult off = integrateEmergent(scene, 2, 4096, 0, 5);
  const sss::ReferenceResult on = integrateEmergent(scene, 2, 4096, 256, 5);
  EXPECT_EQ(off.emergent.width, 0);
  EXPECT_EQ(off.emitterPoints, 0);
  EXPECT_EQ(on.emitterPoints, 256);
  const double direct = 0.5 / kPi * 1.0 + 0.5 * 0.1;
  int receivers = 0;
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 12; ++x) {
      if (off.standardError.at(x, y).a > 0.0f) {
        EXPECT_EQ(on.radiance.at(x, y), off.radiance.at(x, y)) << "sphere pixel " << x << "," << y;
        continue;
      }
      ++receivers;
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(off.radiance.at(x, y)[c], direct, 1e-6) << "pixel " << x << "," << y;
        EXPECT_EQ(off.standardError.at(x, y)[c], 0.0f);
        EXPECT_NEAR(on.radiance.at(x, y)[c], off.radiance.at(x, y)[c] + on.emergent.at(x, y)[c], 1e-6);
        EXPECT_GT(on.emergent.at(x, y)[c], 0.0f);
      }
    }
  EXPECT_EQ(receivers, 44);
  EXPECT_EQ(on.emergentPixels, 44);
}

// The emitter points and their gathers are counter-based too: the same result on 1 and 2 threads.
TEST(ReferenceIntegrator, EmergentLightIsDeterministicAcrossThreadCounts) {
  const app::LoadedScene scene = emergentSphere();
  sss::ReferenceSettings s;
  s.maxPasses = 2;
  s.pointsPerPass = 2048;
  s.emergentLight = true;
  s.emitterPoints = 128;
  s.threads = 1;
  const sss::ReferenceResult one = sss::renderReference(scene.config.scene, scene.config.render, s);
  s.threads = 2;
  const sss::ReferenceResult two = sss::renderReference(scene.config.scene, scene.config.render, s);
  EXPECT_EQ(one.emergent.pixels, two.emergent.pixels);
  EXPECT_EQ(one.radiance.pixels, two.radiance.pixels);
}

// The command: --emergent=N writes REF_emergent.exr beside REF.exr, the receivers marked in its alpha,
// with the emitter count and its error in the header.
TEST(ReferenceIntegrator, CommandWritesTheEmergentImage) {
  test::TempDir dir;
  const std::string out = (dir.path() / "ref.exr").string();
  const std::string preset = std::string(TALLOW_TEST_SOURCE_DIR) + "/tests/data/emergent_sphere.json";
  const test::CommandResult r = test::runTallow(
      {"reference", "--preset", preset, "--spp", "2", "--points", "1024", "--emergent=64", "--pixel-filter", "centre",
       "--out", out});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const gpu::Image emergent = gpu::readExr(app::emergentPath(out));
  EXPECT_EQ(emergent.width, 12);
  EXPECT_EQ(emergent.height, 4);
  EXPECT_EQ(emergent.at(0, 0).a, 1.0f) << "a receiver pixel";
  EXPECT_EQ(emergent.at(5, 1).a, 0.0f) << "a sphere pixel";
  EXPECT_GT(emergent.at(0, 0).x, 0.0f);
  const std::map<std::string, std::string> header = gpu::readExrStringAttributes(app::emergentPath(out));
  EXPECT_EQ(header.at("tallow.emergent"), "on");
  EXPECT_EQ(header.at("tallow.emitter_points"), "64");
  EXPECT_EQ(header.at("tallow.emergent_pixels"), "44");  // the receivers seen at the pixel centres
  EXPECT_EQ(gpu::readExrStringAttributes(out).at("tallow.pixel_filter"), "centre");
  EXPECT_EQ(gpu::readExrStringAttributes(out).at("tallow.emergent"), "on");
  EXPECT_EQ(app::emergentPath("/a/REF.exr"), std::filesystem::path("/a/REF_emergent.exr"));

  const test::CommandResult bad = test::runTallow(
      {"reference", "--preset", preset, "--spp", "1", "--emergent=-1", "--out", (dir.path() / "bad.exr").string()});
  EXPECT_NE(bad.exitCode, 0);
  EXPECT_EQ(test::lineCount(bad.err), 1) << bad.err;
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "bad.exr"));

  const std::string plain = (dir.path() / "plain.exr").string();  // without --emergent: no file, "off"
  ASSERT_EQ(test::runTallow({"reference", "--preset", preset, "--spp", "1", "--points", "1024", "--out", plain}).exitCode, 0);
  EXPECT_FALSE(std::filesystem::exists(app::emergentPath(plain)));
  EXPECT_EQ(gpu::readExrStringAttributes(plain).at("tallow.emergent"), "off");
}

}  // namespace
}  // namespace tallow
