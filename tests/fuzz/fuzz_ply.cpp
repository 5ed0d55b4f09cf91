// libFuzzer entry for the PLY reader: any input must give a mesh or a std::exception, never a
// crash, leak, hang or huge allocation.
#include <cstddef>
#include <cstdint>
#include <exception>
#include <string_view>

#include "geometry/ply_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    tallow::geometry::parsePly(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.ply");
  } catch (const std::exception&) {
    // Rejecting the input is fine; only crashes and sanitizer reports are findings.
  }
  return 0;
}
