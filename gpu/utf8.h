#pragma once
// Whether text is well-formed UTF-8 (Unicode 15, Table 3-7: no overlong forms, no surrogates,
// nothing above U+10FFFF). Names a user gives (files, materials) end up in JSON, which must be UTF-8,
// so they are checked where they come in, with an error that names them, not when a report is
// written after the work.
#include <cstddef>
#include <string_view>

namespace tallow::gpu {

/// The byte offset of the first byte that is not part of a well-formed UTF-8 sequence, or
/// std::string_view::npos when all of `text` is well-formed.
inline std::size_t firstInvalidUtf8(std::string_view text) {
  const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(text[i]); };
  std::size_t i = 0;
  while (i < text.size()) {
    const unsigned char b = byte(i);
    std::size_t length = 0;
    unsigned char lo = 0x80, hi = 0xBF;  // the range of the second byte (Table 3-7)
    if (b < 0x80) length = 1;
    else if (b >= 0xC2 && b <= 0xDF) length = 2;
    else if (b == 0xE0) length = 3, lo = 0xA0;
    else if ((b >= 0xE1 && b <= 0xEC) || b == 0xEE || b == 0xEF) length = 3;
    else if (b == 0xED) length = 3, hi = 0x9F;  // no surrogates
    else if (b == 0xF0) length = 4, lo = 0x90;
    else if (b >= 0xF1 && b <= 0xF3) length = 4;
    else if (b == 0xF4) length = 4, hi = 0x8F;  // nothing above U+10FFFF
    else return i;
    if (i + length > text.size()) return i;
    for (std::size_t k = 1; k < length; ++k) {
      const unsigned char c = byte(i + k);
      const unsigned char min = k == 1 ? lo : 0x80, max = k == 1 ? hi : 0xBF;
      if (c < min || c > max) return i;
    }
    i += length;
  }
  return std::string_view::npos;
}

inline bool validUtf8(std::string_view text) { return firstInvalidUtf8(text) == std::string_view::npos; }

}  // namespace tallow::gpu
