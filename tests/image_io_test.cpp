// PNG and EXR reading and writing (gpu/image_io) and atomic file writes (gpu/atomic_file).
#include "gpu/image_io.h"

#include <gtest/gtest.h>

#include "support/temp_dir.h"
#include <png.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "gpu/atomic_file.h"

namespace tallow::gpu {
namespace {

namespace fs = std::filesystem;

using test::TempDir;

std::vector<std::uint8_t> readBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string readText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// The sRGB encoding (IEC 61966-2-1), in double, independent of the code under test.
double srgbReference(double linear) {
  const double c = std::clamp(linear, 0.0, 1.0);
  return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
}

/// Expects `f()` to throw std::runtime_error whose message is one line containing `fragment`.
template <class F>
void expectOneLineError(F&& f, const std::string& fragment) {
  try {
    f();
    ADD_FAILURE() << "no exception; expected one containing \"" << fragment << "\"";
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(fragment), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

// ---------------------------------------------------------------------------------------------
// Atomic writes

TEST(AtomicFile, WritesTextAndLeavesNoTemporaryFile) {
  TempDir dir;
  const fs::path target = dir.path() / "a.txt";
  writeTextFileAtomically(target, "first");
  EXPECT_EQ(readText(target), "first");
  writeTextFileAtomically(target, "second, longer");
  EXPECT_EQ(readText(target), "second, longer");
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"a.txt"});
}

TEST(AtomicFile, ThrowingWriterLeavesNoPartialFileAndKeepsTheOld) {
  TempDir dir;
  const fs::path fresh = dir.path() / "fresh.png";
  EXPECT_THROW(writeFileAtomically(fresh,
                                   [](const fs::path& tmp) {
                                     std::ofstream(tmp) << "partial";
                                     throw std::logic_error("writer failed");
                                   }),
               std::logic_error);  // the writer's own exception, unchanged
  EXPECT_TRUE(dir.entries().empty());

  const fs::path old = dir.path() / "old.txt";
  writeTextFileAtomically(old, "old contents");
  EXPECT_THROW(writeFileAtomically(old,
                                   [](const fs::path& tmp) {
                                     std::ofstream(tmp) << "new but partial";
                                     throw std::runtime_error("disk full");
                                   }),
               std::runtime_error);
  EXPECT_EQ(readText(old), "old contents");
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"old.txt"});
}

TEST(AtomicFile, TemporaryIsBesideTheTargetAndHidden) {
  TempDir dir;
  fs::path seen;
  writeFileAtomically(dir.path() / "x.png", [&](const fs::path& tmp) {
    seen = tmp;
    std::ofstream(tmp) << "x";
  });
  EXPECT_EQ(seen.parent_path(), dir.path());
  EXPECT_EQ(seen.filename().string().rfind(".x.png.tmp-", 0), 0u) << seen;
}

TEST(AtomicFile, MissingFolderGivesOneLineError) {
  TempDir dir;
  const fs::path target = dir.path() / "no" / "such" / "x.png";
  try {
    writeTextFileAtomically(target, "x");
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), "cannot write " + target.string() + ": No such file or directory");
  }
}

TEST(AtomicFile, FileInPlaceOfFolderGivesOneLineError) {
  TempDir dir;
  writeTextFileAtomically(dir.path() / "plain", "x");
  expectOneLineError([&] { writeTextFileAtomically(dir.path() / "plain" / "x.png", "x"); }, "Not a directory");
}

TEST(AtomicFile, UnwritableFolderGivesOneLineError) {
  TempDir dir;
  const fs::path locked = dir.path() / "locked";
  fs::create_directory(locked);
  fs::permissions(locked, fs::perms::owner_read | fs::perms::owner_exec, fs::perm_options::replace);
  if (::access(locked.c_str(), W_OK) == 0) {
    fs::permissions(locked, fs::perms::owner_all, fs::perm_options::replace);
    GTEST_SKIP() << "running with privileges that ignore folder permissions (root?)";
  }
  Image image(1, 1);
  try {
    writePng(locked / "x.png", image, {});
    ADD_FAILURE() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), "cannot write " + (locked / "x.png").string() + ": Permission denied");
  }
  fs::permissions(locked, fs::perms::owner_all, fs::perm_options::replace);
  EXPECT_TRUE(fs::is_empty(locked));
}

// ---------------------------------------------------------------------------------------------
// PNG

