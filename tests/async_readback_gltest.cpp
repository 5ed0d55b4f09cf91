// Issue 39, point 4: a capture's read-backs through a ring of pixel-pack buffers (gpu::AsyncReadback)
// and the masks carried in the alpha of the picture shown, so that a frame reads back two targets
// and never waits for its own pixels.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <fstream>
#include <stdexcept>

#include "gpu/gl_context.h"
#include "gpu/readback.h"
#include "support/render_support.h"
#include "support/run_tallow.h"
#include "support/temp_dir.h"

namespace tallow {
namespace {

void fill(const gpu::Texture& t, float base) {
  std::vector<glm::vec4> pixels(static_cast<std::size_t>(t.width() * t.height()));
  for (std::size_t i = 0; i < pixels.size(); ++i) pixels[i] = glm::vec4(base + float(i), -float(i), 0.5f, base);
  glTextureSubImage2D(t.id(), 0, 0, 0, t.width(), t.height(), GL_RGBA, GL_FLOAT, pixels.data());
}

TEST(AsyncReadback, FetchesEachTextureAsItWasWhenIssued) {
  auto context = gpu::GlContext::create(gpu::ContextOptions{});
  const gpu::Texture a = gpu::Texture::create2D(GL_RGBA32F, 5, 3), b = gpu::Texture::create2D(GL_RGBA32F, 2, 7);
  fill(a, 1.0f);
  fill(b, 100.0f);
  const gpu::Image a1 = gpu::readTexture(a), b1 = gpu::readTexture(b);  // the synchronous read's answer
  gpu::AsyncReadback ring;
  const std::uint64_t before = gpu::targetReads();
  const std::uint64_t first = ring.issue({&a, &b});
  EXPECT_EQ(gpu::targetReads() - before, 2u);
  fill(a, 1000.0f);  // after the copy was issued: the fetch must not see it
  const gpu::Image a2 = gpu::readTexture(a);
  const std::uint64_t second = ring.issue({&a});
  EXPECT_THROW(ring.issue({&a}), std::logic_error) << "both slots hold reads not fetched";
  const std::vector<gpu::Image> got1 = ring.fetch(first);
  ASSERT_EQ(got1.size(), 2u);
  EXPECT_EQ(got1[0].width, 5);
  EXPECT_EQ(got1[0].height, 3);
  EXPECT_TRUE(got1[0].pixels == a1.pixels);  // top row first, as readTexture gives it
  EXPECT_TRUE(got1[1].pixels == b1.pixels);
  EXPECT_THROW(ring.fetch(first), std::logic_error) << "fetched already";
  const std::vector<gpu::Image> got2 = ring.fetch(second);
  ASSERT_EQ(got2.size(), 1u);
  EXPECT_TRUE(got2[0].pixels == a2.pixels);
  EXPECT_FALSE(got2[0].pixels == a1.pixels);
  const std::uint64_t third = ring.issue({&b});  // a slot free again
  EXPECT_TRUE(ring.fetch(third)[0].pixels == b1.pixels);
}

// The glare's output carries the coverage's masks in its alpha (common/coverage_masks.glsl): read
// from it they are the masks the coverage target gives.
TEST(AsyncReadback, ThePictureShownCarriesTheCoverageMasks) {
  for (const char* effect : {"render.local_exposure=0", "render.bloom=0"}) {
    test::PresetSession s("candle", {"render.width=96", "render.height=54", "field.res=48", "vpl.count=8", effect});
    s.render(s.scene().startS);
    ASSERT_FALSE(s.renderer().showsRadiance()) << effect << ": the candle shows a glare or a local exposure";
    const sss::PixelMasks direct = s.renderer().pixelMasks();
    const sss::PixelMasks coded = sss::pixelMasksOfCode(s.renderer().readShown());
    std::size_t translucent = 0, receivers = 0;
    for (std::uint8_t m : direct.translucent) translucent += m;
    for (std::uint8_t m : direct.receivers) receivers += m;
    EXPECT_GT(translucent, 200u) << effect;
    EXPECT_GT(receivers, 1000u) << effect;
    EXPECT_TRUE(coded.translucent == direct.translucent) << effect;
    EXPECT_TRUE(coded.receivers == direct.receivers) << effect;
  }
}

// A capture reads back two targets a frame (the radiance; the picture shown, or the coverage when
// the picture is the radiance) and writes what the synchronous path wrote: the PNG of the picture
// shown, the flicker figures of both masks.
TEST(AsyncReadback, ACaptureReadsTwoTargetsAFrame) {
  test::TempDir dir;
  for (const bool effects : {true, false}) {
    const auto out = dir.path() / (effects ? "with" : "without");
    std::vector<std::string> args = {"capture", "--preset", "candle", "--size", "96x54", "--frames", "3", "--fps", "8",
                                     "--time", "10", "--set", "field.res=48", "--out", out.string()};
    if (!effects) args.insert(args.end(), {"--set", "render.bloom=0", "--set", "render.local_exposure=0"});
    const auto r = test::runTallow(args);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    std::ifstream in(out / "stats.json");
    const auto stats = nlohmann::json::parse(in);
    ASSERT_EQ(stats["frames"].size(), 3u);
    for (const auto& f : stats["frames"]) {
      EXPECT_EQ(f["target_reads"].get<int>(), 2) << (effects ? "with" : "without") << " the glare";
      if (f["index"].get<int>() > 0) {
        EXPECT_GT(f["translucent_change"].get<double>(), 0.0);
        EXPECT_GT(f["receiver_change"].get<double>(), 0.0);
      }
    }
  }
}

}  // namespace
}  // namespace tallow
