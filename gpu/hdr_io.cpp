#include "gpu/hdr_io.h"

#include "gpu/file_bytes.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <new>
#include <stdexcept>
#include <string_view>
#include <vector>

#include "gpu/image_io.h"

namespace tallow::gpu {
namespace {

[[noreturn]] void fail(const std::string& name, const std::string& what) {
  throw std::runtime_error(name + ": " + what);
}

/// A header line shown in a message: printable ASCII only, at most 60 characters.
std::string printable(std::string_view text) {
  std::string out;
  for (char c : text.substr(0, 60)) out += (c >= 0x20 && c < 0x7f) ? c : '?';
  if (text.size() > 60) out += "...";
  return out;
}

/// A decimal integer in [1, kMaxHdrSide], the whole of `text`.
bool parseSide(std::string_view text, int& out) {
  if (text.empty() || text.size() > 9) return false;
  for (char c : text)
    if (c < '0' || c > '9') return false;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), out);
  return r.ec == std::errc() && r.ptr == text.data() + text.size();
}

/// A finite number > 0, the whole of `text` (surrounding spaces allowed).
bool parseExposure(std::string_view text, double& out) {
  while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
  while (!text.empty() && (text.back() == ' ' || text.back() == '\t' || text.back() == '\r')) text.remove_suffix(1);
  if (text.empty()) return false;
  if (text.front() == '+') text.remove_prefix(1);
  const auto r = std::from_chars(text.data(), text.data() + text.size(), out);
  return r.ec == std::errc() && r.ptr == text.data() + text.size() && std::isfinite(out) && out > 0.0;
}

glm::vec4 rgbeToFloat(const std::uint8_t* p, float scale) {
  if (p[3] == 0) return {0.0f, 0.0f, 0.0f, 1.0f};
  const float f = std::ldexp(1.0f, static_cast<int>(p[3]) - (128 + 8)) * scale;
  return {(p[0] + 0.5f) * f, (p[1] + 0.5f) * f, (p[2] + 0.5f) * f, 1.0f};
}

class HdrDecoder {
 public:
  HdrDecoder(std::span<const std::uint8_t> data, const std::string& name) : data_(data), name_(name) {}

  Image decode() {
    readHeader();
    checkDataSize();
    Image image(width_, height_);
    std::vector<std::uint8_t> line(static_cast<std::size_t>(width_) * 4);
    std::vector<std::uint8_t> planes(static_cast<std::size_t>(width_) * 4);
    for (int y = 0; y < height_; ++y) {
      readScanline(y, line, planes);
      for (int x = 0; x < width_; ++x) {
        const glm::vec4 pixel = rgbeToFloat(&line[static_cast<std::size_t>(x) * 4], scale_);
        // The largest RGBE values (about 1.7e38) overflow a float once EXPOSURE divides them.
        if (!std::isfinite(pixel.r) || !std::isfinite(pixel.g) || !std::isfinite(pixel.b))
          fail(name_, "scanline " + std::to_string(y) + ", pixel " + std::to_string(x) +
                          ": the value is beyond a float's range (exponent " +
                          std::to_string(line[static_cast<std::size_t>(x) * 4 + 3]) + " with the file's EXPOSURE)");
        image.at(x, y) = pixel;
      }
    }
    return image;
  }

 private:
  std::span<const std::uint8_t> data_;
  const std::string& name_;
  std::size_t pos_ = 0;
  int width_ = 0, height_ = 0;
  float scale_ = 1.0f;

  [[noreturn]] void failAt(int y, std::size_t offset, const std::string& what) const {
    fail(name_, "scanline " + std::to_string(y) + " (byte " + std::to_string(offset) + "): " + what);
  }

  /// The next line of the header without its '\n'; an error when none ends within the limit.
  std::string_view nextLine(const char* what) {
    const std::size_t start = pos_;
    while (pos_ < data_.size() && data_[pos_] != '\n') {
      if (pos_ >= kMaxHdrHeaderBytes)
        fail(name_, "header longer than " + std::to_string(kMaxHdrHeaderBytes) + " bytes (no " + what + ")");
      ++pos_;
    }
    if (pos_ >= data_.size()) fail(name_, std::string("truncated header (no ") + what + ")");
    std::string_view line(reinterpret_cast<const char*>(data_.data()) + start, pos_ - start);
    ++pos_;  // the '\n'
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    return line;
  }

