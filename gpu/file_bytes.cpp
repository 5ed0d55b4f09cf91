#include "gpu/file_bytes.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <new>
#include <stdexcept>
#include <string>

#include "gpu/byte_size.h"

namespace tallow::gpu {
namespace {

const char* fileKind(mode_t mode) {
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISFIFO(mode)) return "a pipe";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a file";
}

std::string overLimit(std::uintmax_t size, std::uintmax_t maxBytes, std::string_view what) {
  return formatBytes(size) + " is over the " + formatBytes(maxBytes) + " limit for " + std::string(what);
}

}  // namespace

void checkInputFile(const std::filesystem::path& path, std::uintmax_t maxBytes, std::string_view what) {
  struct stat info {};
  // stat, not lstat: a symbolic link to a regular file is as good as the file.
  if (::stat(path.c_str(), &info) != 0 || S_ISDIR(info.st_mode)) return;
  if (!S_ISREG(info.st_mode))
    throw std::runtime_error(path.string() + ": not a regular file (" + fileKind(info.st_mode) + ")");
  const auto size = static_cast<std::uintmax_t>(info.st_size);
  if (size > maxBytes)
    throw std::runtime_error(path.string() + ": " + overLimit(size, maxBytes, what));
}

void throwOutOfMemoryReading(const std::filesystem::path& path) {
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  throw std::runtime_error(path.string() + ": out of memory reading it" + (ec ? "" : " (" + formatBytes(size) + ")"));
}

std::vector<std::uint8_t> readFileBytes(const std::filesystem::path& path, std::uintmax_t maxBytes,
                                        std::string_view what) {
  const std::string name = path.string();
  const auto fail = [&](const std::string& message) { throw std::runtime_error(name + ": " + message); };
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) fail("is a directory");
  checkInputFile(path, maxBytes, what);
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(std::strerror(errno));
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  if (size < 0) fail("cannot determine the file size");
  // The file may have grown since it was checked: the limit holds for what is read.
  if (static_cast<std::uintmax_t>(size) > maxBytes) fail(overLimit(static_cast<std::uintmax_t>(size), maxBytes, what));
  in.seekg(0, std::ios::beg);
  try {
    std::vector<std::uint8_t> bytes(static_cast<std::size_t>(size));
    if (size > 0 && !in.read(reinterpret_cast<char*>(bytes.data()), size)) fail("read error");
    return bytes;
  } catch (const std::bad_alloc&) {
    throwOutOfMemoryReading(path);
  }
}

}  // namespace tallow::gpu
