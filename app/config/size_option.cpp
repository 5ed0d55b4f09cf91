// --size's text, apart from the rest of the setup so that the fuzz target of the command-line
// values (tests/fuzz/fuzz_cli_values.cpp) links it alone.
#include <charconv>

#include "app/config/input_error.h"
#include "app/config/setup.h"

namespace tallow::app {

std::pair<int, int> parseSize(const std::string& text) {
  const auto x = text.find('x');
  int w = 0, h = 0;
  auto parse = [](std::string_view s, int& out) {
    const auto r = std::from_chars(s.data(), s.data() + s.size(), out);
    return r.ec == std::errc() && r.ptr == s.data() + s.size();
  };
  if (x == std::string::npos || !parse(std::string_view(text).substr(0, x), w) ||
      !parse(std::string_view(text).substr(x + 1), h))
    throw InputError("--size: expected WIDTHxHEIGHT (e.g. 960x540), got " + quote(text));
  // The range of render.width and render.height.
  if (w < 1 || h < 1 || w > 16384 || h > 16384)
    throw InputError("--size: " + text + " is out of range (1 to 16384 pixels per side)");
  return {w, h};
}

}  // namespace tallow::app
