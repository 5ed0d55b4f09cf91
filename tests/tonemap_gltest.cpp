// The window's tone map (sss::DisplayPass: shaders/display.frag, which includes
// shaders/common/tonemap.glsl) against the PNG writer's C++ compilation of the same file, at float
// precision, on HDR colours chosen to reach every branch of every operator: black, dim, mid grey,
// saturated primaries and a candle-flame orange from 2^-6 to 2^20, and huge values.
#include "gpu/gl_context.h"
#include "gpu/gl_objects.h"
#include "gpu/readback.h"
#include "gpu/shader_library.h"
#include "gpu/image_io.h"
#include "gpu/tonemap.h"
#include "sss/display_pass.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace tallow {
namespace {

std::vector<glm::vec4> hdrColours() {
  std::vector<glm::vec4> out{{0, 0, 0, 1}, {0.18f, 0.18f, 0.18f, 1}, {1e-5f, 2e-5f, 0, 1}, {3e30f, 1e30f, 2e29f, 1}};
  for (const glm::vec3& c : {glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1), glm::vec3(1, 0.45f, 0.08f),
                             glm::vec3(0.3f, 0.6f, 0.9f)})
    for (int ev = -6; ev <= 20; ev += 2) out.emplace_back(c * std::exp2(static_cast<float>(ev)), 1.0f);
  return out;
}

TEST(ToneMapGL, DisplayShaderAgreesWithTheCppToneMapAtFloatPrecision) {
  auto context = gpu::GlContext::create(gpu::ContextOptions{});
  const gpu::ShaderLibrary shaders;
  sss::DisplayPass display(shaders);
  const std::vector<glm::vec4> colours = hdrColours();
  const int width = static_cast<int>(colours.size());
  gpu::Texture radiance = gpu::Texture::create2D(GL_RGBA32F, width, 1);
  radiance.setFilter(GL_NEAREST, GL_NEAREST);
  glTextureSubImage2D(radiance.id(), 0, 0, 0, width, 1, GL_RGBA, GL_FLOAT, colours.data());
  gpu::Texture target = gpu::Texture::create2D(GL_RGBA32F, width, 1);
  gpu::Framebuffer fb;
  fb.attachColor(0, target);
  fb.setDrawBuffers(1);
  fb.checkComplete("tone-map target");

  for (gpu::ToneMap op : {gpu::ToneMap::Clamp, gpu::ToneMap::Reinhard, gpu::ToneMap::Aces, gpu::ToneMap::HuePreserving})
    for (float ev : {0.0f, -1.5f}) {
      const gpu::ToneMapSettings settings{op, ev};
      display.render(radiance, fb.id(), width, 1, settings, gpu::Dither::Off);
      const gpu::Image shown = gpu::readColor(fb, 0, width, 1);
      double worst = 0.0;
      for (int x = 0; x < width; ++x) {
        const glm::vec3 cpu = gpu::toneMapToSrgb(glm::vec3(colours[static_cast<std::size_t>(x)]), settings);
        for (int c = 0; c < 3; ++c) worst = std::max(worst, static_cast<double>(std::abs(cpu[c] - shown.at(x, 0)[c])));
      }
      std::printf("[ tonemap ] %s at %+.1f EV: largest |GPU - C++| %.2e\n",
                  std::string(gpu::toneMapName(op)).c_str(), ev, worst);
      // The same float operations on both sides; pow, exp2 and inversesqrt may differ by a few units in
      // the last place between the driver and libm (measured on llvmpipe: at most 2.4e-7, four units
      // at 1); the bound is about eight times that.
      EXPECT_LT(worst, 2e-6) << gpu::toneMapName(op) << " at " << ev << " EV";
      // Dithered, the window's levels are the PNG writer's (the same hash of the pixel; row 0 is
      // y = 0 for both in a one-row target): equal but where float rounding puts the two sides of
      // a level boundary.
      display.render(radiance, fb.id(), width, 1, settings, gpu::Dither::On);
      const gpu::Image levels = gpu::readColor(fb, 0, width, 1);
      gpu::Image one(width, 1);
      for (int x = 0; x < width; ++x) one.at(x, 0) = colours[static_cast<std::size_t>(x)];
      const std::vector<std::uint8_t> png = gpu::toneMappedRgb8(one, settings);
      int differ = 0;
      for (int x = 0; x < width; ++x)
        for (int c = 0; c < 3; ++c)
          differ += std::lround(levels.at(x, 0)[c] * 255.0f) != png[3 * static_cast<std::size_t>(x) + static_cast<std::size_t>(c)];
      EXPECT_LE(differ, 1) << gpu::toneMapName(op) << " at " << ev << " EV: dithered levels differ from the PNG's";
    }
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

}  // namespace
}  // namespace tallow
