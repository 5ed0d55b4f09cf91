#include "app/view/numbered_file.h"

#include <algorithm>
#include <cctype>
#include <cstdio>

namespace tallow::app {

std::filesystem::path nextNumberedFile(const std::string& base, const std::string& extension) {
  const std::filesystem::path path(base);
  const std::filesystem::path folder = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  const std::string stem = path.filename().string() + "-";
  unsigned long largest = 0;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(folder, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.size() <= stem.size() + extension.size() || name.compare(0, stem.size(), stem) != 0 ||
        name.compare(name.size() - extension.size(), extension.size(), extension) != 0)
      continue;
    const std::string digits = name.substr(stem.size(), name.size() - stem.size() - extension.size());
    if (digits.empty() || digits.size() > 9 ||
        !std::all_of(digits.begin(), digits.end(), [](unsigned char c) { return std::isdigit(c); }))
      continue;
    largest = std::max(largest, std::stoul(digits));
  }
  char number[16];
  std::snprintf(number, sizeof number, "%04lu", largest + 1);
  return std::filesystem::path(base + "-" + number + extension);
}

}  // namespace tallow::app
