// Issue 39, point 1: dual contouring's vertex and quad passes in compute shaders beside the
// geometry-shader path. The two run the same per-cell source (shaders/dual_contouring/
// cell_vertices.glsl, cell_quads.glsl) on the same lattice, so they must make the same vertices
// (positions and normals, bit for bit) and the same triangles (same corners, same winding), in
// whatever order their atomics and transform feedback store them; the renderer must then draw the
// same pictures from either.
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <memory>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "geometry/analytic_fields.h"
#include "geometry/blob_field.h"
#include "geometry/gpu_dual_contouring.h"
#include "geometry/grid_sampler.h"
#include "gpu/gl_context.h"
#include "gpu/shader_library.h"
#include "sss/field_objects.h"
#include "sss/field_source.h"
#include "support/mesh_checks.h"
#include "support/render_support.h"

namespace tallow {
namespace {

using geometry::ExtractionPath;
using geometry::GpuDualContouring;
using geometry::SampledLattice;
using geometry::TriangleMesh;

using Corner = std::array<float, 6>;  // position, normal
using Triangle = std::array<Corner, 3>;

/// Triangles as (position, normal) triples rotated to start at their smallest corner (keeps the
/// winding), sorted: meshes compare regardless of the order their passes stored them in.
std::vector<Triangle> triangleSet(const TriangleMesh& mesh) {
  std::vector<Triangle> set;
  for (const auto& t : mesh.triangles) {
    Triangle tri;
    for (std::size_t k = 0; k < 3; ++k) {
      const glm::vec3 p = mesh.positions[t[k]], n = mesh.normals[t[k]];
      tri[k] = {p.x, p.y, p.z, n.x, n.y, n.z};
    }
    std::rotate(tri.begin(), std::min_element(tri.begin(), tri.end()), tri.end());
    set.push_back(tri);
  }
  std::sort(set.begin(), set.end());
  return set;
}

struct Extraction {
  TriangleMesh mesh;
  std::size_t vertices = 0, triangles = 0;
};

/// Runs `dc` on the lattice `put` leaves in it, growing its buffers until the mesh fits.
Extraction run(GpuDualContouring& dc) {
  dc.extract();
  for (int growths = 0; dc.overflowed(true) == std::optional<bool>(true) && growths < 4; ++growths) {
    EXPECT_TRUE(dc.growToFit());
    dc.extract();
  }
  EXPECT_EQ(dc.overflowed(true), std::optional<bool>(false));
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  return {dc.readBack(), dc.vertexCount(), dc.triangleCount()};
}

void expectSameMeshes(const Extraction& compute, const Extraction& geometry, const std::string& what) {
  SCOPED_TRACE(what);
  std::printf("[ paths ] %-28s %7zu vertices %7zu triangles (compute) %7zu %7zu (geometry)\n", what.c_str(),
              compute.vertices, compute.triangles, geometry.vertices, geometry.triangles);
  ASSERT_GT(geometry.triangles, 0u) << "an empty mesh proves nothing";
  EXPECT_EQ(compute.vertices, geometry.vertices);
  EXPECT_EQ(compute.triangles, geometry.triangles);
  // Welded by vertex-buffer index (readBack): the same sharing, so the same welded vertex count.
  EXPECT_EQ(compute.mesh.positions.size(), geometry.mesh.positions.size());
  EXPECT_TRUE(triangleSet(compute.mesh) == triangleSet(geometry.mesh)) << "the triangles differ";
}

class DualContouringPaths : public ::testing::Test {
 protected:
  void SetUp() override { context_ = gpu::GlContext::create(gpu::ContextOptions{}); }

  Extraction extract(const SampledLattice& lattice, ExtractionPath path, geometry::VertexPlacement placement) {
    GpuDualContouring dc(library_, lattice.n, placement, geometry::NormalSource::LatticeGradient, path);
    EXPECT_EQ(dc.path(), path);
    dc.upload(lattice);
    return run(dc);
  }

  void expectSame(const SampledLattice& lattice, const std::string& what,
                  geometry::VertexPlacement placement = geometry::kDefaultPlacement) {
    expectSameMeshes(extract(lattice, ExtractionPath::Compute, placement),
                     extract(lattice, ExtractionPath::GeometryShader, placement), what);
  }

