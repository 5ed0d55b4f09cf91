// `tallow mesh` and `tallow field` through the executable: the blob's mesh is closed, outward and
// on the field's zero level set; GPU and OpenVDB meshes of the same lattice agree; the object's
// transform is applied; the field's sign, gradient and translation; the one-line errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <regex>
#include <sstream>

#include "app/config/setup.h"
#include "geometry/ply_reader.h"
#include "sss/field_source.h"
#include "support/mesh_checks.h"
#include "support/run_tallow.h"
#include "support/temp_dir.h"

namespace tallow {
namespace {

using test::runTallow;

constexpr double kTimeS = 2.5;  // blobs apart and merging (at t = 0 they coincide)
constexpr int kRes = 48;        // small: the tests run on llvmpipe on 2 cores

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The blob preset with its object moved and turned (JSON text edited, everything else kept).
std::filesystem::path movedBlobPreset(const test::TempDir& dir, const std::string& name, const std::string& position,
                                      const std::string& rotation = "[0, 0, 0]") {
  std::string json = slurp(std::string(TALLOW_TEST_SOURCE_DIR) + "/presets/blob.json");
  const std::string from = "\"position\": [0.0, 0.06, 0.0]";
  const auto at = json.find(from);
  EXPECT_NE(at, std::string::npos) << "presets/blob.json changed; update this test";
  json.replace(at, from.size(), "\"position\": " + position + ", \"rotation_deg\": " + rotation);
  return dir.write(name + ".json", json);
}

geometry::TriangleMesh meshOf(const std::vector<std::string>& extra, const test::TempDir& dir, const std::string& name,
                              const std::string& preset = "blob") {
  const auto out = dir.path() / (name + ".ply");
  std::vector<std::string> args{"mesh", "--preset", preset, "--time", std::to_string(kTimeS), "--res",
                                std::to_string(kRes), "--out", out.string()};
  args.insert(args.end(), extra.begin(), extra.end());
  const auto r = runTallow(args);
  EXPECT_EQ(r.exitCode, 0) << r.err;
  return geometry::readPly(out);
}

struct FieldRow {
  glm::dvec3 p, gradient;
  double value = 0.0;
};

std::vector<FieldRow> fieldAt(const std::vector<glm::dvec3>& points, const test::TempDir& dir,
                              const std::string& preset = "blob", double timeS = kTimeS) {
  std::ostringstream csv;
  csv.precision(17);
  csv << "x,y,z\n";
  for (const auto& p : points) csv << p.x << "," << p.y << "," << p.z << "\n";
  const auto in = dir.write("points.csv", csv.str());
  const auto out = dir.path() / "values.csv";
  const auto r = runTallow({"field", "--preset", preset, "--time", std::to_string(timeS), "--in", in.string(),
                            "--out", out.string()});
  EXPECT_EQ(r.exitCode, 0) << r.err;
  std::istringstream text(slurp(out));
  std::string line;
  std::getline(text, line);
  EXPECT_EQ(line, "x,y,z,value,grad_x,grad_y,grad_z");
  std::vector<FieldRow> rows;
  while (std::getline(text, line)) {
    std::vector<double> v;
    std::stringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) v.push_back(std::stod(cell));
    EXPECT_EQ(v.size(), 7u);
    if (v.size() == 7) rows.push_back({{v[0], v[1], v[2]}, {v[4], v[5], v[6]}, v[3]});
  }
  EXPECT_EQ(rows.size(), points.size());
  return rows;
}

/// Metres between lattice samples for the blob preset at kRes: sampled exactly as the commands do.
double blobCellSize() {
  app::SceneOptions options;
  options.preset = "blob";
  const app::LoadedScene loaded = app::loadScene(options);
  for (const auto& o : loaded.config.scene.objects)
    if (o.shape == sss::ShapeKind::Field) return sss::FieldSource(o).sample(kTimeS, kRes).cellSize;
  ADD_FAILURE() << "blob preset without a field object";
  return 0.0;
}

TEST(MeshFieldCli, BlobMeshIsClosedOutwardAndOnTheZeroLevelSet) {
  test::TempDir dir;
  const geometry::TriangleMesh mesh = meshOf({}, dir, "gpu");
  ASSERT_GT(mesh.triangles.size(), 1000u);
  EXPECT_EQ(test::badEdges(mesh), 0);
  EXPECT_GT(test::signedVolume(mesh), 0.0);
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{"gpu.ply"}));  // no temporary file left

  // Every vertex within half a cell of the surface, by the first-order distance |value| / |∇value|
  // of the continuous field (the mesh interpolates the lattice linearly, so it is off by less).
  const double cell = blobCellSize();
  ASSERT_GT(cell, 0.0);
  std::vector<glm::dvec3> points(mesh.positions.begin(), mesh.positions.end());
  const auto rows = fieldAt(points, dir);
  double worst = 0.0;
  for (const auto& r : rows) worst = std::max(worst, std::abs(r.value) / glm::length(r.gradient));
  EXPECT_LT(worst, 0.5 * cell) << "cell " << cell;
  // Normals point out: along the field's gradient.
  int against = 0;
  for (std::size_t i = 0; i < rows.size(); ++i)
    against += glm::dot(glm::dvec3(mesh.normals[i]), rows[i].gradient) <= 0.0 ? 1 : 0;
  EXPECT_EQ(against, 0);
}

