#include "gpu/image_io.h"

#include "gpu/file_bytes.h"

#include <OpenEXR/IexBaseExc.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfCompression.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <png.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <memory>
#include <new>
#include <stdexcept>
#include <string_view>
#include <vector>

#include "gpu/atomic_file.h"

namespace tallow::gpu {
namespace {

// ---------------------------------------------------------------------------------------------
// Shared helpers

/// Library messages may span lines (OpenEXR's do); our errors are one line.
std::string oneLine(std::string_view text) {
  std::string line;
  line.reserve(text.size());
  for (char c : text) {
    const bool space = c == '\n' || c == '\r' || c == '\t';
    if (space && (line.empty() || line.back() == ' ')) continue;
    line += space ? ' ' : c;
  }
  while (!line.empty() && line.back() == ' ') line.pop_back();
  return line.empty() ? std::string("unknown error") : line;
}

[[noreturn]] void fail(const std::string& name, std::string_view what) {
  throw std::runtime_error(name + ": " + oneLine(what));
}

/// The checks every reader makes before it allocates pixels.
void checkImageSize(const std::string& name, std::int64_t width, std::int64_t height) {
  if (width <= 0 || height <= 0)
    fail(name, "empty image (" + std::to_string(width) + " × " + std::to_string(height) + ")");
  if (width > kMaxImagePixels / height)
    fail(name, "image of " + std::to_string(width) + " × " + std::to_string(height) +
                   " pixels is larger than the limit of " + std::to_string(kMaxImagePixels) + " pixels");
}

void checkPixelCount(const std::filesystem::path& path, const Image& image) {
  if (image.width <= 0 || image.height <= 0 ||
      image.pixels.size() != static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height))
    throw std::runtime_error("cannot write " + path.string() + ": image is " + std::to_string(image.width) +
                             " × " + std::to_string(image.height) + " but holds " +
                             std::to_string(image.pixels.size()) + " pixels");
}

// ---------------------------------------------------------------------------------------------
// PNG

constexpr std::size_t kPngSignatureBytes = 8;
/// Deflate's largest possible expansion is 1032:1 (a 258-byte match coded in 2 bits); a little
/// more allows for interlacing. Lets us reject a tiny file that claims a huge image before
/// allocating its rows.
constexpr std::uint64_t kDeflateMaxRatio = 1040;
constexpr std::uint64_t kPngRawSlackBytes = 1 << 16;

std::uint32_t bigEndian32(const std::uint8_t* p) {
  return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) | p[3];
}

/// Sum of the lengths of the IDAT chunks present (a bound only; libpng validates the chunks).
std::uint64_t pngCompressedBytes(std::span<const std::uint8_t> data) {
  std::uint64_t total = 0;
  std::size_t offset = kPngSignatureBytes;
  while (data.size() - offset >= 8) {
    const std::uint64_t length = bigEndian32(&data[offset]);
    const std::uint8_t* type = &data[offset + 4];
    const std::uint64_t available = data.size() - offset - 8;
    if (std::memcmp(type, "IDAT", 4) == 0) total += std::min(length, available);
    if (std::memcmp(type, "IEND", 4) == 0 || length + 4 > available) break;
    offset += static_cast<std::size_t>(8 + length + 4);
  }
  return total;
}

struct PngMemory {
  const std::uint8_t* data;
  std::size_t size;
  std::size_t offset;
};

struct PngErrorText {
  char text[256];
};

void pngOnError(png_structp png, png_const_charp message) {
  auto* error = static_cast<PngErrorText*>(png_get_error_ptr(png));
  std::snprintf(error->text, sizeof(error->text), "%s", message ? message : "libpng error");
  png_longjmp(png, 1);
}

void pngOnWarning(png_structp, png_const_charp) {}

void pngReadMemory(png_structp png, png_bytep out, png_size_t count) {
  auto* memory = static_cast<PngMemory*>(png_get_io_ptr(png));
  if (count > memory->size - memory->offset) png_error(png, "truncated");
  std::memcpy(out, memory->data + memory->offset, count);
  memory->offset += count;
}

struct PngLayout {
  png_uint_32 width;
  png_uint_32 height;
  std::size_t fileRowBytes;  ///< one row as stored (before expansion), for the size bound
  std::size_t rowBytes;      ///< one row after expansion to RGBA
  int bitDepth;              ///< 8 or 16 after expansion
  int channels;              ///< 4 after expansion
};

// The two functions below call setjmp: libpng reports errors by longjmp-ing back to it, so they
// hold only trivially destructible locals (no C++ destructor may be skipped).