TEST(PngIo, RoundTripGivesToneMappedSrgbBytes) {
  TempDir dir;
  // Linear values whose sRGB byte is not within 0.01 of a rounding boundary (checked below), plus
  // out-of-range values that must clamp.
  const std::vector<float> values = {0.0f, 0.001f, 0.01f, 0.05f, 0.18f, 0.3f, 0.5f, 0.75f, 0.9f, 1.0f, 4.0f, -1.0f};
  Image image(static_cast<int>(values.size()), 3);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const float v = values[static_cast<std::size_t>(x)];
      // Each row puts the value in a different channel, the others at 0.
      image.at(x, y) = glm::vec4(y == 0 ? v : 0.0f, y == 1 ? v : 0.0f, y == 2 ? v : 0.0f, 0.25f);
    }
  const fs::path file = dir.path() / "ramp.png";
  writePng(file, image, ToneMapSettings{ToneMap::Clamp, 0.0f}, Dither::Off);
  const Image back = readPng(file);
  ASSERT_EQ(back.width, image.width);
  ASSERT_EQ(back.height, image.height);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const double exact = srgbReference(values[static_cast<std::size_t>(x)]) * 255.0;
      ASSERT_GT(std::abs(exact - std::floor(exact) - 0.5), 0.01) << "test value too close to a rounding boundary";
      const float expected = static_cast<float>(std::lround(exact)) / 255.0f;
      for (int c = 0; c < 3; ++c) EXPECT_EQ(back.at(x, y)[c], c == y ? expected : 0.0f) << x << "," << y << "," << c;
      EXPECT_EQ(back.at(x, y).a, 1.0f);  // RGB file: alpha reads as 1
    }
}

TEST(PngIo, MiddleGreyRoundsHalfUpAndExposureScales) {
  // sRGB 0.5 is linear ((0.5 + 0.055) / 1.055)^2.4 = 0.2140411405; 0.5 × 255 = 127.5.
  const double middle = std::pow(0.555 / 1.055, 2.4);
  constexpr double kStep = 1e-5;  // moves the byte value by ~3e-3, far above float error
  TempDir dir;
  Image image(3, 1);
  image.at(0, 0) = glm::vec4(glm::vec3(static_cast<float>(middle + kStep)), 1.0f);
  image.at(1, 0) = glm::vec4(glm::vec3(static_cast<float>(middle - kStep)), 1.0f);
  image.at(2, 0) = glm::vec4(glm::vec3(static_cast<float>((middle + kStep) / 2.0)), 1.0f);
  writePng(dir.path() / "grey.png", image, ToneMapSettings{ToneMap::Clamp, 0.0f}, Dither::Off);
  Image back = readPng(dir.path() / "grey.png");
  EXPECT_EQ(std::lround(back.at(0, 0).r * 255.0f), 128);
  EXPECT_EQ(std::lround(back.at(1, 0).r * 255.0f), 127);
  // Half of it, without exposure: sRGB 0.3613 → byte 92.
  EXPECT_EQ(std::lround(back.at(2, 0).r * 255.0f), std::lround(srgbReference((middle + kStep) / 2.0) * 255.0));
  writePng(dir.path() / "grey.png", image, ToneMapSettings{ToneMap::Clamp, 1.0f}, Dither::Off);  // +1 EV doubles
  back = readPng(dir.path() / "grey.png");
  EXPECT_EQ(std::lround(back.at(2, 0).r * 255.0f), 128);
}

TEST(PngIo, UsesTheDisplayToneMap) {
  TempDir dir;
  Image image(2, 1);
  image.at(0, 0) = glm::vec4(0.3f, 2.0f, 10.0f, 1.0f);
  image.at(1, 0) = glm::vec4(std::nanf(""), INFINITY, -INFINITY, 1.0f);
  const ToneMapSettings aces{ToneMap::Aces, 0.5f};
  writePng(dir.path() / "aces.png", image, aces, Dither::Off);
  const Image back = readPng(dir.path() / "aces.png");
  const glm::vec3 expected = toneMapToSrgb(glm::vec3(image.at(0, 0)), aces);
  for (int c = 0; c < 3; ++c) EXPECT_EQ(std::lround(back.at(0, 0)[c] * 255.0f), std::lround(expected[c] * 255.0f));
  for (int c = 0; c < 3; ++c) EXPECT_TRUE(std::isfinite(back.at(1, 0)[c]));  // no crash, no UB on NaN/inf
}

