// The OBJ writer (geometry/obj_writer): a reader written here from the format (v, vn, f a//a …)
// gets back the positions bit for bit, unit normals in the same directions and the triangles.
#include "geometry/obj_writer.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <sstream>
#include <stdexcept>
#include <string>

#include "geometry/primitives.h"
#include "support/temp_dir.h"

namespace tallow::geometry {
namespace {

TEST(ObjWriter, AReaderGetsBackThePositionsNormalsAndTriangles) {
  TriangleMesh mesh = makeSphere(5, 9);
  for (glm::vec3& p : mesh.positions) p = p * 0.123f + glm::vec3(1.0f, -2.5f, 1e-7f);
  for (std::size_t i = 0; i < mesh.normals.size(); ++i) mesh.normals[i] *= 0.5f + static_cast<float>(i % 3);
  std::istringstream in(encodeObj(mesh, {"made by a test"}));
  std::string line;
  std::vector<glm::vec3> v, vn;
  std::vector<std::array<std::uint32_t, 3>> f;
  int comments = 0;
  while (std::getline(in, line)) {
    glm::vec3 a;
    unsigned i[6];
    if (line.rfind("# ", 0) == 0) ++comments;
    else if (std::sscanf(line.c_str(), "vn %f %f %f", &a.x, &a.y, &a.z) == 3) vn.push_back(a);
    else if (std::sscanf(line.c_str(), "v %f %f %f", &a.x, &a.y, &a.z) == 3) v.push_back(a);
    else if (std::sscanf(line.c_str(), "f %u//%u %u//%u %u//%u", &i[0], &i[1], &i[2], &i[3], &i[4], &i[5]) == 6) {
      EXPECT_TRUE(i[0] == i[1] && i[2] == i[3] && i[4] == i[5]) << line;
      f.push_back({i[0] - 1, i[2] - 1, i[4] - 1});
    } else {
      ADD_FAILURE() << "unexpected line: " << line;
    }
  }
  EXPECT_EQ(comments, 1);
  ASSERT_EQ(v.size(), mesh.positions.size());
  ASSERT_EQ(vn.size(), mesh.positions.size());
  EXPECT_EQ(f, mesh.triangles);
  for (std::size_t i = 0; i < v.size(); ++i) {
    EXPECT_EQ(v[i], mesh.positions[i]) << i;  // 9 significant digits: a float reads back exactly
    EXPECT_NEAR(glm::length(vn[i]), 1.0f, 1e-6f);
    EXPECT_LT(glm::length(vn[i] - glm::normalize(mesh.normals[i])), 1e-6f);
  }
}

TEST(ObjWriter, BadTrianglesAndCommentsAreRefusedAndNothingIsLeft) {
  TriangleMesh mesh = makeSphere(3, 5);
  mesh.triangles.push_back({0, 1, static_cast<std::uint32_t>(mesh.positions.size())});
  EXPECT_THROW(encodeObj(mesh), std::invalid_argument);
  EXPECT_THROW(encodeObj(makeSphere(3, 5), {"two\nlines"}), std::invalid_argument);
  test::TempDir dir;
  EXPECT_THROW(writeObj(dir.path() / "m.obj", mesh), std::invalid_argument);
  EXPECT_TRUE(dir.entries().empty()) << "no partial or temporary file";
}

}  // namespace
}  // namespace tallow::geometry