bool pngReadLayout(png_structp png, png_infop info, PngLayout* layout) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_read_info(png, info);
  layout->width = png_get_image_width(png, info);
  layout->height = png_get_image_height(png, info);
  layout->fileRowBytes = png_get_rowbytes(png, info);
  const int colourType = png_get_color_type(png, info);
  const bool hasTransparency = png_get_valid(png, info, PNG_INFO_tRNS) != 0;
  // Expand everything to RGBA, 8 or 16 bits per channel, without touching the stored values.
  if (colourType == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
  if (colourType == PNG_COLOR_TYPE_GRAY && png_get_bit_depth(png, info) < 8) png_set_expand_gray_1_2_4_to_8(png);
  if (hasTransparency) png_set_tRNS_to_alpha(png);
  if (colourType == PNG_COLOR_TYPE_GRAY || colourType == PNG_COLOR_TYPE_GRAY_ALPHA) png_set_gray_to_rgb(png);
  if ((colourType & PNG_COLOR_MASK_ALPHA) == 0 && !hasTransparency)
    png_set_add_alpha(png, 0xffff, PNG_FILLER_AFTER);  // libpng uses the low byte for 8-bit data
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  layout->rowBytes = png_get_rowbytes(png, info);
  layout->bitDepth = png_get_bit_depth(png, info);
  layout->channels = png_get_channels(png, info);
  return true;
}

bool pngReadRows(png_structp png, png_bytepp rows) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_read_image(png, rows);
  return true;
}

/// Owns libpng's read structures.
class PngReadHandle {
public:
  explicit PngReadHandle(PngErrorText* error) {
    png_ = png_create_read_struct(PNG_LIBPNG_VER_STRING, error, pngOnError, pngOnWarning);
    if (png_) info_ = png_create_info_struct(png_);
  }
  ~PngReadHandle() { png_destroy_read_struct(&png_, info_ ? &info_ : nullptr, nullptr); }
  PngReadHandle(const PngReadHandle&) = delete;
  PngReadHandle& operator=(const PngReadHandle&) = delete;
  png_structp png() const { return png_; }
  png_infop info() const { return info_; }

private:
  png_structp png_ = nullptr;
  png_infop info_ = nullptr;
};

// ---------------------------------------------------------------------------------------------
// OpenEXR

/// An Imf::IStream over bytes in memory, so that the same code reads files and fuzz inputs.
class MemoryIStream final : public Imf::IStream {
public:
  MemoryIStream(std::span<const std::uint8_t> data, const std::string& name)
      : Imf::IStream(name.c_str()), data_(data) {}
  bool read(char c[], int n) override {
    // Iex::InputExc is what the library's own streams throw, and what it expects to catch.
    if (n < 0 || static_cast<std::uint64_t>(n) > remaining()) throw Iex::InputExc("truncated");
    std::memcpy(c, data_.data() + position_, static_cast<std::size_t>(n));
    position_ += static_cast<std::uint64_t>(n);
    return position_ < data_.size();
  }
  std::uint64_t tellg() override { return position_; }
  void seekg(std::uint64_t position) override { position_ = position; }

private:
  std::uint64_t remaining() const { return position_ < data_.size() ? data_.size() - position_ : 0; }
  std::span<const std::uint8_t> data_;
  std::uint64_t position_ = 0;
};

// Layout of an OpenEXR file (openexr.com, "OpenEXR File Layout"): magic, version and flags,
// then one header (a list of attributes, ended by an empty name) per part, then the chunk
// offset tables, then the chunks.
constexpr std::uint8_t kExrMagic[4] = {0x76, 0x2f, 0x31, 0x01};
constexpr std::uint32_t kExrVersion = 2;
constexpr std::uint32_t kExrTiledFlag = 0x200;
constexpr std::uint32_t kExrLongNamesFlag = 0x400;
constexpr std::uint32_t kExrDeepFlag = 0x800;
constexpr std::uint32_t kExrMultiPartFlag = 0x1000;
/// OpenEXR 3.1 reads every name (attribute, type, channel) up to 255 bytes, whatever the long-names flag says.
constexpr std::size_t kExrMaxNameBytes = 255;
/// Each chunk needs an 8-byte offset-table entry and at least an 8-byte chunk header.
constexpr std::uint64_t kExrMinBytesPerChunk = 16;
/// Largest tile we accept, in pixels (libraries allocate whole tiles and rows of tiles).
constexpr std::int64_t kExrMaxTilePixels = std::int64_t{1} << 24;
/// Raw data a tiny file may claim regardless of the compression bound below.
constexpr std::uint64_t kExrRawSlackBytes = 1 << 20;

struct ExrCompressionInfo {
  int linesPerChunk;
  std::uint64_t maxRatio;  ///< generous bound on raw ÷ compressed bytes, measured and rounded up
};

