// The field kinds as plug-ins (issue 38, point 3; sss/field_kind.h): each kind answers what the
// renderer and the commands ask of a field — animated, its box, how it is sampled, its normals on
// the GPU, its own model — and the description questions (fieldAnimated, candleOf) that must not
// build a model agree with the model built. A still mesh has no GPU fill (it is uploaded).
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <stdexcept>

#include "geometry/blob_field.h"
#include "geometry/candle_field.h"
#include "geometry/grid_sampler.h"
#include "geometry/ply_writer.h"
#include "geometry/primitives.h"
#include "gpu/shader_library.h"
#include "sss/field_kind.h"
#include "sss/field_source.h"
#include "support/temp_dir.h"

namespace tallow {
namespace {

using geometry::NormalSource;

sss::SceneObject fieldObject(sss::FieldKind kind) {
  sss::SceneObject o;
  o.name = "field";
  o.shape = sss::ShapeKind::Field;
  o.field.kind = kind;
  return o;
}

/// A mesh field over a unit box written to `dir`, 5 cm, melting over `meltS` seconds (0: still).
sss::SceneObject boxField(const test::TempDir& dir, double meltS) {
  sss::SceneObject o = fieldObject(sss::FieldKind::Mesh);
  o.field.meshPath = dir.path() / "box.ply";
  geometry::writePly(o.field.meshPath, geometry::makeBox());
  o.field.meltDurationS = meltS;
  o.transform.scale = 0.05f;
  return o;
}

/// The lattice's values are the kind's field at its points (the same numbers, in float).
void expectSampleIsTheField(const sss::FieldSource& source, double t, int n) {
  const geometry::SampledLattice lattice = source.sample(t, n);
  const std::unique_ptr<geometry::ScalarField> field = source.at(t);
  for (int z = 0; z < n; z += 3)
    for (int y = 0; y < n; y += 3)
      for (int x = 0; x < n; x += 3)
        ASSERT_EQ(lattice.at(x, y, z), static_cast<float>(field->value(lattice.position(x, y, z))))
            << x << "," << y << "," << z;
}

void expectSameLattice(const geometry::SampledLattice& a, const geometry::SampledLattice& b) {
  EXPECT_EQ(a.n, b.n);
  EXPECT_EQ(a.origin, b.origin);
  EXPECT_EQ(a.cellSize, b.cellSize);
}

TEST(FieldKind, TheBlobIsAnimatedWithItsAnalyticNormalsOverTheBoxOfEveryTime) {
  const sss::SceneObject o = fieldObject(sss::FieldKind::Blob);
  const sss::FieldSource source(o);
  EXPECT_TRUE(source.animated());
  EXPECT_EQ(sss::fieldAnimated(o.field), source.animated());
  EXPECT_EQ(source.gpuNormals(), NormalSource::BlobGradient);
  ASSERT_TRUE(source.blobAt(1.5).has_value());
  EXPECT_FALSE(source.candleAt(1.5).has_value());
  EXPECT_FALSE(source.meltAt(1.5).has_value());
  EXPECT_FALSE(sss::candleOf(o.field, 1.5).has_value());
  EXPECT_FALSE(sss::fieldCarriesFlame(o.field));
  // The preset's scale reaches the model.
  sss::SceneObject scaled = o;
  scaled.field.blobScale = 0.05;
  EXPECT_EQ(sss::FieldSource(scaled).blobAt(0.0)->params().scale, 0.05);
  // The box of every t: the GPU's lattice is the CPU's, and the blob at any t lies inside it.
  expectSameLattice(source.sample(2.0, 16), source.gpuLattice(16));
  expectSampleIsTheField(source, 2.0, 16);
  const geometry::Aabb box = source.bounds();
  for (double t : {0.0, 1.0, 3.7, 9.0}) {
    const geometry::Aabb at = source.blobAt(t)->bounds();
    EXPECT_TRUE(glm::all(glm::greaterThanEqual(at.min, box.min)) && glm::all(glm::lessThanEqual(at.max, box.max)))
        << "t = " << t;
  }
}

TEST(FieldKind, TheCandleCarriesAFlameAndItsModelIsTheDescriptionsCandle) {
  sss::SceneObject o = fieldObject(sss::FieldKind::Candle);
  o.field.candleDrips = 3;
  o.field.candleSeed = 7;
  const sss::FieldSource source(o);
  EXPECT_TRUE(source.animated());
  EXPECT_EQ(sss::fieldAnimated(o.field), source.animated());
  EXPECT_EQ(source.gpuNormals(), NormalSource::CandleGradient);
  EXPECT_TRUE(sss::fieldCarriesFlame(o.field));
  EXPECT_FALSE(source.blobAt(0.0).has_value());
  const geometry::CandleField model = *source.candleAt(12.0);
  const geometry::CandleField described = *sss::candleOf(o.field, 12.0);
  EXPECT_EQ(model.params().dripCount, 3);
  EXPECT_EQ(model.params().seed, 7u);
  EXPECT_EQ(model.rimHeight(), described.rimHeight());
  EXPECT_EQ(model.poolRadius(), described.poolRadius());
  // The lattice holds still: the same box at every t, which is the candle's lifetime box.
  expectSameLattice(source.sample(0.0, 16), source.sample(15.0, 16));
  expectSameLattice(source.sample(15.0, 16), source.gpuLattice(16));
  expectSameLattice(source.gpuLattice(16),
                    geometry::latticeOver(geometry::CandleField::lifetimeBounds(sss::candleParams(o.field)), 16));
  expectSampleIsTheField(source, 15.0, 16);
}

TEST(FieldKind, AStillMeshIsSampledOverItsLevelSetAndHasNoGpuFill) {
  const test::TempDir dir;
  const sss::SceneObject o = boxField(dir, 0.0);
  const sss::FieldSource source(o);
  EXPECT_FALSE(source.animated());
  EXPECT_EQ(sss::fieldAnimated(o.field), source.animated());
  EXPECT_EQ(source.gpuNormals(), NormalSource::LatticeGradient);
  EXPECT_FALSE(source.meltAt(0.0).has_value());
  EXPECT_FALSE(sss::fieldCarriesFlame(o.field));
  const gpu::ShaderLibrary shaders;  // no GL needed: a still mesh makes no program
  EXPECT_EQ(source.gpuFill(shaders), nullptr);
  // Over its level set's box (which holds its narrow band).
  const std::unique_ptr<geometry::ScalarField> field = source.at(0.0);
  expectSameLattice(source.sample(0.0, 16), geometry::latticeOver(field->bounds(), 16));
  expectSampleIsTheField(source, 0.0, 16);
  // As a mesh object: largest extent 5 cm, bottom centre at the origin.
  const geometry::Aabb box = source.bounds();
  EXPECT_NEAR(box.max.y - box.min.y, 0.05, 0.01);
}

TEST(FieldKind, AMeltingMeshIsAnimatedOverTheBoxOfItsWholeMelt) {
  const test::TempDir dir;
  const sss::SceneObject o = boxField(dir, 4.0);
  const sss::FieldSource source(o);
  EXPECT_TRUE(source.animated());
  EXPECT_EQ(sss::fieldAnimated(o.field), source.animated());
  EXPECT_EQ(source.gpuNormals(), NormalSource::LatticeGradient);
  ASSERT_TRUE(source.meltAt(2.0).has_value());
  EXPECT_FALSE(source.candleAt(2.0).has_value());
  // Melted, the box spreads: wider than the still box, which it contains.
  const sss::FieldSource still(boxField(dir, 0.0));
  EXPECT_GT(source.bounds().max.x - source.bounds().min.x, still.bounds().max.x - still.bounds().min.x);
  expectSameLattice(source.sample(0.0, 16), source.sample(4.0, 16));
  expectSameLattice(source.sample(4.0, 16), source.gpuLattice(16));
  expectSampleIsTheField(source, 2.0, 16);
}

TEST(FieldKind, AnObjectThatIsNotAFieldIsRefused) {
  sss::SceneObject o;
  o.name = "sphere";
  o.shape = sss::ShapeKind::Sphere;
  EXPECT_THROW(sss::makeFieldKind(o), std::invalid_argument);
  EXPECT_THROW(sss::FieldSource{o}, std::invalid_argument);
}

}  // namespace
}  // namespace tallow