TEST(MeshFieldCli, CpuAndGpuMeshesOfTheSameLatticeAgree) {
  test::TempDir dir;
  const geometry::TriangleMesh gpu = meshOf({}, dir, "gpu");
  const geometry::TriangleMesh cpu = meshOf({"--cpu"}, dir, "cpu");
  EXPECT_EQ(test::badEdges(cpu), 0);
  const double vGpu = test::signedVolume(gpu), vCpu = test::signedVolume(cpu);
  EXPECT_GT(vCpu, 0.0);
  EXPECT_NEAR(vGpu / vCpu, 1.0, 0.02);  // both contour one lattice; vertices placed differently
  const geometry::Aabb a = gpu.bounds(), b = cpu.bounds();
  const double cell = blobCellSize();
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(a.min[k], b.min[k], cell);
    EXPECT_NEAR(a.max[k], b.max[k], cell);
  }
}

TEST(MeshFieldCli, MeshIsInWorldUnits) {
  test::TempDir dir;
  const auto moved = movedBlobPreset(dir, "moved", "[1.0, 0.06, 0.0]");
  const geometry::TriangleMesh base = meshOf({}, dir, "base");
  const geometry::TriangleMesh shifted = meshOf({}, dir, "shifted", moved.string());
  ASSERT_EQ(shifted.positions.size(), base.positions.size());
  const geometry::Aabb a = base.bounds(), b = shifted.bounds();
  constexpr double kFloatAtOne = 1e-6;  // positions are floats: one ulp at 1 m is 1.2e-7
  EXPECT_NEAR(b.min.x - a.min.x, 1.0, kFloatAtOne);
  EXPECT_NEAR(b.max.x - a.max.x, 1.0, kFloatAtOne);
  for (int k = 1; k < 3; ++k) {
    EXPECT_NEAR(b.min[k], a.min[k], kFloatAtOne);
    EXPECT_NEAR(b.max[k], a.max[k], kFloatAtOne);
  }
  // The blob sits around its position: y about 0.06 m, not about 0 (field units).
  EXPECT_NEAR(0.5 * (a.min.y + a.max.y), 0.06, 0.05);

  // Turned 90° about z: field x becomes world y, so the extents swap.
  const auto turned = movedBlobPreset(dir, "turned", "[0.0, 0.06, 0.0]", "[0, 0, 90]");
  const geometry::Aabb t = meshOf({}, dir, "turned", turned.string()).bounds();
  EXPECT_NEAR(t.size().y, a.size().x, 1e-5);
  EXPECT_NEAR(t.size().x, a.size().y, 1e-5);
}

TEST(MeshFieldCli, MeltingMeshFieldSlumpsAndSpreadsOverTime) {
  // The bunny as a mesh field that melts over 10 s (MeltParams defaults: the height shrinks to
  // 1 − 0.4 = 0.6 by slumping, then mean-curvature flow rounds it; the puddle widens the base).
  test::TempDir dir;
  const std::string kCamera = R"({"camera": {"position": [0, 0.06, 0.3], "target": [0, 0.05, 0]},
  "lights": [{"type": "directional", "direction": [0, 1, 1], "irradiance": [3, 3, 3]}],
  )";
  const auto preset = dir.write("melting.json", kCamera + R"("objects": [{"field": {"type": "mesh", "mesh": "data:bunny.ply", "melt_s": 10}, "scale": 0.1}]})");
  const auto still = dir.write("still.json", kCamera + R"("objects": [{"field": {"type": "mesh", "mesh": "data:bunny.ply"}, "scale": 0.1}]})");
  const auto at = [&](const std::filesystem::path& p, double t, const std::string& name) {
    const auto out = dir.path() / (name + ".ply");
    const auto r = runTallow({"mesh", "--preset", p.string(), "--time", std::to_string(t), "--res", "64", "--out", out.string()});
    EXPECT_EQ(r.exitCode, 0) << r.err;
    return geometry::readPly(out);
  };
  const geometry::TriangleMesh start = at(preset, 0.0, "start"), end = at(preset, 10.0, "end");
  const geometry::TriangleMesh stillEnd = at(still, 10.0, "still");
  for (const auto* m : {&start, &end}) {
    EXPECT_EQ(test::badEdges(*m), 0);
    EXPECT_GT(test::signedVolume(*m), 0.0);
  }
  const geometry::Aabb a = start.bounds(), b = end.bounds();
  EXPECT_LT(b.max.y - b.min.y, 0.62 * (a.max.y - a.min.y));  // slumped to at most 0.6 (+ a cell)
  EXPECT_GT(b.size().x, 1.2 * a.size().x);                    // the puddle spreads beyond the footprint
  // Without melt_s the mesh field does not change with time.
  EXPECT_EQ(stillEnd.triangles.size(), at(still, 0.0, "still0").triangles.size());
}

