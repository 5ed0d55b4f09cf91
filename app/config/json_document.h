#pragma once
// A parsed JSON file that remembers where every value and every object key came from, so that
// readers can report `file:line:col` for the exact spot a user has to fix (pbrt-v4's FileLoc).
#include <nlohmann/json.hpp>

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace tallow::app {

/// A position in a text file. Lines and columns are 1-based; columns count UTF-8 characters.
struct SourceLoc {
  std::string file;
  int line = 0;
  int col = 0;
  /// "file:line:col"
  std::string str() const;
};

/// Source positions parallel to a JSON DOM, one node per value: JsonDocument's bookkeeping. (Not
/// std::pair<std::string, JsonSourceNode> for members: clang with libstdc++ cannot complete a pair
/// of the type being defined.)
struct JsonSourceNode {
  struct Member;
  static constexpr std::size_t kNoKey = static_cast<std::size_t>(-1);
  std::size_t value = 0;     ///< byte offset of the value's first character
  std::size_t key = kNoKey;  ///< byte offset of the key's opening quote (object members only)
  std::vector<JsonSourceNode> elements;  ///< array elements, in order
  std::vector<Member> members;           ///< object members, in document order
};

struct JsonSourceNode::Member {
  std::string key;
  JsonSourceNode node;
};

class JsonDocument {
 public:
  using Pointer = nlohmann::json::json_pointer;

  /// Deepest nesting of arrays and objects accepted; deeper input is rejected before it is built
  /// (bounds the recursion of nlohmann's copy, compare and dump, and of our readers).
  static constexpr std::size_t kMaxDepth = 64;

  /// Parses `text` (strict JSON; a UTF-8 byte-order mark is skipped). Throws InputError
  /// `fileName:line:col: message` on a syntax error, a duplicate key (at its second occurrence) or
  /// nesting deeper than kMaxDepth.
  static JsonDocument parse(std::string_view text, std::string fileName);
  /// Reads and parses a file; the path as given names it in messages.
  static JsonDocument load(const std::filesystem::path& file);

  const nlohmann::json& root() const { return root_; }
  const std::string& fileName() const { return fileName_; }

  /// Where the value at `ptr` starts. A pointer to nothing falls back to its nearest existing
  /// ancestor (so "missing key" errors point at the enclosing object).
  SourceLoc locate(const Pointer& ptr) const;
  /// Where the key that names `ptr` in its parent object starts; for an array element or the root,
  /// or a member that does not exist, the same as locate(ptr).
  SourceLoc locateKey(const Pointer& ptr) const;

  /// The keys of the object at `ptr` in the order the file gives them (nlohmann's object is sorted);
  /// empty when `ptr` is not an object.
  std::vector<std::string> keysInOrder(const Pointer& ptr) const;

  /// Throws InputError "<locate(ptr)>: message".
  [[noreturn]] void fail(const Pointer& ptr, std::string_view message) const;
  /// Throws InputError "<locateKey(ptr)>: message".
  [[noreturn]] void failAtKey(const Pointer& ptr, std::string_view message) const;

  /// Byte offset → location in this document's text.
  SourceLoc locateOffset(std::size_t offset) const;

 private:
  /// The node at `ptr`, or its deepest existing ancestor (`exact` tells which).
  const JsonSourceNode& deepest(const Pointer& ptr, bool& exact) const;

  nlohmann::json root_;
  JsonSourceNode rootNode_;
  std::string fileName_;
  std::string text_;                     ///< kept to turn offsets into UTF-8 columns
  std::vector<std::size_t> lineStarts_;  ///< byte offset of each line's first character
};

}  // namespace tallow::app
