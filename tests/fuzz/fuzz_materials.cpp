// libFuzzer target: MaterialTable::parse on arbitrary bytes. Bad input must end in
// std::runtime_error (file:line: message); anything else is reported as a crash.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string_view>

#include "sss/bssrdf/material.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const tallow::sss::MaterialTable table = tallow::sss::MaterialTable::parse(text, "fuzz.csv");
    for (const tallow::sss::Material& m : table.materials()) tallow::sss::validateMaterial(m);  // must hold
  } catch (const std::runtime_error&) {
  }
  return 0;
}
