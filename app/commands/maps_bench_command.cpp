#include "app/commands/maps_bench_command.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>

#include "app/commands/frame_stats.h"
#include "app/commands/provenance.h"
#include "app/commands/progress.h"
#include "app/commands/option_checks.h"
#include "app/config/input_error.h"
#include "app/config/params.h"
#include "gpu/atomic_file.h"
#include "gpu/gl_context.h"
#include "gpu/gl_objects.h"
#include "sss/maps/radiosity_maps.h"
#include "sss/renderer.h"

namespace tallow::app {
namespace {

constexpr int kNeverConverge = 1 << 20;  ///< sss.frames: the registry's maximum, far above any run here

/// Texels with alpha > 0 in level 0 of the maps (alpha counts the frames accumulated at a texel
/// the estimator shaded; texels no translucent surface covers stay 0), over all K layers.
std::size_t shadedTexels(const gpu::Texture& maps) {
  const std::size_t texels =
      static_cast<std::size_t>(maps.width()) * static_cast<std::size_t>(maps.height()) * static_cast<std::size_t>(maps.depth());
  std::vector<float> rgba(texels * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glGetTextureImage(maps.id(), 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(rgba.size() * sizeof(float)), rgba.data());
  std::size_t count = 0;
  for (std::size_t i = 0; i < texels; ++i)
    if (rgba[4 * i + 3] > 0.0f) ++count;
  return count;
}

double passMs(const sss::FrameTimings& t, const std::string& name) {
  for (const auto& p : t.passes)
    if (p.name == name) return p.gpuMs;
  return -1.0;  // did not run
}

bool plans(const std::vector<sss::PlannedPass>& passes, const char* name) {
  return std::any_of(passes.begin(), passes.end(), [&](const sss::PlannedPass& p) { return p.name == name; });
}

}  // namespace

LinearFit fitLine(const std::vector<double>& x, const std::vector<double>& y) {
  LinearFit f;
  const std::size_t n = std::min(x.size(), y.size());
  if (n == 0) return f;
  double mx = 0.0, my = 0.0;
  for (std::size_t i = 0; i < n; ++i) mx += x[i], my += y[i];
  mx /= double(n), my /= double(n);
  double sxx = 0.0, sxy = 0.0, syy = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    sxx += (x[i] - mx) * (x[i] - mx);
    sxy += (x[i] - mx) * (y[i] - my);
    syy += (y[i] - my) * (y[i] - my);
  }
  f.slope = sxx > 0.0 ? sxy / sxx : 0.0;
  f.intercept = my - f.slope * mx;
  double ssRes = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double r = y[i] - (f.intercept + f.slope * x[i]);
    ssRes += r * r;
  }
  f.r2 = syy > 0.0 ? 1.0 - ssRes / syy : (ssRes == 0.0 ? 1.0 : 0.0);
  return f;
}

PlaneFit fitPlane(const std::vector<double>& x1, const std::vector<double>& x2, const std::vector<double>& y) {
  PlaneFit f;
  const std::size_t n = std::min({x1.size(), x2.size(), y.size()});
  if (n == 0) return f;
  double m1 = 0.0, m2 = 0.0, my = 0.0;
  for (std::size_t i = 0; i < n; ++i) m1 += x1[i], m2 += x2[i], my += y[i];
  m1 /= double(n), m2 /= double(n), my /= double(n);
  double s11 = 0.0, s12 = 0.0, s22 = 0.0, s1y = 0.0, s2y = 0.0, syy = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double d1 = x1[i] - m1, d2 = x2[i] - m2, dy = y[i] - my;
    s11 += d1 * d1, s12 += d1 * d2, s22 += d2 * d2, s1y += d1 * dy, s2y += d2 * dy, syy += dy * dy;
  }
  const double det = s11 * s22 - s12 * s12;
  if (std::abs(det) > 1e-12 * std::max(1.0, s11 * s22)) {
    f.a = (s22 * s1y - s12 * s2y) / det;
    f.b = (s11 * s2y - s12 * s1y) / det;
  }
  f.intercept = my - f.a * m1 - f.b * m2;
  double ssRes = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double r = y[i] - (f.intercept + f.a * x1[i] + f.b * x2[i]);
    ssRes += r * r;
  }
  f.r2 = syy > 0.0 ? 1.0 - ssRes / syy : (ssRes == 0.0 ? 1.0 : 0.0);
  return f;
}