/// Indexed by Imf::Compression (NONE, RLE, ZIPS, ZIP, PIZ, PXR24, B44, B44A, DWAA, DWAB).
/// Measured ratios on constant images: RLE 60, ZIP ~900 (deflate's limit is 1032), PIZ ~400,
/// PXR24 ~1100, B44 ≤ 11, DWAA ~3000, DWAB ~15000; the bounds leave ample room above those.
constexpr ExrCompressionInfo kExrCompressions[] = {
    {1, 1}, {1, 128}, {1, 2048}, {16, 2048}, {32, 2048}, {16, 4096}, {32, 64}, {32, 64}, {32, 1 << 16}, {256, 1 << 16},
};

class ExrHeaderScanner {
public:
  explicit ExrHeaderScanner(std::span<const std::uint8_t> data) : data_(data) {}

  std::uint8_t u8() {
    need(1);
    return data_[position_++];
  }
  std::uint32_t u32() {
    need(4);
    const std::uint8_t* p = &data_[position_];
    position_ += 4;
    return std::uint32_t{p[0]} | (std::uint32_t{p[1]} << 8) | (std::uint32_t{p[2]} << 16) | (std::uint32_t{p[3]} << 24);
  }
  std::int32_t i32() { return static_cast<std::int32_t>(u32()); }
  /// A NUL-terminated string of at most maxBytes characters.
  std::string_view cString(std::size_t maxBytes) {
    const std::size_t start = position_;
    const std::size_t limit = std::min(data_.size(), start + maxBytes + 1);
    for (std::size_t i = start; i < limit; ++i) {
      if (data_[i] == 0) {
        position_ = i + 1;
        return {reinterpret_cast<const char*>(&data_[start]), i - start};
      }
    }
    if (limit == data_.size()) throw std::runtime_error("truncated header");
    throw std::runtime_error("attribute name longer than " + std::to_string(maxBytes) + " bytes");
  }
  std::span<const std::uint8_t> bytes(std::size_t count) {
    need(count);
    const auto span = data_.subspan(position_, count);
    position_ += count;
    return span;
  }
  std::uint8_t peek() {
    need(1);
    return data_[position_];
  }
  std::size_t position() const { return position_; }
  std::size_t remaining() const { return data_.size() - position_; }

private:
  void need(std::size_t count) const {
    if (count > data_.size() - position_) throw std::runtime_error("truncated header");
  }
  std::span<const std::uint8_t> data_;
  std::size_t position_ = 0;
};

struct ExrChannelInfo {
  std::string name;
  int bytes;  ///< per sample
  int xSampling;
  int ySampling;
};

struct ExrPartInfo {
  bool hasDataWindow = false;
  std::int32_t window[4] = {0, 0, 0, 0};  ///< min x, min y, max x, max y
  int compression = -1;
  bool hasChannels = false;
  std::vector<ExrChannelInfo> channels;
  bool hasTiles = false;
  std::uint32_t tileWidth = 0, tileHeight = 0;
  std::uint8_t tileMode = 0;
  std::int64_t chunkCount = -1;
  std::string type;
};

std::int32_t littleEndian32(std::span<const std::uint8_t> bytes, std::size_t offset) {
  return static_cast<std::int32_t>(std::uint32_t{bytes[offset]} | (std::uint32_t{bytes[offset + 1]} << 8) |
                                   (std::uint32_t{bytes[offset + 2]} << 16) | (std::uint32_t{bytes[offset + 3]} << 24));
}

std::vector<ExrChannelInfo> parseChannelList(std::span<const std::uint8_t> value) {
  ExrHeaderScanner scan(value);
  std::vector<ExrChannelInfo> channels;
  constexpr std::size_t kChannelFieldBytes = 16;  // type, pLinear + 3 reserved, x and y sampling
  while (true) {
    const std::string_view name = scan.cString(kExrMaxNameBytes);
    if (name.empty()) break;
    const auto fields = scan.bytes(kChannelFieldBytes);
    const std::int32_t type = littleEndian32(fields, 0);
    if (type < 0 || type > 2) throw std::runtime_error("channel " + std::string(name) + " has an unknown pixel type");
    ExrChannelInfo channel{std::string(name), type == Imf::HALF ? 2 : 4, littleEndian32(fields, 8), littleEndian32(fields, 12)};
    if (channel.xSampling < 1 || channel.ySampling < 1)
      throw std::runtime_error("channel " + channel.name + " has an invalid sampling rate");
    channels.push_back(std::move(channel));
  }
  if (scan.remaining() != 0) throw std::runtime_error("attribute channels is malformed");
  return channels;
}

