#include "sss/reference/reference_integrator.h"

#include <embree3/rtcore.h>
#include <tbb/blocked_range.h>
#include <tbb/blocked_range2d.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <vector>

#include "geometry/cpu_mesher.h"
#include "gpu/hdr_io.h"
#include "sss/bssrdf/bssrdf.h"
#include "sss/field_source.h"
#include "sss/flame_pass.h"
#include "sss/pixel_jitter.h"
#include "sss/reference/parallel_for.h"
#include "sss/scene_geometry.h"
#include "sss/translucent_slots.h"
#include "sss/view_setup.h"

namespace tallow::sss {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kMmPerM = 1000.0;

// Counter-based random numbers (SplitMix64 finaliser, nested per coordinate): any number of any
// stream is one pure function call, so the result does not depend on threads or scheduling.
std::uint64_t mix64(std::uint64_t z) {
  z += 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}
std::uint64_t streamHash(std::uint64_t seed, std::uint64_t a, std::uint64_t b, std::uint64_t c, std::uint64_t d) {
  return mix64(seed ^ mix64(a ^ mix64(b ^ mix64(c ^ mix64(d)))));
}
double unit(std::uint64_t h) { return static_cast<double>(h >> 11) * 0x1.0p-53; }  // [0, 1)

/// One object's triangles in world units (metres), with per-vertex unit normals.
struct WorldMesh {
  int objectIndex = 0;
  std::vector<glm::dvec3> positions, normals;
  std::vector<std::array<std::uint32_t, 3>> triangles;
};

WorldMesh placeMesh(int objectIndex, geometry::TriangleMesh mesh, const glm::mat4& model) {
  if (mesh.normals.size() != mesh.positions.size()) geometry::computeVertexNormals(mesh);
  WorldMesh w;
  w.objectIndex = objectIndex;
  const glm::dmat4 m(model);
  const glm::dmat3 normalMatrix = glm::transpose(glm::inverse(glm::dmat3(m)));
  for (const glm::vec3& p : mesh.positions) w.positions.emplace_back(m * glm::dvec4(glm::dvec3(p), 1.0));
  for (const glm::vec3& n : mesh.normals) {
    const glm::dvec3 t = normalMatrix * glm::dvec3(n);
    const double l = glm::length(t);
    w.normals.push_back(l > 0.0 ? t / l : glm::dvec3(0.0, 1.0, 0.0));
  }
  w.triangles = std::move(mesh.triangles);
  return w;
}

/// The scene's shapes as drawn at time t: meshes and primitives by SceneGeometry::shapeMesh, field
/// objects as `drawn` holds them (the GPU's triangles) or else meshed on the CPU (geometry::meshOnCpu)
/// from the lattice the GPU contours (a blob's and a candle's the GPU fills itself from the same
/// lines, shaders/fields/blob.glsl and candle.glsl: equal up to float rounding).
std::vector<WorldMesh> worldMeshes(const Scene& scene, int fieldRes, double timeS, const FieldMeshes& drawn) {
  std::vector<WorldMesh> out;
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const SceneObject& o = scene.objects[i];
    if (o.shape == ShapeKind::Field) {
      const FieldSource source(o);
      geometry::TriangleMesh mesh;
      if (const auto given = drawn.find(static_cast<int>(i)); given != drawn.end()) {
        mesh = given->second;
      } else {
        const geometry::SampledLattice lattice = source.sample(timeS, fieldRes);
        mesh = geometry::meshOnCpu(lattice, *source.at(timeS));
      }
      out.push_back(placeMesh(static_cast<int>(i), std::move(mesh), SceneGeometry::modelMatrix(o, source.bounds())));
    } else {
      geometry::TriangleMesh mesh = SceneGeometry::shapeMesh(o);
      const geometry::Aabb local = mesh.bounds();
      out.push_back(placeMesh(static_cast<int>(i), std::move(mesh), SceneGeometry::modelMatrix(o, local)));
    }
  }
  return out;
}

