#include "sss/maps/environment_lights.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "gpu/hdr_io.h"

namespace tallow::sss {
namespace {

constexpr double kPi = std::numbers::pi;

/// Weights of the cut and their summed-area table, in double.
class WeightTable {
 public:
  explicit WeightTable(const gpu::Image& map) : w_(map.width), h_(map.height) {
    sat_.assign(static_cast<std::size_t>(w_ + 1) * (h_ + 1), 0.0);
    rowSolidAngle_.resize(static_cast<std::size_t>(h_));
    for (int y = 0; y < h_; ++y) {
      rowSolidAngle_[static_cast<std::size_t>(y)] =
          (2.0 * kPi / w_) * (std::cos(kPi * y / h_) - std::cos(kPi * (y + 1) / h_));
      for (int x = 0; x < w_; ++x) {
        const double l = environmentLuminance(map.at(x, y));
        const double wgt = (std::isfinite(l) && l > 0.0) ? l * rowSolidAngle_[static_cast<std::size_t>(y)] : 0.0;
        sat(x + 1, y + 1) = wgt + sat(x, y + 1) + sat(x + 1, y) - sat(x, y);
      }
    }
  }

  /// Σ weight over [x0, x1) × [y0, y1).
  double sum(int x0, int y0, int x1, int y1) const {
    return std::max(0.0, sat(x1, y1) - sat(x0, y1) - sat(x1, y0) + sat(x0, y0));
  }
  double rowSolidAngle(int y) const { return rowSolidAngle_[static_cast<std::size_t>(y)]; }

 private:
  int w_, h_;
  std::vector<double> sat_;
  std::vector<double> rowSolidAngle_;
  double& sat(int x, int y) { return sat_[static_cast<std::size_t>(y) * (w_ + 1) + x]; }
  double sat(int x, int y) const { return sat_[static_cast<std::size_t>(y) * (w_ + 1) + x]; }
};

struct Cutter {
  const WeightTable& table;
  int width, height;
  std::vector<glm::ivec4> regions;

  void cut(glm::ivec4 r, int lights) {
    const int w = r.z - r.x, h = r.w - r.y;
    if (lights <= 1 || (w <= 1 && h <= 1)) {
      regions.push_back(r);
      return;
    }
    const int low = lights / 2;
    const double fraction = static_cast<double>(low) / lights;
    // Angular extents: azimuth scaled by sin θ of the middle row, polar as is.
    const double midTheta = kPi * 0.5 * (r.y + r.w) / height;
    const double across = (2.0 * kPi * w / width) * std::sin(midTheta);
    const double down = kPi * h / height;
    const bool splitX = w > 1 && (h <= 1 || across >= down);
    const double total = table.sum(r.x, r.y, r.z, r.w);
    const int begin = splitX ? r.x : r.y, end = splitX ? r.z : r.w;
    int best = (begin + end) / 2;
    if (total > 0.0) {
      // The cut k ∈ (begin, end) whose lower part's weight is closest to fraction × total.
      double bestError = 2.0 * total + 1.0;
      const double target = fraction * total;
      for (int k = begin + 1; k < end; ++k) {
        const double part = splitX ? table.sum(r.x, r.y, k, r.w) : table.sum(r.x, r.y, r.z, k);
        const double error = std::abs(part - target);
        if (error < bestError) {
          bestError = error;
          best = k;
        }
        if (part > target) break;  // the lower part only grows with k
      }
    }
    if (splitX) {
      cut({r.x, r.y, best, r.w}, low);
      cut({best, r.y, r.z, r.w}, lights - low);
    } else {
      cut({r.x, r.y, r.z, best}, low);
      cut({r.x, best, r.z, r.w}, lights - low);
    }
  }
};

glm::dvec3 rotateY(const glm::dvec3& d, double rotationDeg) {
  const double a = rotationDeg * kPi / 180.0;
  const double c = std::cos(a), s = std::sin(a);
  return {c * d.x + s * d.z, d.y, -s * d.x + c * d.z};
}

}  // namespace

glm::dvec3 environmentDirection(double u, double v, double rotationDeg) {
  const double theta = kPi * v, phi = 2.0 * kPi * (u - 0.5);
  const glm::dvec3 d(std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi));
  return rotateY(d, rotationDeg);
}

std::vector<EnvironmentLight> medianCutEnvironment(const gpu::Image& map, int count, double rotationDeg) {
  if (map.width < 1 || map.height < 1 ||
      map.pixels.size() != static_cast<std::size_t>(map.width) * static_cast<std::size_t>(map.height))
    throw std::invalid_argument("environment map: empty or inconsistent image");
  if (count < 1) throw std::invalid_argument("environment map: the number of lights must be at least 1");
  const WeightTable table(map);
  Cutter cutter{table, map.width, map.height, {}};
  cutter.cut({0, 0, map.width, map.height}, count);

  std::vector<EnvironmentLight> lights;
  for (const glm::ivec4& r : cutter.regions) {
    glm::dvec3 rgb(0.0), centroid(0.0);
    double weight = 0.0, solidAngle = 0.0, brightest = -1.0;
    glm::dvec3 brightestDir(0.0, 1.0, 0.0);
    for (int y = r.y; y < r.w; ++y) {
      const double dOmega = table.rowSolidAngle(y);
      solidAngle += dOmega * (r.z - r.x);
      for (int x = r.x; x < r.z; ++x) {
        const glm::vec4 c = map.at(x, y);
        const glm::dvec3 dir = environmentDirection((x + 0.5) / map.width, (y + 0.5) / map.height, 0.0);
        for (int k = 0; k < 3; ++k)
          if (std::isfinite(c[k]) && c[k] > 0.0f) rgb[k] += c[k] * dOmega;
        const double l = environmentLuminance(c);
        const double wgt = (std::isfinite(l) && l > 0.0) ? l * dOmega : 0.0;
        weight += wgt;
        centroid += wgt * dir;
        if (wgt > brightest) {
          brightest = wgt;
          brightestDir = dir;
        }
      }
    }
    if (weight <= 0.0) continue;  // no power: no light
    const double length = glm::length(centroid);
    const glm::dvec3 dir = length > 1e-9 * weight ? centroid / length : brightestDir;
    EnvironmentLight light;
    light.direction = glm::vec3(glm::normalize(rotateY(dir, rotationDeg)));
    light.irradiance = glm::vec3(rgb);
    light.region = r;
    light.solidAngle = solidAngle;
    lights.push_back(light);
  }
  std::stable_sort(lights.begin(), lights.end(),
                   [](const EnvironmentLight& a, const EnvironmentLight& b) { return a.solidAngle < b.solidAngle; });
  return lights;
}

std::vector<Light> environmentLights(const gpu::Image& map, const Environment& env) {
  std::vector<Light> out;
  int index = 0;
  for (const EnvironmentLight& e : medianCutEnvironment(map, env.lights, env.rotationDeg)) {
    Light l;
    l.kind = LightKind::Directional;
    l.direction = e.direction;
    l.intensity = e.irradiance * env.scale;
    l.castsShadows = index++ < kEnvironmentShadowLights;
    out.push_back(l);
  }
  return out;
}

std::vector<Light> environmentLights(const Environment& env) {
  const gpu::Image map = gpu::readHdr(env.file);
  try {
    return environmentLights(map, env);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(env.file.string() + ": " + e.what());
  }
}

}  // namespace tallow::sss
