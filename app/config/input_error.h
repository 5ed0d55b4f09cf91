#pragma once
// The one exception type for bad user input (presets, --set, file names), and the "did you mean"
// hint its messages carry. what() is the complete line the command line prints after "tallow: ",
// e.g. `presets/x.json:12:5: unknown key "mpas" (did you mean "maps"?)`.
#include <algorithm>
#include <cctype>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <limits>
#include <new>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "gpu/file_bytes.h"

namespace tallow::app {

class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

[[noreturn]] inline void throwOutOfMemoryReading(const std::filesystem::path& file);

/// The whole of a file the user named (a preset, a script, a CSV); InputError naming it when it is a
/// folder or not a regular file (/dev/zero), larger than `maxBytes` (the limits of gpu/file_bytes.h,
/// checked before reading), cannot be opened, fails to read or does not fit in memory.
inline std::string readInputFile(const std::filesystem::path& file, std::uintmax_t maxBytes = gpu::kMaxTextFileBytes,
                                 std::string_view what = "a text file") {
  std::error_code ec;
  if (std::filesystem::is_directory(file, ec)) throw InputError(file.string() + ": is a folder, not a file");
  try {
    gpu::checkInputFile(file, maxBytes, what);
  } catch (const std::runtime_error& e) {
    throw InputError(e.what());
  }
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string() + ": cannot open");
  try {
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad()) throw InputError(file.string() + ": read error");
    return text.str();
  } catch (const std::bad_alloc&) {
    throwOutOfMemoryReading(file);
  }
}

/// InputError `FILE: out of memory reading it (SIZE)`: a std::bad_alloc while reading or decoding
/// a file the user named.
[[noreturn]] inline void throwOutOfMemoryReading(const std::filesystem::path& file) {
  try {
    gpu::throwOutOfMemoryReading(file);
  } catch (const std::runtime_error& e) {
    throw InputError(e.what());
  }
}

/// parse(readInputFile(file, …)): what the file's contents decode to, with a std::bad_alloc in the
/// decoding (a table or document larger in memory than on disk) named as readInputFile names it.
template <class Parse>
auto parseInputFile(const std::filesystem::path& file, Parse&& parse, std::uintmax_t maxBytes = gpu::kMaxTextFileBytes,
                    std::string_view what = "a text file") {
  const std::string text = readInputFile(file, maxBytes, what);
  try {
    return parse(text);
  } catch (const std::bad_alloc&) {
    throwOutOfMemoryReading(file);
  }
}

/// Optimal-string-alignment distance (Levenshtein plus adjacent transpositions, so "mpas" is one
/// edit from "maps"), compared case-insensitively.
inline std::size_t editDistance(std::string_view a, std::string_view b) {
  const auto lower = [](char c) {
    return static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  };
  const std::size_t n = a.size(), m = b.size();
  // Three rows suffice for the transposition look-back.
  std::vector<std::size_t> prev2(m + 1), prev(m + 1), cur(m + 1);
  for (std::size_t j = 0; j <= m; ++j) prev[j] = j;
  for (std::size_t i = 1; i <= n; ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= m; ++j) {
      const std::size_t cost = lower(a[i - 1]) == lower(b[j - 1]) ? 0 : 1;
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + cost});
      if (i > 1 && j > 1 && lower(a[i - 1]) == lower(b[j - 2]) && lower(a[i - 2]) == lower(b[j - 1]))
        cur[j] = std::min(cur[j], prev2[j - 2] + 1);
    }
    std::swap(prev2, prev);
    std::swap(prev, cur);
  }
  return prev[m];
}

/// `s` in double quotes for a one-line message: quotes, backslashes and control characters
/// escaped as in JSON, and cut (at a UTF-8 character boundary) after kMaxQuoted bytes.
inline std::string quote(std::string_view s) {
  constexpr std::size_t kMaxQuoted = 60;
  bool cut = false;
  if (s.size() > kMaxQuoted) {
    std::size_t n = kMaxQuoted;
    while (n > 0 && (static_cast<unsigned char>(s[n]) & 0xC0) == 0x80) --n;  // not mid-character
    s = s.substr(0, n);
    cut = true;
  }
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7F) {
      constexpr char kHex[] = "0123456789abcdef";
      out += "\\u00";
      out += kHex[(static_cast<unsigned char>(c) >> 4) & 0xF];
      out += kHex[static_cast<unsigned char>(c) & 0xF];
    } else {
      out += c;
    }
  }
  return out + (cut ? "...\"" : "\"");
}

/// The candidate closest to `word`, or "" when none is close enough to be a plausible typo: at most
/// one edit per three characters (at least one, at most three) and fewer edits than letters; or,
/// failing that, a candidate that `word` (of three or more letters) abbreviates ("fov" → "fov_deg").
inline std::string closestMatch(std::string_view word, const std::vector<std::string>& candidates) {
  constexpr std::size_t kMinPrefix = 3;
  const std::size_t allowed = std::clamp<std::size_t>(word.size() / 3, 1, 3);
  const auto abbreviates = [&](std::string_view c) {
    return word.size() >= kMinPrefix && word.size() < c.size() &&
           std::equal(word.begin(), word.end(), c.begin(), [](char a, char b) {
             return std::tolower(static_cast<unsigned char>(a)) == std::tolower(static_cast<unsigned char>(b));
           });
  };
  std::size_t best = std::numeric_limits<std::size_t>::max();
  std::string match;
  for (const std::string& c : candidates) {
    const std::size_t lengthGap = word.size() > c.size() ? word.size() - c.size() : c.size() - word.size();
    std::size_t d = allowed;
    if (lengthGap > allowed) {
      // At least lengthGap edits apart, too many for a typo (and no need to count them, which
      // for long input is the costly part): only an abbreviation can still match.
      if (!abbreviates(c)) continue;
    } else {
      d = editDistance(word, c);
      if (d > allowed && abbreviates(c)) d = allowed;  // an abbreviation ranks after any typo within the allowance
    }
    if (d < best && d <= allowed && d < std::max(word.size(), c.size())) {
      best = d;
      match = c;
    }
  }
  return match;
}

/// ` (did you mean "x"?)` when a candidate is close, else "".
inline std::string didYouMean(std::string_view word, const std::vector<std::string>& candidates) {
  const std::string match = closestMatch(word, candidates);
  return match.empty() ? std::string() : " (did you mean " + quote(match) + "?)";
}

}  // namespace tallow::app
