#include "app/commands/placement_probe_command.h"

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <thread>
#include <utility>
#include <vector>

#include "app/commands/frame_stats.h"
#include "app/commands/provenance.h"
#include "app/commands/option_checks.h"
#include "app/config/input_error.h"
#include "geometry/analytic_fields.h"
#include "geometry/blob_field.h"
#include "geometry/candle_field.h"
#include "geometry/cpu_mesher.h"
#include "geometry/gpu_dual_contouring.h"
#include "geometry/grid_sampler.h"
#include "geometry/mesh_distance.h"
#include "gpu/atomic_file.h"
#include "gpu/gl_context.h"
#include "gpu/shader_library.h"

namespace tallow::app {
namespace {

using geometry::TriangleMesh;
using geometry::VertexPlacement;

constexpr double kBlobTimeS = 2.5;  ///< as `probe extraction`: blobs apart and merging
/// Samples per axis of the blob's and the candle's reference meshes (OpenVDB's mesher, then every
/// vertex projected onto the zero set): twice the finest lattice measured by default.
constexpr int kReferenceSamples = 256;
/// Spacing of the sphere's and the cube's exact surface samples, in cells of the measured lattice:
/// a point of the surface is at most 0.2·√2/2 ≈ 0.14 cells from a sample, which bounds by how much
/// the sampled surface-to-mesh maximum can fall short of the true one (distances are 1-Lipschitz).
constexpr double kExactSpacingCells = 0.2;
/// Distances are capped here (cells): a larger one means a surface missing from the mesh.
constexpr double kCapCells = 8.0;
/// Newton steps onto the zero set stop below this fraction of the reference lattice's cell.
constexpr double kProjectionTolerance = 1e-6;

/// Runs body(i) for i in [0, count) on every hardware thread.
void parallelFor(std::size_t count, const std::function<void(std::size_t)>& body) {
  const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  std::vector<std::jthread> pool;
  for (unsigned t = 0; t < threads; ++t)
    pool.emplace_back([&, t] {
      for (std::size_t i = t; i < count; i += threads) body(i);
    });
}

/// Newton's method for value = 0 along the gradient, p ← p − value ∇/‖∇‖² (for a signed distance,
/// one step lands on the closest surface point). False when it does not converge to the surface.
bool projectToSurface(const geometry::ScalarField& field, glm::dvec3& p, double tolerance) {
  for (int i = 0; i < 32; ++i) {
    const double v = field.value(p);
    const glm::dvec3 g = field.gradient(p);
    const double gg = glm::dot(g, g);
    if (!(gg > 0.0) || !std::isfinite(v)) return false;
    const glm::dvec3 step = (v / gg) * g;
    p -= step;
    if (glm::length(step) < tolerance) return std::abs(field.value(p)) < 10.0 * tolerance * std::sqrt(gg);
  }
  return false;
}

struct Shape {
  std::string name, description;
  bool sharp = false;
  std::unique_ptr<geometry::ScalarField> field;
  /// True for a signed distance (sphere, cube): |value| is the distance to the surface and
  /// exactSamples() gives points on it; otherwise `reference` stands for the surface.
  bool exact = false;
  std::function<std::vector<glm::dvec3>(double spacing)> exactSamples;
  TriangleMesh reference;
  std::vector<glm::dvec3> referenceSamples;
  std::size_t unprojected = 0;  ///< reference vertices whose projection failed (left out)
  std::function<bool(glm::dvec3)> measured = [](glm::dvec3) { return true; };  ///< region compared
};

/// The reference surface of a field without a closed form: OpenVDB's mesh of a fine lattice with
/// every vertex moved onto the zero set by Newton's method, and its vertices, edge midpoints and
/// centroids as the surface's samples (the midpoints and centroids lie on chords a fine cell long).
void buildReference(Shape& shape) {
  const geometry::SampledLattice lattice = geometry::sampleField(*shape.field, kReferenceSamples);
  shape.reference = geometry::meshOnCpu(lattice, *shape.field);
  std::vector<char> ok(shape.reference.positions.size(), 0);
  const double tolerance = kProjectionTolerance * lattice.cellSize;
  parallelFor(shape.reference.positions.size(), [&](std::size_t i) {
    glm::dvec3 p(shape.reference.positions[i]);
    if (projectToSurface(*shape.field, p, tolerance)) {
      shape.reference.positions[i] = glm::vec3(p);
      ok[i] = 1;
    }
  });
  // Triangles with a vertex that did not reach the surface are dropped from the reference.
  std::vector<std::array<std::uint32_t, 3>> kept;
  for (const auto& t : shape.reference.triangles)
    if (ok[t[0]] && ok[t[1]] && ok[t[2]]) kept.push_back(t);
  shape.reference.triangles = std::move(kept);
  for (char c : ok) shape.unprojected += c ? 0 : 1;
  for (std::size_t i = 0; i < ok.size(); ++i)
    if (ok[i]) shape.referenceSamples.emplace_back(shape.reference.positions[i]);
  for (const auto& t : shape.reference.triangles) {
    const glm::dvec3 a(shape.reference.positions[t[0]]), b(shape.reference.positions[t[1]]),
        c(shape.reference.positions[t[2]]);
    shape.referenceSamples.push_back(0.5 * (a + b));
    shape.referenceSamples.push_back(0.5 * (b + c));
    shape.referenceSamples.push_back(0.5 * (c + a));
    shape.referenceSamples.push_back((a + b + c) / 3.0);
  }
}

Shape makeShape(const std::string& name) {
  Shape s;
  s.name = name;
  if (name == "cube") {
    // 6 cm, turned off the lattice's axes (Euler angles 20°, 35°, 10°) and off its centre, so that
    // no edge or face lies along lattice lines.
    const glm::dmat3 frame = glm::dmat3(glm::rotate(glm::dmat4(1.0), glm::radians(10.0), glm::dvec3(0, 0, 1)) *
                                        glm::rotate(glm::dmat4(1.0), glm::radians(35.0), glm::dvec3(0, 1, 0)) *
                                        glm::rotate(glm::dmat4(1.0), glm::radians(20.0), glm::dvec3(1, 0, 0)));
    auto box = std::make_unique<geometry::BoxField>(glm::dvec3(0.0013, -0.0021, 0.0007), glm::dvec3(0.03), frame);
    const geometry::BoxField* b = box.get();
    s.description = "cube of 6 cm edge, rotated 20/35/10 degrees about x/y/z, exact signed distance";
    s.sharp = true;
    s.exact = true;
    s.exactSamples = [b](double spacing) { return b->surfaceSamples(spacing); };
    s.field = std::move(box);
  } else if (name == "sphere") {
    auto sphere = std::make_unique<geometry::SphereField>(glm::dvec3(0.0013, -0.0021, 0.0007), 0.04);
    const geometry::SphereField* p = sphere.get();
    s.description = "sphere of 4 cm radius, exact signed distance";
    s.exact = true;
    s.exactSamples = [p](double spacing) { return p->surfaceSamples(spacing); };
    s.field = std::move(sphere);
  } else if (name == "blob") {
    s.description = "the blob at t = 2.5 s (four Gaussian blobs, about 0.1 m across)";
    s.field = std::make_unique<geometry::BlobField>(kBlobTimeS);
  } else if (name == "candle") {
    auto candle = std::make_unique<geometry::CandleField>(0.0);
    // The wick (1 mm radius: under a cell of most lattices) is left out of both directions of the
    // comparison: a cylinder of 3 wick radii about the axis above 3 mm below the pool's floor (the
    // wick's root is 2 mm below it).
    const double wickZone = 3.0 * candle->params().wickRadius;
    const double wickFloor = candle->poolY() - candle->poolDepth() - 0.003;
    s.description = "the candle at t = 0 (cylinder of 2 cm radius, 6.5 cm tall, before it melts), wick left out";
    s.sharp = true;
    s.measured = [wickZone, wickFloor](glm::dvec3 p) { return std::hypot(p.x, p.z) > wickZone || p.y < wickFloor; };
    s.field = std::move(candle);
  } else {
    throw InputError("--shapes: unknown shape \"" + name + "\" (expected cube, candle, sphere or blob)");
  }
  if (!s.exact) buildReference(s);
  return s;
}

struct Distances {
  double meshMax = 0.0, meshMean = 0.0, surfaceMax = 0.0, surfaceMean = 0.0;  ///< cells
  std::size_t meshSamples = 0, surfaceSamples = 0;
};

/// Mesh → surface at each measured triangle's vertices, edge midpoints and centroid (the mean:
/// each triangle's mean of those 7, weighted by its area); surface → mesh at the surface samples.
Distances distances(const Shape& shape, const TriangleMesh& mesh, double cell) {
  Distances d;
  const double cap = kCapCells * cell;
  std::unique_ptr<geometry::TriangleGrid> referenceGrid;
  if (!shape.exact) referenceGrid = std::make_unique<geometry::TriangleGrid>(shape.reference, 0.5 * cell);
  auto toSurface = [&](glm::dvec3 p) {
    return shape.exact ? std::min(std::abs(shape.field->value(p)), cap) : referenceGrid->distance(p, cap);
  };
  struct TriangleResult {
    double max = 0.0, weighted = 0.0, area = 0.0;
    bool measured = false;
  };
  std::vector<TriangleResult> perTriangle(mesh.triangles.size());
  parallelFor(mesh.triangles.size(), [&](std::size_t i) {
    const auto& t = mesh.triangles[i];
    const glm::dvec3 a(mesh.positions[t[0]]), b(mesh.positions[t[1]]), c(mesh.positions[t[2]]);
    const glm::dvec3 centroid = (a + b + c) / 3.0;
    if (!shape.measured(centroid)) return;
    TriangleResult& r = perTriangle[i];
    r.measured = true;
    r.area = 0.5 * glm::length(glm::cross(b - a, c - a));
    double sum = 0.0;
    for (const glm::dvec3& p : {a, b, c, 0.5 * (a + b), 0.5 * (b + c), 0.5 * (c + a), centroid}) {
      const double dist = toSurface(p);
      r.max = std::max(r.max, dist);
      sum += dist;
    }
    r.weighted = r.area * sum / 7.0;
  });
  double weighted = 0.0, area = 0.0;
  for (const TriangleResult& r : perTriangle) {
    if (!r.measured) continue;
    d.meshMax = std::max(d.meshMax, r.max);
    weighted += r.weighted;
    area += r.area;
    d.meshSamples += 7;
  }
  d.meshMean = area > 0.0 ? weighted / area : 0.0;

  std::vector<glm::dvec3> samples;
  if (shape.exact) {
    samples = shape.exactSamples(kExactSpacingCells * cell);
  } else {
    samples = shape.referenceSamples;
  }
  std::erase_if(samples, [&](const glm::dvec3& p) { return !shape.measured(p); });
  const geometry::TriangleGrid grid(mesh, cell);
  std::vector<double> toMesh(samples.size());
  parallelFor(samples.size(), [&](std::size_t i) { toMesh[i] = grid.distance(samples[i], cap); });
  double sum = 0.0;
  for (double v : toMesh) {
    d.surfaceMax = std::max(d.surfaceMax, v);
    sum += v;
  }
  d.surfaceSamples = samples.size();
  d.surfaceMean = samples.empty() ? 0.0 : sum / static_cast<double>(samples.size());
  d.meshMax /= cell;
  d.meshMean /= cell;
  d.surfaceMax /= cell;
  d.surfaceMean /= cell;
  return d;
}

struct Checks {
  std::size_t badEdges = 0, zeroArea = 0, againstGradient = 0;
};

/// Watertight and manifold along edges (every edge in exactly two triangles), no zero-area
/// triangle, winding outward (against the field's gradient at the centroid: counted).
Checks check(const geometry::ScalarField& field, const TriangleMesh& mesh, double cell) {
  Checks c;
  std::vector<std::pair<std::uint64_t, int>> edges;
  edges.reserve(3 * mesh.triangles.size());
  for (const auto& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      const auto [lo, hi] = std::minmax(t[k], t[(k + 1) % 3]);
      edges.emplace_back((static_cast<std::uint64_t>(lo) << 32) | hi, 1);
    }
    const glm::dvec3 a(mesh.positions[t[0]]), b(mesh.positions[t[1]]), cc(mesh.positions[t[2]]);
    const glm::dvec3 n = glm::cross(b - a, cc - a);
    if (0.5 * glm::length(n) <= 1e-12 * cell * cell) ++c.zeroArea;
    if (!(glm::dot(n, field.gradient((a + b + cc) / 3.0)) > 0.0)) ++c.againstGradient;
  }
  std::sort(edges.begin(), edges.end());
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && edges[j].first == edges[i].first) ++j;
    if (j - i != 2) ++c.badEdges;
    i = j;
  }
  return c;
}

