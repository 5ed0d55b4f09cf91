// The PLY writer (geometry/ply_writer): what it writes, readPly reads back bit for bit; written
// atomically, nothing left behind on failure.
#include "geometry/ply_writer.h"

#include <gtest/gtest.h>

#include <cstring>
#include <stdexcept>

#include "geometry/ply_reader.h"
#include "geometry/primitives.h"
#include "support/temp_dir.h"

namespace tallow::geometry {
namespace {

TEST(PlyWriter, ReadBackIsExact) {
  TriangleMesh mesh = makeSphere(7, 11);
  // Normals of every length and direction: the writer stores unit ones that re-normalising keeps.
  for (std::size_t i = 0; i < mesh.normals.size(); ++i)
    mesh.normals[i] = mesh.normals[i] * (0.3f + 0.37f * static_cast<float>(i % 9)) + glm::vec3(1e-3f * static_cast<float>(i % 5));
  for (glm::vec3& p : mesh.positions) p = p * 0.123f + glm::vec3(1.0f, -2.5f, 1e-7f);
  test::TempDir dir;
  const auto path = dir.path() / "m.ply";
  writePly(path, mesh);
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"m.ply"});  // no temporary file left
  const TriangleMesh back = readPly(path);
  ASSERT_EQ(back.positions.size(), mesh.positions.size());
  ASSERT_EQ(back.normals.size(), mesh.normals.size());
  EXPECT_EQ(back.triangles, mesh.triangles);
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    EXPECT_EQ(back.positions[i], mesh.positions[i]) << i;
    EXPECT_NEAR(glm::length(back.normals[i]), 1.0f, 1e-6f);
    EXPECT_LT(glm::length(back.normals[i] - glm::normalize(mesh.normals[i])), 1e-6f);
  }
  // Read back and written again: the same bytes, so the stored normals are what readPly returns.
  EXPECT_EQ(encodePly(back), encodePly(mesh));
}

TEST(PlyWriter, HeaderIsBinaryLittleEndianWithFloatNormalsAndUintLists) {
  TriangleMesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  mesh.triangles = {{0, 1, 2}};  // no normals: computed from the face
  const std::string bytes = encodePly(mesh);
  const std::string header =
      "ply\nformat binary_little_endian 1.0\ncomment written by tallow\nelement vertex 3\n"
      "property float x\nproperty float y\nproperty float z\nproperty float nx\nproperty float ny\n"
      "property float nz\nelement face 1\nproperty list uchar uint vertex_indices\nend_header\n";
  ASSERT_EQ(bytes.substr(0, header.size()), header);
  EXPECT_EQ(bytes.size(), header.size() + 3 * 6 * 4 + 1 + 3 * 4);
  float nz = 0.0f;
  std::memcpy(&nz, bytes.data() + header.size() + 5 * 4, 4);
  EXPECT_EQ(nz, 1.0f);
  const TriangleMesh back = parsePly(bytes, "m.ply");
  EXPECT_EQ(back.normals[2], glm::vec3(0, 0, 1));
}

TEST(PlyWriter, CommentsGoInTheHeaderOneLineEach) {
  const TriangleMesh mesh = makeSphere(4, 4);
  const std::string bytes = encodePly(mesh, {"tallow.candle c t 8", "second"});
  EXPECT_EQ(bytes.find("comment written by tallow\ncomment tallow.candle c t 8\ncomment second\nelement vertex"),
            std::string("ply\nformat binary_little_endian 1.0\n").size());
  EXPECT_EQ(parsePly(bytes, "m.ply").triangles, mesh.triangles);  // readers skip comments
  EXPECT_THROW(encodePly(mesh, {"two\nlines"}), std::invalid_argument);
}

TEST(PlyWriter, EmptyMeshAndBadIndices) {
  // Written, though readPly refuses a mesh without faces (`tallow mesh` reports an empty surface first).
  const std::string empty = encodePly(TriangleMesh{});
  EXPECT_NE(empty.find("element vertex 0\n"), std::string::npos);
  EXPECT_NE(empty.find("element face 0\n"), std::string::npos);
  TriangleMesh bad;
  bad.positions = {{0, 0, 0}};
  bad.normals = {{0, 1, 0}};
  bad.triangles = {{0, 0, 1}};
  EXPECT_THROW(encodePly(bad), std::invalid_argument);
  test::TempDir dir;
  EXPECT_THROW(writePly(dir.path() / "missing" / "m.ply", makeSphere(4, 4)), std::runtime_error);
  EXPECT_TRUE(dir.entries().empty());
}

}  // namespace
}  // namespace tallow::geometry
