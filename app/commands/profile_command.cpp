#include "app/commands/profile_command.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <vector>

#include "app/commands/gnuplot.h"
#include "app/commands/output_folder.h"
#include "app/commands/option_checks.h"
#include "app/config/input_error.h"
#include "app/config/setup.h"
#include "gpu/atomic_file.h"
#include "sss/bssrdf/bssrdf.h"
#include "sss/bssrdf/material.h"
#include "sss/reference/planar_mc.h"

namespace tallow::app {
namespace {

constexpr double kPi = 3.14159265358979323846;

struct Medium {
  double sigmaA, sigmaS, g, eta;
  std::string label;
};

Medium resolveMedium(const ProbeProfileOptions& o) {
  if (!o.material.empty()) {
    if (o.sigmaA >= 0.0 || o.sigmaS >= 0.0) throw InputError("probe profile: give --material or --sigma-a/--sigma-s, not both");
    if (o.band < 0 || o.band > 2) throw InputError("--band: expected 0 (red), 1 (green) or 2 (blue)");
    const auto table = sss::MaterialTable::load(dataDir() / "materials.csv");
    const auto m = table.find(o.material);
    if (!m) {
      std::vector<std::string> names;
      for (const auto& row : table.materials()) names.push_back(row.name);
      throw InputError("--material: unknown material \"" + o.material + "\"" + didYouMean(o.material, names));
    }
    return {m->sigma_a[o.band], m->sigma_s[o.band], m->g[o.band], m->eta,
            m->name + " (band " + std::to_string(o.band) + ")"};
  }
  if (o.sigmaA < 0.0 || o.sigmaS < 0.0) throw InputError("probe profile: give --material NAME or both --sigma-a and --sigma-s (mm^-1, >= 0)");
  char label[160];
  std::snprintf(label, sizeof label, "sigma_a %g, sigma_s %g /mm, g %g, eta %g", o.sigmaA, o.sigmaS, o.g, o.eta);
  return {o.sigmaA, o.sigmaS, o.g, o.eta, label};
}

/// R_d at x_o on the surface z = 0 for a ray arriving at the origin from direction `towardLight`:
/// the exitance per unit incident power, T₁₂(θ)·S_d·4π·C_φ(1/η) (directional-dipole paper, Eq. 16),
/// which is π·S_d for an index-matched boundary.
struct AnalyticProfile {
  sss::BssrdfModel model;
  Medium medium;
  glm::dvec3 towardLight;
  double scale;  ///< T₁₂(θ)·4π·C_φ(1/η)