int runProbeMaps(const ProbeMapsOptions& o) {
  if (o.out.empty()) throw InputError("probe maps: --out FILE.json is required");
  checkOutputFile("--out", o.out, {".json"});  // before the work, not after it
  if (o.maps.empty()) throw InputError("--k: give at least one number of maps");
  if (o.samples.empty()) throw InputError("--n: give at least one number of samples");
  for (int k : o.maps)
    if (k < 1) throw InputError("--k: " + std::to_string(k) + " maps; K must be at least 1");
  for (int n : o.samples)
    if (n < 1) throw InputError("--n: " + std::to_string(n) + " samples; N must be at least 1");
  if (o.repeats < 1 || o.repeats > 100) throw InputError("--repeats: must be in [1, 100]");

  // Every configuration through the registry before any GL work: its ranges (sss.maps ≤ 256,
  // sss.samples ≤ 4096, sss.map_size) give the one-line errors.
  struct Case {
    int k = 0, n = 0;
    LoadedScene loaded;
  };
  std::vector<Case> cases;
  for (int k : o.maps)
    for (int n : o.samples) {
      SceneOptions scene = o.scene;
      if (o.mapSize != 0) scene.sets.push_back("sss.map_size=" + std::to_string(o.mapSize));
      if (!o.gather.empty()) scene.sets.push_back("sss.gather=" + o.gather);
      scene.sets.push_back("method=radiosity-maps");
      scene.sets.push_back("sss.maps=" + std::to_string(k));
      scene.sets.push_back("sss.samples=" + std::to_string(n));
      scene.sets.push_back("sss.frames=" + std::to_string(kNeverConverge));
      cases.push_back({k, n, loadScene(scene)});
    }
  const std::string presetName = cases.front().loaded.presetName;

  gpu::ContextOptions contextOptions;
  contextOptions.backend = gpu::parseGlBackend(o.gl);
  contextOptions.visible = false;
  const auto context = gpu::GlContext::create(contextOptions);
  const gpu::ShaderLibrary shaders = makeShaderLibrary(o.scene.shaderDir);

  nlohmann::json rows = nlohmann::json::array();
  std::vector<double> fitX, fitK, fitY;
  Progress progress("probe maps", "case", static_cast<int>(cases.size()));
  for (const Case& c : cases) {
    const sss::Scene& scene = c.loaded.config.scene;
    const sss::RenderSettings& settings = c.loaded.config.render;
    if (!sss::RadiosityMaps::applies(scene, settings))
      throw InputError("probe maps: preset " + presetName + " has no translucent object, so it has no radiosity maps");
    sss::Renderer renderer(shaders, scene, settings);
    constexpr double t = 0.0;  // nothing moves: the maps accumulate frame after frame
    sss::FrameTimings first = renderer.render(scene, settings, t);  // warm-up: restarts the maps
    glFinish();
    renderer.resolveTimings(first);

    std::vector<double> mapsMs, surfaceMs, frameMs, wallMs;
    for (int r = 0; r < o.repeats; ++r) {
      const auto plan = renderer.planFrame(scene, settings, t);
      // Only the maps accumulate: the light G-buffers of the warm-up frame are kept (their pass reads
      // the lights, the geometry and the sizes, and none of them changed).
      if (plans(plan, "sss.light_gbuffer") || !plans(plan, "sss.maps"))
        throw std::runtime_error("probe maps: timed frame " + std::to_string(r) +
                                 " would not run sss.maps alone on kept light G-buffers");
      const auto start = std::chrono::steady_clock::now();
      sss::FrameTimings timings = renderer.render(scene, settings, t);
      glFinish();
      renderer.resolveTimings(timings);
      wallMs.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
      mapsMs.push_back(passMs(timings, "sss.maps"));
      surfaceMs.push_back(passMs(timings, "surface"));
      frameMs.push_back(timings.gpuTotalMs);
      if (mapsMs.back() < 0.0) throw std::runtime_error("probe maps: sss.maps did not run in a timed frame");
    }
    const sss::RadiosityMaps* maps = renderer.module<sss::RadiosityMaps>();
    if (!maps) throw std::runtime_error("probe maps: the renderer made no radiosity maps");
    const std::size_t shaded = shadedTexels(maps->maps());
    const std::size_t texels = static_cast<std::size_t>(c.k) * static_cast<std::size_t>(maps->maps().width()) *
                               static_cast<std::size_t>(maps->maps().height());
    const double mapsMedian = median(mapsMs);
    const double lights = static_cast<double>(scene.lights.size());
    const double evaluations = static_cast<double>(shaded) * 3.0 * c.n * lights;  // per frame, upper bound
    const double perSecond = mapsMedian > 0.0 ? evaluations / (mapsMedian * 1e-3) : 0.0;
    rows.push_back({{"k", c.k},
                    {"n", c.n},
                    {"k_times_n", c.k * c.n},
                    {"map_size", maps->mapSize()},  // as chosen where the preset says auto
                    {"light_map_size", maps->lightMapSize()},
                    {"lights", scene.lights.size()},
                    {"light_gbuffer_ms", passMs(first, "sss.light_gbuffer")},  // drawn once, in the warm-up
                    {"maps_ms", mapsMedian},
                    {"surface_ms", median(surfaceMs)},
                    {"frame_gpu_ms", median(frameMs)},
                    {"frame_wall_ms", median(wallMs)},
                    {"first_frame",
                     {{"light_gbuffer_ms", passMs(first, "sss.light_gbuffer")},
                      {"maps_ms", passMs(first, "sss.maps")},
                      {"surface_ms", passMs(first, "surface")}}},
                    {"map_bytes", maps->maps().bytes() + maps->mapDepth().bytes()},
                    {"sss_bytes", maps->bytes()},
                    {"map_texels", texels},
                    {"shaded_texels", shaded},
                    {"shaded_share", texels ? double(shaded) / double(texels) : 0.0},
                    {"frames_accumulated", maps->frames()},
                    {"evaluations_per_frame", evaluations},
                    {"evaluations_per_s", perSecond}});
    fitX.push_back(static_cast<double>(c.k) * c.n);
    fitK.push_back(static_cast<double>(c.k));
    fitY.push_back(mapsMedian);
    char line[256];
    std::snprintf(line, sizeof line,
                  "K %3d N %4d  light G-buffer %8.3f ms  maps %9.3f ms  surface %8.3f ms  shaded %8zu texels  "
                  "%.3g evaluations/s  %zu bytes",
                  c.k, c.n, passMs(first, "sss.light_gbuffer"), mapsMedian, median(surfaceMs), shaded, perSecond,
                  static_cast<std::size_t>(maps->bytes()));
    progress.print(line, stdout);
    progress.update(static_cast<int>(rows.size()));
  }
  progress.finish();
  const LinearFit fit = fitLine(fitX, fitY);
  const LinearFit fitByK = fitLine(fitK, fitY);
  const PlaneFit fitBoth = fitPlane(fitK, fitX, fitY);
  std::printf("fit: sss.maps ms = %.4g + %.4g * K*N  (R^2 = %.4f)\n", fit.intercept, fit.slope, fit.r2);
  std::printf("fit: sss.maps ms = %.4g + %.4g * K + %.4g * K*N  (R^2 = %.4f)\n", fitBoth.intercept, fitBoth.a,
              fitBoth.b, fitBoth.r2);

  const auto& first = cases.front().loaded.config.render;
  nlohmann::json effectiveGather = nullptr;  // sss.gather as the registry holds it (null if this build has none)
  try {
    effectiveGather = parameterRegistry(cases.front().loaded.materials).get(cases.front().loaded.config, "sss.gather");
  } catch (const std::exception&) {
  }
  const nlohmann::json result = {
      {"preset", presetName},
      {"settings",
       {{"k", o.maps},
        {"n", o.samples},
        {"map_size", first.sss.mapSize == sss::kAuto ? nlohmann::json("auto") : nlohmann::json(first.sss.mapSize)},
        {"light_map_size",
         first.sss.lightMapSize == sss::kAuto ? nlohmann::json("auto") : nlohmann::json(first.sss.lightMapSize)},
        {"model", std::string(sss::bssrdfModelName(first.sss.model))},
        {"gather", effectiveGather},
        {"width", first.width},
        {"height", first.height},
        {"sets", o.scene.sets},
        {"repeats", o.repeats}}},
      {"rows", rows},
      {"fit",
       {{"model", "maps_ms = intercept_ms + slope_ms * K * N (least squares over the rows)"},
        {"intercept_ms", fit.intercept},
        {"slope_ms", fit.slope},
        {"r2", fit.r2}}},
      {"fit_k",
       {{"model", "maps_ms = intercept_ms + slope_ms * K (ignores N; the paper's Fig. 13 axis)"},
        {"intercept_ms", fitByK.intercept},
        {"slope_ms", fitByK.slope},
        {"r2", fitByK.r2}}},
      {"fit_k_kn",
       {{"model", "maps_ms = intercept_ms + per_map_ms * K + per_sample_ms * K * N: a fixed cost per map (depth "
                  "pre-pass, rasterisation, mipmaps) and one per map and sample"},
        {"intercept_ms", fitBoth.intercept},
        {"per_map_ms", fitBoth.a},
        {"per_sample_ms", fitBoth.b},
        {"r2", fitBoth.r2}}},
      {"gpu",
       glJson(*context)},
      {"notes",
       "after one warm-up frame (which restarts the maps: light G-buffers, depth pre-pass, first N samples; its times "
       "are first_frame), `repeats` frames with nothing changed and sss.frames raised so the maps keep accumulating: "
       "each runs sss.light_gbuffer (which reuses the first frame's G-buffers, so it is nearly free) and sss.maps "
       "(N more samples per shaded texel, map and band); *_ms are medians of GL timestamp queries. map_bytes is the "
       "maps (RGBA32F with mipmaps) and their depth (DEPTH_COMPONENT32F); sss_bytes adds the light G-buffers. "
       "shaded_texels counts level-0 map texels with alpha > 0 (alpha = frames accumulated) over all K layers. "
       "evaluations_per_s = shaded_texels * 3 bands * N * lights / maps time: an upper bound, since every sample is "
       "counted as a BSSRDF evaluation, including samples that miss the object"}};
  gpu::writeTextFileAtomically(o.out, result.dump(2) + "\n");
  return 0;
}

}  // namespace tallow::app