  void readHeader() {
    if (data_.empty()) fail(name_, "empty file");
    const std::string_view magic = nextLine("end of the first line");
    if (magic != "#?RADIANCE" && magic != "#?RGBE")
      fail(name_, "not a Radiance HDR file (the first line is \"" + printable(magic) +
                      "\", expected \"#?RADIANCE\" or \"#?RGBE\")");
    double exposure = 1.0;
    for (;;) {
      const std::size_t lineStart = pos_;
      const std::string_view line = nextLine("empty line ending the header");
      if (line.empty()) break;
      constexpr std::string_view kFormat = "FORMAT=", kExposure = "EXPOSURE=";
      if (line.substr(0, kFormat.size()) == kFormat) {
        std::string_view format = line.substr(kFormat.size());
        while (!format.empty() && (format.back() == ' ' || format.back() == '\t')) format.remove_suffix(1);
        if (format != "32-bit_rle_rgbe")
          fail(name_, "unsupported FORMAT \"" + printable(format) + "\" (only 32-bit_rle_rgbe is read)");
      } else if (line.substr(0, kExposure.size()) == kExposure) {
        double e = 0.0;
        if (!parseExposure(line.substr(kExposure.size()), e))
          fail(name_, "bad EXPOSURE line at byte " + std::to_string(lineStart) + " (\"" + printable(line) +
                          "\"; expected a finite number > 0)");
        exposure *= e;
        if (!std::isfinite(exposure) || exposure <= 0.0 || exposure > 1e30 || exposure < 1e-30)
          fail(name_, "the product of the EXPOSURE lines is out of range");
      }
    }
    scale_ = static_cast<float>(1.0 / exposure);
    const std::size_t resStart = pos_;
    const std::string_view res = nextLine("resolution line");
    // "-Y H +X W", single spaces.
    std::vector<std::string_view> words;
    std::size_t i = 0;
    while (i < res.size()) {
      const std::size_t j = res.find(' ', i);
      const std::size_t end = j == std::string_view::npos ? res.size() : j;
      if (end > i) words.push_back(res.substr(i, end - i));
      i = end + 1;
    }
    // Built piecewise: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string&&.
    std::string shown = "\"";
    shown += printable(res);
    shown += "\" at byte ";
    shown += std::to_string(resStart);
    if (words.size() != 4 || words[0].size() != 2 || words[2].size() != 2 ||
        (words[0][0] != '-' && words[0][0] != '+') || (words[2][0] != '-' && words[2][0] != '+'))
      fail(name_, "bad resolution line " + shown + " (expected \"-Y height +X width\")");
    if (words[0] != "-Y" || words[2] != "+X")
      fail(name_, "unsupported orientation " + shown + " (only \"-Y height +X width\" is read)");
    if (!parseSide(words[1], height_) || !parseSide(words[3], width_) || width_ < 1 || height_ < 1 ||
        width_ > kMaxHdrSide || height_ > kMaxHdrSide)
      fail(name_, "bad image size in " + shown + " (each side must be an integer in [1, " +
                      std::to_string(kMaxHdrSide) + "])");
    if (static_cast<std::int64_t>(width_) * height_ > kMaxImagePixels)
      fail(name_, "image of " + std::to_string(width_) + " × " + std::to_string(height_) +
                      " pixels is larger than the limit of " + std::to_string(kMaxImagePixels) + " pixels");
  }

  bool rleWidth() const { return width_ >= 8 && width_ <= 0x7fff; }

