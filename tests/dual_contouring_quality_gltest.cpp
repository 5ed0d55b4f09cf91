// Quality matrix of the GPU dual contouring (issue 4, point 7): {blob, candle, bunny level set} ×
// several t × lattices 32³..128³, an analytic sphere, and hard cases (blobs just merging, drips
// about a cell thick, random draws), each with both vertex placements (field.placement: the mass
// point of the edge crossings and the QEF of their tangent planes, issue 16). Every mesh must be
//   1. watertight: every undirected edge in exactly two triangles (all surfaces lie inside the
//      lattice: sampleField pads the field's bounds by a cell);
//   2. outward: signed volume > 0, and ≥ 99% of the triangles' winding normals agree with the
//      stored vertex normals and with the field's gradient at the centroid;
//   3. free of zero-area triangles (every area > 1e-12 cell²);
//   4. on the surface: every vertex within half a cell, |value| / |∇value| ≤ cell / 2 (for the
//      level sets |value| / max(|∇value|, 1), see checkAll);
//   5. of the right volume: within 1% of an independent 512³ estimate from the continuous field
//      (midpoint rule with a linear sub-cell correction, see referenceVolume) at 128³;
//   6. close to OpenVDB's mesh of the same lattice: symmetric Hausdorff distance ≤ 1 cell.
// Timings are printed, never asserted (STYLE.md §14).
#include "geometry/analytic_fields.h"
#include "geometry/blob_field.h"
#include "geometry/candle_field.h"
#include "geometry/cpu_mesher.h"
#include "geometry/gpu_dual_contouring.h"
#include "geometry/grid_sampler.h"
#include "geometry/mesh_level_set_field.h"
#include "geometry/ply_reader.h"
#include "gpu/gl_context.h"
#include "gpu/shader_library.h"

#include <gtest/gtest.h>

#include "support/mesh_checks.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <numbers>
#include <ostream>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <tuple>
#include <utility>
#include <vector>

