#pragma once
// Writing output files so that a reader never sees a partial one: write a temporary file beside
// the target, then rename it over the target (rename is atomic within one file system, POSIX).
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>

namespace tallow::gpu {

/// Twelve random lower-case letters and digits (getrandom(2)): the part of a temporary name that
/// no one else can predict.
std::string randomToken();

/// A folder of our own for temporary files (`.PREFIX-<random>` in `parent`, mode 0700, created by
/// mkdir, which fails rather than follow anything planted at the name), removed with everything in
/// it when destroyed. Files inside it can have fixed names: no one else can create or replace them.
/// Throws std::runtime_error `cannot write PATH: REASON`.
class PrivateFolder {
 public:
  PrivateFolder(const std::filesystem::path& parent, std::string_view prefix);
  ~PrivateFolder();
  PrivateFolder(const PrivateFolder&) = delete;
  PrivateFolder& operator=(const PrivateFolder&) = delete;

  const std::filesystem::path& path() const { return path_; }
  /// Its name alone (`.PREFIX-<random>`), e.g. to name files relative to `parent`.
  const std::string& name() const { return name_; }

 private:
  std::filesystem::path path_;
  std::string name_;
};

/// A file written over time (a video fed frame by frame): a fresh temporary beside `path`
/// (`.NAME.tmp-<pid>-<random>`, created empty with O_EXCL) that commit() renames onto `path`; destroyed
/// uncommitted, it removes the temporary. Throws std::runtime_error `cannot write PATH: REASON`.
class PendingFile {
 public:
  explicit PendingFile(std::filesystem::path path);
  ~PendingFile();
  PendingFile(const PendingFile&) = delete;
  PendingFile& operator=(const PendingFile&) = delete;

  const std::filesystem::path& temporary() const { return tmp_; }
  /// Renames the temporary onto the target (once).
  void commit();

 private:
  std::filesystem::path path_, tmp_;
  bool committed_ = false;
};

/// Calls `writer` with a fresh, unique temporary path in the folder of `path`
/// (`.NAME.tmp-<pid>-<random>`, already created empty with O_EXCL), then renames it onto `path`.
/// If `writer` throws, the temporary file is removed and the exception propagates unchanged.
/// If the folder is missing or not writable, or the rename fails, throws std::runtime_error
/// with one line: `cannot write PATH: REASON`.
void writeFileAtomically(const std::filesystem::path& path,
                         const std::function<void(const std::filesystem::path& tmp)>& writer);

/// writeFileAtomically with a writer that stores `text` byte for byte.
void writeTextFileAtomically(const std::filesystem::path& path, std::string_view text);

}  // namespace tallow::gpu