/// Embree 3 scene of every triangle; geometry ID = index into the WorldMesh list.
class RayScene {
 public:
  explicit RayScene(const std::vector<WorldMesh>& meshes) {
    device_ = rtcNewDevice(nullptr);
    if (!device_) throw std::runtime_error("reference: Embree could not create a device");
    scene_ = rtcNewScene(device_);
    for (std::size_t k = 0; k < meshes.size(); ++k) {
      const WorldMesh& m = meshes[k];
      RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
      auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                            3 * sizeof(float), std::max<std::size_t>(m.positions.size(), 1)));
      for (std::size_t i = 0; i < m.positions.size(); ++i)
        for (int c = 0; c < 3; ++c) v[3 * i + static_cast<std::size_t>(c)] = static_cast<float>(m.positions[i][c]);
      auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                 3 * sizeof(unsigned), m.triangles.size()));
      for (std::size_t t = 0; t < m.triangles.size(); ++t)
        for (int c = 0; c < 3; ++c) idx[3 * t + static_cast<std::size_t>(c)] = m.triangles[t][static_cast<std::size_t>(c)];
      rtcCommitGeometry(g);
      rtcAttachGeometryByID(scene_, g, static_cast<unsigned>(k));
      rtcReleaseGeometry(g);
      triangles_ += m.triangles.size();
    }
    rtcCommitScene(scene_);
  }
  ~RayScene() {
    if (scene_) rtcReleaseScene(scene_);
    if (device_) rtcReleaseDevice(device_);
  }
  RayScene(const RayScene&) = delete;
  RayScene& operator=(const RayScene&) = delete;

  struct Hit {
    unsigned geom = RTC_INVALID_GEOMETRY_ID, prim = 0;
    double u = 0, v = 0, t = 0;
  };
  std::optional<Hit> intersect(const glm::dvec3& origin, const glm::dvec3& dir, double tnear, double tfar) const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRayHit rh{};
    setRay(rh.ray, origin, dir, tnear, tfar);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene_, &ctx, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
    return Hit{rh.hit.geomID, rh.hit.primID, rh.hit.u, rh.hit.v, rh.ray.tfar};
  }
  bool occluded(const glm::dvec3& origin, const glm::dvec3& dir, double tfar) const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRay r{};
    setRay(r, origin, dir, 0.0, tfar);
    rtcOccluded1(scene_, &ctx, &r);
    return r.tfar < 0.0f;
  }
  std::size_t triangles() const { return triangles_; }

 private:
  static void setRay(RTCRay& r, const glm::dvec3& o, const glm::dvec3& d, double tnear, double tfar) {
    r.org_x = static_cast<float>(o.x);
    r.org_y = static_cast<float>(o.y);
    r.org_z = static_cast<float>(o.z);
    r.dir_x = static_cast<float>(d.x);
    r.dir_y = static_cast<float>(d.y);
    r.dir_z = static_cast<float>(d.z);
    r.tnear = static_cast<float>(tnear);
    r.tfar = std::isfinite(tfar) ? static_cast<float>(tfar) : std::numeric_limits<float>::infinity();
    r.mask = 0xffffffffu;
    r.flags = 0;
    r.time = 0.0f;
  }
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  std::size_t triangles_ = 0;
};

/// A light as seen from a point: unit direction toward it, the irradiance it gives a surface facing
/// it (E for directional lights, I/d² for point lights) and the distance a shadow ray may travel.
struct Incident {
  glm::dvec3 toLight;
  glm::dvec3 irradiance;
  double distance;
};
Incident incident(const Light& l, const glm::dvec3& x) {
  if (l.kind == LightKind::Directional)
    return {glm::normalize(glm::dvec3(l.direction)), glm::dvec3(l.intensity), std::numeric_limits<double>::infinity()};
  const glm::dvec3 d = glm::dvec3(l.position) - x;
  const double d2 = std::max(glm::dot(d, d), 1e-300);
  const double dist = std::sqrt(d2);
  return {d / dist, glm::dvec3(l.intensity) / d2, dist};
}

/// Lat-long environment radiance in the mirror direction, as surface.frag samples it (bilinear,
/// u wrapping, v clamped).
class EnvironmentLookup {
 public:
  EnvironmentLookup(const Environment& env) : map_(gpu::readHdr(env.file)), env_(env) {
    if (map_.width < 1 || map_.height < 1) throw std::runtime_error(env.file.string() + ": empty environment map");
  }
  glm::dvec3 radiance(const glm::dvec3& d) const {
    const double a = env_.rotationDeg * kPi / 180.0;
    const double c = std::cos(a), s = std::sin(a);
    const glm::dvec3 r(c * d.x - s * d.z, d.y, s * d.x + c * d.z);
    const double theta = std::acos(std::clamp(r.y, -1.0, 1.0));
    const double phi = std::atan2(r.x, -r.z);
    const double u = phi / (2.0 * kPi) + 0.5, v = theta / kPi;
    const double fx = u * map_.width - 0.5, fy = std::clamp(v * map_.height - 0.5, 0.0, map_.height - 1.0);
    const double x0 = std::floor(fx), y0 = std::floor(fy);
    const double tx = fx - x0, ty = fy - y0;
    auto at = [&](double x, double y) {
      int xi = static_cast<int>(x) % map_.width;
      if (xi < 0) xi += map_.width;
      const int yi = std::clamp(static_cast<int>(y), 0, map_.height - 1);
      return glm::dvec3(glm::vec3(map_.at(xi, yi)));
    };
    const glm::dvec3 top = glm::mix(at(x0, y0), at(x0 + 1, y0), tx);
    const glm::dvec3 bottom = glm::mix(at(x0, y0 + 1), at(x0 + 1, y0 + 1), tx);
    return static_cast<double>(env_.scale) * glm::mix(top, bottom, ty);
  }

 private:
  gpu::Image map_;
  Environment env_;
};

/// A material per band, in double.
struct MaterialBands {
  std::array<double, 3> sigmaA{}, sigmaS{}, g{};
  double eta = 1.3;
};
MaterialBands materialBands(const Material& m) {
  MaterialBands b;
  for (std::size_t c = 0; c < 3; ++c) {
    b.sigmaA[c] = m.sigma_a[static_cast<int>(c)];
    b.sigmaS[c] = m.sigma_s[static_cast<int>(c)];
    b.g[c] = m.g[static_cast<int>(c)];
  }
  b.eta = m.eta;
  return b;
}

