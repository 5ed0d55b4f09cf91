// Radiance RGBE reading (gpu/hdr_io): hand-built flat and run-length files with known pixels,
// the shipped env.hdr, and malformed input.
#include "gpu/hdr_io.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace tallow::gpu {
namespace {

using Bytes = std::vector<std::uint8_t>;

Bytes text(const std::string& s) { return Bytes(s.begin(), s.end()); }

Bytes header(int w, int h, const std::string& extra = "") {
  return text("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n" + extra + "\n-Y " + std::to_string(h) + " +X " +
              std::to_string(w) + "\n");
}

void append(Bytes& out, const Bytes& more) { out.insert(out.end(), more.begin(), more.end()); }

/// Ward's colr_color, written out: (m + 0.5) · 2^(e − 136), 0 when e = 0.
float rgbe(int m, int e) { return e == 0 ? 0.0f : static_cast<float>((m + 0.5) * std::ldexp(1.0, e - 136)); }

std::string errorOf(const Bytes& data) {
  try {
    decodeHdr(data, "t.hdr");
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(HdrIo, FlatPixelsDecodeToWardsValues) {
  // 2 × 2, flat (width < 8 cannot be run-length encoded).
  Bytes f = header(2, 2);
  append(f, {128, 64, 32, 129,  /**/ 0, 0, 0, 0,  /**/ 255, 255, 255, 136,  /**/ 10, 20, 30, 100});
  const Image img = decodeHdr(f, "t.hdr");
  ASSERT_EQ(img.width, 2);
  ASSERT_EQ(img.height, 2);
  // 128 · 2^(129−136) + 0.5 · 2^-7: 1.00390625.
  EXPECT_EQ(img.at(0, 0).r, 128.5f / 128.0f);
  EXPECT_EQ(img.at(0, 0).g, rgbe(64, 129));
  EXPECT_EQ(img.at(0, 0).b, rgbe(32, 129));
  EXPECT_EQ(img.at(0, 0).a, 1.0f);
  EXPECT_EQ(img.at(1, 0), glm::vec4(0, 0, 0, 1));
  EXPECT_EQ(img.at(0, 1).r, 255.5f);  // e = 136: the mantissa itself
  EXPECT_EQ(img.at(1, 1).r, rgbe(10, 100));
  EXPECT_EQ(img.at(1, 1).b, rgbe(30, 100));
}

TEST(HdrIo, RunLengthScanlines) {
  // 10 × 2; row 0: R a run of 10 × 200, G literal 0..9, B run 3 + literal 7, E run 10 × 130.
  const int w = 10;
  Bytes f = text("#?RGBE\n# comment\nGAMMA=1\n\n-Y 2 +X 10\n");
  append(f, {2, 2, 0, 10});
  append(f, {128 + 10, 200});
  append(f, {10, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9});
  append(f, {128 + 3, 50, 7, 1, 2, 3, 4, 5, 6, 7});
  append(f, {128 + 10, 130});
  // Row 1 flat (allowed in the same file: each scanline says which it is).
  for (int x = 0; x < w; ++x) append(f, {static_cast<std::uint8_t>(x), 1, 2, 140});
  const Image img = decodeHdr(f, "t.hdr");
  ASSERT_EQ(img.width, 10);
  ASSERT_EQ(img.height, 2);
  for (int x = 0; x < w; ++x) {
    EXPECT_EQ(img.at(x, 0).r, rgbe(200, 130));
    EXPECT_EQ(img.at(x, 0).g, rgbe(x, 130));
    EXPECT_EQ(img.at(x, 0).b, rgbe(x < 3 ? 50 : x - 2, 130));
    EXPECT_EQ(img.at(x, 1).r, rgbe(x, 140));
    EXPECT_EQ(img.at(x, 1).b, rgbe(2, 140));
  }
}

TEST(HdrIo, ExposureIsDividedOut) {
  Bytes f = header(1, 1, "EXPOSURE=2\nEXPOSURE= 4.0\n");
  append(f, {128, 128, 128, 137});
  const Image img = decodeHdr(f, "t.hdr");
  EXPECT_FLOAT_EQ(img.at(0, 0).r, rgbe(128, 137) / 8.0f);
}

TEST(HdrIo, ShippedEnvironmentMap) {
  const Image img = readHdr(std::filesystem::path(TALLOW_TEST_DATA_DIR) / "env.hdr");
  ASSERT_EQ(img.width, 1024);
  ASSERT_EQ(img.height, 512);
  double maxY = 0.0;
  int maxX = -1, maxRow = -1;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const glm::vec4 c = img.at(x, y);
      for (int k = 0; k < 3; ++k) {
        ASSERT_TRUE(std::isfinite(c[k])) << x << "," << y;
        ASSERT_GE(c[k], 0.0f) << x << "," << y;
      }
      const double lum = 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
      if (lum > maxY) maxY = lum, maxX = x, maxRow = y;
    }
  // data/MODELS.md: maximum luminance about 3,360 at pixel (235, 133).
  EXPECT_EQ(maxX, 235);
  EXPECT_EQ(maxRow, 133);
  EXPECT_NEAR(maxY, 3360.0, 20.0);
}

TEST(HdrIo, ErrorsNameTheFileAndWhere) {
  struct Case {
    Bytes data;
    std::string expected;
  };
  std::vector<Case> cases;
  cases.push_back({{}, "empty file"});
  cases.push_back({text("P6\n"), "not a Radiance HDR file"});
  cases.push_back({text("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n"), "truncated header"});
  cases.push_back({text("#?RADIANCE\nFORMAT=32-bit_rle_xyze\n\n-Y 1 +X 1\n"), "unsupported FORMAT"});
  cases.push_back({text("#?RADIANCE\nEXPOSURE=-1\n\n-Y 1 +X 1\n"), "bad EXPOSURE"});
  cases.push_back({text("#?RADIANCE\n\n+Y 1 +X 1\n\1\1\1\1"), "unsupported orientation"});
  cases.push_back({text("#?RADIANCE\n\n-Y 1 -X 1\n\1\1\1\1"), "unsupported orientation"});
  cases.push_back({text("#?RADIANCE\n\n-Y 1\n"), "bad resolution line"});
  cases.push_back({text("#?RADIANCE\n\n-Y 0 +X 1\n"), "bad image size"});
  cases.push_back({text("#?RADIANCE\n\n-Y -3 +X 1\n"), "bad image size"});
  cases.push_back({text("#?RADIANCE\n\n-Y 16385 +X 1\n"), "bad image size"});
  cases.push_back({text("#?RADIANCE\n\n-Y 16384 +X 16384\n"), "truncated: 16384 × 16384 pixels need"});
  cases.push_back({text("#?RADIANCE\n\n-Y 1 +X 2\n\1\2\3\4"), "truncated"});
  cases.push_back({text(std::string("#?RADIANCE\n") + std::string(70000, 'x')), "header longer than"});
  {
    Bytes f = header(8, 1);
    append(f, {2, 2, 0, 9});  // declared width 9 in an 8-wide image
    append(f, Bytes(40, 0));
    cases.push_back({f, "scanline 0 (byte "});
  }
  {
    Bytes f = header(8, 1);
    append(f, {2, 2, 0, 8, 128 + 9, 1});  // run overruns the scanline
    append(f, Bytes(40, 0));
    cases.push_back({f, "overruns the scanline"});
  }
  {
    Bytes f = header(8, 1);
    append(f, {2, 2, 0, 8, 0});  // zero-length run
    append(f, Bytes(40, 0));
    cases.push_back({f, "zero-length run"});
  }
  {
    Bytes f = header(8, 2);
    append(f, {2, 2, 0, 8, 128 + 8, 1, 128 + 8, 1, 128 + 8, 1, 128 + 8, 130});
    append(f, {2, 2, 0, 8, 128 + 8, 1, 128 + 9, 1});  // scanline 1: a run of 9 in G
    append(f, Bytes(20, 3));
    cases.push_back({f, "scanline 1 (byte "});
  }
  {
    Bytes f = header(2, 1);
    append(f, {1, 1, 1, 5, 9, 9, 9, 9});
    cases.push_back({f, "old-style run-length"});
  }
  for (const Case& c : cases) {
    const std::string message = errorOf(c.data);
    EXPECT_EQ(message.rfind("t.hdr: ", 0), 0u) << message;
    EXPECT_NE(message.find(c.expected), std::string::npos) << "expected \"" << c.expected << "\" in: " << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
  EXPECT_THROW(readHdr("/nonexistent/x.hdr"), std::runtime_error);
}

}  // namespace
}  // namespace tallow::gpu
