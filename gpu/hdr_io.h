#pragma once
// Reading Radiance RGBE (.hdr) images (G. Ward, "Real Pixels", Graphics Gems II, 1991; the Radiance
// file format). Strict: every malformed input throws std::runtime_error with one line,
// `NAME: WHAT` (naming the scanline and byte offset where the data broke), never crashes or hangs,
// and sizes are checked before anything is allocated.
//
// Accepted:
// - first line `#?RADIANCE` or `#?RGBE`; then header lines up to an empty line. `FORMAT=` must be
//   `32-bit_rle_rgbe` (XYZE is refused); absent means RGBE. `EXPOSURE=e` lines are APPLIED: Radiance
//   multiplies the stored values by every exposure it records, so the returned pixels are the
//   stored ones divided by the product of all EXPOSURE values (each must be a finite number > 0).
//   Other lines (comments, GAMMA, PRIMARIES, VIEW, …) are ignored; PRIMARIES in particular is not
//   applied (the data are taken as linear RGB). At most kMaxHdrHeaderBytes of header.
// - resolution line `-Y H +X W` only (rows top to bottom, columns left to right — the standard
//   orientation); any other orientation is refused. 1 ≤ W, H ≤ kMaxHdrSide.
// - scanlines that are flat (4 bytes R G B E per pixel) or new-style run-length encoded (2 2 W/256
//   W%256, then the four components one after another, each as runs: a count byte c > 128 followed
//   by one byte repeated c − 128 times, or 0 < c ≤ 128 followed by c literal bytes). Old-style runs
//   (a pixel 1 1 1 n meaning "repeat the last pixel") are refused. Bytes after the last scanline are
//   ignored.
//
// Decoding (Ward's colr_color): E = 0 gives 0; otherwise each channel is (m + 0.5) · 2^(E − 136).
// Alpha is 1. Row 0 of the result is the first scanline (the top of the image).
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>

#include "gpu/image.h"

namespace tallow::gpu {

/// Largest width or height accepted (the pixel total is then at most kMaxImagePixels).
inline constexpr int kMaxHdrSide = 16384;
/// Longest header (all lines up to and including the resolution line) accepted.
inline constexpr std::size_t kMaxHdrHeaderBytes = 64 * 1024;

/// Reads a Radiance RGBE file. Throws std::runtime_error `PATH: WHAT`.
Image readHdr(const std::filesystem::path& path);
/// readHdr on bytes in memory; `nameForErrors` starts every error message.
Image decodeHdr(std::span<const std::uint8_t> data, const std::string& nameForErrors);

}  // namespace tallow::gpu