  std::unique_ptr<gpu::GlContext> context_;
  gpu::ShaderLibrary library_;
};

TEST_F(DualContouringPaths, SmoothAndSharpShapesGiveTheSameMeshes) {
  const test::SphereField sphere(glm::dvec3(0.0), 0.05);
  expectSame(geometry::sampleField(sphere, 40), "sphere 40^3 qef");
  expectSame(geometry::sampleField(sphere, 40), "sphere 40^3 mass", geometry::VertexPlacement::Mass);
  // Sharp edges and corners, turned off the lattice's axes: the QEF's case.
  const glm::dmat3 turned(glm::rotate(glm::dmat4(1.0), 0.4, glm::normalize(glm::dvec3(1.0, 2.0, 3.0))));
  const geometry::BoxField box(glm::dvec3(0.0), glm::dvec3(0.02, 0.03, 0.025), turned);
  expectSame(geometry::sampleField(box, 33), "box 33^3 qef");
  const geometry::BlobField blob(3.0);
  expectSame(geometry::sampleField(blob, 48), "blob t=3 48^3");
}

TEST_F(DualContouringPaths, AmbiguousCellsFaceVerticesAndOverflowGiveTheSameMeshes) {
  // Uniform noise: many cells with several patches, face vertices (necks thinner than a cell).
  for (unsigned seed = 1; seed <= 3; ++seed) {
    const int n = 14;
    SampledLattice lattice;
    lattice.n = n;
    lattice.cellSize = 1.0 / (n - 1);
    lattice.values.assign(static_cast<std::size_t>(n) * n * n, 1.0f);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> noise(-1.0f, 1.0f);
    for (int z = 1; z < n - 1; ++z)
      for (int y = 1; y < n - 1; ++y)
        for (int x = 1; x < n - 1; ++x) lattice.values[lattice.index(x, y, z)] = noise(rng);
    expectSame(lattice, "random signs, seed " + std::to_string(seed));
  }
  // Alternating signs: every edge changes sign; both paths overflow their first buffers and grow.
  const int n = 16;
  SampledLattice checker;
  checker.n = n;
  checker.cellSize = 1.0 / (n - 1);
  checker.values.resize(static_cast<std::size_t>(n) * n * n);
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) checker.values[checker.index(x, y, z)] = ((x + y + z) % 2) ? 1.0f : -1.0f;
  expectSame(checker, "checkerboard 16^3");
}

TEST_F(DualContouringPaths, TheMeltingCandleFilledOnTheGpuGivesTheSameMesh) {
  // As the renderer makes it: the candle's lattice filled on the GPU from t, normals from its
  // analytic gradient (CandleGradient), at a moment with a pool, a rim and drips.
  test::PresetSession session("candle", {"render.width=8", "render.height=8"});
  const sss::Scene& scene = session.scene();
  const auto object = std::find_if(scene.objects.begin(), scene.objects.end(),
                                   [](const sss::SceneObject& o) { return o.shape == sss::ShapeKind::Field; });
  ASSERT_NE(object, scene.objects.end());
  const sss::FieldSource source(*object);
  const double t = scene.startS + 6.0;
  std::array<Extraction, 2> made;
  for (ExtractionPath path : {ExtractionPath::Compute, ExtractionPath::GeometryShader}) {
    sss::FieldMeshing meshing;
    meshing.res = 64;
    meshing.extraction = path;
    const auto dc = sss::makeFieldExtractor(session.shaders(), source, meshing);
    EXPECT_NE(dc->normalSource(), geometry::NormalSource::LatticeGradient);
    const auto fill = source.gpuFill(session.shaders());
    ASSERT_NE(fill, nullptr);
    sss::putFieldLattice(source, t, *dc, fill.get());
    made[path == ExtractionPath::Compute ? 0 : 1] = run(*dc);
  }
  expectSameMeshes(made[0], made[1], "candle t=start+6 s 64^3");
}

// The renderer draws the same pictures from either path: the candle (camera, shadow cube, maps,
// VPLs all draw the field) and the blob.
gpu::Image render(const std::string& preset, std::vector<std::string> sets, const char* extraction) {
  sets.push_back(std::string("field.extraction=") + extraction);
  test::PresetSession s(preset, sets);
  return s.render(s.scene().startS + 2.0);
}

void expectSamePictures(const std::string& preset, const std::vector<std::string>& sets) {
  const gpu::Image compute = render(preset, sets, "compute");
  const gpu::Image geometry = render(preset, sets, "geometry");
  ASSERT_EQ(compute.pixels.size(), geometry.pixels.size());
  double lit = 0.0;
  std::size_t differ = 0;
  for (std::size_t i = 0; i < compute.pixels.size(); ++i) {
    const glm::vec4 a = compute.pixels[i], b = geometry.pixels[i];
    lit += a.r + a.g + a.b;
    differ += a == b ? 0 : 1;
  }
  EXPECT_GT(lit, 0.0) << preset << ": a black picture proves nothing";
  EXPECT_EQ(differ, 0u) << preset << ": pixels differ between the extraction paths";
}

TEST_F(DualContouringPaths, TheRendererDrawsTheSamePicturesFromEither) {
  expectSamePictures("candle", {"render.width=96", "render.height=54", "render.aa=1", "sss.frames=1",
                                "flame.flicker=0", "field.res=48", "vpl.count=16"});
  expectSamePictures("blob", {"render.width=64", "render.height=48", "sss.frames=1", "field.res=32"});
}

}  // namespace
}  // namespace tallow