/// OpenEXR 3.1 picks the reader by type name and reads a fixed-size type (or a channel list up to
/// its terminator) without looking at the stored size, and sizes some buffers from attribute
/// contents: a size that disagrees with the type would desynchronise it from this scan and let it
/// allocate what the header claims. So each known type's value must have exactly the layout the
/// library will read.
void checkAttributeValue(std::string_view name, std::string_view type, std::span<const std::uint8_t> value) {
  struct FixedType {
    std::string_view name;
    std::size_t bytes;
  };
  static constexpr FixedType kFixedTypes[] = {
      {"box2i", 16}, {"box2f", 16},    {"chromaticities", 32}, {"compression", 1}, {"deepImageState", 1},
      {"double", 8}, {"envmap", 1},    {"float", 4},           {"int", 4},         {"keycode", 28},
      {"lineOrder", 1}, {"m33f", 36},  {"m33d", 72},           {"m44f", 64},       {"m44d", 128},
      {"rational", 8}, {"tiledesc", 9}, {"timecode", 8},       {"v2i", 8},         {"v2f", 8},
      {"v2d", 16},   {"v3i", 12},      {"v3f", 12},            {"v3d", 24},
  };
  const auto malformed = [&] { throw std::runtime_error("attribute " + std::string(name) + " is malformed"); };
  for (const FixedType& fixed : kFixedTypes)
    if (type == fixed.name && value.size() != fixed.bytes) malformed();
  if (type == "chlist") parseChannelList(value);  // throws unless the list fills the value exactly
  if (type == "floatvector" && value.size() % 4 != 0) malformed();
  if (type == "idmanifest" && value.size() < 8) malformed();
  if (type == "preview") {  // width, height, then width × height RGBA bytes
    if (value.size() < 8) malformed();
    const std::uint64_t w = static_cast<std::uint32_t>(littleEndian32(value, 0));
    const std::uint64_t h = static_cast<std::uint32_t>(littleEndian32(value, 4));
    if (w * h * 4 != value.size() - 8) malformed();
  }
  if (type == "stringvector") {  // (length, bytes)* filling the value exactly
    std::size_t offset = 0;
    while (offset < value.size()) {
      if (value.size() - offset < 4) malformed();
      const std::int32_t length = littleEndian32(value, offset);
      offset += 4;
      if (length < 0 || static_cast<std::size_t>(length) > value.size() - offset) malformed();
      offset += static_cast<std::size_t>(length);
    }
  }
}

std::int64_t ceilDiv(std::int64_t a, std::int64_t b) { return (a + b - 1) / b; }

