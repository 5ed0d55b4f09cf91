#include "app/commands/option_checks.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>

#include "app/config/input_error.h"
#include "app/config/params.h"
#include "gpu/utf8.h"

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

/// The longest file name and path the folder's file system takes (pathconf(3); 255 and 4096 where
/// it does not say).
std::pair<std::size_t, std::size_t> nameLimits(const fs::path& folder) {
  const long name = ::pathconf(folder.c_str(), _PC_NAME_MAX), path = ::pathconf(folder.c_str(), _PC_PATH_MAX);
  return {name > 0 ? static_cast<std::size_t>(name) : 255, path > 0 ? static_cast<std::size_t>(path) : 4096};
}

/// The nearest folder above `p` (itself included) that exists, to ask its file system.
fs::path existingFolder(fs::path p) {
  std::error_code ec;
  p = fs::absolute(p, ec);
  while (!fs::is_directory(p, ec) && p.has_parent_path() && p.parent_path() != p) p = p.parent_path();
  return p;
}

}  // namespace

void checkOutputName(std::string_view option, const fs::path& path) {
  const std::string opt(option), text = path.string();
  if (const std::size_t bad = gpu::firstInvalidUtf8(text); bad != std::string::npos)
    throw InputError(opt + ": " + quote(text) + " is not valid UTF-8 (byte " + std::to_string(bad + 1) +
                     "): the run's JSON records every output's name");
  const auto [maxName, maxPath] = nameLimits(existingFolder(folderOf(path)));
  std::error_code ec;
  if (fs::absolute(path, ec).string().size() >= maxPath)
    throw InputError(opt + ": " + quote(text) + " is longer than the " + std::to_string(maxPath) +
                     " bytes a path may have here");
  for (const fs::path& part : path)
    if (part.string().size() > maxName)
      throw InputError(opt + ": the name " + quote(part.string()) + " is " + std::to_string(part.string().size()) +
                       " bytes long; names here take at most " + std::to_string(maxName));
}

void checkTime(std::string_view option, double seconds) {
  if (!std::isfinite(seconds))
    throw InputError(std::string(option) + ": " + formatNumber(seconds) + " is not a finite number of seconds");
  if (seconds < 0.0 || seconds > kMaxTimeS)
    throw InputError(std::string(option) + ": " + formatNumber(seconds) + " s is out of range [0, " +
                     formatNumber(kMaxTimeS) + "] (animation time, as a preset's start_s)");
}

void checkFps(std::string_view option, double fps) {
  if (!(fps >= kMinFps && fps <= kMaxFps))
    throw InputError(std::string(option) + ": " + formatNumber(fps) + " is out of range [" + formatNumber(kMinFps) +
                     ", " + formatNumber(kMaxFps) + "] frames per second");
}

void checkWritableFolder(const fs::path& dir, std::string_view option) {
  const std::string opt(option);
  if (dir.empty()) throw InputError(opt + ": empty folder name");
  checkOutputName(option, dir);
  std::error_code ec;
  const fs::path target = fs::absolute(dir, ec);
  if (ec) throw InputError(opt + ": " + dir.string() + ": " + ec.message());
  // The folders that do not exist yet, deepest first, and the nearest one that does. A link is an
  // entry that exists even when what it points to does not: it is never taken for a missing folder
  // (and so never removed as one created here).
  std::vector<fs::path> missing;
  fs::path existing = target;
  while (!fs::exists(fs::symlink_status(existing, ec))) {
    if (!existing.has_parent_path() || existing.parent_path() == existing) break;
    missing.push_back(existing);
    existing = existing.parent_path();
  }
  if (fs::is_symlink(fs::symlink_status(existing, ec)) && !fs::exists(existing, ec))
    throw InputError(opt + ": " + existing.string() + " is a symbolic link to " +
                     fs::read_symlink(existing, ec).string() + ", which does not exist");
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

namespace {
/// checkOutputFile's checks of the name: not empty, writable as a name, one of `extensions`, not a folder.
void checkOutputFileName(std::string_view option, const fs::path& file, const std::vector<std::string>& extensions) {
  const std::string opt(option);
  if (file.empty()) throw InputError(opt + ": empty file name");
  checkOutputName(option, file);
  if (!extensions.empty() &&
      std::find(extensions.begin(), extensions.end(), file.extension().string()) == extensions.end()) {
    std::string expected;
    for (std::size_t i = 0; i < extensions.size(); ++i)
      expected += (i == 0 ? "" : i + 1 == extensions.size() ? " or " : ", ") + extensions[i];
    throw InputError(opt + ": expected a " + expected + " file, got " + quote(file.string()));
  }
  std::error_code ec;
  if (fs::is_directory(file, ec)) throw InputError(opt + ": " + file.string() + " is a folder");
}
}  // namespace

void checkOutputFile(std::string_view option, const fs::path& file, const std::vector<std::string>& extensions) {
  checkOutputFileName(option, file, extensions);
  const std::string opt(option);
  std::error_code ec;
  const fs::path folder = folderOf(file);
  if (!fs::exists(folder, ec)) throw InputError(opt + ": folder " + folder.string() + " does not exist");
  if (!fs::is_directory(folder, ec)) throw InputError(opt + ": " + folder.string() + " is not a folder");
  const std::string why = tryWrite(folder);
  if (!why.empty()) throw InputError(opt + ": cannot write to folder " + folder.string() + ": " + why);
}

void checkOutputFileInNewFolder(std::string_view option, const fs::path& file, const std::vector<std::string>& extensions) {
  checkOutputFileName(option, file, extensions);
  checkWritableFolder(folderOf(file), option);
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
