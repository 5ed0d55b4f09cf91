// libFuzzer target: the points CSV of `tallow field`. Bad input must end in InputError
// (file:line:col: message); every point that parses is finite and within the coordinate limit, and
// its row formats back into CSV.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "app/commands/points_csv.h"
#include "app/config/input_error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const auto points = tallow::app::parsePoints(text, "fuzz.csv");
    for (const auto& p : points)
      for (int k = 0; k < 3; ++k)
        if (!std::isfinite(p[k]) || std::abs(p[k]) > tallow::app::kMaxCoordinateM) std::abort();
    (void)tallow::app::formatFieldValues(points, std::vector<tallow::app::FieldSample>(points.size()));
  } catch (const tallow::app::InputError& e) {
    if (std::string_view(e.what()).substr(0, 9) != "fuzz.csv:") std::abort();  // always names the file
  }
  return 0;
}