/// Checks the header fields that decide how much the reader allocates, against the file size:
/// OpenEXR 3.1 trusts them, so a corrupt 100-byte file could otherwise claim gigabytes.
/// Returns part 0 (the one InputFile reads). Throws std::runtime_error without the file name.
ExrPartInfo scanExrHeaders(std::span<const std::uint8_t> data) {
  if (data.size() < 4 || std::memcmp(data.data(), kExrMagic, 4) != 0) throw std::runtime_error("not an OpenEXR file");
  ExrHeaderScanner scan(data);
  scan.bytes(4);
  const std::uint32_t versionField = scan.u32();
  if ((versionField & 0xff) != kExrVersion)
    throw std::runtime_error("unsupported OpenEXR version " + std::to_string(versionField & 0xff));
  const std::uint32_t flags = versionField & ~0xffu;
  if (flags & ~(kExrTiledFlag | kExrLongNamesFlag | kExrDeepFlag | kExrMultiPartFlag))
    throw std::runtime_error("unsupported OpenEXR feature flags");
  if (flags & kExrDeepFlag) throw std::runtime_error("deep images are not supported");
  const bool multiPart = (flags & kExrMultiPartFlag) != 0;

  std::vector<ExrPartInfo> parts;
  while (true) {
    if (multiPart && !parts.empty() && scan.peek() == 0) {
      scan.u8();
      break;
    }
    ExrPartInfo part;
    while (true) {
      const std::string_view name = scan.cString(kExrMaxNameBytes);
      if (name.empty()) break;
      const std::string_view type = scan.cString(kExrMaxNameBytes);
      const std::int32_t size = scan.i32();
      if (size < 0) throw std::runtime_error("attribute " + std::string(name) + " has a negative size");
      const auto value = scan.bytes(static_cast<std::size_t>(size));
      checkAttributeValue(name, type, value);
      const auto expect = [&](std::string_view wantedType, std::size_t wantedSize) {
        if (type != wantedType || value.size() != wantedSize)
          throw std::runtime_error("attribute " + std::string(name) + " is malformed");
      };
      if (name == "dataWindow") {
        expect("box2i", 16);
        for (int i = 0; i < 4; ++i) part.window[i] = littleEndian32(value, 4 * static_cast<std::size_t>(i));
        part.hasDataWindow = true;
      } else if (name == "compression") {
        expect("compression", 1);
        part.compression = value[0];
      } else if (name == "channels") {
        if (type != "chlist") throw std::runtime_error("attribute channels is malformed");
        part.channels = parseChannelList(value);
        part.hasChannels = true;
      } else if (name == "tiles") {
        expect("tiledesc", 9);
        part.tileWidth = static_cast<std::uint32_t>(littleEndian32(value, 0));
        part.tileHeight = static_cast<std::uint32_t>(littleEndian32(value, 4));
        part.tileMode = value[8];
        part.hasTiles = true;
      } else if (name == "chunkCount") {
        expect("int", 4);
        part.chunkCount = littleEndian32(value, 0);
      } else if (name == "type") {
        if (type != "string") throw std::runtime_error("attribute type is malformed");
        part.type.assign(reinterpret_cast<const char*>(value.data()), value.size());
      }
    }
    parts.push_back(std::move(part));
    if (!multiPart) break;
  }

  const std::uint64_t dataBytes = scan.remaining();
  std::uint64_t totalChunks = 0;
  for (const ExrPartInfo& part : parts) {
    if (!part.hasDataWindow) throw std::runtime_error("header has no dataWindow");
    if (!part.hasChannels) throw std::runtime_error("header has no channels");
    if (part.compression < 0 || part.compression >= static_cast<int>(std::size(kExrCompressions)))
      throw std::runtime_error("unknown compression " + std::to_string(part.compression));
    if (part.type.starts_with("deep")) throw std::runtime_error("deep images are not supported");
    const bool tiled = multiPart ? part.type == "tiledimage" : (flags & kExrTiledFlag) != 0;
    const std::int64_t width = std::int64_t{part.window[2]} - part.window[0] + 1;
    const std::int64_t height = std::int64_t{part.window[3]} - part.window[1] + 1;
    if (width <= 0 || height <= 0) throw std::runtime_error("empty data window");
    if (width > kMaxImagePixels / height)
      throw std::runtime_error("data window of " + std::to_string(width) + " × " + std::to_string(height) +
                               " pixels is larger than the limit of " + std::to_string(kMaxImagePixels) + " pixels");
    const ExrCompressionInfo& compression = kExrCompressions[part.compression];
    std::int64_t minChunks = 0;
    if (tiled) {
      if (!part.hasTiles) throw std::runtime_error("tiled image has no tiles attribute");
      const std::int64_t tw = part.tileWidth, th = part.tileHeight;
      if (tw < 1 || th < 1 || tw > kExrMaxTilePixels / th) throw std::runtime_error("invalid tile size");
      if ((part.tileMode & 0x0f) > 2 || (part.tileMode >> 4) > 1) throw std::runtime_error("invalid tile level mode");
      // A row of tiles is buffered whole.
      if (width > kMaxImagePixels / th) throw std::runtime_error("tile rows are too large");
      minChunks = ceilDiv(width, tw) * ceilDiv(height, th);  // level 0 alone: a lower bound
    } else {
      minChunks = ceilDiv(height, compression.linesPerChunk);
    }
    if (multiPart) {
      if (part.chunkCount < minChunks || (!tiled && part.chunkCount != minChunks))
        throw std::runtime_error("chunkCount does not match the data window");
      minChunks = part.chunkCount;
    }
    totalChunks += static_cast<std::uint64_t>(minChunks);
    std::uint64_t rawBytes = 0;
    for (const ExrChannelInfo& channel : part.channels)
      rawBytes += static_cast<std::uint64_t>(ceilDiv(width, channel.xSampling) * ceilDiv(height, channel.ySampling)) *
                  static_cast<std::uint64_t>(channel.bytes);
    if (rawBytes > compression.maxRatio * dataBytes + kExrRawSlackBytes)
      throw std::runtime_error("truncated (" + std::to_string(dataBytes) + " bytes of data cannot hold a " +
                               std::to_string(width) + " × " + std::to_string(height) + " image)");
  }
  if (totalChunks > dataBytes / kExrMinBytesPerChunk)
    throw std::runtime_error("truncated (" + std::to_string(totalChunks) + " chunks cannot fit in " +
                             std::to_string(dataBytes) + " bytes)");
  return parts.front();
}

Imf::Header exrHeaderFor(const Image& image, Imf::PixelType type, const std::map<std::string, std::string>& attributes) {
  Imf::Header header(image.width, image.height);
  header.compression() = Imf::ZIP_COMPRESSION;
  for (const char* channel : {"R", "G", "B", "A"}) header.channels().insert(channel, Imf::Channel(type));
  for (const auto& [key, value] : attributes) {
    if (key.empty()) throw std::runtime_error("empty attribute name");
    header.insert(key, Imf::StringAttribute(value));
  }
  return header;
}

