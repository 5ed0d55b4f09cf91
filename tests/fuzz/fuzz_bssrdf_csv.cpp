// libFuzzer target: the configuration CSV of `tallow probe bssrdf`. Bad input must end in
// InputError (file:line: message); every row that parses must evaluate to finite values in double
// precision (float cannot hold every finite double input, so it is exercised but not judged).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "app/commands/bssrdf_csv.h"
#include "app/config/input_error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const auto configs = tallow::app::parseBssrdfConfigs(text, "fuzz.csv");
    for (const auto& c : configs)
      for (auto model : {tallow::sss::BssrdfModel::Standard, tallow::sss::BssrdfModel::Directional,
                         tallow::sss::BssrdfModel::PhotonBeamDiffusion}) {
        const auto d = tallow::sss::evaluateBssrdf<double>(model, c);
        (void)tallow::sss::evaluateBssrdf<float>(model, c);
        if (!std::isfinite(d.sd) || !std::isfinite(d.sdClamped)) std::abort();
      }
    (void)tallow::app::formatBssrdfValues(configs, std::vector<tallow::sss::BssrdfValue>(configs.size()));
  } catch (const tallow::app::InputError&) {
  }
  return 0;
}
