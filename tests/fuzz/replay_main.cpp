// Replays the kept fuzz corpora (tests/fuzz/corpus/<target>/) through the targets' entry points in
// the ordinary build, so that every ctest run checks that no input the fuzzers have learned — and
// no crash they once found, kept there after its fix — fails again. The targets' sources are
// compiled into this one executable with LLVMFuzzerTestOneInput renamed per target
// (tests/CMakeLists.txt), and `tallow_fuzz_replay TARGET DIR…` runs each file of DIR once.
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <string_view>
#include <vector>

#define TALLOW_FUZZ_TARGET(name) extern "C" int tallowFuzz_##name(const std::uint8_t* data, std::size_t size);
#include "fuzz_targets.inc"
#undef TALLOW_FUZZ_TARGET

namespace {

using EntryPoint = int (*)(const std::uint8_t*, std::size_t);

struct Target {
  const char* name;
  EntryPoint entry;
};

#define TALLOW_FUZZ_TARGET(name) Target{#name, &tallowFuzz_##name},
constexpr Target kTargets[] = {
#include "fuzz_targets.inc"
};
#undef TALLOW_FUZZ_TARGET

/// The input being replayed, for the crash handler.
char currentInput[4096] = "";

/// A crash names the input before the default action ends the process (write(2) is safe here).
extern "C" void reportCrash(int signal) {
  const char prefix[] = "replay: crashed on ";
  [[maybe_unused]] ssize_t n = ::write(STDERR_FILENO, prefix, sizeof prefix - 1);
  n = ::write(STDERR_FILENO, currentInput, std::strlen(currentInput));
  n = ::write(STDERR_FILENO, "\n", 1);
  std::signal(signal, SIG_DFL);
  std::raise(signal);
}

std::vector<std::filesystem::path> inputsOf(const std::filesystem::path& path) {
  std::vector<std::filesystem::path> files;
  if (std::filesystem::is_directory(path)) {
    for (const auto& entry : std::filesystem::directory_iterator(path))
      if (entry.is_regular_file()) files.push_back(entry.path());
    std::sort(files.begin(), files.end());  // the same order on every machine
  } else {
    files.push_back(path);
  }
  return files;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: %s TARGET CORPUS_DIR_OR_FILE...\n", argv[0]);
    return 2;
  }
  const std::string_view wanted = argv[1];
  const auto target = std::find_if(std::begin(kTargets), std::end(kTargets),
                                   [&](const Target& t) { return wanted == t.name; });
  if (target == std::end(kTargets)) {
    std::fprintf(stderr, "replay: no fuzz target \"%s\"\n", argv[1]);
    return 2;
  }
  for (const int s : {SIGSEGV, SIGABRT, SIGFPE, SIGBUS, SIGILL}) std::signal(s, reportCrash);
  std::size_t replayed = 0;
  for (int a = 2; a < argc; ++a) {
    if (!std::filesystem::exists(argv[a])) {
      std::fprintf(stderr, "replay: %s does not exist\n", argv[a]);
      return 1;
    }
    for (const std::filesystem::path& file : inputsOf(argv[a])) {
      std::snprintf(currentInput, sizeof currentInput, "%s", file.c_str());
      std::ifstream in(file, std::ios::binary);
      const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      try {
        target->entry(bytes.data(), bytes.size());
      } catch (const std::exception& e) {
        std::fprintf(stderr, "replay: %s: escaped the target: %s\n", file.c_str(), e.what());
        return 1;
      }
      ++replayed;
    }
  }
  if (replayed == 0) {
    std::fprintf(stderr, "replay: no inputs for %s\n", target->name);
    return 1;
  }
  std::printf("replay: %zu input(s) through fuzz_%s, none failed\n", replayed, target->name);
  return 0;
}