/// Reads the data window in bands, so that memory grows only as real data decodes: a corrupt file
/// fails on its first bad chunk, long before a full-size buffer would have been filled.
Image readExrPixels(Imf::InputFile& file, const ExrPartInfo& layout) {
  const Imath::Box2i window = file.header().dataWindow();
  const int width = window.max.x - window.min.x + 1;
  const int height = window.max.y - window.min.y + 1;
  const Imf::ChannelList& channels = file.header().channels();
  const bool hasRgb = channels.findChannel("R") || channels.findChannel("G") || channels.findChannel("B");
  const bool greyOnly = !hasRgb && channels.findChannel("Y");
  if (!hasRgb && !greyOnly) throw std::runtime_error("no R, G, B or Y channel");
  for (const char* name : {"R", "G", "B", "A", "Y"}) {
    const Imf::Channel* channel = channels.findChannel(name);
    if (channel && (channel->xSampling != 1 || channel->ySampling != 1))
      throw std::runtime_error(std::string("channel ") + name + " is subsampled (not supported)");
  }
  // Bands a whole number of chunks high avoid decoding a chunk twice.
  constexpr int kMinBandRows = 64;
  const int chunkRows = layout.hasTiles ? static_cast<int>(layout.tileHeight)
                                        : kExrCompressions[layout.compression].linesPerChunk;
  const int bandRows = std::max(kMinBandRows, chunkRows);

  Image image;
  image.width = width;
  image.height = height;
  for (int y0 = window.min.y; y0 <= window.max.y;) {
    const int rows = static_cast<int>(std::min<std::int64_t>(bandRows, std::int64_t{window.max.y} - y0 + 1));
    const std::size_t first = image.pixels.size();
    image.pixels.resize(first + static_cast<std::size_t>(rows) * static_cast<std::size_t>(width));
    char* base = reinterpret_cast<char*>(&image.pixels[first]);
    constexpr std::size_t kPixelBytes = sizeof(glm::vec4);
    const std::size_t rowBytes = kPixelBytes * static_cast<std::size_t>(width);
    const Imath::V2i origin(window.min.x, y0);
    Imf::FrameBuffer frameBuffer;
    const char* sources[4] = {greyOnly ? "Y" : "R", "G", "B", "A"};
    const int slices = greyOnly ? 1 : 4;
    for (int c = 0; c < 4; ++c) {
      if (c >= slices && c != 3) continue;
      const double fill = c == 3 ? 1.0 : 0.0;
      frameBuffer.insert(sources[c], Imf::Slice::Make(Imf::FLOAT, base + c * sizeof(float), origin, width, rows,
                                                      kPixelBytes, rowBytes, 1, 1, fill));
    }
    file.setFrameBuffer(frameBuffer);
    file.readPixels(y0, y0 + rows - 1);
    y0 += rows;
  }
  if (greyOnly)
    for (glm::vec4& p : image.pixels) p.g = p.b = p.r;
  return image;
}

}  // namespace

// -----------------------------------------------------------------------------------------------
// PNG

std::vector<std::uint8_t> toneMappedRgb8(const Image& image, const ToneMapSettings& toneMap, Dither dither) {
  constexpr int kChannels = 3;
  std::vector<std::uint8_t> bytes(image.pixels.size() * kChannels);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(image.width) + static_cast<std::size_t>(x);
      const glm::vec3 srgb = toneMapToSrgb(glm::vec3(image.pixels[i]), toneMap);
      // Dithered as the window is (shaders/common/tonemap.glsl); NaN is stored as 0.
      const float offset = dither == Dither::On ? ditherLevels(x, y) : 0.0f;
      for (int c = 0; c < kChannels; ++c)
        bytes[i * kChannels + static_cast<std::size_t>(c)] = static_cast<std::uint8_t>(quantize8(srgb[c], offset));
    }
  return bytes;
}

void writePng(const std::filesystem::path& path, const Image& image, const ToneMapSettings& toneMap, Dither dither) {
  checkPixelCount(path, image);
  writePngRgb8(path, image.width, image.height, toneMappedRgb8(image, toneMap, dither));
}

void writePngRgb8(const std::filesystem::path& path, int width, int height, std::span<const std::uint8_t> rgb) {
  if (width < 1 || height < 1 || rgb.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3)
    throw std::runtime_error("cannot write " + path.string() + ": " + std::to_string(rgb.size()) +
                             " bytes are not an RGB image of " + std::to_string(width) + "x" + std::to_string(height));
  writeFileAtomically(path, [&](const std::filesystem::path& tmp) {
    png_image png{};
    png.version = PNG_IMAGE_VERSION;
    png.width = static_cast<png_uint_32>(width);
    png.height = static_cast<png_uint_32>(height);
    png.format = PNG_FORMAT_RGB;
    if (!png_image_write_to_file(&png, tmp.c_str(), 0, rgb.data(), 0, nullptr)) {
      const std::string message = png.message;
      png_image_free(&png);
      throw std::runtime_error("cannot write " + path.string() + ": " + oneLine(message));
    }
  });
}