TEST(PngIo, ReadsOtherLayoutsAsStored) {
  TempDir dir;
  // 16-bit grey: words / 65535 (the simplified API stores linear 16-bit data unchanged).
  {
    const std::uint16_t words[3] = {0, 1000, 65535};
    png_image png{};
    png.version = PNG_IMAGE_VERSION;
    png.width = 3;
    png.height = 1;
    png.format = PNG_FORMAT_LINEAR_Y;
    ASSERT_TRUE(png_image_write_to_file(&png, (dir.path() / "g16.png").c_str(), 0, words, 0, nullptr)) << png.message;
    const Image back = readPng(dir.path() / "g16.png");
    for (int x = 0; x < 3; ++x) {
      const float expected = static_cast<float>(words[x]) / 65535.0f;
      EXPECT_EQ(back.at(x, 0), glm::vec4(expected, expected, expected, 1.0f)) << x;
    }
  }
  // 8-bit grey + alpha.
  {
    const std::uint8_t bytes[4] = {10, 200, 255, 0};
    png_image png{};
    png.version = PNG_IMAGE_VERSION;
    png.width = 2;
    png.height = 1;
    png.format = PNG_FORMAT_GA;
    ASSERT_TRUE(png_image_write_to_file(&png, (dir.path() / "ga.png").c_str(), 0, bytes, 0, nullptr)) << png.message;
    const Image back = readPng(dir.path() / "ga.png");
    EXPECT_EQ(back.at(0, 0), glm::vec4(10 / 255.0f, 10 / 255.0f, 10 / 255.0f, 200 / 255.0f));
    EXPECT_EQ(back.at(1, 0), glm::vec4(1.0f, 1.0f, 1.0f, 0.0f));
  }
  // Palette.
  {
    const std::uint8_t colourMap[6] = {255, 0, 0, 0, 64, 255};
    const std::uint8_t indices[3] = {1, 0, 1};
    png_image png{};
    png.version = PNG_IMAGE_VERSION;
    png.width = 3;
    png.height = 1;
    png.format = PNG_FORMAT_RGB_COLORMAP;
    png.colormap_entries = 2;
    ASSERT_TRUE(png_image_write_to_file(&png, (dir.path() / "pal.png").c_str(), 0, indices, 0, colourMap))
        << png.message;
    const Image back = readPng(dir.path() / "pal.png");
    EXPECT_EQ(back.at(0, 0), glm::vec4(0.0f, 64 / 255.0f, 1.0f, 1.0f));
    EXPECT_EQ(back.at(1, 0), glm::vec4(1.0f, 0.0f, 0.0f, 1.0f));
  }
}

