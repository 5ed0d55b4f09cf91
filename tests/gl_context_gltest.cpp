// Context creation on each headless backend, and GLSL compile errors mapped to file:line.
#include <gtest/gtest.h>

#include "gpu/gl_context.h"
#include "gpu/program.h"
#include "support/temp_dir.h"
#include "sss/frame_plan.h"
#include "sss/translucency_method.h"

namespace tallow {
namespace {

void expectCore45(gpu::GlBackend backend) {
  gpu::ContextOptions options;
  options.backend = backend;
  auto context = gpu::GlContext::create(options);
  ASSERT_NE(context, nullptr);
  EXPECT_EQ(context->backend(), backend);
  const gpu::GlInfo& info = context->info();
  EXPECT_GE(info.major * 10 + info.minor, 45) << info.version;
  EXPECT_FALSE(info.renderer.empty());
  GLint profile = 0;
  glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
  EXPECT_TRUE(profile & GL_CONTEXT_CORE_PROFILE_BIT) << "not a core profile context";
  std::printf("%s: %s | %s\n", std::string(gpu::glBackendName(backend)).c_str(), info.version.c_str(),
              info.renderer.c_str());
}

TEST(GlContext, OsMesaGivesCore45) { expectCore45(gpu::GlBackend::OsMesa); }
TEST(GlContext, EglGivesCore45) { expectCore45(gpu::GlBackend::Egl); }

TEST(GlContext, CompileErrorNamesTheIncludedFileAndLine) {
  gpu::ContextOptions options;
  auto context = gpu::GlContext::create(options);
  test::TempDir dir;
  dir.write("broken.frag", "#version 450 core\n#include \"inc.glsl\"\nout vec4 o;\nvoid main() { o = f(); }\n");
  dir.write("inc.glsl", "// line 1\n// line 2\nvec4 f() { return undeclared_name; }\n");
  dir.write("ok.vert", "#version 450 core\nvoid main() { gl_Position = vec4(0.0); }\n");
  const gpu::ShaderLibrary lib(dir.path());
  try {
    gpu::Program program(lib, {{{GL_VERTEX_SHADER, "ok.vert"}, {GL_FRAGMENT_SHADER, "broken.frag"}}});
    FAIL() << "expected a compile error";
  } catch (const gpu::ShaderError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("shaders/inc.glsl:3: ", 0), 0u) << e.what();
  }
}

TEST(GlContext, ErrorAfterAnIncludeNamesTheOuterFileLine) {
  gpu::ContextOptions options;
  auto context = gpu::GlContext::create(options);
  test::TempDir dir;
  dir.write("broken.frag", "#version 450 core\n#include \"inc.glsl\"\nout vec4 o;\n\nvoid main() { o = g(); }\n");
  dir.write("inc.glsl", "vec4 f() { return vec4(1.0); }\n");
  const gpu::ShaderLibrary lib(dir.path());
  try {
    gpu::Program program(lib, {{{GL_FRAGMENT_SHADER, "broken.frag"}}});
    FAIL() << "expected a compile error";
  } catch (const gpu::ShaderError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("shaders/broken.frag:5: ", 0), 0u) << e.what();
  }
}

TEST(GlContext, AllEmbeddedPassesCompileAndLink) {
  gpu::ContextOptions options;
  auto context = gpu::GlContext::create(options);
  const gpu::ShaderLibrary lib;
  // The camera pass: one variant per translucency method (its file as TALLOW_SURFACE_METHOD).
  for (const auto& method : sss::makeTranslucencyMethods())
    EXPECT_NO_THROW(gpu::Program(lib, {{{GL_VERTEX_SHADER, "surface.vert"}, {GL_FRAGMENT_SHADER, "surface.frag"}},
                                       {"TALLOW_SURFACE_METHOD \"" + method->surfaceShader() + "\""}}))
        << method->surfaceShader();
  EXPECT_NO_THROW(gpu::Program(lib, {{{GL_VERTEX_SHADER, "shadow_depth.vert"}}}));  // depth only
  EXPECT_NO_THROW(gpu::Program(lib, {{{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, "display.frag"}}}));
}

}  // namespace
}  // namespace tallow

namespace tallow {
namespace {

TEST(GlContext, DebugOutputReachesTheLog) {
  gpu::ContextOptions options;
  options.debugOutput = true;  // the default in debug builds
  auto context = gpu::GlContext::create(options);
  testing::internal::CaptureStderr();
  glEnable(0x7FFF);  // not a capability: the driver reports GL_INVALID_ENUM through KHR_debug
  const std::string log = testing::internal::GetCapturedStderr();
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_ENUM));
  EXPECT_NE(log.find("gl error"), std::string::npos) << log;
}

}  // namespace
}  // namespace tallow