Image readPng(const std::filesystem::path& path) {
  const std::vector<std::uint8_t> bytes = readFileBytes(path);
  try {
    return readPngFromMemory(bytes, path.string());
  } catch (const std::bad_alloc&) {
    throwOutOfMemoryReading(path);
  }
}

Image readPngFromMemory(std::span<const std::uint8_t> data, const std::string& nameForErrors) {
  if (data.size() < kPngSignatureBytes || png_sig_cmp(data.data(), 0, kPngSignatureBytes) != 0)
    fail(nameForErrors, "not a PNG file");
  PngErrorText error{};
  PngReadHandle handle(&error);
  if (!handle.png() || !handle.info()) fail(nameForErrors, "out of memory");
  PngMemory memory{data.data(), data.size(), 0};
  png_set_read_fn(handle.png(), &memory, pngReadMemory);
#ifdef FUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION
  // Let mutated inputs reach the decoder instead of stopping at a checksum (libpng's own fuzzer
  // does the same). Never in a normal build: checksums are how corruption shows.
  png_set_crc_action(handle.png(), PNG_CRC_QUIET_USE, PNG_CRC_QUIET_USE);
  png_set_option(handle.png(), PNG_IGNORE_ADLER32, PNG_OPTION_ON);
#endif

  PngLayout layout{};
  if (!pngReadLayout(handle.png(), handle.info(), &layout)) fail(nameForErrors, error.text);
  checkImageSize(nameForErrors, layout.width, layout.height);
  if (layout.channels != 4 || (layout.bitDepth != 8 && layout.bitDepth != 16))
    fail(nameForErrors, "unsupported pixel layout");
  const std::uint64_t storedBytes = std::uint64_t{layout.height} * (layout.fileRowBytes + 1);
  if (storedBytes > kDeflateMaxRatio * pngCompressedBytes(data) + kPngRawSlackBytes)
    fail(nameForErrors, "truncated (too little image data for " + std::to_string(layout.width) + " × " +
                            std::to_string(layout.height) + " pixels)");

  std::vector<std::uint8_t> raw(layout.rowBytes * layout.height);
  std::vector<png_bytep> rows(layout.height);
  for (png_uint_32 y = 0; y < layout.height; ++y) rows[y] = raw.data() + layout.rowBytes * y;
  if (!pngReadRows(handle.png(), rows.data())) fail(nameForErrors, error.text);

  Image image(static_cast<int>(layout.width), static_cast<int>(layout.height));
  const std::size_t samples = image.pixels.size() * 4;
  if (layout.bitDepth == 8) {
    for (std::size_t i = 0; i < samples; ++i) image.pixels[i / 4][static_cast<int>(i % 4)] = raw[i] / 255.0f;
  } else {
    for (std::size_t i = 0; i < samples; ++i) {
      const unsigned word = (unsigned{raw[2 * i]} << 8) | raw[2 * i + 1];  // PNG stores big-endian
      image.pixels[i / 4][static_cast<int>(i % 4)] = static_cast<float>(word) / 65535.0f;
    }
  }
  return image;
}

// -----------------------------------------------------------------------------------------------
// OpenEXR

PixelCensus censusPixels(const Image& image) {
  PixelCensus census;
  for (const glm::vec4& p : image.pixels) {
    bool nonFinite = false, beyond = false;
    for (int c = 0; c < 4; ++c) {
      if (!std::isfinite(p[c])) nonFinite = true;
      else if (std::abs(p[c]) > kHalfMax) beyond = true;
    }
    census.nonFinite += nonFinite ? 1 : 0;
    census.beyondHalf += beyond ? 1 : 0;
  }
  return census;
}

