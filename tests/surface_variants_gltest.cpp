// One variant of the camera pass per translucency method (issue 38): shaders/surface.frag includes
// the frame's method's file as TALLOW_SURFACE_METHOD, so a variant holds only that method's code
// and samplers. Checked from the compiled programs themselves: the samplers beyond the shared ones
// (shadow maps, environment: those of the albedo baseline's variant, which adds none) belong to one
// method each and fit its texture units, and a define that names no file is one clear error.
#include <gtest/gtest.h>

#include <map>
#include <set>
#include <string>

#include "gpu/gl_context.h"
#include "gpu/program.h"
#include "gpu/shader_library.h"
#include "sss/frame_plan.h"
#include "sss/translucency_method.h"
#include "support/temp_dir.h"

namespace tallow {
namespace {

bool isSampler(GLenum type) {
  switch (type) {
    case GL_SAMPLER_2D: case GL_SAMPLER_3D: case GL_SAMPLER_CUBE: case GL_SAMPLER_2D_SHADOW:
    case GL_SAMPLER_2D_ARRAY: case GL_SAMPLER_2D_ARRAY_SHADOW: case GL_SAMPLER_CUBE_MAP_ARRAY:
    case GL_SAMPLER_CUBE_MAP_ARRAY_SHADOW: case GL_SAMPLER_CUBE_SHADOW: case GL_INT_SAMPLER_2D:
    case GL_UNSIGNED_INT_SAMPLER_2D: case GL_INT_SAMPLER_3D: case GL_UNSIGNED_INT_SAMPLER_3D:
    case GL_UNSIGNED_INT_SAMPLER_2D_ARRAY: case GL_INT_SAMPLER_2D_ARRAY:
      return true;
    default:
      return false;
  }
}

/// The active samplers of the camera pass compiled for `file`.
std::set<std::string> samplersOf(const gpu::ShaderLibrary& shaders, const std::string& file) {
  const gpu::Program p(shaders, {{{GL_VERTEX_SHADER, "surface.vert"}, {GL_FRAGMENT_SHADER, "surface.frag"}},
                                 {"TALLOW_SURFACE_METHOD \"" + file + "\""}});
  GLint count = 0;
  glGetProgramiv(p.id(), GL_ACTIVE_UNIFORMS, &count);
  std::set<std::string> out;
  for (GLint i = 0; i < count; ++i) {
    char name[256];
    GLsizei length = 0;
    GLint size = 0;
    GLenum type = 0;
    glGetActiveUniform(p.id(), static_cast<GLuint>(i), sizeof(name), &length, &size, &type, name);
    if (isSampler(type)) out.insert(std::string(name, static_cast<std::size_t>(length)));
  }
  return out;
}

TEST(SurfaceVariants, EachMethodsVariantHoldsOnlyItsOwnSamplers) {
  gpu::ContextOptions options;
  options.visible = false;
  const auto context = gpu::GlContext::create(options);
  const gpu::ShaderLibrary shaders;
  const std::set<std::string> shared = samplersOf(shaders, "camera/surface_albedo.glsl");
  EXPECT_TRUE(shared.count("uDirShadow") && shared.count("uPointShadow") && shared.count("uEnvMap"));
  std::map<std::string, std::string> owner;  // sampler → the method whose variant has it
  for (const auto& method : sss::makeTranslucencyMethods()) {
    const std::string file = method->surfaceShader();
    std::set<std::string> own;
    for (const std::string& s : samplersOf(shaders, file))
      if (!shared.count(s)) own.insert(s);
    std::string list;
    for (const std::string& s : own) list += " " + s;
    std::printf("[ variants ] %s: %zu sampler(s) of its own:%s\n", file.c_str(), own.size(), list.c_str());
    // Its samplers go to its own units (bindSurface), so they must fit them.
    EXPECT_LE(own.size(), static_cast<std::size_t>(method->surfaceUnits())) << file;
    for (const std::string& s : own) {
      const auto [it, inserted] = owner.emplace(s, file);
      EXPECT_TRUE(inserted) << s << " is in the variants of both " << it->second << " and " << file;
    }
  }
  // The methods with GPU transport each bring theirs: maps (Algorithm 1, VPL shadows), the gather's
  // light G-buffers, the image-space accumulation, SSLPV's grids.
  EXPECT_TRUE(owner.count("uMaps") && owner.count("uSssDirPosition"));
  EXPECT_GE(owner.size(), 8u);
}

TEST(SurfaceVariants, AnIncludeOfAnUndefinedNameIsOneClearError) {
  const gpu::ShaderLibrary shaders;
  try {
    shaders.expand("surface.frag");
    FAIL() << "surface.frag expanded without TALLOW_SURFACE_METHOD";
  } catch (const gpu::ShaderError& e) {
    EXPECT_NE(std::string(e.what()).find("surface.frag:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("TALLOW_SURFACE_METHOD"), std::string::npos) << e.what();
  }
  const gpu::ExpandedSource s = shaders.expand("surface.frag", {"TALLOW_SURFACE_METHOD \"maps/surface_gather.glsl\""});
  EXPECT_NE(s.text.find("gatherScatteredRadiosity"), std::string::npos);
  EXPECT_EQ(s.text.find("scatteredRadiosity(vec3 xo, vec3 no, vec3 dpdx"), std::string::npos)
      << "the no-cache variant holds Algorithm 1";
  EXPECT_EQ(s.text.find("#define TALLOW_SURFACE_METHOD"), std::string::npos) << "a path is no GLSL define";
  // `#include <x>` (C headers shared with GLSL, e.g. PNanoVDB.h inside its #if C branch) is no
  // include of ours and stays as written.
  test::TempDir dir;
  dir.write("c_branch.glsl", "#version 450 core\n#if defined(C_ONLY)\n#include <stdint.h>\n#endif\n");
  const gpu::ShaderLibrary own(dir.path());
  EXPECT_NE(own.expand("c_branch.glsl").text.find("#include <stdint.h>"), std::string::npos);
}

}  // namespace
}  // namespace tallow