namespace tallow::geometry {
namespace {

using test::countComponents;
using test::edgeUses;
using test::faceCross;
using test::hausdorffDistance;
using test::signedVolume;
using test::SphereField;
using test::surfaceArea;

constexpr int kVolumeCheckSamples = 128;  ///< criterion 5 applies to the 128³ meshes

// --- Fields, built once per (kind, t) and process -------------------------------------------

enum class Kind { Blob, Candle, Bunny };

const char* kindName(Kind kind) {
  switch (kind) {
    case Kind::Blob: return "blob";
    case Kind::Candle: return "candle";
    case Kind::Bunny: return "bunny";
  }
  return "?";
}

/// Voxels across the bunny's largest extent for its level set; the 128³ lattice then has cells
/// about one voxel wide, so the lattice sees every voxel of the level set.
constexpr int kBunnyResolution = 128;
/// Half-width of the bunny's narrow band in voxels. The default 3 (3.6 mm) is narrower than a
/// cell of the lattices below ~44³; there most samples read the clamped ±band value, the linear
/// edge crossings of those samples are no distance interpolation any more, and vertices land up
/// to 3 cells off the level set's zero (OpenVDB's mesher alike). 12 voxels are ≥ 2 cells of the
/// 32³ lattice: band w ≥ 2·(extent + 2w) / 29 ⇔ w ≥ 0.08·extent = 10.2 voxels.
constexpr double kBunnyBandVoxels = 12.0;

const TriangleMesh& bunnyMesh() {
  static const TriangleMesh mesh = readPly(std::string(TALLOW_TEST_DATA_DIR) + "/bunny.ply");
  return mesh;
}

/// The static bunny has no t: its one case is listed with t = 0.
const ScalarField& fieldFor(Kind kind, double t) {
  static std::map<std::pair<int, double>, std::unique_ptr<ScalarField>> cache;
  auto& slot = cache[{static_cast<int>(kind), kind == Kind::Bunny ? 0.0 : t}];
  if (!slot) {
    const auto start = std::chrono::steady_clock::now();
    switch (kind) {
      case Kind::Blob: slot = std::make_unique<BlobField>(t); break;
      case Kind::Candle: slot = std::make_unique<CandleField>(t); break;
      case Kind::Bunny: slot = std::make_unique<MeshLevelSetField>(bunnyMesh(), kBunnyResolution, kBunnyBandVoxels); break;
    }
    std::printf("[ dcq ] %s t=%.3f field built in %.2f s\n", kindName(kind), t,
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  return *slot;
}

/// Upper bound of |∇value| over all space, for the volume reference's cell culling.
double lipschitzBound(const ScalarField& field) {
  if (const auto* blob = dynamic_cast<const BlobField*>(&field)) {
    // |∇ exp(−σ‖d‖²)| = 2σ‖d‖ exp(−σ‖d‖²) ≤ √(2σ) e^(−1/2) (at ‖d‖ = 1/√(2σ)); four blobs, and
    // d = p / scale − c.
    const BlobParams& p = blob->params();
    return BlobParams::kBlobCount * std::sqrt(2.0 * p.sigma) * std::exp(-0.5) / p.scale;
  }
  if (dynamic_cast<const SphereField*>(&field)) return 1.0;
  // Level sets (candle, bunny): trilinear interpolation of voxel samples of a signed distance.
  // Each partial derivative of a trilinear cell is a blend of its four voxel differences along
  // that axis / voxel, which for samples of a 1-Lipschitz distance (clamped to ± the band:
  // still 1-Lipschitz) are ≤ 1, so |∇| ≤ √3. OpenVDB renormalises after CSG and mean-curvature
  // smoothing only to |∇| ≈ 1, hence 2 rather than √3 ≈ 1.73.
  return 2.0;
}

/// Half-width of a level set's narrow band (values beyond it are clamped), 0 for other fields.
double narrowBand(const ScalarField& field) {
  if (const auto* candle = dynamic_cast<const CandleField*>(&field)) return candle->bandWidth();
  if (const auto* mesh = dynamic_cast<const MeshLevelSetField*>(&field)) return mesh->bandWidth();
  return 0.0;
}

/// The shortest of the three axis-aligned chords through q of the region on q's side of the surface
/// (inside or outside), in cells, found by steps of a twentieth of a cell out to `reach` cells each
/// way; 2 · reach when no chord ends within it. A chord under two cells is a feature the lattice
/// cannot resolve: at most two samples span it.
double shortestChordCells(const ScalarField& field, const glm::dvec3& q, double cell, double reach) {
  const bool inside = field.value(q) < 0.0;
  const double step = cell / 20.0;
  auto run = [&](const glm::dvec3& direction) {
    for (double t = step; t <= reach * cell; t += step)
      if ((field.value(q + t * direction) < 0.0) != inside) return t / cell;
    return reach;
  };
  double shortest = 2.0 * reach;
  for (int axis = 0; axis < 3; ++axis) {
    glm::dvec3 direction(0.0);
    direction[axis] = 1.0;
    shortest = std::min(shortest, run(direction) + run(-direction));
  }
  return shortest;
}

// --- Criterion 5: the independent volume reference -----------------------------------------

struct VolumeEstimate {
  double fine = 0.0;    ///< on 512³ cells
  double coarse = 0.0;  ///< the same on 256³ cells (a convergence check of `fine`)
  long evaluations = 0;
};

/// Volume where value < 0 on 512³ cells over the cube around field.bounds() (2% margin), from
/// the continuous field alone (no lattice, no mesh). A cell whose centre value exceeds
/// L·(half diagonal) has one sign throughout and counts whole or not at all; only the others are
/// split (64³ top cells, three halvings), so this costs a few million evaluations, not 512³.
/// A 512³ cell the surface may cross counts the inside fraction of the plane through its centre,
/// clamp(1/2 − value / (s·‖∇value‖₁), 0, 1) (s·‖n‖₁ is the cube's extent along the unit normal
/// n): the midpoint rule of the sign with a linear sub-cell correction. The plain sign count errs
/// by O(h) on faces parallel to a lattice plane (the candle's flat base and top: area·h/2 ≈ 0.15%
/// at 512³); the plane fraction is exact there and second order elsewhere.
/// Its own error: for any order p ≥ 1, |V₅₁₂ − V₂₅₆| ≥ (2^p − 1)·|error of V₅₁₂| ≥ |error of V₅₁₂|,
/// so cachedReferenceVolume() asserts |V₅₁₂ / V₂₅₆ − 1| ≤ 0.1%: the reference is good to 0.1%,
/// a tenth of the 1% tolerance. The sphere test checks it against the exact volume as well.
VolumeEstimate referenceVolume(const ScalarField& field) {
  constexpr int kTop = 64, kLevels = 3;
  const Aabb box = field.bounds();
  const glm::dvec3 size(box.size());
  const double side = 1.02 * std::max({size.x, size.y, size.z});
  const glm::dvec3 origin = glm::dvec3(box.centre()) - 0.5 * side;
  const double lipschitz = lipschitzBound(field);
  const double halfDiagonalFactor = 0.5 * std::sqrt(3.0);

  struct Sum {
    double fine = 0.0, coarse = 0.0;
    long evaluations = 0;
  };
  // Returns the fine and coarse volumes of one cell of edge s at `level`.
  auto cell = [&](auto&& self, glm::dvec3 centre, double s, int level, Sum& sum) -> std::pair<double, double> {
    const double v = field.value(centre);
    ++sum.evaluations;
    const double whole = v < 0.0 ? s * s * s : 0.0;
    if (std::abs(v) > lipschitz * halfDiagonalFactor * s) return {whole, whole};
    auto planeFraction = [&] {
      const glm::dvec3 g = field.gradient(centre);
      sum.evaluations += 6;
      const double extent = s * (std::abs(g.x) + std::abs(g.y) + std::abs(g.z));
      if (!(extent > 0.0)) return whole;
      return std::clamp(0.5 - v / extent, 0.0, 1.0) * s * s * s;
    };
    if (level == kLevels) return {planeFraction(), 0.0};
    double fine = 0.0, coarse = 0.0;
    for (int k = 0; k < 8; ++k) {
      const glm::dvec3 offset(k & 1 ? 0.25 : -0.25, k & 2 ? 0.25 : -0.25, k & 4 ? 0.25 : -0.25);
      const auto [f, c] = self(self, centre + s * offset, 0.5 * s, level + 1, sum);
      fine += f;
      coarse += c;
    }
    return {fine, level == kLevels - 1 ? planeFraction() : coarse};  // a 256³ cell
  };
  const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  std::vector<Sum> sums(threads);
  {
    std::vector<std::jthread> pool;
    for (unsigned i = 0; i < threads; ++i)
      pool.emplace_back([&, i] {
        const double s = side / kTop;
        for (int z = static_cast<int>(i); z < kTop; z += static_cast<int>(threads))
          for (int y = 0; y < kTop; ++y)
            for (int x = 0; x < kTop; ++x) {
              const auto [f, c] = cell(cell, origin + s * (glm::dvec3(x, y, z) + 0.5), s, 0, sums[i]);
              sums[i].fine += f;
              sums[i].coarse += c;
            }
      });
  }
  VolumeEstimate estimate;
  for (const Sum& s : sums) {
    estimate.fine += s.fine;
    estimate.coarse += s.coarse;
    estimate.evaluations += s.evaluations;
  }
  return estimate;
}

const VolumeEstimate& cachedReferenceVolume(const ScalarField& field) {
  static std::map<const ScalarField*, VolumeEstimate> cache;
  auto it = cache.find(&field);
  if (it == cache.end()) {
    const auto start = std::chrono::steady_clock::now();
    it = cache.emplace(&field, referenceVolume(field)).first;
    std::printf("[ dcq ] reference volume %.6e m^3 (256^3: %.6e), %ld evaluations, %.2f s\n", it->second.fine,
                it->second.coarse, it->second.evaluations,
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    EXPECT_NEAR(it->second.coarse / it->second.fine, 1.0, 1e-3) << "the 512^3 reference has not converged";
  }
  return it->second;
}

// --- Fixture: GL context, extraction, the per-mesh criteria ----------------------------------

std::string describeEdgeUses(const TriangleMesh& mesh, std::size_t* bad) {
  std::map<int, std::size_t> histogram;  // uses → edges
  for (const auto& [edge, uses] : edgeUses(mesh)) ++histogram[uses];
  std::ostringstream out;
  *bad = 0;
  for (const auto& [uses, edges] : histogram)
    if (uses != 2) {
      out << " " << edges << " edges used " << uses << "x;";
      *bad += edges;
    }
  return out.str();
}

class QualityFixture : public ::testing::Test {
 protected:
  void SetUp() override { context_ = gpu::GlContext::create(gpu::ContextOptions{}); }

  TriangleMesh extract(const SampledLattice& lattice) {
    GpuDualContouring dc(library_, lattice.n, placement_);
    dc.upload(lattice);
    dc.extract();
    TriangleMesh mesh = dc.readBack();
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
    return mesh;
  }

  /// Criteria 1–4 (and 6 against meshOnCpu unless skipped); returns the GPU mesh.
  TriangleMesh checkAll(const ScalarField& field, const SampledLattice& lattice, const std::string& what,
                        bool compareWithCpu = true) {
    const auto start = std::chrono::steady_clock::now();
    const TriangleMesh mesh = extract(lattice);
    const double extractS = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double cell = lattice.cellSize;
    EXPECT_GT(mesh.triangles.size(), 0u) << what;
    if (mesh.triangles.empty()) return mesh;
    EXPECT_EQ(mesh.normals.size(), mesh.positions.size());

    // 1. Watertight.
    std::size_t bad = 0;
    const std::string edgeReport = describeEdgeUses(mesh, &bad);
    EXPECT_EQ(bad, 0u) << what << ": not watertight:" << edgeReport;

    // 2. Outward; 3. no zero-area triangles.
    const double volume = signedVolume(mesh);
    EXPECT_GT(volume, 0.0) << what;
    std::size_t againstNormals = 0, againstGradient = 0, againstGradientThin = 0, zeroArea = 0;
    for (const auto& t : mesh.triangles) {
      const glm::dvec3 n = faceCross(mesh, t);
      if (0.5 * glm::length(n) <= 1e-12 * cell * cell) ++zeroArea;
      const glm::dvec3 stored =
          glm::dvec3(mesh.normals[t[0]]) + glm::dvec3(mesh.normals[t[1]]) + glm::dvec3(mesh.normals[t[2]]);
      if (!(glm::dot(n, stored) > 0.0)) ++againstNormals;
      const glm::dvec3 centroid =
          (glm::dvec3(mesh.positions[t[0]]) + glm::dvec3(mesh.positions[t[1]]) + glm::dvec3(mesh.positions[t[2]])) / 3.0;
      // Across a feature under two cells thick (the candle's lip and drips on coarse lattices, its
      // wick) the lattice has at most two samples: the mesh's one sheet there lies about the medial
      // axis, where the gradient may be the other side's. Such faces are counted apart, as the
      // vertex bound below treats their vertices.
      if (!(glm::dot(n, field.gradient(centroid)) > 0.0)) {
        if (shortestChordCells(field, centroid, cell, 2.0) < 2.0) ++againstGradientThin;
        else ++againstGradient;
      }
    }
    const double allowed = 0.01 * static_cast<double>(mesh.triangles.size());
    EXPECT_LE(static_cast<double>(againstNormals), allowed) << what << ": winding against the stored normals";
    EXPECT_LE(static_cast<double>(againstGradient), allowed) << what << ": winding against the field's gradient";
    EXPECT_EQ(zeroArea, 0u) << what << ": zero-area triangles";

    // 4. Every vertex within half a cell of the surface (first-order distance |f| / |∇f|).
    std::size_t far = 0;
    double worst = 0.0, worstValue = 0.0, worstGradient = 0.0;
    glm::dvec3 worstAt(0.0);
    const double band = narrowBand(field);
    const auto* levelSet = dynamic_cast<const LevelSetField*>(&field);
    // The candle is a clamped signed distance with an analytic gradient since issue 16 (|∇f| = 1 up
    // to the wick's axis): its ridge test below uses what its level set's gradient was, central
    // differences of value() with a step of half a voxel.
    const auto* candle = dynamic_cast<const CandleField*>(&field);
    const double voxel = levelSet ? levelSet->voxelSize() : candle ? candle->voxelSize() : 0.0;
    for (const auto& p : mesh.positions) {
      const glm::dvec3 q(p);
      const double f = field.value(q), g = glm::length(field.gradient(q));
      // Level sets store signed distances, so |f| is itself the distance to their accuracy and
      // |∇f| should be 1. Their trilinear interpolation's central-difference gradient is not:
      // on a medial ridge the slopes of both sides cancel (∇f = 0 on the wick's axis, |f| = the
      // wick's radius) and it drops below 1 next to kinks, where |f| / |∇f| overstates the
      // distance. So |f| / max(|∇f|, 1) for them, except that a clamped value (outside the
      // band, where |f| only bounds the distance from below) fails outright.
      // Near a ridge, a feature under two cells thick is below what the lattice can resolve (two
      // samples across it at most): the one vertex of its cross-section lies near the axis, about
      // the half-thickness from the surface, and there the bound is one cell, not half. This is the
      // candle's 2 mm wick at t = 0 on 48³ and 64³ lattices (0.53 and 0.71 cells; OpenVDB's vertex
      // too) and the bunny's ears on a 40³ lattice. Which vertices: the distance rises with slope 1
      // away from the medial axis, and the central differences of its trilinear interpolation (step
      // half a voxel) see that slope fall to 0 within about a voxel of the axis, so |∇f| < 1 puts
      // the vertex within δ ≈ |∇f| · voxel of it and the half-thickness there is at most |f| + δ.
      // Under two cells thick: |f| + |∇f| · voxel < one cell.
      double d = std::abs(f) / g / cell;
      if (band > 0.0) d = std::abs(f) >= 0.999 * band ? HUGE_VAL : std::abs(f) / std::max(g, 1.0) / cell;
      const double slope = candle ? glm::length(field.centralDifferenceGradient(q, 0.5 * voxel)) : g;
      const bool underResolvedRidge = band > 0.0 && slope < 1.0 && std::abs(f) + slope * voxel < cell;
      // The same bound at the end of such a feature, where the nearest surface is its cap and not its
      // sides, so |∇f| = 1 and the ridge test above cannot see it: the mass point of the wick's tip
      // cell (flat top, 2 mm across = 1.45 cells on 54³) averages the top's crossings with the
      // sides' and sits on the axis 0.52 cells under the top (TALLOW_TEST_SEED=3378219646, candle
      // t = 6.37 s). So: a chord through the vertex under two cells long, and within one cell.
      const bool underResolvedFeature =
          !(d <= 0.5) && d <= 1.0 && shortestChordCells(field, q, cell, 2.0) < 2.0;
      if (!(d <= 0.5) && !underResolvedRidge && !underResolvedFeature) ++far;
      if (!(d <= worst)) {
        worst = d;
        worstAt = q;
        worstValue = f / cell;
        worstGradient = g;
      }
    }
    EXPECT_EQ(far, 0u) << what << ": vertices over half a cell from the surface; worst " << worst << " cells at ("
                       << worstAt.x << ", " << worstAt.y << ", " << worstAt.z << "), value " << worstValue
                       << " cells, |gradient| " << worstGradient;

    // 6. Hausdorff distance to OpenVDB's mesh of the same lattice.
    double hausdorffCells = -1.0;
    if (compareWithCpu) {
      const TriangleMesh cpu = meshOnCpu(lattice, field);
      hausdorffCells = hausdorffDistance(mesh, cpu, cell, 8.0 * cell) / cell;
      EXPECT_LE(hausdorffCells, 1.0) << what << ": Hausdorff distance to the OpenVDB mesh, in cells";
    }
    std::printf("[ dcq ] %s: %zu tris, %d comps, extract %.2f s; bad edges %zu;%s zero-area %zu, against normals "
                "%zu / gradient %zu (+ %zu across features under two cells); worst vertex %.3f cells; Hausdorff %.3f "
                "cells; %.2f s in all\n",
                what.c_str(), mesh.triangles.size(), countComponents(mesh), extractS, bad, edgeReport.c_str(), zeroArea,
                againstNormals, againstGradient, againstGradientThin, worst, hausdorffCells,
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    return mesh;
  }

  /// Criterion 5 at 128³ (printed at every resolution).
  void checkVolume(const ScalarField& field, const SampledLattice& lattice, const TriangleMesh& mesh,
                   const std::string& what) {
    if (lattice.n < kVolumeCheckSamples) return;
    const double ratio = signedVolume(mesh) / cachedReferenceVolume(field).fine;
    std::printf("[ dcq ] %s: volume / 512^3 reference %.5f\n", what.c_str(), ratio);
    EXPECT_NEAR(ratio, 1.0, 0.01) << what << ": enclosed volume against the 512^3 reference";
  }

  std::unique_ptr<gpu::GlContext> context_;
  gpu::ShaderLibrary library_;
  VertexPlacement placement_ = kDefaultPlacement;  ///< of every extraction
};

constexpr VertexPlacement kPlacements[] = {VertexPlacement::Mass, VertexPlacement::Qef};

std::string placementName(VertexPlacement p) { return std::string(vertexPlacementName(p)); }

// --- The matrix: {blob, candle, bunny} × t × n -------------------------------------------------

struct Case {
  Kind kind;
  double t;
  int n;
  VertexPlacement placement;
};

std::string caseName(const Case& c) {
  std::string t = std::to_string(static_cast<int>(std::lround(c.t * 100.0)));
  return std::string(kindName(c.kind)) + "_t" + t + "cs_n" + std::to_string(c.n) + "_" + placementName(c.placement);
}

void PrintTo(const Case& c, std::ostream* os) { *os << caseName(c); }

std::vector<Case> matrix() {
  const std::vector<std::pair<Kind, std::vector<double>>> times{
      {Kind::Blob, {0.0, 3.95, 11.3}},  // one merged ball, split apart, a later mixed state
      // Fresh, mid-burn with drips running, burnt down. At t = 0 the lattice is symmetric about
      // the wick's axis and, for odd n − 3, the wick (radius 1 mm, 0.53 cells at 48³, 0.71 at
      // 64³) lies in one column of cells: the mean of its edge crossings sits on the axis, a
      // wick radius from the surface (OpenVDB's vertex too); criterion 4 allows one cell there.
      {Kind::Candle, {0.0, 9.0, 20.0}},
      {Kind::Bunny, {0.0}}};            // static
  std::vector<Case> cases;
  for (VertexPlacement placement : kPlacements)
    for (const auto& [kind, ts] : times)
      for (double t : ts)
        for (int n : {32, 48, 64, 96, 128}) cases.push_back({kind, t, n, placement});
  return cases;
}

class DualContouringQuality : public QualityFixture, public ::testing::WithParamInterface<Case> {};

TEST_P(DualContouringQuality, ClosedOutwardOnTheSurfaceAndNearOpenVdb) {
  const Case c = GetParam();
  placement_ = c.placement;
  const ScalarField& field = fieldFor(c.kind, c.t);
  const SampledLattice lattice = sampleField(field, c.n);
  const std::string what = caseName(c);
  const TriangleMesh mesh = checkAll(field, lattice, what);
  if (!mesh.triangles.empty()) checkVolume(field, lattice, mesh, what);
}

INSTANTIATE_TEST_SUITE_P(Matrix, DualContouringQuality, ::testing::ValuesIn(matrix()),
                         [](const ::testing::TestParamInfo<Case>& info) { return caseName(info.param); });

// --- The analytic sphere ----------------------------------------------------------------------

class DualContouringQualitySphere : public QualityFixture,
                                    public ::testing::WithParamInterface<std::tuple<int, VertexPlacement>> {};

TEST_P(DualContouringQualitySphere, VolumeAreaAndRadiusMatchTheExactSphere) {
  constexpr double kRadius = 0.05;
  const glm::dvec3 centre(0.01, -0.02, 0.03);  // off the lattice's symmetry
  const SphereField sphere(centre, kRadius);
  const auto [n, placement] = GetParam();
  placement_ = placement;
  const SampledLattice lattice = sampleField(sphere, n);
  const std::string what = "sphere_n" + std::to_string(n) + "_" + placementName(placement);
  const TriangleMesh mesh = checkAll(sphere, lattice, what);
  if (mesh.triangles.empty()) return;
  const double exactVolume = 4.0 / 3.0 * std::numbers::pi * kRadius * kRadius * kRadius;
  const double exactArea = 4.0 * std::numbers::pi * kRadius * kRadius;
  const double volumeRatio = signedVolume(mesh) / exactVolume, areaRatio = surfaceArea(mesh) / exactArea;
  double worstRadius = 0.0;
  for (const auto& p : mesh.positions)
    worstRadius = std::max(worstRadius, std::abs(glm::length(glm::dvec3(p) - centre) - kRadius));
  std::printf("[ dcq ] %s: volume/exact %.5f, area/exact %.5f, worst radius error %.3f cells\n", what.c_str(),
              volumeRatio, areaRatio, worstRadius / lattice.cellSize);
  EXPECT_NEAR(volumeRatio, 1.0, 0.01) << what;
  EXPECT_NEAR(areaRatio, 1.0, 0.02) << what;
  EXPECT_LE(worstRadius, 0.5 * lattice.cellSize) << what;
}

INSTANTIATE_TEST_SUITE_P(Lattices, DualContouringQualitySphere,
                         ::testing::Combine(::testing::Values(32, 48, 64, 96, 128), ::testing::ValuesIn(kPlacements)),
                         [](const ::testing::TestParamInfo<std::tuple<int, VertexPlacement>>& info) {
                           std::string name = "n";  // not "n" + …: GCC 12's false -Wrestrict
                           name += std::to_string(std::get<0>(info.param));
                           name += '_';
                           return name += placementName(std::get<1>(info.param));
                         });

TEST(DualContouringQualityReference, VolumeEstimateOfTheSphereIsFarWithinTheTolerance) {
  // The reference of criterion 5 on the one shape whose volume is known: its error must be ≪ 1%.
  constexpr double kRadius = 0.05;
  const SphereField sphere(glm::dvec3(0.01, -0.02, 0.03), kRadius);
  const VolumeEstimate estimate = referenceVolume(sphere);
  const double exact = 4.0 / 3.0 * std::numbers::pi * kRadius * kRadius * kRadius;
  std::printf("[ dcq ] sphere reference: 512^3 / exact %.6f, 256^3 / exact %.6f, %ld evaluations\n",
              estimate.fine / exact, estimate.coarse / exact, estimate.evaluations);
  EXPECT_NEAR(estimate.fine / exact, 1.0, 1e-4);  // measured 1.3e-5
  EXPECT_NEAR(estimate.coarse / exact, 1.0, 2e-4);  // measured 5.4e-5
}

TEST(DualContouringQualityReference, GridHausdorffEqualsBruteForce) {
  // Criterion 6's bucket grid against the plain double loop, on two small different meshes.
  const TriangleMesh a = meshOnCpu(SphereField(glm::dvec3(0.0), 0.05), 16);
  const TriangleMesh b = meshOnCpu(SphereField(glm::dvec3(0.004, -0.003, 0.002), 0.045), 21);
  auto bruteForce = [](const TriangleMesh& from, const TriangleMesh& to) {
    double worst = 0.0;
    for (const auto& p : from.positions) {
      double best = HUGE_VAL;
      for (const auto& t : to.triangles)
        best = std::min(best, test::pointTriangleDistance(glm::dvec3(p), glm::dvec3(to.positions[t[0]]),
                                                          glm::dvec3(to.positions[t[1]]), glm::dvec3(to.positions[t[2]])));
      worst = std::max(worst, best);
    }
    return worst;
  };
  ASSERT_GT(a.triangles.size(), 100u);
  ASSERT_GT(b.triangles.size(), 100u);
  const double cell = 0.12 / 13.0;  // about a's lattice cell: a bucket of about a triangle's size
  const double ab = test::directedHausdorff(a, b, cell, 1.0), ba = test::directedHausdorff(b, a, cell, 1.0);
  std::printf("[ dcq ] Hausdorff a->b %.6f, b->a %.6f m\n", ab, ba);
  EXPECT_GT(ab, 0.001);
  EXPECT_DOUBLE_EQ(ab, bruteForce(a, b));
  EXPECT_DOUBLE_EQ(ba, bruteForce(b, a));
  EXPECT_DOUBLE_EQ(hausdorffDistance(a, b, 0.25 * cell, 1.0), std::max(ab, ba));
  EXPECT_DOUBLE_EQ(hausdorffDistance(a, b, cell, 0.001), 0.001);  // capped
}

// --- Hard cases -------------------------------------------------------------------------------

class DualContouringQualityHard : public QualityFixture {};

/// Components of OpenVDB's mesh of the blob at t on an n³ lattice.
int cpuComponents(double t, int n) { return countComponents(meshOnCpu(BlobField(t), n)); }

TEST_F(DualContouringQualityHard, BlobsJustMerging) {
  // Scan forward in t on a coarse lattice for the first drop in the component count (two blobs
  // joining), then, per lattice, bisect to the last t before and the first t after the join on
  // that lattice: the neck is then thinner than a cell.
  constexpr double kStep = 0.1;
  double before = -1.0;
  int previous = cpuComponents(0.0, 32);
  for (double t = kStep; t < 60.0; t += kStep) {
    const int count = cpuComponents(t, 32);
    if (count < previous) {
      before = t - kStep;
      break;
    }
    previous = count;
  }
  ASSERT_GE(before, 0.0) << "no merge found in 60 s of the animation";
  std::printf("[ dcq ] first merge between t = %.2f and %.2f on 32^3\n", before, before + kStep);
  for (int n : {32, 64, 128}) {
    double lo = before - kStep, hi = before + 2.0 * kStep;
    const int countLo = cpuComponents(lo, n), countHi = cpuComponents(hi, n);
    if (countHi >= countLo) {
      ADD_FAILURE() << "no merge between t = " << lo << " and " << hi << " on " << n << "^3";
      continue;
    }
    for (int i = 0; i < 10; ++i) {
      const double mid = 0.5 * (lo + hi);
      (cpuComponents(mid, n) == countLo ? lo : hi) = mid;
    }
    for (double t : {lo, hi}) {
      const BlobField blob(t);
      const SampledLattice lattice = sampleField(blob, n);
      std::ostringstream what;
      what << "merging blob t=" << t << " n" << n << " (" << (t == lo ? "before" : "after") << ", CPU "
           << (t == lo ? countLo : countHi) << " components)";
      for (VertexPlacement placement : kPlacements) {
        placement_ = placement;
        checkAll(blob, lattice, what.str() + " " + placementName(placement));
      }
    }
  }
}

TEST_F(DualContouringQualityHard, CandleDripsAboutOneAndAHalfCellsThin) {
  // Drip radius 1.5 cells of the tested lattice (the top of a drip is 0.7 of that); t = the end,
  // where all three drips have run their full length.
  const double extent = [] {
    const glm::dvec3 size(CandleField(20.0).bounds().size());
    return std::max({size.x, size.y, size.z});
  }();
  for (int n : {48, 128}) {
    CandleParams params;
    params.dripRadius = 1.5 * extent / (n - 3);  // sampleField: n − 3 cells span the bounds
    const CandleField candle(20.0, params);
    const SampledLattice lattice = sampleField(candle, n);
    std::ostringstream what;
    what << "thin drips n" << n << " (drip radius " << params.dripRadius / lattice.cellSize << " cells)";
    for (VertexPlacement placement : kPlacements) {
      placement_ = placement;
      const std::string name = what.str() + " " + placementName(placement);
      const TriangleMesh mesh = checkAll(candle, lattice, name);
      if (!mesh.triangles.empty()) checkVolume(candle, lattice, mesh, name);
    }
  }
}

TEST(ShortestChord, IsTheBoxsThinnestSideThroughItsInsideAndTheGapOutside) {
  // A 1 × 3 × 5 mm box (exact distance): through its centre the chords are its sides, and outside,
  // 0.5 mm off its thin face, nothing ends within the reach along y and z.
  const double cell = 0.001;
  const BoxField box(glm::dvec3(0.0), glm::dvec3(0.0005, 0.0015, 0.0025), glm::dmat3(1.0));
  // Each end is found at most one step (0.05 cells) past the face.
  const double inside = shortestChordCells(box, glm::dvec3(0.0), cell, 4.0);
  EXPECT_GE(inside, 1.0);
  EXPECT_LE(inside, 1.1);
  EXPECT_DOUBLE_EQ(shortestChordCells(box, glm::dvec3(0.0), cell, 0.4), 0.8) << "nothing ends within 0.4 cells";
  const double outside = shortestChordCells(box, glm::dvec3(0.001, 0.0, 0.0), cell, 2.0);
  EXPECT_GE(outside, 2.5) << "outside: 0.5 mm back to the face along x, the 2-cell reach the other way";
  EXPECT_LE(outside, 2.55);
}

TEST_F(DualContouringQualityHard, TheWicksTipNarrowerThanTwoCells) {
  // The case TALLOW_TEST_SEED=3378219646 drew (CI, 2026-12-03): the 2 mm wick is 1.45 cells across
  // on 54³, and the mass point of its tip's cell sits 0.52 cells under its flat top.
  const double t = 6.37153;
  const CandleField candle(t);
  const SampledLattice lattice = sampleField(candle, 54);
  for (VertexPlacement placement : kPlacements) {
    placement_ = placement;
    const TriangleMesh mesh = checkAll(candle, lattice, std::string("wick tip n54 ") + placementName(placement));
    if (!mesh.triangles.empty()) checkVolume(candle, lattice, mesh, std::string("wick tip n54 ") + placementName(placement));
  }
}

TEST_F(DualContouringQualityHard, RandomFieldsTimesAndLattices) {
  // Times and resolutions nobody chose: TALLOW_TEST_SEED=<seed> replays a failure.
  unsigned seed = 0;
  if (const char* env = std::getenv("TALLOW_TEST_SEED"); env && *env)
    seed = static_cast<unsigned>(std::strtoul(env, nullptr, 10));
  else
    seed = std::random_device{}();
  std::printf("[ dcq ] random cases from TALLOW_TEST_SEED=%u\n", seed);
  SCOPED_TRACE("TALLOW_TEST_SEED=" + std::to_string(seed));
  std::mt19937 random(seed);
  std::uniform_int_distribution<int> kinds(0, 2), lattices(32, 128);
  std::uniform_real_distribution<double> times(0.0, 20.0);
  for (int i = 0; i < 6; ++i) {
    const Kind kind = static_cast<Kind>(kinds(random));
    const double drawn = times(random);
    const double t = kind == Kind::Bunny ? 0.0 : drawn;  // the bunny is static
    const int n = lattices(random);
    std::ostringstream what;
    what << "random " << kindName(kind) << " t=" << t << " n" << n;
    SCOPED_TRACE(what.str());
    const ScalarField& field = fieldFor(kind, t);
    const SampledLattice lattice = sampleField(field, n);
    for (VertexPlacement placement : kPlacements) {
      placement_ = placement;
      const std::string name = what.str() + " " + placementName(placement);
      const TriangleMesh mesh = checkAll(field, lattice, name);
      if (!mesh.triangles.empty()) checkVolume(field, lattice, mesh, name);
    }
  }
}

}  // namespace
}  // namespace tallow::geometry