namespace {
/// One EXR into `tmp` (a fresh temporary), named `path` in errors; returns the sample type written.
/// The sample type writeExr stores `image` with when asked for `type`: float where a half file would
/// turn a finite value beyond kHalfMax into infinity.
ExrPixelType storedType(const Image& image, ExrPixelType type) {
  return type == ExrPixelType::Half && censusPixels(image).beyondHalf > 0 ? ExrPixelType::Float : type;
}

ExrPixelType writeExrInto(const std::filesystem::path& tmp, const std::filesystem::path& path, const Image& image,
                          ExrPixelType type, const std::map<std::string, std::string>& attributes) {
  checkPixelCount(path, image);
  type = storedType(image, type);
  try {
    const Imf::PixelType pixelType = type == ExrPixelType::Half ? Imf::HALF : Imf::FLOAT;
    Imf::Header header = exrHeaderFor(image, pixelType, attributes);
    // OutputFile does not convert sample types, so half data gets its own buffer.
    std::vector<Imath::half> halves;
    const char* base = reinterpret_cast<const char*>(image.pixels.data());
    std::size_t sampleBytes = sizeof(float);
    if (pixelType == Imf::HALF) {
      halves.resize(image.pixels.size() * 4);
      for (std::size_t i = 0; i < image.pixels.size(); ++i)
        for (int c = 0; c < 4; ++c) halves[4 * i + static_cast<std::size_t>(c)] = Imath::half(image.pixels[i][c]);
      base = reinterpret_cast<const char*>(halves.data());
      sampleBytes = sizeof(Imath::half);
    }
    const std::size_t pixelBytes = 4 * sampleBytes;
    Imf::FrameBuffer frameBuffer;
    const char* names[4] = {"R", "G", "B", "A"};
    for (std::size_t c = 0; c < 4; ++c)
      frameBuffer.insert(names[c], Imf::Slice(pixelType, const_cast<char*>(base + c * sampleBytes), pixelBytes,
                                              pixelBytes * static_cast<std::size_t>(image.width)));
    Imf::OutputFile file(tmp.c_str(), header);
    file.setFrameBuffer(frameBuffer);
    file.writePixels(image.height);
  } catch (const std::exception& e) {
    throw std::runtime_error("cannot write " + path.string() + ": " + oneLine(e.what()));
  }
  return type;
}
}  // namespace

Image storedAsExr(const Image& image, ExrPixelType type) {
  if (storedType(image, type) != ExrPixelType::Half) return image;
  Image stored = image;
  for (glm::vec4& p : stored.pixels)
    for (int c = 0; c < 4; ++c) p[c] = static_cast<float>(Imath::half(p[c]));
  return stored;
}

ExrPixelType writeExr(const std::filesystem::path& path, const Image& image, ExrPixelType type,
                      const std::map<std::string, std::string>& attributes) {
  ExrPixelType written = type;
  writeFileAtomically(path, [&](const std::filesystem::path& tmp) {
    written = writeExrInto(tmp, path, image, type, attributes);
  });
  return written;
}

void writeExrFiles(const std::vector<ExrOutput>& files) {
  // Every file into its temporary first; only when all are written are they renamed.
  std::vector<std::unique_ptr<PendingFile>> pending;
  for (const ExrOutput& f : files) {
    pending.push_back(std::make_unique<PendingFile>(f.path));
    writeExrInto(pending.back()->temporary(), f.path, *f.image, f.type, f.attributes);
  }
  for (const auto& p : pending) p->commit();
}

Image readExr(const std::filesystem::path& path) {
  const std::vector<std::uint8_t> bytes = readFileBytes(path);
  try {
    return readExrFromMemory(bytes, path.string());
  } catch (const std::bad_alloc&) {
    throwOutOfMemoryReading(path);
  }
}

Image readExrFromMemory(std::span<const std::uint8_t> data, const std::string& nameForErrors) {
  try {
    const ExrPartInfo layout = scanExrHeaders(data);
    MemoryIStream stream(data, nameForErrors);
    Imf::InputFile file(stream);
    return readExrPixels(file, layout);
  } catch (const std::bad_alloc&) {
    throw;  // the caller names the file and its size
  } catch (const std::exception& e) {
    fail(nameForErrors, e.what());
  }
}

std::map<std::string, std::string> readExrStringAttributes(const std::filesystem::path& path) {
  const std::vector<std::uint8_t> bytes = readFileBytes(path);
  try {
    return readExrStringAttributesFromMemory(bytes, path.string());
  } catch (const std::bad_alloc&) {
    throwOutOfMemoryReading(path);
  }
}

std::map<std::string, std::string> readExrStringAttributesFromMemory(std::span<const std::uint8_t> data,
                                                                     const std::string& nameForErrors) {
  try {
    scanExrHeaders(data);
    MemoryIStream stream(data, nameForErrors);
    Imf::InputFile file(stream);
    std::map<std::string, std::string> attributes;
    const Imf::Header& header = file.header();
    for (auto it = header.begin(); it != header.end(); ++it) {
      if (std::strcmp(it.attribute().typeName(), Imf::StringAttribute::staticTypeName()) == 0)
        attributes[it.name()] = static_cast<const Imf::StringAttribute&>(it.attribute()).value();
    }
    return attributes;
  } catch (const std::bad_alloc&) {
    throw;  // the caller names the file and its size
  } catch (const std::exception& e) {
    fail(nameForErrors, e.what());
  }
}

}  // namespace tallow::gpu
