#include "sss/reference/planar_mc.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <condition_variable>
#include <exception>
#include <map>
#include <mutex>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>

namespace tallow::sss {

namespace planar_mc {

double fresnelReflectance(double cosIncident, double nIncident, double nTransmitted) {
  const double cosI = std::clamp(cosIncident, 0.0, 1.0);
  if (nIncident == nTransmitted) return 0.0;
  const double ratio = nIncident / nTransmitted;
  const double sin2T = ratio * ratio * (1.0 - cosI * cosI);  // Snell: sin θ_t = (n_i/n_t) sin θ_i
  if (sin2T >= 1.0) return 1.0;                               // total internal reflection
  const double cosT = std::sqrt(1.0 - sin2T);
  // Fresnel amplitude ratios for s and p polarisation (Born & Wolf §1.5.2); unpolarised light
  // reflects the mean of their squares.
  const double rs = (nIncident * cosI - nTransmitted * cosT) / (nIncident * cosI + nTransmitted * cosT);
  const double rp = (nTransmitted * cosI - nIncident * cosT) / (nTransmitted * cosI + nIncident * cosT);
  return 0.5 * (rs * rs + rp * rp);
}

double sampleHenyeyGreensteinCos(double g, double u) {
  // Inverse CDF of HG (Henyey & Greenstein 1941; Witt 1977), with s = 2u − 1:
  //   μ = (1 + g² − ((1 − g²)/(1 + g s))²) / (2g).
  // Expanding the numerator over (1 + g s)² cancels the 1/g exactly:
  //   μ = (s + (g/2)(3 + s² + 2 g s + g²(s² − 1))) / (1 + g s)²,
  // which is μ = s at g = 0 and has no cancellation for small |g|.
  const double s = 2.0 * u - 1.0;
  const double d = 1.0 + g * s;
  const double mu = (s + 0.5 * g * (3.0 + s * s + 2.0 * g * s + g * g * (s * s - 1.0))) / (d * d);
  return std::clamp(mu, -1.0, 1.0);
}

}  // namespace planar_mc

namespace {

/// Russian roulette below this weight, survival chance kRouletteSurvival (MCML's choices,
/// Wang, Jacques & Zheng 1995, §3.9): the game is unbiased whatever the values.
constexpr double kRouletteThreshold = 1e-4;
constexpr double kRouletteSurvival = 0.1;
/// Photons per work unit: a unit is what a thread takes at a time; the results do not depend on it.
constexpr std::uint64_t kPhotonsPerUnit = 1024;
/// Limits that keep tallies within memory.
constexpr int kMaxProfileBins = 1 << 20;
constexpr int kMaxMapBins = 2048;

/// splitmix64 (Steele, Lea & Flood 2014): seeds xoshiro from a 64-bit key.
std::uint64_t splitmix64(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

/// xoshiro256+ (Blackman & Vigna 2018), the generator for doubles; one stream per photon, keyed by
/// (seed, photon index), so a photon's path does not depend on which thread runs it.
class Rng {
 public:
  Rng(std::uint64_t seedKey, std::uint64_t photon) {
    std::uint64_t sm = seedKey ^ (photon * 0xD1B54A32D192ED03ull);
    for (auto& word : s_) word = splitmix64(sm);
  }
  /// Uniform in [0, 1), 53 random bits.
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  /// Uniform in (0, 1], for logarithms.
  double uniformPositive() { return 1.0 - uniform(); }

 private:
  static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  std::uint64_t next() {
    const std::uint64_t result = s_[0] + s_[3];
    const std::uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = rotl(s_[3], 45);
    return result;
  }
  std::uint64_t s_[4];
};

/// Everything the walk needs, derived once from the setup.
struct Medium {
  double sigmaT;       ///< [mm⁻¹]
  double albedo;       ///< σ_s/σ_t
  double g, eta;
  bool slab;
  double thickness;    ///< [mm], ∞ for the half-space
  double entryWeight;  ///< 1 − specular reflectance
  double ux0, uz0;     ///< refracted direction of the beam inside
  double maxPath;      ///< [mm]
};

enum class Exit : std::uint8_t { None, Top, Bottom };

/// What one photon contributed; merged into the tallies in photon order.
struct Outcome {
  double x = 0.0, y = 0.0;  ///< exit point [mm]
  double weight = 0.0;      ///< weight leaving the medium
  double absorbed = 0.0;
  double rouletteNet = 0.0;
  double truncatedWeight = 0.0;
  Exit exit = Exit::None;
  std::uint8_t order = 0;  ///< scattering events before leaving, saturated at 2
  bool truncated = false;
};

/// One photon's random walk (MCML's scheme: implicit capture of absorption, weight roulette,
/// probabilistic Fresnel reflection at the boundaries, the unused part of a step kept after a
/// reflection; Wang, Jacques & Zheng 1995, §3).
Outcome tracePhoton(const Medium& m, Rng& rng, std::uint64_t& interactions) {
  Outcome out;
  double w = m.entryWeight;
  if (w <= 0.0) return out;  // total reflection at entry (η < 1 beyond the critical angle)
  double x = 0.0, y = 0.0, z = 0.0;
  double ux = m.ux0, uy = 0.0, uz = m.uz0;
  double path = 0.0;
  unsigned order = 0;
  const bool fresnel = m.eta != 1.0;
  for (;;) {
    // Free path: exponential with mean 1/σ_t.
    double s = -std::log(rng.uniformPositive()) / m.sigmaT;
    for (;;) {
      double toBoundary = std::numeric_limits<double>::infinity();
      if (uz > 0.0)
        toBoundary = -z / uz;
      else if (uz < 0.0 && m.slab)
        toBoundary = (-m.thickness - z) / uz;
      if (s < toBoundary) {
        x += s * ux;
        y += s * uy;
        z += s * uz;
        path += s;
        break;
      }
      x += toBoundary * ux;
      y += toBoundary * uy;
      path += toBoundary;
      s -= toBoundary;
      const bool top = uz > 0.0;
      z = top ? 0.0 : -m.thickness;
      if (!fresnel || rng.uniform() >= planar_mc::fresnelReflectance(std::abs(uz), m.eta, 1.0)) {
        out.x = x;
        out.y = y;
        out.weight = w;
        out.exit = top ? Exit::Top : Exit::Bottom;
        out.order = static_cast<std::uint8_t>(std::min(order, 2u));
        return out;
      }
      uz = -uz;  // reflected back into the medium; the rest of the step continues
    }
    if (path > m.maxPath) {
      out.truncated = true;
      out.truncatedWeight = w;
      return out;
    }
    // Interaction: deposit the absorbed fraction, scatter the rest (implicit capture).
    ++interactions;
    ++order;
    out.absorbed += w * (1.0 - m.albedo);
    w *= m.albedo;
    const double cosT = planar_mc::sampleHenyeyGreensteinCos(m.g, rng.uniform());
    const double sinT = std::sqrt(std::max(0.0, 1.0 - cosT * cosT));
    const double phi = 2.0 * std::numbers::pi * rng.uniform();
    const double cosP = std::cos(phi), sinP = std::sin(phi);
    // Rotate the direction by (θ, φ) about itself (MCML §3.5, Eqs. 3.26–3.27).
    if (std::abs(uz) > 0.99999) {
      ux = sinT * cosP;
      uy = sinT * sinP;
      uz = uz > 0.0 ? cosT : -cosT;
    } else {
      const double t = std::sqrt(1.0 - uz * uz);
      const double nx = sinT * (ux * uz * cosP - uy * sinP) / t + ux * cosT;
      const double ny = sinT * (uy * uz * cosP + ux * sinP) / t + uy * cosT;
      uz = -sinT * cosP * t + uz * cosT;
      ux = nx;
      uy = ny;
    }
    if (w < kRouletteThreshold) {
      if (w > 0.0 && rng.uniform() < kRouletteSurvival) {
        out.rouletteNet += w / kRouletteSurvival - w;
        w /= kRouletteSurvival;
      } else {
        out.rouletteNet -= w;
        return out;
      }
    }
  }
}

/// Sums of a per-photon quantity and of its square.
struct Moments {
  double sum = 0.0, sumSq = 0.0;
  void add(double v) {
    sum += v;
    sumSq += v * v;
  }
  McEstimate estimate(double photons, double scale = 1.0) const {
    McEstimate e;
    e.mean = sum / photons * scale;
    if (photons > 1.0) {
      const double mean = sum / photons;
      e.stdErr = std::sqrt(std::max(0.0, sumSq / photons - mean * mean) / (photons - 1.0)) * scale;
    }
    return e;
  }
};

/// Binned tally: per-bin moments.
struct Bins {
  std::vector<Moments> bins;
  explicit Bins(std::size_t n = 0) : bins(n) {}
  void add(std::size_t i, double v) { bins[i].add(v); }
  /// Bin i's estimate, divided by area(i).
  template <class Area>
  McProfile profile(double photons, Area area) const {
    McProfile p;
    p.mean.resize(bins.size());
    p.stdErr.resize(bins.size());
    for (std::size_t i = 0; i < bins.size(); ++i) {
      const McEstimate e = bins[i].estimate(photons, 1.0 / area(i));
      p.mean[i] = e.mean;
      p.stdErr[i] = e.stdErr;
    }
    return p;
  }
};

/// Bin index of v in `bins` equal bins over [lo, hi), or −1 outside.
int binOf(double v, double lo, double hi, int bins) {
  if (!(v >= lo && v < hi)) return -1;
  return std::min(bins - 1, static_cast<int>((v - lo) / (hi - lo) * bins));
}

/// All tallies; photons are added strictly in index order, which makes results bitwise
/// reproducible for every thread count.
class Tally {
 public:
  explicit Tally(const PlanarMcSetup& s)
      : s_(s),
        x_(static_cast<std::size_t>(s.xBins)),
        xSingle_(static_cast<std::size_t>(s.xBins)),
        map_(static_cast<std::size_t>(s.mapBins) * static_cast<std::size_t>(s.mapBins)),
        radial_(static_cast<std::size_t>(s.rBins)) {}

  void add(const Outcome& o) {
    const bool top = o.exit == Exit::Top, bottom = o.exit == Exit::Bottom;
    reflected_.add(top ? o.weight : 0.0);
    transmitted_.add(bottom ? o.weight : 0.0);
    absorbed_.add(o.absorbed);
    single_.add(top && o.order == 1 ? o.weight : 0.0);
    unscatteredR_.add(top && o.order == 0 ? o.weight : 0.0);
    unscatteredT_.add(bottom && o.order == 0 ? o.weight : 0.0);
    roulette_.add(o.rouletteNet);
    if (o.truncated) {
      ++truncatedPaths_;
      truncatedWeight_ += o.truncatedWeight;
    }
    if (!top) return;
    if (s_.xBins > 0 && std::abs(o.y) < 0.5 * s_.stripWidthMm) {
      const int i = binOf(o.x, s_.xMinMm, s_.xMaxMm, s_.xBins);
      if (i >= 0) {
        x_.add(static_cast<std::size_t>(i), o.weight);
        if (o.order == 1) xSingle_.add(static_cast<std::size_t>(i), o.weight);
      }
    }
    if (s_.mapBins > 0) {
      const double h = s_.mapHalfWidthMm;
      const int ix = binOf(o.x, -h, h, s_.mapBins), iy = binOf(o.y, -h, h, s_.mapBins);
      if (ix >= 0 && iy >= 0)
        map_.add(static_cast<std::size_t>(iy) * static_cast<std::size_t>(s_.mapBins) + static_cast<std::size_t>(ix),
                 o.weight);
    }
    if (s_.rBins > 0) {
      const int i = binOf(std::hypot(o.x, o.y), 0.0, s_.rMaxMm, s_.rBins);
      if (i >= 0) radial_.add(static_cast<std::size_t>(i), o.weight);
    }
  }

  PlanarMcResult result(double specular, std::uint64_t interactions) const {
    const auto n = static_cast<double>(s_.photons);
    PlanarMcResult r;
    r.photons = s_.photons;
    r.specularReflectance = specular;
    r.diffuseReflectance = reflected_.estimate(n);
    r.transmittance = transmitted_.estimate(n);
    r.absorbed = absorbed_.estimate(n);
    r.singleScatterReflectance = single_.estimate(n);
    r.unscatteredReflectance = unscatteredR_.estimate(n);
    r.unscatteredTransmittance = unscatteredT_.estimate(n);
    r.rouletteNet = roulette_.estimate(n);
    r.truncatedPaths = truncatedPaths_;
    r.truncatedWeight = truncatedWeight_ / n;
    r.interactions = interactions;
    const double xArea = (s_.xMaxMm - s_.xMinMm) / std::max(1, s_.xBins) * s_.stripWidthMm;
    r.xProfile = x_.profile(n, [&](std::size_t) { return xArea; });
    r.xProfileSingle = xSingle_.profile(n, [&](std::size_t) { return xArea; });
    const double cell = 2.0 * s_.mapHalfWidthMm / std::max(1, s_.mapBins);
    r.map = map_.profile(n, [&](std::size_t) { return cell * cell; });
    const double dr = s_.rMaxMm / std::max(1, s_.rBins);
    r.radial = radial_.profile(n, [&](std::size_t i) {
      const double r0 = dr * static_cast<double>(i), r1 = r0 + dr;
      return std::numbers::pi * (r1 * r1 - r0 * r0);
    });
    return r;
  }

 private:
  const PlanarMcSetup& s_;
  Moments reflected_, transmitted_, absorbed_, single_, unscatteredR_, unscatteredT_, roulette_;
  std::uint64_t truncatedPaths_ = 0;
  double truncatedWeight_ = 0.0;
  Bins x_, xSingle_, map_, radial_;
};

std::string fmt(double v) {
  std::ostringstream os;
  os.precision(17);
  os << v;
  return os.str();
}

void require(bool ok, const std::string& message) {
  if (!ok) throw std::invalid_argument("planar MC: " + message);
}

}  // namespace

void validatePlanarMcSetup(const PlanarMcSetup& s) {
  require(std::isfinite(s.sigma_a) && s.sigma_a >= 0.0, "sigma_a must be finite and >= 0 (" + fmt(s.sigma_a) + ")");
  require(std::isfinite(s.sigma_s) && s.sigma_s >= 0.0, "sigma_s must be finite and >= 0 (" + fmt(s.sigma_s) + ")");
  require(s.sigma_a + s.sigma_s > 0.0, "sigma_a + sigma_s must be > 0 (nothing scatters or absorbs)");
  require(std::abs(s.g) < 1.0, "g must be in (-1, 1) (" + fmt(s.g) + ")");
  require(std::isfinite(s.eta) && s.eta > 0.0, "eta must be finite and > 0 (" + fmt(s.eta) + ")");
  require(s.thicknessMm > 0.0, "thicknessMm must be > 0, or infinity for a half-space (" + fmt(s.thicknessMm) + ")");
  require(std::abs(s.thetaDeg) < 90.0, "thetaDeg must be in (-90, 90) (" + fmt(s.thetaDeg) + ")");
  require(s.photons >= 1, "photons must be >= 1");
  require(s.threads >= 0, "threads must be >= 0 (" + std::to_string(s.threads) + ")");
  require(std::isfinite(s.maxPathLengthMfp) && s.maxPathLengthMfp > 0.0,
          "maxPathLengthMfp must be finite and > 0 (" + fmt(s.maxPathLengthMfp) + ")");
  require(s.xBins >= 0 && s.xBins <= kMaxProfileBins,
          "xBins must be in [0, " + std::to_string(kMaxProfileBins) + "] (" + std::to_string(s.xBins) + ")");
  if (s.xBins > 0) {
    require(std::isfinite(s.xMinMm) && std::isfinite(s.xMaxMm) && s.xMinMm < s.xMaxMm,
            "xMinMm < xMaxMm, both finite, is required (" + fmt(s.xMinMm) + ", " + fmt(s.xMaxMm) + ")");
    require(std::isfinite(s.stripWidthMm) && s.stripWidthMm > 0.0,
            "stripWidthMm must be finite and > 0 (" + fmt(s.stripWidthMm) + ")");
  }
  require(s.mapBins >= 0 && s.mapBins <= kMaxMapBins,
          "mapBins must be in [0, " + std::to_string(kMaxMapBins) + "] (" + std::to_string(s.mapBins) + ")");
  if (s.mapBins > 0)
    require(std::isfinite(s.mapHalfWidthMm) && s.mapHalfWidthMm > 0.0,
            "mapHalfWidthMm must be finite and > 0 (" + fmt(s.mapHalfWidthMm) + ")");
  require(s.rBins >= 0 && s.rBins <= kMaxProfileBins,
          "rBins must be in [0, " + std::to_string(kMaxProfileBins) + "] (" + std::to_string(s.rBins) + ")");
  if (s.rBins > 0)
    require(std::isfinite(s.rMaxMm) && s.rMaxMm > 0.0, "rMaxMm must be finite and > 0 (" + fmt(s.rMaxMm) + ")");
}

PlanarMcResult simulatePlanarMedium(const PlanarMcSetup& setup) {
  validatePlanarMcSetup(setup);

  Medium m{};
  m.sigmaT = setup.sigma_a + setup.sigma_s;
  m.albedo = setup.sigma_s / m.sigmaT;
  m.g = setup.g;
  m.eta = setup.eta;
  m.slab = std::isfinite(setup.thicknessMm);
  m.thickness = setup.thicknessMm;
  m.maxPath = setup.maxPathLengthMfp / m.sigmaT;
  const double theta = setup.thetaDeg * std::numbers::pi / 180.0;
  const double cosI = std::cos(theta), sinI = std::sin(theta);
  const double specular = planar_mc::fresnelReflectance(cosI, 1.0, setup.eta);
  m.entryWeight = 1.0 - specular;
  const double sinT = sinI / setup.eta;  // Snell's law; |sinT| ≥ 1 means nothing enters
  m.ux0 = std::abs(sinT) < 1.0 ? sinT : 0.0;
  m.uz0 = -std::sqrt(std::max(0.0, 1.0 - m.ux0 * m.ux0));

  std::uint64_t seedState = setup.seed;
  const std::uint64_t seedKey = splitmix64(seedState);
  const std::uint64_t units = (setup.photons + kPhotonsPerUnit - 1) / kPhotonsPerUnit;
  const unsigned hardware = std::max(1u, std::thread::hardware_concurrency());
  const auto threads = static_cast<unsigned>(
      std::min<std::uint64_t>(setup.threads > 0 ? static_cast<unsigned>(setup.threads) : hardware, units));
  // A unit may run at most this far ahead of the oldest unmerged one, which bounds the memory of
  // finished-but-unmerged units when one path is very long.
  const std::uint64_t maxAhead = 4ull * threads + 16;

  Tally tally(setup);
  std::uint64_t interactions = 0;
  std::atomic<std::uint64_t> nextUnit{0};
  std::mutex mutex;
  std::condition_variable merged;
  std::uint64_t mergedUnits = 0;
  std::map<std::uint64_t, std::pair<std::vector<Outcome>, std::uint64_t>> pending;
  std::exception_ptr failure;
  bool failed = false;

  auto worker = [&] {
    try {
      for (;;) {
        const std::uint64_t unit = nextUnit.fetch_add(1);
        if (unit >= units) return;
        {
          std::unique_lock lock(mutex);
          merged.wait(lock, [&] { return failed || unit < mergedUnits + maxAhead; });
          if (failed) return;
        }
        const std::uint64_t first = unit * kPhotonsPerUnit;
        const std::uint64_t last = std::min(setup.photons, first + kPhotonsPerUnit);
        std::vector<Outcome> outcomes;
        outcomes.reserve(static_cast<std::size_t>(last - first));
        std::uint64_t unitInteractions = 0;
        for (std::uint64_t p = first; p < last; ++p) {
          Rng rng(seedKey, p);
          outcomes.push_back(tracePhoton(m, rng, unitInteractions));
        }
        std::lock_guard lock(mutex);
        pending.emplace(unit, std::make_pair(std::move(outcomes), unitInteractions));
        // Merge every finished unit that is next in order: photon order, whatever the threads.
        for (auto it = pending.begin(); it != pending.end() && it->first == mergedUnits; it = pending.erase(it)) {
          for (const Outcome& o : it->second.first) tally.add(o);
          interactions += it->second.second;
          ++mergedUnits;
        }
        merged.notify_all();
      }
    } catch (...) {
      std::lock_guard lock(mutex);
      if (!failure) failure = std::current_exception();
      failed = true;
      merged.notify_all();
    }
  };

  std::vector<std::thread> pool;
  pool.reserve(threads);
  try {
    for (unsigned t = 0; t < threads; ++t) pool.emplace_back(worker);
  } catch (...) {  // could not start a thread: stop the others, then report
    {
      std::lock_guard lock(mutex);
      if (!failure) failure = std::current_exception();
      failed = true;
      nextUnit = units;
    }
    merged.notify_all();
  }
  for (std::thread& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
  return tally.result(specular, interactions);
}

}  // namespace tallow::sss
