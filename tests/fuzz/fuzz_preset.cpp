// libFuzzer target: parsePreset on arbitrary bytes. Bad input must end in InputError; any other
// exception escapes and is reported as a crash, since it means a reader skipped a check.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "app/config/input_error.h"
#include "app/config/preset.h"
#include "sss/bssrdf/material.h"

namespace {

// A small fixed table, so that material names in the corpus resolve without reading files.
constexpr const char* kMaterialsCsv =
    "name,source,sigma_s_r,sigma_s_g,sigma_s_b,sigma_a_r,sigma_a_g,sigma_a_b,g_r,g_g,g_b,eta,unit\n"
    "Marble,Jensen et al. 2001,2.19,2.62,3,0.0021,0.0041,0.0071,0,0,0,1.5,mm^-1\n"
    "Ketchup,Jensen et al. 2001,0.18,0.07,0.03,0.061,0.97,1.45,0,0,0,1.3,mm^-1\n"
    "Coke,Narasimhan et al. 2006,0.00254,0.00299,0,0.10014,0.16503,0.2468,0.965,0.972,0,1.33,mm^-1\n";

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const tallow::sss::MaterialTable table = tallow::sss::MaterialTable::parse(kMaterialsCsv, "fuzz.csv");
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    tallow::app::parsePreset(text, "fuzz.json", "/presets", table, "/data");
  } catch (const tallow::app::InputError&) {
  }
  return 0;
}
