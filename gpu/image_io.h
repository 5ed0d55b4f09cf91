#pragma once
// Reading and writing images: 8-bit sRGB PNG (libpng) and linear half/float EXR (OpenEXR).
// Every function throws std::runtime_error with one line, `NAME: WHAT`, on any failure; writes are
// atomic (a reader sees the old file or the complete new one, never a partial file).
#include <cstdint>
#include <filesystem>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "gpu/image.h"
#include "gpu/tonemap.h"

namespace tallow::gpu {

/// Largest image any reader accepts, in pixels (2^28: 4 GiB as RGBA float). Checked before
/// anything is allocated, so that a corrupt header cannot exhaust memory.
inline constexpr std::int64_t kMaxImagePixels = std::int64_t{1} << 28;

/// Tone maps each pixel with toneMapToSrgb and stores 8-bit RGB, round(v × 255 + dither). Alpha is dropped.
void writePng(const std::filesystem::path& path, const Image& image, const ToneMapSettings& toneMap,
              Dither dither = Dither::On);
/// The bytes writePng stores: 8-bit sRGB, RGB interleaved, top row first.
std::vector<std::uint8_t> toneMappedRgb8(const Image& image, const ToneMapSettings& toneMap, Dither dither = Dither::On);
/// Writes 8-bit RGB bytes already display-encoded (e.g. a window read back), top row first.
void writePngRgb8(const std::filesystem::path& path, int width, int height, std::span<const std::uint8_t> rgb);

/// Reads any PNG (grey, grey+alpha, palette, RGB, RGBA; 1–16 bits) into RGBA. Values are returned
/// as stored — byte / 255, or word / 65535 for 16-bit files — i.e. still sRGB-encoded, NOT
/// linearised; no gamma chunk is applied. A missing alpha channel reads as 1.
Image readPng(const std::filesystem::path& path);
/// readPng on bytes in memory; `nameForErrors` starts every error message.
Image readPngFromMemory(std::span<const std::uint8_t> data, const std::string& nameForErrors);

enum class ExrPixelType { Half, Float };

/// Largest finite half-float value; a larger magnitude becomes ±Inf in a half channel.
inline constexpr float kHalfMax = 65504.0f;

/// Pixels a file format cannot store as they are.
struct PixelCensus {
  std::size_t nonFinite = 0;   ///< pixels with a NaN or ±Inf channel
  std::size_t beyondHalf = 0;  ///< pixels with a finite channel of magnitude above kHalfMax
};
PixelCensus censusPixels(const Image& image);

/// Writes linear RGBA (channels R, G, B, A; ZIP compression) with the given sample type, except
/// that a half file whose image has a finite value beyond kHalfMax is written with float channels
/// instead, so that a bright pixel never turns into +Inf. Returns the sample type written.
/// `attributes` become string attributes in the header (e.g. "tallow.spp" → "1024"); a name that
/// clashes with a standard attribute of another type is an error.
ExrPixelType writeExr(const std::filesystem::path& path, const Image& image, ExrPixelType type,
                      const std::map<std::string, std::string>& attributes = {});

/// The image as writeExr(…, type) stores it: rounded to half floats where it would write half (the
/// same choice: float where a finite value is beyond kHalfMax), unchanged otherwise. What a file
/// read back holds, so that an image compared with its own capture differs by exactly 0.
Image storedAsExr(const Image& image, ExrPixelType type);

/// Several EXR files (a reference and its standard error) written whole or not at all: each into a
/// temporary beside it, then, only when every one is written, all renamed onto their names.
struct ExrOutput {
  std::filesystem::path path;
  const Image* image = nullptr;
  ExrPixelType type = ExrPixelType::Float;
  std::map<std::string, std::string> attributes;
};
void writeExrFiles(const std::vector<ExrOutput>& files);

/// Reads R, G, B and A (1 where absent) of a single-part flat EXR, any sample type, as float.
/// The result covers the data window. A file with only a Y channel reads as grey.
Image readExr(const std::filesystem::path& path);
/// readExr on bytes in memory; `nameForErrors` starts every error message.
Image readExrFromMemory(std::span<const std::uint8_t> data, const std::string& nameForErrors);

/// Every string attribute in the header of an EXR file (name → value).
std::map<std::string, std::string> readExrStringAttributes(const std::filesystem::path& path);
/// readExrStringAttributes on bytes in memory; `nameForErrors` starts every error message.
std::map<std::string, std::string> readExrStringAttributesFromMemory(std::span<const std::uint8_t> data,
                                                                     const std::string& nameForErrors);

}  // namespace tallow::gpu