std::uint32_t crc32(const std::uint8_t* data, std::size_t size) {  // PNG's CRC (ISO 3309)
  std::uint32_t crc = 0xffffffffu;
  for (std::size_t i = 0; i < size; ++i) {
    crc ^= data[i];
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  return crc ^ 0xffffffffu;
}

void appendChunk(std::vector<std::uint8_t>& png, const char* type, const std::vector<std::uint8_t>& body) {
  const auto be32 = [&](std::uint32_t v) {
    for (int shift = 24; shift >= 0; shift -= 8) png.push_back(static_cast<std::uint8_t>(v >> shift));
  };
  be32(static_cast<std::uint32_t>(body.size()));
  const std::size_t start = png.size();
  png.insert(png.end(), type, type + 4);
  png.insert(png.end(), body.begin(), body.end());
  be32(crc32(&png[start], png.size() - start));
}

/// A PNG with a valid IHDR claiming width × height RGBA, and `idatBytes` of (bogus) image data.
std::vector<std::uint8_t> pngWithHeader(std::uint32_t width, std::uint32_t height, std::size_t idatBytes) {
  std::vector<std::uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  std::vector<std::uint8_t> ihdr;
  for (std::uint32_t v : {width, height})
    for (int shift = 24; shift >= 0; shift -= 8) ihdr.push_back(static_cast<std::uint8_t>(v >> shift));
  ihdr.insert(ihdr.end(), {8, 6, 0, 0, 0});  // 8-bit RGBA, deflate, no filter, no interlace
  appendChunk(png, "IHDR", ihdr);
  appendChunk(png, "IDAT", std::vector<std::uint8_t>(idatBytes, 0));
  appendChunk(png, "IEND", {});
  return png;
}

TEST(PngIo, AbsurdSizesFailBeforeAllocating) {
  expectOneLineError([] { readPngFromMemory(pngWithHeader(60000, 60000, 16), "huge.png"); }, "huge.png: image of");
  // Under the pixel limit, but 100 bytes of data cannot inflate to 1 GB.
  expectOneLineError([] { readPngFromMemory(pngWithHeader(16000, 16000, 100), "big.png"); }, "big.png: truncated");
  expectOneLineError([] { readPngFromMemory(pngWithHeader(0, 10, 16), "zero.png"); }, "zero.png: ");
}

TEST(PngIo, CorruptAndTruncatedFilesThrow) {
  TempDir dir;
  Image image(7, 5);
  for (std::size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = glm::vec4(static_cast<float>(i) / 35.0f);
  writePng(dir.path() / "ok.png", image, {});
  const std::vector<std::uint8_t> good = readBytes(dir.path() / "ok.png");
  ASSERT_NO_THROW(readPngFromMemory(good, "ok.png"));

  expectOneLineError([] { readPngFromMemory({}, "empty.png"); }, "empty.png: not a PNG file");
  const std::string text = "GIF89a, not a PNG at all";
  expectOneLineError([&] { readPngFromMemory({reinterpret_cast<const std::uint8_t*>(text.data()), text.size()}, "x.png"); },
                     "x.png: not a PNG file");
  // Truncated anywhere before the image data is complete (the IEND chunk is the last 12 bytes).
  for (std::size_t size = 8; size + 12 < good.size(); ++size)
    expectOneLineError([&] { readPngFromMemory(std::span(good).first(size), "cut.png"); }, "cut.png: ");
  // A flipped byte anywhere (signature, lengths, CRCs, data): an error or a readable image, never a crash.
  for (std::size_t i = 0; i < good.size(); ++i) {
    std::vector<std::uint8_t> bad = good;
    bad[i] ^= 0x5a;
    try {
      readPngFromMemory(bad, "flip.png");
    } catch (const std::runtime_error& e) {
      EXPECT_EQ(std::string(e.what()).rfind("flip.png: ", 0), 0u) << e.what();
    }
  }
  expectOneLineError([&] { readPng(dir.path() / "missing.png"); }, "missing.png: No such file or directory");
}

// ---------------------------------------------------------------------------------------------
// OpenEXR

/// An uncompressed single-part scanline OpenEXR file with FLOAT channels (openexr.com, "OpenEXR
/// File Layout"), built byte by byte so that tests can shape headers freely.
struct ExrBuilder {
  ExrBuilder(std::vector<std::string> channelNames, int x0, int y0, int w, int h)
      : channels(std::move(channelNames)), minX(x0), minY(y0), width(w), height(h) {}
  std::vector<std::string> channels;  ///< sorted, as the format requires
  int minX, minY, width, height;
  std::vector<std::uint8_t> extraAttributes;  ///< raw bytes placed at the end of the header

  std::vector<std::uint8_t> bytes;
  void u8(std::uint8_t v) { bytes.push_back(v); }
  void i32(std::int32_t v) {
    for (int k = 0; k < 4; ++k) bytes.push_back(static_cast<std::uint8_t>(static_cast<std::uint32_t>(v) >> (8 * k)));
  }
  void u64(std::uint64_t v) {
    for (int k = 0; k < 8; ++k) bytes.push_back(static_cast<std::uint8_t>(v >> (8 * k)));
  }
  void f32(float v) {
    std::uint32_t u;
    std::memcpy(&u, &v, 4);
    i32(static_cast<std::int32_t>(u));
  }
  void str(const std::string& s) {
    bytes.insert(bytes.end(), s.begin(), s.end());
    bytes.push_back(0);
  }
  void attribute(const std::string& name, const std::string& type, std::int32_t size) {
    str(name);
    str(type);
    i32(size);
  }

  void header() {
    bytes = {0x76, 0x2f, 0x31, 0x01, 2, 0, 0, 0};
    std::int32_t chlistSize = 1;
    for (const auto& c : channels) chlistSize += static_cast<std::int32_t>(c.size()) + 1 + 16;
    attribute("channels", "chlist", chlistSize);
    for (const auto& c : channels) {
      str(c);
      i32(2);  // FLOAT
      for (int k = 0; k < 4; ++k) u8(0);
      i32(1);
      i32(1);
    }
    u8(0);
    attribute("compression", "compression", 1);
    u8(0);
    for (const char* window : {"dataWindow", "displayWindow"}) {
      attribute(window, "box2i", 16);
      i32(minX);
      i32(minY);
      i32(minX + width - 1);
      i32(minY + height - 1);
    }
    attribute("lineOrder", "lineOrder", 1);
    u8(0);
    attribute("pixelAspectRatio", "float", 4);
    f32(1.0f);
    attribute("screenWindowCenter", "v2f", 8);
    f32(0.0f);
    f32(0.0f);
    attribute("screenWindowWidth", "float", 4);
    f32(1.0f);
    bytes.insert(bytes.end(), extraAttributes.begin(), extraAttributes.end());
    u8(0);
  }

  /// value(channel index, x, y) for each sample.
  template <class F>
  std::vector<std::uint8_t> build(F value) {
    header();
    const std::size_t lineBytes = static_cast<std::size_t>(width) * 4 * channels.size();
    const std::size_t tableEnd = bytes.size() + 8 * static_cast<std::size_t>(height);
    for (int y = 0; y < height; ++y) u64(tableEnd + static_cast<std::size_t>(y) * (8 + lineBytes));
    for (int y = 0; y < height; ++y) {
      i32(minY + y);
      i32(static_cast<std::int32_t>(lineBytes));
      for (std::size_t c = 0; c < channels.size(); ++c)
        for (int x = 0; x < width; ++x) f32(value(c, x, y));
    }
    return bytes;
  }
};

TEST(ExrIo, HalfRoundTripIsExactForRepresentableValues) {
  TempDir dir;
  // Halves: 0, ±1, the smallest normal 2^-14, the largest 65504, a subnormal 2^-24, π to 11 bits.
  const std::vector<float> values = {0.0f, 1.0f, -1.0f, 0.5f, 6.103515625e-05f, 65504.0f, 5.9604644775390625e-08f,
                                     3.140625f, 0.0009765625f, 123.5f, -0.25f, 2048.0f};
  Image image(4, 3);
  for (std::size_t i = 0; i < image.pixels.size(); ++i)
    image.pixels[i] = glm::vec4(values[i], values[(i + 1) % 12], values[(i + 2) % 12], values[(i + 3) % 12]);
  writeExr(dir.path() / "h.exr", image, ExrPixelType::Half);
  const Image back = readExr(dir.path() / "h.exr");
  ASSERT_EQ(back.width, 4);
  ASSERT_EQ(back.height, 3);
  EXPECT_EQ(back.pixels, image.pixels);
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"h.exr"});
}