  /// Rejects data too short to hold the scanlines before the pixels are allocated: a run-length
  /// scanline needs at least 4 bytes plus 2 per 127 values of each component, a flat one 4 per pixel.
  void checkDataSize() const {
    const std::uint64_t flat = 4ull * static_cast<std::uint64_t>(width_);
    const std::uint64_t runs = 4 + 4 * 2 * ((static_cast<std::uint64_t>(width_) + 126) / 127);
    const std::uint64_t perLine = rleWidth() ? std::min(flat, runs) : flat;
    const std::uint64_t available = data_.size() - pos_;
    if (perLine * static_cast<std::uint64_t>(height_) > available)
      fail(name_, "truncated: " + std::to_string(width_) + " × " + std::to_string(height_) + " pixels need at least " +
                      std::to_string(perLine * static_cast<std::uint64_t>(height_)) + " bytes of pixel data, the file has " +
                      std::to_string(available) + " after the header");
  }

  void readScanline(int y, std::vector<std::uint8_t>& line, std::vector<std::uint8_t>& planes) {
    const std::size_t start = pos_;
    const std::size_t available = data_.size() - pos_;
    if (rleWidth() && available >= 4 && data_[pos_] == 2 && data_[pos_ + 1] == 2 && (data_[pos_ + 2] & 0x80) == 0) {
      const int declared = (data_[pos_ + 2] << 8) | data_[pos_ + 3];
      if (declared != width_)
        failAt(y, start, "run-length scanline of width " + std::to_string(declared) + " in an image " +
                             std::to_string(width_) + " wide");
      pos_ += 4;
      for (int c = 0; c < 4; ++c) {
        std::uint8_t* plane = &planes[static_cast<std::size_t>(c) * width_];
        int x = 0;
        while (x < width_) {
          if (pos_ >= data_.size()) failAt(y, pos_, "truncated run-length data");
          const int count = data_[pos_];
          if (count > 128) {
            const int n = count - 128;
            if (n > width_ - x) failAt(y, pos_, "run of " + std::to_string(n) + " overruns the scanline");
            if (pos_ + 1 >= data_.size()) failAt(y, pos_, "truncated run-length data");
            std::memset(plane + x, data_[pos_ + 1], static_cast<std::size_t>(n));
            pos_ += 2;
            x += n;
          } else {
            if (count == 0) failAt(y, pos_, "zero-length run");
            if (count > width_ - x) failAt(y, pos_, "run of " + std::to_string(count) + " overruns the scanline");
            if (data_.size() - pos_ - 1 < static_cast<std::size_t>(count)) failAt(y, pos_, "truncated run-length data");
            std::memcpy(plane + x, &data_[pos_ + 1], static_cast<std::size_t>(count));
            pos_ += 1 + static_cast<std::size_t>(count);
            x += count;
          }
        }
      }
      for (int x = 0; x < width_; ++x)
        for (int c = 0; c < 4; ++c)
          line[static_cast<std::size_t>(x) * 4 + c] = planes[static_cast<std::size_t>(c) * width_ + x];
      return;
    }
    const std::size_t bytes = static_cast<std::size_t>(width_) * 4;
    if (available < bytes)
      failAt(y, start, "truncated: a flat scanline needs " + std::to_string(bytes) + " bytes, " +
                           std::to_string(available) + " remain");
    for (int x = 0; x < width_; ++x) {
      const std::uint8_t* p = &data_[pos_ + static_cast<std::size_t>(x) * 4];
      if (p[0] == 1 && p[1] == 1 && p[2] == 1)
        failAt(y, pos_ + static_cast<std::size_t>(x) * 4, "old-style run-length pixel (1 1 1 n) is not supported");
    }
    std::memcpy(line.data(), &data_[pos_], bytes);
    pos_ += bytes;
  }
};

}  // namespace

Image decodeHdr(std::span<const std::uint8_t> data, const std::string& nameForErrors) {
  return HdrDecoder(data, nameForErrors).decode();
}

Image readHdr(const std::filesystem::path& path) {
  const std::vector<std::uint8_t> bytes = readFileBytes(path);
  try {
    return decodeHdr(bytes, path.string());
  } catch (const std::bad_alloc&) {
    throwOutOfMemoryReading(path);
  }
}

}  // namespace tallow::gpu