/// A translucent object: its triangles by area, its materials per band and the Russian-roulette rate.
struct TranslucentObject {
  const WorldMesh* mesh = nullptr;
  std::vector<double> cdf;  ///< cumulative triangle areas [m²]
  double areaMm2 = 0.0;
  MaterialBands solid;                ///< the object's material
  std::optional<MaterialBands> liquid;  ///< a candle's melt pool (sss/translucent_slots.h)
  std::optional<LiquidPart> liquidPart;  ///< where it is
  double rouletteRate = 0.0;  ///< the smallest band's σ_tr of its materials [mm⁻¹]
  double sigmaTpMax = 0.0;    ///< the largest band's σ_t' [mm⁻¹]
  int points = 0;             ///< M of this object

  /// The material at a surface point (world metres, unit normal): the liquid's on the pool.
  const MaterialBands& at(const glm::dvec3& x, const glm::dvec3& n) const {
    return liquidPart && liquidPart->contains(x, n) ? *liquid : solid;
  }
};

/// A point uniform by area on a translucent object: a triangle by its area (binary search in the
/// cumulative areas), then barycentrics (1 − √ξ₁, √ξ₁(1 − ξ₂), √ξ₁ ξ₂); n: the interpolated vertex
/// normal. Random numbers: (stream, pass, object, 3i…3i+2). Empty where the normal vanishes.
struct SurfaceSample {
  glm::dvec3 x, n;  ///< metres, unit
};
std::optional<SurfaceSample> sampleSurface(const TranslucentObject& t, std::uint64_t seed, std::uint64_t stream,
                                           std::uint64_t pass, std::size_t object, int i) {
  const auto ui = static_cast<std::uint64_t>(i);
  const double xiTri = unit(streamHash(seed, stream, pass, object, 3 * ui)) * t.cdf.back();
  const double xi1 = unit(streamHash(seed, stream, pass, object, 3 * ui + 1));
  const double xi2 = unit(streamHash(seed, stream, pass, object, 3 * ui + 2));
  const auto k = static_cast<std::size_t>(std::upper_bound(t.cdf.begin(), t.cdf.end(), xiTri) - t.cdf.begin());
  const auto& tri = t.mesh->triangles[std::min(k, t.cdf.size() - 1)];
  const double su = std::sqrt(xi1);
  const double b0 = 1.0 - su, b1 = su * (1.0 - xi2), b2 = su * xi2;
  const glm::dvec3 x = b0 * t.mesh->positions[tri[0]] + b1 * t.mesh->positions[tri[1]] + b2 * t.mesh->positions[tri[2]];
  const glm::dvec3 n = b0 * t.mesh->normals[tri[0]] + b1 * t.mesh->normals[tri[1]] + b2 * t.mesh->normals[tri[2]];
  if (!(glm::length(n) > 0.0)) return std::nullopt;
  return SurfaceSample{x, glm::normalize(n)};
}

/// One surface point of a pass and the lights that reach it.
struct LitPoint {
  glm::dvec3 xMm, n;
  std::vector<std::pair<glm::dvec3, glm::dvec3>> lights;  ///< (w_l, L F_t(cos θ_l) cos θ_l per band)
};

/// A cell of the uniform grid the lit points of one object and pass are sorted into: the bounds
/// of its points [mm] and their range in the sorted list. Russian roulette is first played per
/// cell with Q = exp(−σ d_min) (d_min: distance from x_o to the bounds, so Q ≥ every q_i inside),
/// then per point with q_i/Q: each point survives with probability q_i as before, and far cells
/// cost one test each.
struct PointCell {
  glm::dvec3 lo{std::numeric_limits<double>::max()}, hi{-std::numeric_limits<double>::max()};
  std::size_t begin = 0, end = 0;
};

/// Sorts `points` by grid cell (edge ≥ 1/σ, at most 128 cells per axis) and returns the cells.
std::vector<PointCell> sortIntoCells(std::vector<LitPoint>& points, double sigma) {
  std::vector<PointCell> cells;
  if (points.empty()) return cells;
  glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  for (const LitPoint& p : points) {
    lo = glm::min(lo, p.xMm);
    hi = glm::max(hi, p.xMm);
  }
  const glm::dvec3 extent = hi - lo;
  const double largest = std::max({extent.x, extent.y, extent.z, 1e-9});
  const double h = std::max(sigma > 0.0 ? 1.0 / sigma : largest, largest / 128.0);
  auto key = [&](const glm::dvec3& x) {
    const glm::dvec3 c = glm::floor((x - lo) / h);
    const auto clampAxis = [](double v) { return static_cast<std::uint64_t>(std::clamp(v, 0.0, 1023.0)); };
    return (clampAxis(c.x) << 20) | (clampAxis(c.y) << 10) | clampAxis(c.z);
  };
  std::vector<std::pair<std::uint64_t, std::size_t>> order(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) order[i] = {key(points[i].xMm), i};
  std::sort(order.begin(), order.end());
  std::vector<LitPoint> sorted;
  sorted.reserve(points.size());
  for (std::size_t i = 0; i < order.size(); ++i) {
    if (i == 0 || order[i].first != order[i - 1].first) {
      cells.emplace_back();
      cells.back().begin = i;
    }
    sorted.push_back(std::move(points[order[i].second]));
    PointCell& c = cells.back();
    c.lo = glm::min(c.lo, sorted.back().xMm);
    c.hi = glm::max(c.hi, sorted.back().xMm);
    c.end = i + 1;
  }
  points = std::move(sorted);
  return cells;
}