TEST(ExrIo, FloatRoundTripIsExact) {
  TempDir dir;
  std::mt19937 random(7);
  std::uniform_real_distribution<float> uniform(-1e6f, 1e6f);
  Image image(37, 19);  // odd sizes: more than one 16-line ZIP block, not a multiple of it
  for (glm::vec4& p : image.pixels) p = glm::vec4(uniform(random), uniform(random) * 1e-30f, 3.4e38f, uniform(random));
  writeExr(dir.path() / "f.exr", image, ExrPixelType::Float);
  EXPECT_EQ(readExr(dir.path() / "f.exr").pixels, image.pixels);
}

TEST(ExrIo, StringAttributesRoundTrip) {
  TempDir dir;
  const std::map<std::string, std::string> attributes = {
      {"tallow.spp", "1024"}, {"tallow.relativeError", "0.0031"}, {"tallow.note", "a b\tc"}};
  writeExr(dir.path() / "a.exr", Image(2, 2), ExrPixelType::Half, attributes);
  const auto back = readExrStringAttributes(dir.path() / "a.exr");
  for (const auto& [key, value] : attributes) {
    ASSERT_TRUE(back.count(key)) << key;
    EXPECT_EQ(back.at(key), value);
  }
  // A clash with a standard attribute of another type is an error, and leaves nothing behind.
  expectOneLineError([&] { writeExr(dir.path() / "b.exr", Image(2, 2), ExrPixelType::Half, {{"compression", "x"}}); },
                     "cannot write");
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"a.exr"});
}

TEST(ExrIo, ReadsDataWindowMissingAlphaAndGrey) {
  ExrBuilder rgb{{"B", "G", "R"}, -3, 10, 3, 2};
  const auto file = rgb.build([](std::size_t c, int x, int y) { return static_cast<float>(100 * c + 10 * y + x); });
  const Image image = readExrFromMemory(file, "rgb.exr");
  ASSERT_EQ(image.width, 3);
  ASSERT_EQ(image.height, 2);
  // Channels are stored B, G, R: index 2 is R.
  EXPECT_EQ(image.at(2, 1), glm::vec4(212.0f, 112.0f, 12.0f, 1.0f));

  ExrBuilder grey{{"Y"}, 0, 0, 2, 1};
  const Image greyImage = readExrFromMemory(grey.build([](std::size_t, int x, int) { return 0.25f + x; }), "y.exr");
  EXPECT_EQ(greyImage.at(1, 0), glm::vec4(1.25f, 1.25f, 1.25f, 1.0f));

  ExrBuilder none{{"Z"}, 0, 0, 2, 1};
  expectOneLineError([&] { readExrFromMemory(none.build([](std::size_t, int, int) { return 1.0f; }), "z.exr"); },
                     "z.exr: no R, G, B or Y channel");
}

