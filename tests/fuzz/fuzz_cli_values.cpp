// libFuzzer target: the command-line values read as text — `--set key=value` (the registry, on a
// scene with an object and a light so that scene-bound parameters apply), `--size WxH`, and
// `bench --sweep key=v1,v2,…` with each value through the registry as the bench checks it. Bad text
// must end in InputError; any other exception escapes and is reported as a crash, since it means
// a parser skipped a check.
#include <cstddef>
#include <cstdint>
#include <string>

#include "app/commands/bench_command.h"
#include "app/commands/option_checks.h"
#include "app/config/input_error.h"
#include "app/config/params.h"
#include "app/config/preset.h"
#include "app/config/setup.h"
#include "sss/bssrdf/material.h"

namespace {

constexpr const char* kMaterialsCsv =
    "name,source,sigma_s_r,sigma_s_g,sigma_s_b,sigma_a_r,sigma_a_g,sigma_a_b,g_r,g_g,g_b,eta,unit\n"
    "Marble,Jensen et al. 2001,2.19,2.62,3,0.0021,0.0041,0.0071,0,0,0,1.5,mm^-1\n"
    "Ketchup,Jensen et al. 2001,0.18,0.07,0.03,0.061,0.97,1.45,0,0,0,1.3,mm^-1\n";

/// A translucent sphere, an opaque floor, a directional and a point light: enough for every
/// scene-bound key to apply.
constexpr const char* kPreset = R"({
  "camera": {"position": [0, 1, 2], "target": [0, 0, 0]},
  "lights": [{"type": "directional", "direction": [0, 1, 0], "irradiance": [1, 1, 1]},
             {"type": "point", "position": [0.2, 0.5, 0.1], "intensity": [1, 0.9, 0.8]}],
  "objects": [{"shape": "sphere", "material": "Marble", "scale": 0.05},
              {"shape": "box", "size": [1, 0.1, 1]}]
})";

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tallow;
  static const sss::MaterialTable table = sss::MaterialTable::parse(kMaterialsCsv, "fuzz.csv");
  static const app::Registry registry = app::parameterRegistry(table);
  static const app::Config base = app::parsePreset(kPreset, "fuzz.json", "/presets", table, "/data");
  const std::string text(reinterpret_cast<const char*>(data), size);

  app::Config config = base;
  try {
    registry.setFromString(config, text);  // --set
    (void)registry.snapshot(config);      // what stats.json records of the value set
  } catch (const app::InputError&) {
  }
  try {
    (void)app::parseSize(text);  // --size
  } catch (const app::InputError&) {
  }
  try {
    const app::Sweep sweep = app::parseSweep(text);  // bench --sweep
    for (const std::string& value : sweep.values) app::checkSweepValue(registry, base, text, sweep.key, value);
  } catch (const app::InputError&) {
  }
  return 0;
}