TEST(MeshFieldCli, FieldSignGradientAndTransform) {
  test::TempDir dir;
  const glm::dvec3 centre(0.0, 0.06, 0.0);  // the preset's position: all blobs meet there at t = 0
  const glm::dvec3 far(0.5, 1.0, -0.7);
  const glm::dvec3 nearSurface = centre + glm::dvec3(0.012, 0.004, -0.003);
  {
    const auto rows = fieldAt({centre, far}, dir, "blob", 0.0);
    ASSERT_EQ(rows.size(), 2u);
    EXPECT_LT(rows[0].value, 0.0);
    EXPECT_GT(rows[1].value, 0.0);
    EXPECT_EQ(rows[1].value, 0.5);  // iso − Φ with Φ ≈ 0 far away
  }
  // Gradient against central differences of the returned values (a second evaluation).
  constexpr double h = 1e-6;  // metres: small against the blob (~0.1 m), large against round-off
  std::vector<glm::dvec3> points{nearSurface};
  for (int k = 0; k < 3; ++k)
    for (double s : {-1.0, 1.0}) {
      glm::dvec3 p = nearSurface;
      p[k] += s * h;
      points.push_back(p);
    }
  const auto rows = fieldAt(points, dir);
  ASSERT_EQ(rows.size(), 7u);
  const glm::dvec3 g = rows[0].gradient;
  ASSERT_GT(glm::length(g), 1.0);
  for (int k = 0; k < 3; ++k) {
    const double fd = (rows[2 + 2 * k].value - rows[1 + 2 * k].value) / (2.0 * h);
    EXPECT_NEAR(fd, g[k], 1e-4 * glm::length(g)) << "axis " << k;
  }

  // Moved by +1 m in x: the same values and gradients 1 m further.
  const auto moved = movedBlobPreset(dir, "moved", "[1.0, 0.06, 0.0]");
  const auto shifted = fieldAt({nearSurface + glm::dvec3(1, 0, 0)}, dir, moved.string());
  ASSERT_EQ(shifted.size(), 1u);
  EXPECT_NEAR(shifted[0].value, rows[0].value, 1e-9);
  EXPECT_LT(glm::length(shifted[0].gradient - g), 1e-6 * glm::length(g));

  // Turned 90° about z: the field at R·p is the field at p, and its gradient turns with it.
  const auto turned = movedBlobPreset(dir, "turned", "[0.0, 0.06, 0.0]", "[0, 0, 90]");
  const glm::dvec3 d = nearSurface - centre;
  const auto rotated = fieldAt({centre + glm::dvec3(-d.y, d.x, d.z)}, dir, turned.string());
  ASSERT_EQ(rotated.size(), 1u);
  EXPECT_NEAR(rotated[0].value, rows[0].value, 1e-5 * std::abs(rows[0].value) + 1e-7);
  const glm::dvec3 gTurned(-g.y, g.x, g.z);
  EXPECT_LT(glm::length(rotated[0].gradient - gTurned), 1e-5 * glm::length(g));
}

