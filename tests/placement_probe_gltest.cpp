// `tallow probe placement` through the executable: the JSON contract on a small case (the exact
// cube and sphere at 24³), what it measures (both placements watertight; on the cube the QEF closer
// to the exact surface than the mass point, whose chamfered edges are about half a cell off), and
// one-line errors for bad input.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "support/run_tallow.h"
#include "support/temp_dir.h"

namespace tallow {
namespace {

using test::runTallow;

TEST(PlacementProbe, CubeAndSphereWriteBothPlacementsAndTheQefKeepsTheCubesEdges) {
  test::TempDir dir;
  const auto out = dir.path() / "placement.json";
  const auto r = runTallow({"probe", "placement", "--shapes", "cube,sphere", "--res", "24", "--repeats", "1", "--out",
                            out.string()});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  std::ifstream in(out);
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_FALSE(j["gpu"]["GL_RENDERER"].get<std::string>().empty());
  EXPECT_EQ(j["repeats"], 1);
  EXPECT_TRUE(j["default_placement"] == "qef" || j["default_placement"] == "mass");
  ASSERT_EQ(j["shapes"].size(), 2u);
  for (const auto& shape : j["shapes"]) {
    const bool cube = shape["shape"] == "cube";
    EXPECT_EQ(shape["sharp"].get<bool>(), cube);
    ASSERT_EQ(shape["rows"].size(), 1u);
    const auto& row = shape["rows"][0];
    EXPECT_EQ(row["res"], 24);
    for (const char* placement : {"mass", "qef"}) {
      const auto& m = row[placement];
      for (const char* key : {"hausdorff_cells", "mesh_to_surface_max_cells", "mesh_to_surface_mean_cells",
                              "surface_to_mesh_max_cells", "surface_to_mesh_mean_cells", "gpu_extract_ms"}) {
        ASSERT_TRUE(m.contains(key)) << placement << " " << key;
        EXPECT_TRUE(std::isfinite(m[key].get<double>())) << key;
        EXPECT_GE(m[key].get<double>(), 0.0) << key;
      }
      EXPECT_DOUBLE_EQ(m["hausdorff_cells"].get<double>(), std::max(m["mesh_to_surface_max_cells"].get<double>(),
                                                                    m["surface_to_mesh_max_cells"].get<double>()));
      EXPECT_GT(m["triangles"].get<std::size_t>(), 0u);
      EXPECT_EQ(m["bad_edges"], 0) << placement;
      EXPECT_EQ(m["zero_area_triangles"], 0) << placement;
      // Every dual-contouring vertex lies in a cell the surface crosses: no point of the mesh is a
      // cell diagonal (√3) from the surface; a missing piece of surface would show as the cap, 8.
      EXPECT_LT(m["mesh_to_surface_max_cells"].get<double>(), std::sqrt(3.0)) << placement;
      EXPECT_LT(m["surface_to_mesh_max_cells"].get<double>(), 2.0) << placement;
    }
    // The same lattice and the same cells: the placements differ in where vertices go, not in how many.
    EXPECT_EQ(row["mass"]["triangles"], row["qef"]["triangles"]);
    if (cube) {
      // The mass point's chamfer leaves some of the cube's surface (its edges) about half a cell or
      // more from the mesh; the QEF's vertices sit on the edges (tests/dual_contouring_gltest.cpp).
      EXPECT_GT(row["mass"]["surface_to_mesh_max_cells"].get<double>(), 0.5);
      EXPECT_LT(row["qef"]["hausdorff_cells"].get<double>(), 0.8 * row["mass"]["hausdorff_cells"].get<double>());
      EXPECT_LT(row["qef"]["surface_to_mesh_mean_cells"].get<double>(),
                0.5 * row["mass"]["surface_to_mesh_mean_cells"].get<double>());
    }
  }
}

TEST(PlacementProbe, BadInputGivesOneLineAndNonZeroExit) {
  test::TempDir dir;
  const std::string out = (dir.path() / "x.json").string();
  const std::vector<std::vector<std::string>> cases = {
      {"probe", "placement", "--shapes", "teapot", "--res", "24", "--out", out},
      {"probe", "placement", "--shapes", "cube", "--res", "8", "--out", out},
      {"probe", "placement", "--shapes", "cube", "--res", "512", "--out", out},
      {"probe", "placement", "--shapes", "cube", "--res", "24", "--repeats", "0", "--out", out},
      {"probe", "placement", "--shapes", "cube", "--res", "24", "--gl", "vulkan", "--out", out},
      {"probe", "placement", "--shapes", "cube", "--res", "24"},
  };
  for (const auto& args : cases) {
    const auto r = runTallow(args);
    std::string joined;
    for (const auto& a : args) joined += a + " ";
    EXPECT_NE(r.exitCode, 0) << joined;
    EXPECT_EQ(test::lineCount(r.err), 1) << joined << "\n" << r.err;
  }
  EXPECT_FALSE(std::filesystem::exists(out));
}

}  // namespace
}  // namespace tallow
