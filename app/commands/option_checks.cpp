#include "app/commands/option_checks.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>

#include "app/config/input_error.h"
#include "app/config/params.h"

namespace tallow::app {
namespace fs = std::filesystem;

namespace {

/// Creates and removes a probe file in `folder`; "" when that worked, else why not.
std::string tryWrite(const fs::path& folder) {
  std::string pattern = (folder / ".tallow-write-check-XXXXXX").string();
  const int fd = ::mkstemp(pattern.data());
  if (fd < 0) return std::strerror(errno);
  ::close(fd);
  ::unlink(pattern.c_str());
  return "";
}

/// Removes the folders a check created, deepest first; folders that are not empty stay.
void removeCreated(const std::vector<fs::path>& created) {
  std::error_code ec;
  for (const fs::path& p : created) fs::remove(p, ec);
}

fs::path folderOf(const fs::path& file) { return file.has_parent_path() ? file.parent_path() : fs::path("."); }

}  // namespace

void checkTime(std::string_view option, double seconds) {
  if (!std::isfinite(seconds))
    throw InputError(std::string(option) + ": " + formatNumber(seconds) + " is not a finite number of seconds");
  if (seconds < 0.0 || seconds > kMaxTimeS)
    throw InputError(std::string(option) + ": " + formatNumber(seconds) + " s is out of range [0, " +
                     formatNumber(kMaxTimeS) + "] (animation time, as a preset's start_s)");
}

void checkWritableFolder(const fs::path& dir, std::string_view option) {
  const std::string opt(option);
  if (dir.empty()) throw InputError(opt + ": empty folder name");
  std::error_code ec;
  const fs::path target = fs::absolute(dir, ec);
  if (ec) throw InputError(opt + ": " + dir.string() + ": " + ec.message());
  // The folders that do not exist yet, deepest first, and the nearest one that does.
  std::vector<fs::path> missing;
  fs::path existing = target;
  while (!fs::exists(existing, ec)) {
    if (!existing.has_parent_path() || existing.parent_path() == existing) break;
    missing.push_back(existing);
    existing = existing.parent_path();
  }
  if (fs::exists(existing, ec) && !fs::is_directory(existing, ec))
    throw InputError(opt + ": " + existing.string() + " is not a folder");
  fs::create_directories(target, ec);
  if (ec) {
    removeCreated(missing);
    throw InputError(opt + ": cannot create " + dir.string() + ": " + ec.message());
  }
  const std::string why = tryWrite(target);
  removeCreated(missing);
  if (!why.empty()) throw InputError(opt + ": cannot write to " + dir.string() + ": " + why);
}

void checkOutputFile(std::string_view option, const fs::path& file, const std::vector<std::string>& extensions) {
  const std::string opt(option);
  if (file.empty()) throw InputError(opt + ": empty file name");
  if (!extensions.empty() &&
      std::find(extensions.begin(), extensions.end(), file.extension().string()) == extensions.end()) {
    std::string expected;
    for (std::size_t i = 0; i < extensions.size(); ++i)
      expected += (i == 0 ? "" : i + 1 == extensions.size() ? " or " : ", ") + extensions[i];
    throw InputError(opt + ": expected a " + expected + " file, got " + quote(file.string()));
  }
  std::error_code ec;
  if (fs::is_directory(file, ec)) throw InputError(opt + ": " + file.string() + " is a folder");
  const fs::path folder = folderOf(file);
  if (!fs::exists(folder, ec)) throw InputError(opt + ": folder " + folder.string() + " does not exist");
  if (!fs::is_directory(folder, ec)) throw InputError(opt + ": " + folder.string() + " is not a folder");
  const std::string why = tryWrite(folder);
  if (!why.empty()) throw InputError(opt + ": cannot write to folder " + folder.string() + ": " + why);
}

void checkMethods(const Registry& registry, const std::vector<std::string>& methods) {
  const Registry::Param* method = registry.find("method");
  if (!method) return;
  for (const std::string& m : methods) {
    try {
      checkParamValue(*method, nlohmann::json(m));
    } catch (const InputError& e) {
      throw InputError(std::string("--methods: ") + e.what());
    }
  }
}

void checkSweepValue(const Registry& registry, const Config& config, std::string_view sweepText, std::string_view key,
                     std::string_view value) {
  Config trial = config;
  std::string assignment(key);
  assignment += '=';
  assignment += value;
  try {
    registry.setFromString(trial, assignment);
  } catch (const InputError& e) {
    throw InputError("--sweep " + std::string(sweepText) + ": " + e.what());
  }
}

}  // namespace tallow::app