// Random stream ids (the first coordinate of streamHash after the seed); each use has its own.
constexpr std::uint64_t kStreamLitPoints = 1;     ///< lit points' positions
constexpr std::uint64_t kStreamPixelPoint = 2;    ///< a pixel's roulette per point
constexpr std::uint64_t kStreamPixelCell = 3;     ///< a pixel's roulette per cell
constexpr std::uint64_t kStreamEmitters = 4;      ///< emitter points' positions (emergent light)
constexpr std::uint64_t kStreamEmitterPoint = 5;  ///< an emitter's roulette per point
constexpr std::uint64_t kStreamEmitterCell = 6;   ///< an emitter's roulette per cell

/// The random numbers of one gather: the stream ids of the roulette per cell and per point and the
/// gathering point's own index (pixel, or object and emitter).
struct GatherStreams {
  std::uint64_t cell, point, index;
};

/// One pass's estimate of the scattered radiosity B(x_o) [W/m²] of Eq. 7 from the lit points of
/// object t (sorted into `cells`): π (A/M) Σ_i [u_i < q_i]/q_i Σ_ℓ S_d(x_i, w_ℓ; x_o) e_{i,ℓ} with
/// q_i = exp(−σ_tr r_i), the roulette played per cell first (docs/reference.md, The estimator).
/// Camera pixels and emitter points (emergent light) both gather through this.
/// x_o's material `mo` gives the BSSRDF (a pool point exits through the liquid; light entered
/// anywhere on the object).
glm::dvec3 gatherRadiosity(const TranslucentObject& t, const MaterialBands& mo, const std::vector<LitPoint>& points,
                           const std::vector<PointCell>& cells, const glm::dvec3& xoMm, const glm::dvec3& no,
                           BssrdfModel model, std::uint64_t seed, std::uint64_t pass, const GatherStreams& streams) {
  glm::dvec3 sum(0.0);
  for (std::size_t ci = 0; ci < cells.size(); ++ci) {
    const PointCell& cell = cells[ci];
    const glm::dvec3 nearest = glm::clamp(xoMm, cell.lo, cell.hi);
    const double cellSurvive = std::exp(-t.rouletteRate * glm::length(xoMm - nearest));
    if (cellSurvive < 1.0 && unit(streamHash(seed, streams.cell, pass, streams.index, ci)) >= cellSurvive) continue;
    for (std::size_t i = cell.begin; i < cell.end; ++i) {
      const LitPoint& p = points[i];
      const double r = glm::length(xoMm - p.xMm);
      const double survive = std::exp(-t.rouletteRate * r);
      const double conditional = survive / cellSurvive;
      if (conditional < 1.0 && unit(streamHash(seed, streams.point, pass, streams.index, i)) >= conditional) continue;
      for (const auto& [wl, e] : p.lights) {
        for (int c = 0; c < 3; ++c) {
          const auto cc = static_cast<std::size_t>(c);
          if (!(e[c] > 0.0)) continue;
          const BssrdfConfig cfg{p.xMm, p.n, wl, xoMm, no, mo.sigmaA[cc], mo.sigmaS[cc], mo.g[cc], mo.eta};
          sum[c] += evaluateBssrdf<double>(model, cfg).sdClamped * e[c] / survive;
        }
      }
    }
  }
  return kPi * t.areaMm2 / t.points * sum;
}

/// An emitter point of one pass (emergent light): where the light leaves the object, its B̂, and
/// its share A/N of the object's area.
struct Emitter {
  glm::dvec3 x, n;          ///< metres, unit outward normal
  glm::dvec3 radiosity;     ///< B̂(x) [W/m²]
  double eta = 1.3;
  double areaM2 = 0.0;      ///< A/N
};

/// What a camera ray through a pixel centre sees; the same in every pass.
struct PixelHit {
  int slot = -1;               ///< translucent object, or −1 (then `base` is the whole radiance)
  const MaterialBands* material = nullptr;  ///< x_o's (the liquid's on a candle's pool)
  glm::dvec3 xoMm{0.0}, no{0.0};
  double transmit = 0.0;       ///< F_t(cos θ_o)/π
  glm::dvec3 base{0.0};        ///< background, opaque shading or the specular reflection
  bool receiver = false;       ///< an opaque surface (the emergent light's receivers)
  glm::dvec3 xr{0.0}, nr{0.0}, albedo{0.0};  ///< receiver point [m], normal toward the camera, ρ
};

