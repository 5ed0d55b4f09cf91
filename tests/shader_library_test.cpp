// Shader sources without a GL context: includes, #line mapping, driver-log mapping.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <sstream>

#include "gpu/shader_library.h"
#include "support/temp_dir.h"

namespace tallow {
namespace {

TEST(ShaderLibrary, EmbeddedSourcesMatchTheFilesInTheCheckout) {
  const gpu::ShaderLibrary embedded;
  const gpu::ShaderLibrary disk(std::filesystem::path(TALLOW_TEST_SOURCE_DIR) / "shaders");
  for (const char* file : {"surface.frag", "common/tonemap.glsl", "fullscreen.vert"})
    EXPECT_EQ(embedded.read(file), disk.read(file)) << file;
}

TEST(ShaderLibrary, ExpandsIncludesOnceWithLineDirectives) {
  test::TempDir dir;
  dir.write("a.frag", "#version 450 core\n#include \"lib/b.glsl\"\n#include \"lib/b.glsl\"\nvoid main() {}\n");
  dir.write("lib/b.glsl", "// b\nfloat b() { return 1.0; }\n");
  const gpu::ShaderLibrary lib(dir.path());
  const gpu::ExpandedSource s = lib.expand("a.frag", {"K 4"});
  ASSERT_EQ(s.files.size(), 2u);
  EXPECT_EQ(s.files[0], "a.frag");
  EXPECT_EQ(s.files[1], "lib/b.glsl");
  // #version first, then the defines, then line 2 of file 0; the included file is numbered 1 (its
  // lines from 100001, so that the file can be read off the line number) and the text after the
  // include resumes at the right line of file 0.
  EXPECT_EQ(s.text,
            "#version 450 core\n#define TALLOW_GLSL 1\n#define K 4\n#line 2 0\n"
            "#line 100001 1\n// b\nfloat b() { return 1.0; }\n#line 3 0\n#line 4 0\nvoid main() {}\n");
}

TEST(ShaderLibrary, MissingIncludeNamesTheIncludingLine) {
  test::TempDir dir;
  dir.write("a.frag", "#version 450 core\n\n#include \"nope.glsl\"\n");
  const gpu::ShaderLibrary lib(dir.path());
  try {
    lib.expand("a.frag");
    FAIL() << "expected ShaderError";
  } catch (const gpu::ShaderError& e) {
    EXPECT_STREQ(e.what(), "a.frag:3: error: cannot include \"nope.glsl\"");
  }
}

TEST(ShaderLibrary, IncludeCycleIsAnError) {
  test::TempDir dir;
  dir.write("a.frag", "#version 450 core\n#include \"b.glsl\"\n");
  dir.write("b.glsl", "#include \"c.glsl\"\n");
  dir.write("c.glsl", "#include \"b.glsl\"\n");
  const gpu::ShaderLibrary lib(dir.path());
  EXPECT_THROW(lib.expand("a.frag"), gpu::ShaderError);
}

TEST(ShaderLibrary, MapsMesaAndNvidiaLogsToFileAndLine) {
  gpu::ExpandedSource s;
  s.files = {"surface.frag", "common/lights.glsl"};
  EXPECT_EQ(gpu::mapShaderLog("0:12(5): error: `foo' undeclared\n", s),
            "shaders/surface.frag:12: error: `foo' undeclared\n");
  EXPECT_EQ(gpu::mapShaderLog("1(100040) : error C1008: undefined variable \"x\"\n", s),
            "shaders/common/lights.glsl:40: error C1008: undefined variable \"x\"\n");
  // Mesa sometimes names source string 0 for an error in an included file; the line tells.
  EXPECT_EQ(gpu::mapShaderLog("0:100003(19): error: `y' undeclared\n", s),
            "shaders/common/lights.glsl:3: error: `y' undeclared\n");
  EXPECT_EQ(gpu::mapShaderLog("something else\n", s), "something else\n");
}

// Issue 39, point 3: a fragment shader that writes gl_FragDepth turns off early depth for its
// whole pass (the point lights' shadow cube spent most of its time shading hidden triangles).
// Shadow maps hold the rasterised depth (common/cube_shadow_depth.glsl); no shader writes it.
TEST(ShaderSources, NoShaderWritesGlFragDepth) {
  const std::filesystem::path root = std::filesystem::path(TALLOW_TEST_SOURCE_DIR) / "shaders";
  const std::regex write(R"(gl_FragDepth\s*(=[^=]|[-+*/]=))");
  int files = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(root)) {
    if (!entry.is_regular_file()) continue;
    ++files;
    std::ifstream in(entry.path());
    std::string line;
    for (int n = 1; std::getline(in, line); ++n) {
      const std::string code = line.substr(0, line.find("//"));
      EXPECT_FALSE(std::regex_search(code, write)) << entry.path() << ":" << n << ": " << line;
    }
  }
  EXPECT_GT(files, 50);
}

}  // namespace
}  // namespace tallow
