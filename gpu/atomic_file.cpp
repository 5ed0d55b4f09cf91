#include "gpu/atomic_file.h"

#include <fcntl.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <unistd.h>

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

/// Creates an empty file with a name no other writer (thread or process) can hold or guess, and
/// returns its path. O_EXCL makes the reservation race-free and refuses a planted symbolic link;
/// the random part keeps another user of the folder from planting one at the name we will reopen.
/// The errno of a failed open is what the user needs to see ("Permission denied", "No such file or
/// directory").
std::filesystem::path reserveTemporary(const std::filesystem::path& path) {
  // The longest name the folder allows is typically 255 bytes: keep the prefix short enough.
  constexpr std::size_t kMaxStemBytes = 200;
  std::string stem = path.filename().string().substr(0, kMaxStemBytes);
  const std::filesystem::path folder = path.parent_path();
  // A few attempts are plenty: a clash needs a stale file with the same pid and random part.
  constexpr int kAttempts = 100;
  for (int attempt = 0; attempt < kAttempts; ++attempt) {
    std::string name = ".";
    name += stem;
    name += ".tmp-";
    name += std::to_string(::getpid());
    name += '-';
    name += randomToken();
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

std::string randomToken() {
  // Lower-case letters and digits only: safe in every file system and in any quoting.
  constexpr char kAlphabet[] = "abcdefghijklmnopqrstuvwxyz0123456789";
  constexpr std::size_t kLength = 12;  // 36^12 ≈ 2^62 names
  unsigned char bytes[kLength];
  std::size_t got = 0;
  while (got < kLength) {
    const ssize_t n = ::getrandom(bytes + got, kLength - got, 0);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw std::runtime_error(std::string("no random bytes for a temporary name: ") + std::strerror(errno));
    got += static_cast<std::size_t>(n);
  }
  std::string token;
  for (const unsigned char b : bytes) token += kAlphabet[b % (sizeof kAlphabet - 1)];
  return token;
}

PrivateFolder::PrivateFolder(const std::filesystem::path& parent, std::string_view prefix) {
  const std::filesystem::path base = parent.empty() ? std::filesystem::path(".") : parent;
  constexpr int kAttempts = 100;
  for (int attempt = 0; attempt < kAttempts && path_.empty(); ++attempt) {
    std::string name = ".";
    name += prefix;
    name += '-';
    name += randomToken();
    const std::filesystem::path candidate = base / name;
    // mkdir never follows a link planted at the name, and 0700 keeps every other user out of it.
    if (::mkdir(candidate.c_str(), 0700) == 0) {
      path_ = candidate;
      name_ = name;
    } else if (errno != EEXIST) {
      throwCannotWrite(candidate, std::strerror(errno));
    }
  }
  if (path_.empty()) throwCannotWrite(base, "no unused temporary folder name");
}

PrivateFolder::~PrivateFolder() {
  std::error_code ignored;
  std::filesystem::remove_all(path_, ignored);
}

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