/// The emergent light one pass estimates at a receiver pixel, one bounce onto a Lambertian surface:
/// ρ/π Σ_j (A/N) F_t(cos θ_o)/π B̂(x_j) cos θ_o cos θ_r / d² V(x_j, x_r) (docs/reference.md).
glm::dvec3 emergentRadiance(const PixelHit& px, const std::vector<Emitter>& emitters, const RayScene& rays,
                            double offset) {
  glm::dvec3 sum(0.0);
  const glm::dvec3 origin = px.xr + offset * px.nr;
  for (const Emitter& e : emitters) {
    const glm::dvec3 d = e.x - px.xr;
    const double d2 = glm::dot(d, d);
    if (!(d2 > 0.0)) continue;
    const glm::dvec3 w = d / std::sqrt(d2);  // receiver toward emitter
    const double cosR = glm::dot(px.nr, w), cosO = -glm::dot(e.n, w);
    if (!(cosR > 0.0) || !(cosO > 0.0)) continue;
    const glm::dvec3 toEmitter = e.x + offset * e.n - origin;
    const double length = glm::length(toEmitter);
    if (rays.occluded(origin, toEmitter / length, length - offset)) continue;
    sum += fresnelTransmittance(cosO, e.eta) / kPi * e.radiosity * (cosO * cosR / d2 * e.areaM2);
  }
  return px.albedo / kPi * sum;
}

}  // namespace

