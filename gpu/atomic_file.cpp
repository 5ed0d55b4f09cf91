#include "gpu/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <system_error>

namespace tallow::gpu {
namespace {

[[noreturn]] void throwCannotWrite(const std::filesystem::path& path, const std::string& reason) {
  throw std::runtime_error("cannot write " + path.string() + ": " + reason);
}

/// Creates an empty file with a name no other writer (thread or process) can hold, and returns
/// its path. O_EXCL makes the reservation race-free; the errno of a failed open is what the user
/// needs to see ("Permission denied", "No such file or directory").
std::filesystem::path reserveTemporary(const std::filesystem::path& path) {
  static std::atomic<unsigned long> counter{0};
  // The longest name the folder allows is typically 255 bytes: keep the prefix short enough.
  constexpr std::size_t kMaxStemBytes = 200;
  std::string stem = path.filename().string().substr(0, kMaxStemBytes);
  const std::filesystem::path folder = path.parent_path();
  // A few attempts are plenty: a clash needs a stale file from a dead process with our pid.
  constexpr int kAttempts = 100;
  for (int attempt = 0; attempt < kAttempts; ++attempt) {
    const std::string name = "." + stem + ".tmp-" + std::to_string(::getpid()) + "-" +
                             std::to_string(counter.fetch_add(1));
    const std::filesystem::path tmp = folder.empty() ? std::filesystem::path(name) : folder / name;
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0) {
      ::close(fd);
      return tmp;
    }
    if (errno != EEXIST) throwCannotWrite(path, std::strerror(errno));
  }
  throwCannotWrite(path, "no unused temporary file name");
}

}  // namespace

PendingFile::PendingFile(std::filesystem::path path) : path_(std::move(path)) {
  if (path_.empty() || !path_.has_filename()) throwCannotWrite(path_, "not a file name");
  tmp_ = reserveTemporary(path_);
}

PendingFile::~PendingFile() {
  if (committed_) return;
  std::error_code ignored;
  std::filesystem::remove(tmp_, ignored);
}

void PendingFile::commit() {
  if (committed_) return;
  std::error_code ec;
  std::filesystem::rename(tmp_, path_, ec);
  if (ec) throwCannotWrite(path_, ec.message());  // the destructor removes the temporary
  committed_ = true;
}

void writeFileAtomically(const std::filesystem::path& path,
                         const std::function<void(const std::filesystem::path& tmp)>& writer) {
  PendingFile file(path);
  writer(file.temporary());  // a throw leaves the temporary to the destructor
  file.commit();
}

void writeTextFileAtomically(const std::filesystem::path& path, std::string_view text) {
  writeFileAtomically(path, [&](const std::filesystem::path& tmp) {
    std::FILE* file = std::fopen(tmp.c_str(), "wb");
    if (!file) throwCannotWrite(path, std::strerror(errno));
    const bool written = std::fwrite(text.data(), 1, text.size(), file) == text.size();
    const int writeErrno = errno;
    // fclose flushes: a full disk may only show up here.
    const bool closed = std::fclose(file) == 0;
    if (!written || !closed) throwCannotWrite(path, std::strerror(written ? errno : writeErrno));
  });
}

}  // namespace tallow::gpu
