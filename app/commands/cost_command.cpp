#include "app/commands/cost_command.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>

#include "app/commands/frame_stats.h"
#include "app/commands/provenance.h"
#include "app/commands/option_checks.h"
#include "app/config/input_error.h"
#include "gpu/atomic_file.h"
#include "gpu/gl_context.h"
#include "sss/bssrdf/bssrdf.h"
#include "sss/bssrdf/bssrdf_gpu.h"

namespace tallow::app {
namespace {

/// Random configurations in the ranges the renderer meets: points on a unit-scale surface, mostly
/// front-lit, distances 1e-3…10 mm, coefficients of the measured materials' range.
std::vector<sss::BssrdfConfig> randomConfigs(std::uint64_t count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  auto unit = [&] {
    const double z = 2.0 * u(rng) - 1.0, phi = 2.0 * 3.14159265358979 * u(rng), s = std::sqrt(1.0 - z * z);
    return glm::dvec3(s * std::cos(phi), s * std::sin(phi), z);
  };
  auto logUniform = [&](double lo, double hi) { return lo * std::pow(hi / lo, u(rng)); };
  std::vector<sss::BssrdfConfig> out(count);
  for (auto& c : out) {
    c.xi = glm::dvec3(0.0);
    c.ni = unit();
    c.wi = unit();
    if (u(rng) < 0.8 && glm::dot(c.wi, c.ni) < 0.0) c.wi = -c.wi;  // mostly front-lit
    c.xo = c.xi + unit() * logUniform(1e-3, 10.0);
    c.no = glm::normalize(c.ni + 0.3 * unit());
    c.sigma_a = logUniform(1e-4, 1.0);
    c.sigma_s = logUniform(0.1, 50.0);
    c.g = -0.9 + 1.8 * u(rng);
    c.eta = 1.0 + 0.6 * u(rng);
  }
  return out;
}

template <class Real>
double cpuEvaluationsPerSecond(sss::BssrdfModel model, const std::vector<sss::BssrdfConfig>& configs, int repeats,
                               std::vector<sss::BssrdfValue>& values) {
  std::vector<double> rates;
  for (int r = 0; r < repeats; ++r) {
    values.clear();
    const auto t0 = std::chrono::steady_clock::now();
    for (const auto& c : configs) values.push_back(sss::evaluateBssrdf<Real>(model, c));
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    rates.push_back(static_cast<double>(configs.size()) / s);
  }
  return median(rates);
}

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t i = std::min(v.size() - 1, static_cast<std::size_t>(p * static_cast<double>(v.size() - 1) + 0.5));
  return v[i];
}

}  // namespace

int runProbeCost(const ProbeCostOptions& o) {
  if (o.out.empty()) throw InputError("probe cost: --out FILE.json is required");
  checkOutputFile("--out", o.out, {".json"});  // before the work, not after it
  if (o.count < 100 || o.count > 100000000) throw InputError("--count: must be in [100, 1e8]");
  if (o.repeats < 1 || o.repeats > 100) throw InputError("--repeats: must be in [1, 100]");
  std::unique_ptr<gpu::GlContext> context;
  if (o.gpu) {
    gpu::ContextOptions contextOptions;
    contextOptions.backend = gpu::parseGlBackend(o.gl);
    context = gpu::GlContext::create(contextOptions);
  }
  nlohmann::json models = nlohmann::json::array();
  for (sss::BssrdfModel model : {sss::BssrdfModel::Standard, sss::BssrdfModel::Directional,
                                 sss::BssrdfModel::PhotonBeamDiffusion}) {
    const std::uint64_t n = model == sss::BssrdfModel::PhotonBeamDiffusion ? std::max<std::uint64_t>(o.count / 10, 100)
                                                                            : o.count;
    const auto configs = randomConfigs(n, 20261124);
    std::vector<sss::BssrdfValue> f, d;
    const double floatRate = cpuEvaluationsPerSecond<float>(model, configs, o.repeats, f);
    const double doubleRate = cpuEvaluationsPerSecond<double>(model, configs, o.repeats, d);
    // Float against double, relative to the configuration's magnitude floor (sss::bssrdfMagnitude):
    // where S_d is a small difference of large terms, float rounding of the terms is what counts.
    std::vector<double> relative;
    std::size_t nonFinite = 0;
    for (std::size_t i = 0; i < configs.size(); ++i) {
      if (!std::isfinite(f[i].sd) || !std::isfinite(d[i].sd)) {
        ++nonFinite;
        continue;
      }
      const double floor = 1e-9 * sss::bssrdfMagnitude(model, configs[i]);
      relative.push_back(std::abs(f[i].sd - d[i].sd) / std::max(std::abs(d[i].sd), floor));
    }
    nlohmann::json row = {{"model", std::string(sss::bssrdfModelName(model))},
                          {"configurations", n},
                          {"cpu_float_evals_per_s", floatRate},
                          {"cpu_double_evals_per_s", doubleRate},
                          {"float_vs_double_relative_error",
                           {{"p50", percentile(relative, 0.5)},
                            {"p90", percentile(relative, 0.9)},
                            {"p99", percentile(relative, 0.99)},
                            {"p999", percentile(relative, 0.999)},
                            {"max", percentile(relative, 1.0)},
                            {"non_finite", nonFinite}}}};
    if (context) {
      std::vector<double> rates;
      sss::evaluateBssrdfGpu(gpu::ShaderLibrary(), model, configs);  // warm-up: compile and upload
      for (int r = 0; r < o.repeats; ++r) {
        const auto t0 = std::chrono::steady_clock::now();
        const auto g = sss::evaluateBssrdfGpu(gpu::ShaderLibrary(), model, configs);
        rates.push_back(static_cast<double>(n) / std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
      }
      row["gpu_evals_per_s"] = median(rates);
      row["gpu_note"] = "end to end: upload, compile of the cached program excluded only by the warm-up, dispatch, read-back";
    }
    models.push_back(row);
    std::printf("%-12s cpu float %.3g/s  cpu double %.3g/s%s  float-vs-double p99 %.2g\n",
                std::string(sss::bssrdfModelName(model)).c_str(), floatRate, doubleRate,
                context ? ("  gpu " + std::to_string(static_cast<long long>(row["gpu_evals_per_s"].get<double>())) + "/s").c_str() : "",
                row["float_vs_double_relative_error"]["p99"].get<double>());
  }
  nlohmann::json result = {{"models", models}, {"repeats", o.repeats}};
  if (context)
    result["gpu"] = glJson(*context);
  gpu::writeTextFileAtomically(o.out, result.dump(2) + "\n");
  return 0;
}

}  // namespace tallow::app