ReferenceResult renderReference(const Scene& sceneAsLoaded, const RenderSettings& render,
                                const ReferenceSettings& settings, const ReferenceProgress& progress) {
  if (render.width < 1 || render.height < 1) throw std::invalid_argument("reference: the image size must be at least 1x1");
  if (settings.maxPasses < 0) throw std::invalid_argument("--spp: must be at least 1");
  if (!std::isfinite(settings.relError) || settings.relError < 0.0)
    throw std::invalid_argument("--rel-error: must be a positive number");
  if (settings.maxPasses == 0 && settings.relError == 0.0)
    throw std::invalid_argument("reference: give --spp S (passes) or --rel-error E (relative standard error)");
  if (settings.pointsPerPass < 0) throw std::invalid_argument("--points: must be 0 (automatic) or more");
  if (settings.threads < 0) throw std::invalid_argument("--threads: must be at least 0");
  if (settings.emergentLight && settings.emitterPoints < 1)
    throw std::invalid_argument("--emergent: emitter points per object and pass must be at least 1");
  const auto start = std::chrono::steady_clock::now();

  std::unique_ptr<tbb::global_control> threadLimit;
  if (settings.threads > 0)
    threadLimit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                        static_cast<std::size_t>(settings.threads));

  const Scene scene = sceneAtTime(sceneAsLoaded, settings.timeS);
  const std::vector<WorldMesh> meshes = worldMeshes(scene, render.fieldRes, settings.timeS, settings.fieldMeshes);
  const RayScene rays(meshes);
  geometry::Aabb bounds;
  for (const WorldMesh& m : meshes)
    for (const glm::dvec3& p : m.positions) bounds.extend(glm::vec3(p));
  const double diagonal = bounds.empty() ? 1.0 : std::max(static_cast<double>(glm::length(bounds.size())), 1e-6);
  const double offset = 1e-5 * diagonal;  // shadow-ray start above the surface [m]

  const BssrdfModel model = render.sss.model;
  const bool sssOn = render.sss.method != SssMethod::Albedo;
  std::optional<EnvironmentLookup> environment;
  if (scene.environment && render.specular) environment.emplace(*scene.environment);
  const std::vector<FlameSheet> flames = render.specular ? flameSheets(scene, settings.timeS, render)
                                                         : std::vector<FlameSheet>{};

  // Translucent objects, by slot.
  std::vector<TranslucentObject> objects;
  std::vector<int> slotOfMesh(meshes.size(), -1);
  for (std::size_t k = 0; k < meshes.size(); ++k) {
    const SceneObject& o = scene.objects[static_cast<std::size_t>(meshes[k].objectIndex)];
    if (!o.translucent || !sssOn) continue;
    TranslucentObject t;
    t.mesh = &meshes[k];
    double sum = 0.0;
    for (const auto& tri : meshes[k].triangles) {
      const glm::dvec3& a = meshes[k].positions[tri[0]];
      sum += 0.5 * glm::length(glm::cross(meshes[k].positions[tri[1]] - a, meshes[k].positions[tri[2]] - a));
      t.cdf.push_back(sum);
    }
    t.areaMm2 = sum * kMmPerM * kMmPerM;
    t.solid = materialBands(o.material);
    t.liquidPart = liquidPart(o);
    if (t.liquidPart) t.liquid = materialBands(*o.liquidMaterial);
    t.rouletteRate = std::numeric_limits<double>::infinity();
    for (const MaterialBands* b : {&t.solid, t.liquid ? &*t.liquid : &t.solid})
      for (std::size_t c = 0; c < 3; ++c) {
        const BssrdfCoefficients k = bssrdfCoefficients(b->sigmaA[c], b->sigmaS[c], b->g[c], b->eta);
        t.rouletteRate = std::min(t.rouletteRate, k.sigma_tr);
        t.sigmaTpMax = std::max(t.sigmaTpMax, k.sigma_t_reduced);
      }
    const double nearArea = t.areaMm2 * t.sigmaTpMax * t.sigmaTpMax / kPi;  // A σ_t'²/π
    if (settings.pointsPerPass > 0)
      t.points = settings.pointsPerPass;
    else
      t.points = static_cast<int>(std::clamp(std::ceil(kNearFieldTarget * nearArea), static_cast<double>(kMinAutoPoints),
                                             static_cast<double>(kMaxAutoPoints)));
    if (!std::isfinite(t.rouletteRate) || t.rouletteRate < 0.0) t.rouletteRate = 0.0;
    slotOfMesh[k] = static_cast<int>(objects.size());
    if (sum > 0.0) objects.push_back(std::move(t));
    else slotOfMesh[k] = -1;
  }

  // Camera rays through pixel centres: the same camera as the surface pass.
  const int W = render.width, H = render.height;
  const float aspect = static_cast<float>(W) / static_cast<float>(H);
  const CameraView camera = cameraView(scene.camera, aspect, bounds);
  const glm::dmat4 inverseViewProjection = glm::inverse(glm::dmat4(camera.viewProjection));
  std::vector<PixelHit> pixels(static_cast<std::size_t>(W) * static_cast<std::size_t>(H));
  auto unproject = [&](double x, double y, double z) {
    const glm::dvec4 p = inverseViewProjection * glm::dvec4(x, y, z, 1.0);
    return glm::dvec3(p) / p.w;
  };
  // Whether light l is hidden from the surface point x (normal n), as its shadow map hides it on the GPU.
  const auto shadowed = [&](const Light& l, const Incident& in, const glm::dvec3& x, const glm::dvec3& n) {
    return render.shadows && l.castsShadows && rays.occluded(x + offset * n, in.toLight, in.distance - 2.0 * offset);
  };
  const auto shadeOpaque = [&](const SceneObject& o, const glm::dvec3& x, const glm::dvec3& n) {
    glm::dvec3 e(0.0);
    for (const Light& l : scene.lights) {
      const Incident in = incident(l, x);
      const double c = glm::dot(n, in.toLight);
      if (!(c > 0.0)) continue;
      if (shadowed(l, in, x, n)) continue;
      e += in.irradiance * c;
    }
    const glm::dvec3 albedo(o.albedo);
    return albedo / kPi * e + albedo * glm::dvec3(scene.ambient);
  };
  // What the ray through (x + ½ + jitter.x, y + ½ + jitter.y) sees (jitter in pixels, +y down).
  const auto trace = [&](int x, int y, glm::dvec2 jitter, PixelHit& px) {
    px = PixelHit{};
    const double ndcX = 2.0 * (x + 0.5 + jitter.x) / W - 1.0;
    const double ndcY = 1.0 - 2.0 * (y + 0.5 + jitter.y) / H;  // row 0 at the top
    const glm::dvec3 nearP = unproject(ndcX, ndcY, -1.0), farP = unproject(ndcX, ndcY, 1.0);
    const glm::dvec3 dir = glm::normalize(farP - nearP);
    const glm::dvec3 origin = camera.orthographic ? nearP : glm::dvec3(camera.position);
    px.base = glm::dvec3(scene.background);
    const auto hit = rays.intersect(origin, dir, 0.0, std::numeric_limits<double>::infinity());
    if (!hit) return;
    const WorldMesh& m = meshes[hit->geom];
    const auto& tri = m.triangles[hit->prim];
    const double w0 = 1.0 - hit->u - hit->v;
    const glm::dvec3 xw = w0 * m.positions[tri[0]] + hit->u * m.positions[tri[1]] + hit->v * m.positions[tri[2]];
    glm::dvec3 n = w0 * m.normals[tri[0]] + hit->u * m.normals[tri[1]] + hit->v * m.normals[tri[2]];
    n = glm::length(n) > 0.0 ? glm::normalize(n) : glm::dvec3(0.0, 1.0, 0.0);
    const glm::dvec3 rawNormal = n;  // as drawn: which slot a point is (surface.frag's surfaceSlot)
    const glm::dvec3 toCamera = -dir;
    if (glm::dot(n, toCamera) < 0.0) n = -n;  // open meshes show their inside, as surface.frag does
    const SceneObject& o = scene.objects[static_cast<std::size_t>(m.objectIndex)];
    const int slot = slotOfMesh[hit->geom];
    if (slot < 0) {
      px.base = shadeOpaque(o, xw, n);
      px.receiver = true;
      px.xr = xw;
      px.nr = n;
      px.albedo = glm::dvec3(o.albedo);
      return;
    }
    const double cosO = std::clamp(glm::dot(n, toCamera), 0.0, 1.0);
    const TranslucentObject& t = objects[static_cast<std::size_t>(slot)];
    px.slot = slot;
    px.material = &t.at(xw, rawNormal);
    px.xoMm = xw * kMmPerM;
    px.no = n;
    px.transmit = fresnelTransmittance(cosO, px.material->eta) / kPi;
    px.base = glm::dvec3(0.0);
    if (render.specular) {
      const glm::dvec3 mirror = glm::reflect(dir, n);
      glm::dvec3 mirrored = environment ? environment->radiance(mirror) : glm::dvec3(scene.ambient);
      for (const FlameSheet& f : flames) {  // surface.frag's flame reflection, where the flame's light reaches
        const glm::dvec3 seen = flameSeenAlong(xw, mirror, f);
        if (seen == glm::dvec3(0.0)) continue;
        if (f.light >= 0) {
          const Light& l = scene.lights[static_cast<std::size_t>(f.light)];
          if (shadowed(l, incident(l, xw), xw, n)) continue;
        }
        mirrored += double(f.radianceScale) * seen;
      }
      px.base = fresnelReflectance(cosO, px.material->eta) * mirrored;
    }
  };
  const auto traceAll = [&](glm::dvec2 jitter, std::vector<PixelHit>& out) {
    parallelFor(tbb::blocked_range<int>(0, H), [&](const tbb::blocked_range<int>& rows) {
      for (int y = rows.begin(); y != rows.end(); ++y)
        for (int x = 0; x < W; ++x)
          trace(x, y, jitter, out[static_cast<std::size_t>(y) * static_cast<std::size_t>(W) + static_cast<std::size_t>(x)]);
    });
  };
  // The pixel centres decide which pixels are translucent (the standard error's mask, the stopping
  // statistic); with the box filter each pass then traces its own sub-pixel position.
  traceAll(glm::dvec2(0.0), pixels);
  const std::vector<PixelHit> centres = pixels;

  ReferenceResult result;
  for (const TranslucentObject& t : objects) {
    result.pointsPerPass = std::max(result.pointsPerPass, t.points);
    const double near = t.points * kPi / (t.areaMm2 * t.sigmaTpMax * t.sigmaTpMax);
    result.nearFieldPoints = result.nearFieldPoints == 0.0 ? near : std::min(result.nearFieldPoints, near);
  }
  if (objects.empty()) result.pointsPerPass = settings.pointsPerPass;
  result.triangles = rays.triangles();
  for (const PixelHit& p : centres) result.translucentPixels += p.slot >= 0 ? 1 : 0;
  const std::size_t count = pixels.size();
  std::vector<glm::dvec3> mean(count, glm::dvec3(0.0)), m2(count, glm::dvec3(0.0));
  const int passCap = settings.maxPasses > 0 ? settings.maxPasses : settings.passLimit;
  const int minPasses = std::max(settings.minPasses, 2);

  std::vector<std::vector<LitPoint>> lit(objects.size());
  std::vector<std::vector<PointCell>> cellsOf(objects.size());
  const bool emergent = settings.emergentLight && !objects.empty();
  std::vector<Emitter> emitters;
  std::vector<glm::dvec3> emergentMean(emergent ? count : 0, glm::dvec3(0.0));
  int passes = 0;
  double relError = std::numeric_limits<double>::infinity();
  while (passes < passCap) {
    const auto pass = static_cast<std::uint64_t>(passes);
    // 1. M points per translucent object, uniform by area, each with its lights and visibility.
    for (std::size_t s = 0; s < objects.size(); ++s) {
      const TranslucentObject& t = objects[s];
      const int M = t.points;
      std::vector<LitPoint> points(static_cast<std::size_t>(M));
      std::vector<char> any(static_cast<std::size_t>(M), 0);
      parallelFor(tbb::blocked_range<int>(0, M, 256), [&](const tbb::blocked_range<int>& r) {
        for (int i = r.begin(); i != r.end(); ++i) {
          const std::optional<SurfaceSample> sample = sampleSurface(t, settings.seed, kStreamLitPoints, pass, s, i);
          if (!sample) continue;
          const glm::dvec3 &x = sample->x, &n = sample->n;
          LitPoint& p = points[static_cast<std::size_t>(i)];
          for (const Light& l : scene.lights) {
            const Incident in = incident(l, x);
            const double c = glm::dot(n, in.toLight);
            if (!(c > 0.0)) continue;  // faces away: the light G-buffer gives it no light either
            if (rays.occluded(x + offset * n, in.toLight, in.distance - 2.0 * offset)) continue;
            const double ft = fresnelTransmittance(c, t.at(x, n).eta);
            if (!(ft > 0.0)) continue;
            p.lights.emplace_back(in.toLight, in.irradiance * (ft * c));
          }
          if (!p.lights.empty()) {
            p.xMm = x * kMmPerM;
            p.n = n;
            any[static_cast<std::size_t>(i)] = 1;
          }
        }
      });
      lit[s].clear();
      for (int i = 0; i < M; ++i)
        if (any[static_cast<std::size_t>(i)]) lit[s].push_back(std::move(points[static_cast<std::size_t>(i)]));
      cellsOf[s] = sortIntoCells(lit[s], t.rouletteRate);
    }

    // 1b. Emergent light: N emitter points per object, uniform by area, each with its B̂ gathered
    //     from this pass's lit points exactly as a pixel's.
    emitters.clear();
    if (emergent)
      for (std::size_t s = 0; s < objects.size(); ++s) {
        const TranslucentObject& t = objects[s];
        const int N = settings.emitterPoints;
        std::vector<Emitter> made(static_cast<std::size_t>(N));
        parallelFor(tbb::blocked_range<int>(0, N, 16), [&](const tbb::blocked_range<int>& r) {
          for (int j = r.begin(); j != r.end(); ++j) {
            Emitter& e = made[static_cast<std::size_t>(j)];
            const std::optional<SurfaceSample> sample = sampleSurface(t, settings.seed, kStreamEmitters, pass, s, j);
            if (!sample) continue;
            const GatherStreams streams{kStreamEmitterCell, kStreamEmitterPoint,
                                        (static_cast<std::uint64_t>(s) << 32) | static_cast<std::uint64_t>(j)};
            const MaterialBands& mo = t.at(sample->x, sample->n);
            e = {sample->x, sample->n,
                 gatherRadiosity(t, mo, lit[s], cellsOf[s], sample->x * kMmPerM, sample->n, model, settings.seed, pass,
                                 streams),
                 mo.eta, t.cdf.back() / N};
          }
        });
        for (const Emitter& e : made)
          if (e.radiosity != glm::dvec3(0.0)) emitters.push_back(e);
      }

    // 2. Every translucent pixel gathers the object's lit points (Eq. 7 by area sampling), Russian
    //    roulette on exp(−σ_tr r), and the pass estimate joins the running mean and variance. With
    //    the box filter, pass k looks through sub-pixel position k of sss/pixel_jitter.h (pass 0 the
    //    centre), the positions the GPU's still average (render.aa) cycles through.
    if (settings.pixelFilter == PixelFilter::Box && passes > 0)
      traceAll(pixelJitter(static_cast<unsigned>(passes)), pixels);
    const double n1 = static_cast<double>(passes + 1);
    parallelFor(tbb::blocked_range2d<int>(0, H, 8, 0, W, 8), [&](const tbb::blocked_range2d<int>& tile) {
      for (int y = tile.rows().begin(); y != tile.rows().end(); ++y)
        for (int x = tile.cols().begin(); x != tile.cols().end(); ++x) {
          const std::size_t index = static_cast<std::size_t>(y) * static_cast<std::size_t>(W) + static_cast<std::size_t>(x);
          const PixelHit& px = pixels[index];
          glm::dvec3 value = px.base;
          if (px.slot >= 0) {
            const auto slot = static_cast<std::size_t>(px.slot);
            const GatherStreams streams{kStreamPixelCell, kStreamPixelPoint, index};
            value += px.transmit * gatherRadiosity(objects[slot], *px.material, lit[slot], cellsOf[slot], px.xoMm, px.no,
                                                   model, settings.seed, pass, streams);
          } else if (px.receiver && emergent) {
            const glm::dvec3 e = emergentRadiance(px, emitters, rays, offset);
            value += e;
            emergentMean[index] += (e - emergentMean[index]) / n1;
          }
          const glm::dvec3 delta = value - mean[index];
          mean[index] += delta / n1;
          m2[index] += delta * (value - mean[index]);
        }
    });
    ++passes;

    // 3. The stopping statistic.
    double se2 = 0.0, l2 = 0.0;
    for (std::size_t i = 0; i < count; ++i) {
      if (centres[i].slot < 0) continue;
      if (passes >= 2) se2 += (m2[i].x + m2[i].y + m2[i].z) / ((passes - 1.0) * passes);
      l2 += glm::dot(mean[i], mean[i]);
    }
    if (result.translucentPixels == 0) relError = 0.0;
    else if (passes < 2) relError = std::numeric_limits<double>::infinity();
    else relError = l2 > 0.0 ? std::sqrt(se2 / l2) : (se2 > 0.0 ? std::numeric_limits<double>::infinity() : 0.0);
    if (progress && !progress(passes, relError)) break;
    if (settings.relError > 0.0 && (passes >= minPasses || result.translucentPixels == 0) && relError <= settings.relError)
      break;
  }

  result.passes = passes;
  result.relError = relError;
  result.radiance = gpu::Image(W, H);
  result.standardError = gpu::Image(W, H);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(W) + static_cast<std::size_t>(x);
      result.radiance.at(x, y) = glm::vec4(glm::vec3(mean[i]), 1.0f);
      const glm::dvec3 se = passes >= 2 ? glm::sqrt(m2[i] / ((passes - 1.0) * passes)) : glm::dvec3(0.0);
      result.standardError.at(x, y) = glm::vec4(glm::vec3(se), centres[i].slot >= 0 ? 1.0f : 0.0f);
    }
  if (settings.emergentLight) {
    result.emitterPoints = settings.emitterPoints;
    result.emergent = gpu::Image(W, H);
    double se2 = 0.0, e2 = 0.0;
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < W; ++x) {
        const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(W) + static_cast<std::size_t>(x);
        const glm::dvec3 e = emergent ? emergentMean[i] : glm::dvec3(0.0);
        result.emergent.at(x, y) = glm::vec4(glm::vec3(e), centres[i].receiver ? 1.0f : 0.0f);
        if (!(std::max({e.x, e.y, e.z}) > 0.0)) continue;
        ++result.emergentPixels;
        if (passes >= 2) se2 += (m2[i].x + m2[i].y + m2[i].z) / ((passes - 1.0) * passes);
        e2 += glm::dot(e, e);
      }
    result.emergentRelError = result.emergentPixels == 0 ? 0.0
                              : passes < 2                ? std::numeric_limits<double>::infinity()
                                                          : std::sqrt(se2 / e2);
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace tallow::sss
