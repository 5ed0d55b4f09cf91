// libFuzzer target: the EXR header's string attributes, what `bench --reference` reads from REF.exr
// (readExrStringAttributes). Any input must give the attributes or a std::exception, never a
// crash, leak, hang or huge allocation.
#include <cstddef>
#include <cstdint>
#include <exception>
#include <span>

#include "gpu/image_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const auto attributes =
        tallow::gpu::readExrStringAttributesFromMemory(std::span<const std::uint8_t>(data, size), "fuzz.exr");
    // What the bench does with them: copy every name and value into bench.json.
    std::size_t total = 0;
    for (const auto& [name, value] : attributes) total += name.size() + value.size();
    (void)total;
  } catch (const std::exception&) {
    // Rejecting the input is fine; only crashes and sanitizer reports are findings.
  }
  return 0;
}