TEST(ExrIo, AbsurdHeadersFailBeforeAllocating) {
  ExrBuilder huge{{"R"}, 0, 0, 1 << 20, 1 << 20};
  huge.header();
  expectOneLineError([&] { readExrFromMemory(huge.bytes, "huge.exr"); }, "huge.exr: data window of");
  // Within the pixel limit, but 1,000 bytes cannot hold 8,192 scanlines.
  ExrBuilder tall{{"R"}, 0, 0, 8192, 8192};
  tall.header();
  tall.bytes.resize(tall.bytes.size() + 1000);
  expectOneLineError([&] { readExrFromMemory(tall.bytes, "tall.exr"); }, "tall.exr: truncated");
  ExrBuilder empty{{"R"}, 5, 5, 0, 1};
  empty.header();
  expectOneLineError([&] { readExrFromMemory(empty.bytes, "empty.exr"); }, "empty.exr: empty data window");
  // Attribute sizes that disagree with their types (found by fuzzing: OpenEXR 3.1 reads a v2f's
  // 8 bytes whatever the stored size says, then misreads the rest of the header).
  const auto withAttribute = [](const std::string& type, const std::vector<std::uint8_t>& value) {
    ExrBuilder builder{{"R"}, 0, 0, 1, 1};
    ExrBuilder raw{{}, 0, 0, 1, 1};
    raw.attribute("extra", type, static_cast<std::int32_t>(value.size()));
    raw.bytes.insert(raw.bytes.end(), value.begin(), value.end());
    builder.extraAttributes = raw.bytes;
    return builder.build([](std::size_t, int, int) { return 0.5f; });
  };
  EXPECT_NO_THROW(readExrFromMemory(withAttribute("v2f", std::vector<std::uint8_t>(8)), "ok.exr"));
  expectOneLineError([&] { readExrFromMemory(withAttribute("v2f", {}), "v2f.exr"); }, "v2f.exr: attribute extra is malformed");
  // A preview claiming 65536 × 65536 pixels in 8 bytes; a string vector with a 2 GB string.
  expectOneLineError([&] { readExrFromMemory(withAttribute("preview", {0, 0, 1, 0, 0, 0, 1, 0}), "p.exr"); },
                     "p.exr: attribute extra is malformed");
  expectOneLineError([&] { readExrFromMemory(withAttribute("stringvector", {0, 0, 0, 0x7f, 'a'}), "s.exr"); },
                     "s.exr: attribute extra is malformed");
}

TEST(ExrIo, CorruptAndTruncatedFilesThrow) {
  TempDir dir;
  Image image(5, 20);
  for (std::size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = glm::vec4(static_cast<float>(i));
  writeExr(dir.path() / "ok.exr", image, ExrPixelType::Half);
  const std::vector<std::uint8_t> good = readBytes(dir.path() / "ok.exr");
  ASSERT_EQ(readExrFromMemory(good, "ok.exr").pixels, image.pixels);

  expectOneLineError([] { readExrFromMemory({}, "e.exr"); }, "e.exr: not an OpenEXR file");
  std::vector<std::uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  expectOneLineError([&] { readExrFromMemory(png, "p.exr"); }, "p.exr: not an OpenEXR file");
  for (std::size_t size = 4; size < good.size(); ++size)
    expectOneLineError([&] { readExrFromMemory(std::span(good).first(size), "cut.exr"); }, "cut.exr: ");
  // Flipped bytes in the header (the pixel data is ZIP with a checksum-free layout, so flips there
  // may decode to other values): an error or an image, never a crash.
  for (std::size_t i = 0; i < good.size(); ++i) {
    std::vector<std::uint8_t> bad = good;
    bad[i] ^= 0x5a;
    try {
      readExrFromMemory(bad, "flip.exr");
    } catch (const std::runtime_error& e) {
      EXPECT_EQ(std::string(e.what()).rfind("flip.exr: ", 0), 0u) << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    }
  }
  expectOneLineError([&] { readExr(dir.path() / "missing.exr"); }, "missing.exr: No such file or directory");
}

}  // namespace
}  // namespace tallow::gpu
