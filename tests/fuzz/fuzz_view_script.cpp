// libFuzzer target: parseScript (the view's and capture's --script files) on arbitrary bytes. Bad
// input must end in InputError; any other exception escapes and is reported as a crash, since it
// means the reader skipped a check.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "app/config/input_error.h"
#include "app/config/params.h"
#include "app/playback/view_script.h"
#include "sss/bssrdf/material.h"

namespace {

// A small fixed table, so that `set material=…` in the corpus resolves without reading files.
constexpr const char* kMaterialsCsv =
    "name,source,sigma_s_r,sigma_s_g,sigma_s_b,sigma_a_r,sigma_a_g,sigma_a_b,g_r,g_g,g_b,eta,unit\n"
    "Marble,Jensen et al. 2001,2.19,2.62,3,0.0021,0.0041,0.0071,0,0,0,1.5,mm^-1\n"
    "Ketchup,Jensen et al. 2001,0.18,0.07,0.03,0.061,0.97,1.45,0,0,0,1.3,mm^-1\n";

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const tallow::sss::MaterialTable table = tallow::sss::MaterialTable::parse(kMaterialsCsv, "fuzz.csv");
  static const tallow::app::Registry registry = tallow::app::parameterRegistry(table);
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const tallow::app::Script script = tallow::app::parseScript(text, "fuzz.txt", registry);
    // What a run does with a script it accepted: look commands up by frame.
    (void)script.at(script.lastFrame());
  } catch (const tallow::app::InputError&) {
  }
  return 0;
}
