#include "app/commands/output_folder.h"

#include <fcntl.h>
#include <fnmatch.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "app/commands/provenance.h"
#include "app/config/input_error.h"

namespace tallow::app {
namespace fs = std::filesystem;
namespace {

/// What the lock file says of its holder, read by a run that finds the lock taken.
std::string holderText(int fd) {
  char buffer[512];
  const ssize_t n = ::pread(fd, buffer, sizeof buffer - 1, 0);
  std::string text(buffer, n > 0 ? static_cast<std::size_t>(n) : 0);
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  return text.empty() ? "a run that has not said who it is yet" : text;
}

bool matchesAny(const std::string& name, const std::vector<std::string>& patterns) {
  for (const std::string& p : patterns)
    if (::fnmatch(p.c_str(), name.c_str(), 0) == 0) return true;
  return false;
}

}  // namespace

OutputFolder::OutputFolder(const fs::path& dir, const std::string& command, const std::string& option)
    : dir_(dir.empty() ? fs::path(".") : dir), lock_(dir_ / kOutputLockName) {
  std::error_code ec;
  // The folders that do not exist yet, deepest first (a missing entry's status sets its own error).
  fs::path p = fs::absolute(dir_, ec);
  for (std::error_code missing; !ec && !fs::exists(fs::symlink_status(p, missing)); p = p.parent_path()) {
    created_.push_back(p);
    if (!p.has_parent_path() || p.parent_path() == p) break;
  }
  fs::create_directories(dir_, ec);
  if (ec) throw InputError(option + ": cannot create " + dir_.string() + ": " + ec.message());
  // Open, lock, and check that the file locked is still the one at the name: a holder that just
  // finished removed it, and the lock on a removed file guards nothing.
  for (int attempt = 0; attempt < 100; ++attempt) {
    const int fd = ::open(lock_.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0644);
    if (fd < 0) throw InputError(option + ": cannot write to " + dir_.string() + ": " + std::strerror(errno));
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int error = errno;
      const std::string holder = error == EWOULDBLOCK ? holderText(fd) : std::strerror(error);
      ::close(fd);
      throw InputError(option + ": " + dir_.string() + " is in use by another run (" + holder +
                       "); give another folder or wait for it to finish");
    }
    struct stat opened {}, named {};
    if (::fstat(fd, &opened) == 0 && ::lstat(lock_.c_str(), &named) == 0 && opened.st_ino == named.st_ino &&
        opened.st_dev == named.st_dev) {
      fd_ = fd;
      break;
    }
    ::close(fd);
  }
  if (fd_ < 0) throw InputError(option + ": cannot lock " + dir_.string());
  const std::string holder =
      "tallow " + command + ", pid " + std::to_string(::getpid()) + ", started " + runStartUtc() + "\n";
  if (::ftruncate(fd_, 0) != 0 || ::pwrite(fd_, holder.data(), holder.size(), 0) != static_cast<ssize_t>(holder.size())) {
    // Only the message for a second run is lost: the lock itself holds.
  }
}

OutputFolder::~OutputFolder() {
  ::unlink(lock_.c_str());  // while still locked: a run waiting on it sees it go and retries
  if (fd_ >= 0) ::close(fd_);
  std::error_code ec;
  for (const fs::path& p : created_) fs::remove(p, ec);  // only empty folders go
}

std::size_t OutputFolder::clearEarlierRun(const std::vector<std::string>& patterns) {
  std::vector<std::string> temporaries;
  for (const std::string& p : patterns) temporaries.push_back("." + p + ".tmp-*");
  temporaries.push_back(".tallow-plot-*");
  std::size_t removed = 0;
  std::error_code ec;
  std::vector<fs::path> doomed;
  for (const fs::directory_entry& e : fs::directory_iterator(dir_, ec)) {
    const std::string name = e.path().filename().string();
    if (name == kOutputLockName) continue;
    if (matchesAny(name, patterns) || matchesAny(name, temporaries)) doomed.push_back(e.path());
  }
  for (const fs::path& p : doomed) {
    std::error_code removeError;
    // A link is removed, never followed (remove_all does not follow links).
    if (fs::remove_all(p, removeError) > 0) ++removed;
    if (removeError) throw std::runtime_error("cannot remove " + p.string() + " of an earlier run: " + removeError.message());
  }
  return removed;
}

}  // namespace tallow::app