  sss::BssrdfValue rd(double x, double y) const {
    sss::BssrdfConfig c;
    c.xi = {0, 0, 0};
    c.ni = {0, 0, 1};
    c.wi = towardLight;
    c.xo = {x, y, 0};
    c.no = {0, 0, 1};
    c.sigma_a = medium.sigmaA;
    c.sigma_s = medium.sigmaS;
    c.g = medium.g;
    c.eta = medium.eta;
    const sss::BssrdfValue v = sss::evaluateBssrdf<double>(model, c);
    return {v.sd * scale, v.sdClamped * scale};
  }
};

std::string number(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.9g", v);
  return b;
}

void writePlots(const std::filesystem::path& out, const std::string& title) {
  GnuplotRun(out).draw(
      [&](std::FILE* f, const std::vector<std::string>& output) {
        std::fprintf(f,
                     "set output %s\n"
                     "set title %s noenhanced\n"
                     "set xlabel 'x [mm]'\nset ylabel 'R_d [mm^{-2}]'\nset logscale y\nset format y '10^{%%L}'\n"
                     "set key top right\nset grid\n"
                     "plot 'profile_x.csv' using 1:($4==0 ? $2 : 1/0) with lines lw 2 lc rgb '#1f77b4' title 'R_d', \\\n"
                     "     '' using 1:($4==1 ? -$2 : 1/0) with points pt 7 ps 0.6 lc rgb '#d62728' title '-R_d where negative'\n"
                     "set output %s\n"
                     "unset logscale y\nset format y '%%g'\nset xlabel 'x [mm]'\nset ylabel 'y [mm]'\n"
                     "set size ratio -1\nset view map\nset cblabel 'log_{10} R_d'\n"
                     "set palette defined (0 '#000004', 1 '#3b0f70', 2 '#8c2981', 3 '#de4968', 4 '#fe9f6d', 5 '#fcfdbf')\n"
                     "plot 'profile_map.csv' using 1:2:($3 > 0 ? log10($3) : 1/0) with image notitle, \\\n"
                     "     '' using 1:($4 == 1 ? $2 : 1/0) with points pt 5 ps 0.3 lc rgb '#00ff00' title 'negative (raw S_d < 0)'\n",
                     output[0].c_str(), gnuplotString(title).c_str(), output[1].c_str());
      },
      {"profile_x.png", "profile_map.png"}, "the profile plots");
}

}  // namespace

int runProbeProfile(const ProbeProfileOptions& o) {
  if (o.out.empty()) throw InputError("probe profile: --out DIR is required");
  if (!(o.extentMm > 0.0) || !std::isfinite(o.extentMm)) throw InputError("--extent: must be a positive length in mm");
  if (o.bins < 2 || o.bins > 4096) throw InputError("--bins: must be in [2, 4096]");
  if (!(std::abs(o.thetaDeg) < 90.0)) throw InputError("--theta: must be in (-90, 90) degrees");
  const Medium medium = resolveMedium(o);
  const bool mc = o.model == "mc";
  sss::BssrdfModel model = sss::BssrdfModel::Directional;
  if (!mc) {
    try {
      model = sss::parseBssrdfModel(o.model);
    } catch (const std::invalid_argument& e) {
      throw InputError(std::string("--model: ") + e.what() + " (or mc)");
    }
  }
  {
    // Validate the medium through the same checks as the probe's CSV rows.
    sss::BssrdfConfig c{{0, 0, 0}, {0, 0, 1}, {0, 0, 1}, {1, 0, 0}, {0, 0, 1}, medium.sigmaA, medium.sigmaS, medium.g, medium.eta};
    try {
      sss::validateBssrdfConfig(c);
    } catch (const std::invalid_argument& e) {
      throw InputError(std::string("probe profile: ") + e.what());
    }
  }
  const std::filesystem::path out(o.out);
  checkWritableFolder(out);
  OutputFolder folder(out, "probe profile");  // one run at a time into it (output_folder.h)

  const int n = o.bins;
  const double half = 0.5 * o.extentMm;
  const double step = o.extentMm / n;
  std::vector<double> xs(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) xs[static_cast<std::size_t>(i)] = sss::planarMcBinCentre(-half, half, n, i);

  std::string xCsv = "x_mm,rd,rd_stderr,negative\n";
  std::string mapCsv = "x_mm,y_mm,rd,negative\n";
  std::size_t negatives = 0;
  if (mc) {
    sss::PlanarMcSetup s;
    s.sigma_a = medium.sigmaA;
    s.sigma_s = medium.sigmaS;
    s.g = medium.g;
    s.eta = medium.eta;
    s.thetaDeg = o.thetaDeg;
    s.photons = o.photons;
    s.seed = o.seed;
    s.xMinMm = -half;
    s.xMaxMm = half;
    s.xBins = n;
    s.stripWidthMm = step;
    s.mapHalfWidthMm = half;
    s.mapBins = n;
    try {
      sss::validatePlanarMcSetup(s);
    } catch (const std::invalid_argument& e) {
      throw InputError(std::string("probe profile: ") + e.what());
    }
    const sss::PlanarMcResult r = sss::simulatePlanarMedium(s);
    for (int i = 0; i < n; ++i) {
      const auto k = static_cast<std::size_t>(i);
      xCsv += number(xs[k]) + "," + number(r.xProfile.mean[k]) + "," + number(r.xProfile.stdErr[k]) + ",0\n";
    }
    for (int iy = 0; iy < n; ++iy)
      for (int ix = 0; ix < n; ++ix)
        mapCsv += number(xs[static_cast<std::size_t>(ix)]) + "," + number(xs[static_cast<std::size_t>(iy)]) + "," +
                  number(r.map.mean[static_cast<std::size_t>(iy * n + ix)]) + ",0\n";
    std::printf("tallow: Monte Carlo, %llu photons: total diffuse reflectance %.6f ± %.6f\n",
                static_cast<unsigned long long>(r.photons), r.diffuseReflectance.mean, r.diffuseReflectance.stdErr);
  } else {
    const double theta = o.thetaDeg * kPi / 180.0;
    AnalyticProfile p{model, medium, {-std::sin(theta), 0.0, std::cos(theta)},
                      sss::fresnelTransmittance(std::cos(theta), medium.eta) * 4.0 * kPi * sss::cPhiPolynomial(1.0 / medium.eta)};
    for (double x : xs) {
      const sss::BssrdfValue v = p.rd(x, 0.0);
      xCsv += number(x) + "," + number(v.sd) + ",0," + (v.sd < 0.0 ? "1" : "0") + "\n";
    }
    for (double y : xs)
      for (double x : xs) {
        const sss::BssrdfValue v = p.rd(x, y);
        negatives += v.sd < 0.0;
        mapCsv += number(x) + "," + number(y) + "," + number(v.sd) + "," + (v.sd < 0.0 ? "1" : "0") + "\n";
      }
  }
  folder.clearEarlierRun({"profile_x.csv", "profile_map.csv", "profile_x.png", "profile_map.png"});
  gpu::writeTextFileAtomically(out / "profile_x.csv", xCsv);
  gpu::writeTextFileAtomically(out / "profile_map.csv", mapCsv);
  char title[256];
  std::snprintf(title, sizeof title, "%s, %s, theta %g deg", o.model.c_str(), medium.label.c_str(), o.thetaDeg);
  if (o.plots) writePlots(out, title);
  if (!mc)
    std::printf("tallow: %s profile: %zu of %d map samples negative (raw S_d < 0)\n", o.model.c_str(), negatives, n * n);
  return 0;
}

}  // namespace tallow::app