TEST(MeshFieldCli, SeveralFieldObjectsAreConcatenatedAndUnited) {
  test::TempDir dir;
  std::string json = slurp(std::string(TALLOW_TEST_SOURCE_DIR) + "/presets/blob.json");
  const std::string from = "\"objects\": [";
  const auto at = json.find(from);
  ASSERT_NE(at, std::string::npos);
  json.insert(at + from.size(),
              R"({"name": "second", "field": {"type": "blob", "scale": 0.03}, "material": "Skimmilk",)"
              R"( "albedo": [0.8, 0.8, 0.8], "position": [1.0, 0.06, 0.0]},)");
  const auto two = dir.write("two.json", json);
  const geometry::TriangleMesh one = meshOf({}, dir, "one");
  const geometry::TriangleMesh both = meshOf({}, dir, "both", two.string());
  EXPECT_EQ(both.triangles.size(), 2 * one.triangles.size());
  EXPECT_EQ(test::badEdges(both), 0);
  EXPECT_EQ(test::countComponents(both), 2 * test::countComponents(one));
  EXPECT_NEAR(test::signedVolume(both), 2.0 * test::signedVolume(one), 1e-6 * test::signedVolume(one));
  // The union: inside either blob is inside; the value is the smaller one, with its gradient.
  const glm::dvec3 p(0.012, 0.064, -0.003);
  const auto single = fieldAt({p}, dir);
  const auto united = fieldAt({p, p + glm::dvec3(1, 0, 0), {0.5, 0.06, 0.0}}, dir, two.string());
  ASSERT_EQ(united.size(), 3u);
  for (int i = 0; i < 2; ++i) {
    EXPECT_NEAR(united[static_cast<std::size_t>(i)].value, single[0].value, 1e-9);
    EXPECT_LT(glm::length(united[static_cast<std::size_t>(i)].gradient - single[0].gradient),
              1e-6 * glm::length(single[0].gradient));
  }
  EXPECT_GT(united[2].value, 0.0);  // half-way between: outside both
}

TEST(MeshFieldCli, ErrorsAreOneLineAndWriteNothing) {
  test::TempDir dir;
  const auto out = (dir.path() / "out.file").string();
  const auto meshOut = (dir.path() / "out.ply").string();
  const auto good = dir.write("good.csv", "x,y,z\n0,0,0\n").string();
  const auto header = dir.write("header.csv", "x,y\n0,0\n").string();
  const auto number = dir.write("number.csv", "x,y,z\n0,0,0\n\n0.5, 1e-3 ,0.25q\n").string();
  struct Case {
    std::vector<std::string> args;
    std::string message;  ///< the whole stderr line after "tallow: ", as a regex
  };
  const std::string d = dir.path().string();
  const std::vector<Case> cases{
      {{"field", "--preset", "blob", "--in", d + "/none.csv", "--out", out}, ".*/none\\.csv: cannot open"},
      {{"field", "--preset", "blob", "--in", header, "--out", out}, ".*/header\\.csv:1:4: expected the header x,y,z"},
      {{"field", "--preset", "blob", "--in", number, "--out", out},
       ".*/number\\.csv:4:12: z: \"0\\.25q\" is not a finite number"},
      {{"field", "--preset", "bunny", "--in", good, "--out", out},
       "preset \"bunny\" has no field objects \\(objects with a \"field\": blob, candle or mesh\\)"},
      {{"mesh", "--preset", "bunny", "--out", meshOut},
       "preset \"bunny\" has no field objects \\(objects with a \"field\": blob, candle or mesh\\)"},
      {{"mesh", "--preset", "blob", "--res", "8", "--out", meshOut}, "--res: field\\.res: 8 is out of range \\[16, 512\\]"},
      {{"mesh", "--preset", "blob", "--res", "999", "--cpu", "--out", meshOut},
       "--res: field\\.res: 999 is out of range \\[16, 512\\]"},
      // The folder is created as capture's --out is, unless a file stands in its way.
      {{"mesh", "--preset", "blob", "--out", good + "/m.ply"}, "--out: .*/good\\.csv is not a folder"},
      {{"mesh", "--preset", "blob", "--out", out}, "--out: .*/out\\.file is neither MESH\\.ply nor MESH\\.obj"},
      {{"mesh", "--preset", "blob", "--frames", "-1", "--out", meshOut}, "--frames: must not be negative"},
      {{"mesh", "--preset", "blob", "--frames", "2", "--fps", "0", "--out", meshOut},
       "--fps: 0 is out of range \\[0\\.001, 10000\\] frames per second"},
  };
  for (const auto& c : cases) {
    const auto r = runTallow(c.args);
    EXPECT_EQ(r.exitCode, 1) << c.args[0] << " " << r.err;
    EXPECT_EQ(test::lineCount(r.err), 1) << r.err;
    std::string line = r.err;
    while (!line.empty() && line.back() == '\n') line.pop_back();
    EXPECT_TRUE(std::regex_match(line, std::regex("tallow: " + c.message))) << line << "\nexpected: " << c.message;
  }
  const auto names = dir.entries();
  EXPECT_EQ(std::count(names.begin(), names.end(), "out.file"), 0);
  EXPECT_EQ(names.size(), 3u);  // the three inputs, nothing else
}

}  // namespace
}  // namespace tallow
