// Issue 39, point 2: the VPLs' emergent light on the opaque receivers is summed by a compute pass
// over the receivers' G-buffer the camera pass leaves (shaders/maps/vpl_receivers.comp), not in the
// camera pass's fragment shader. The fragment path is kept as the second implementation: both must
// add the same light to every pixel, up to the G-buffer's storage (the albedo in half floats: 2⁻¹¹
// of the added light; the normal in 2 × 16 bits: under 1e-4 rad).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "sss/maps/virtual_point_lights.h"
#include "support/render_support.h"

namespace tallow {
namespace {

gpu::Image render(const std::string& preset, std::vector<std::string> sets, bool computeReceivers, int vpls) {
  sss::VirtualPointLights::allowComputeReceivers(computeReceivers);
  sets.push_back("vpl.count=" + std::to_string(vpls));
  test::PresetSession s(preset, sets);
  gpu::Image image = s.render(s.scene().startS + 2.0);
  sss::VirtualPointLights::allowComputeReceivers(true);
  return image;
}

void expectSameReceiverLight(const std::string& preset, const std::vector<std::string>& sets, int vpls) {
  SCOPED_TRACE(preset);
  const gpu::Image compute = render(preset, sets, true, vpls);
  const gpu::Image fragment = render(preset, sets, false, vpls);
  const gpu::Image none = render(preset, sets, true, 0);
  ASSERT_EQ(compute.pixels.size(), fragment.pixels.size());
  ASSERT_EQ(none.pixels.size(), fragment.pixels.size());
  double added = 0.0, differ = 0.0, worstShare = 0.0;
  std::size_t lit = 0;
  for (std::size_t i = 0; i < compute.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double v = std::abs(double(fragment.pixels[i][c]) - double(none.pixels[i][c]));  // the VPLs' light
      const double d = std::abs(double(compute.pixels[i][c]) - double(fragment.pixels[i][c]));
      added += v;
      differ += d;
      if (v > 1e-3 * double(fragment.pixels[i][c])) {
        ++lit;
        worstShare = std::max(worstShare, d / v);
      }
    }
  std::printf("[ vpl ] %s: VPL light summed %.4g over %zu pixel bands; compute − fragment %.3g (%.2g of it), worst "
              "pixel %.3g of its VPL light\n",
              preset.c_str(), added, lit, differ, differ / std::max(added, 1e-30), worstShare);
  ASSERT_GT(lit, 100u) << "the VPLs must light the receivers for the comparison to mean anything";
  EXPECT_LE(differ, 1e-3 * added);
  // The albedo in half floats (2⁻¹¹), the normal in 2 × 16 bits and the float sums in another order.
  EXPECT_LE(worstShare, 2e-3);
}

TEST(VplReceivers, TheComputePassAddsWhatTheFragmentShaderDid) {
  expectSameReceiverLight("candle", {"render.width=96", "render.height=54", "render.aa=1", "sss.frames=1",
                                     "flame.flicker=0", "field.res=48"},
                          32);
  expectSameReceiverLight("candle-holder", {"render.width=96", "render.height=72", "render.aa=1", "sss.frames=1"}, 32);
}

}  // namespace
}  // namespace tallow