double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int runProbePlacement(const ProbePlacementOptions& o) {
  if (o.out.empty()) throw InputError("probe placement: --out FILE.json is required");
  checkOutputFile("--out", o.out, {".json"});  // before the work, not after it
  if (o.shapes.empty()) throw InputError("--shapes: give at least one of cube, candle, sphere, blob");
  for (const auto& s : o.shapes)
    if (s != "cube" && s != "candle" && s != "sphere" && s != "blob")
      throw InputError("--shapes: unknown shape \"" + s + "\" (expected cube, candle, sphere or blob)");
  if (o.resolutions.empty()) throw InputError("--res: give at least one resolution");
  for (int n : o.resolutions)
    if (n < 16 || n > 256) throw InputError("--res: " + std::to_string(n) + " is outside [16, 256]");
  if (o.repeats < 1 || o.repeats > 100) throw InputError("--repeats: must be in [1, 100]");

  gpu::ContextOptions contextOptions;
  contextOptions.backend = gpu::parseGlBackend(o.gl);
  const auto context = gpu::GlContext::create(contextOptions);
  const gpu::ShaderLibrary library;

  nlohmann::json shapes = nlohmann::json::array();
  for (const auto& name : o.shapes) {
    auto t0 = std::chrono::steady_clock::now();
    const Shape shape = makeShape(name);
    std::printf("%-6s reference ready in %.1f s%s\n", name.c_str(), msSince(t0) * 1e-3,
                shape.exact ? " (exact)" : "");
    std::fflush(stdout);
    nlohmann::json rows = nlohmann::json::array();
    for (int n : o.resolutions) {
      const geometry::SampledLattice lattice = geometry::sampleField(*shape.field, n);
      const double cell = lattice.cellSize;
      nlohmann::json row = {{"res", n}, {"cell_m", cell}};
      for (VertexPlacement placement : {VertexPlacement::Mass, VertexPlacement::Qef}) {
        geometry::GpuDualContouring dc(library, n, placement);
        dc.upload(lattice);
        dc.extract();  // warm-up
        glFinish();
        std::vector<double> gpuMs, wallMs;
        for (int r = 0; r < o.repeats; ++r) {
          t0 = std::chrono::steady_clock::now();
          dc.extract();
          glFinish();
          wallMs.push_back(msSince(t0));
          gpuMs.push_back(dc.lastExtractionMs());
        }
        const TriangleMesh mesh = dc.readBack();
        const Distances d = distances(shape, mesh, cell);
        const Checks c = check(*shape.field, mesh, cell);
        const double hausdorff = std::max(d.meshMax, d.surfaceMax);
        const std::string key(geometry::vertexPlacementName(placement));
        row[key] = {{"triangles", mesh.triangles.size()},
                    {"vertices", mesh.positions.size()},
                    {"hausdorff_cells", hausdorff},
                    {"mesh_to_surface_max_cells", d.meshMax},
                    {"mesh_to_surface_mean_cells", d.meshMean},
                    {"surface_to_mesh_max_cells", d.surfaceMax},
                    {"surface_to_mesh_mean_cells", d.surfaceMean},
                    {"mesh_samples", d.meshSamples},
                    {"surface_samples", d.surfaceSamples},
                    {"bad_edges", c.badEdges},
                    {"zero_area_triangles", c.zeroArea},
                    {"against_gradient", c.againstGradient},
                    {"gpu_extract_ms", median(gpuMs)},
                    {"gpu_extract_wall_ms", median(wallMs)}};
        std::printf("%-6s %3d³ %-4s  Hausdorff %.3f cells (mesh→surface max %.3f mean %.4f, surface→mesh max %.3f "
                    "mean %.4f)  %zu tris, bad edges %zu, zero-area %zu, against gradient %zu  extract %.2f ms\n",
                    name.c_str(), n, key.c_str(), hausdorff, d.meshMax, d.meshMean, d.surfaceMax, d.surfaceMean,
                    mesh.triangles.size(), c.badEdges, c.zeroArea, c.againstGradient, median(gpuMs));
        std::fflush(stdout);
      }
      const auto ratio = [&](const char* k) {
        const double mass = row["mass"][k].get<double>();
        return mass > 0.0 ? nlohmann::json(row["qef"][k].get<double>() / mass) : nlohmann::json(nullptr);
      };
      row["qef_over_mass"] = {{"hausdorff", ratio("hausdorff_cells")},
                              {"mesh_to_surface_mean", ratio("mesh_to_surface_mean_cells")},
                              {"surface_to_mesh_mean", ratio("surface_to_mesh_mean_cells")},
                              {"gpu_extract", ratio("gpu_extract_ms")}};
      rows.push_back(row);
    }
    shapes.push_back({{"shape", name},
                      {"description", shape.description},
                      {"sharp", shape.sharp},
                      {"reference",
                       shape.exact ? nlohmann::json("exact: |value| of the signed distance; surface samples " +
                                                    std::to_string(static_cast<int>(kExactSpacingCells * 100.0)) +
                                                    "% of a cell apart")
                                   : nlohmann::json("OpenVDB mesh of a " + std::to_string(kReferenceSamples) +
                                                    "^3 lattice, vertices projected onto the zero set (" +
                                                    std::to_string(shape.reference.triangles.size()) + " triangles, " +
                                                    std::to_string(shape.unprojected) + " vertices not projected)")},
                      {"rows", rows}});
  }
  const nlohmann::json result = {
      {"shapes", shapes},
      {"repeats", o.repeats},
      {"default_placement", std::string(geometry::vertexPlacementName(geometry::kDefaultPlacement))},
      {"gpu",
       glJson(*context)},
      {"notes",
       "distances in cells of the measured lattice; hausdorff_cells = max of the two directed maxima; mesh to "
       "surface at every triangle's vertices, edge midpoints and centroid (mean weighted by area), surface to "
       "mesh at the reference's samples; gpu_extract_ms: median of `repeats` GL_TIMESTAMP spans around "
       "extract() after one warm-up, gpu_extract_wall_ms the same with glFinish on the CPU clock"}};
  gpu::writeTextFileAtomically(o.out, result.dump(2) + "\n");
  return 0;
}

}  // namespace tallow::app
