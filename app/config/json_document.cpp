#include "app/config/json_document.h"

#include <algorithm>
#include <fstream>
#include <optional>
#include <sstream>

#include "app/config/input_error.h"

namespace tallow::app {

namespace {

using json = nlohmann::json;

/// Builds the DOM and its parallel tree of source positions from nlohmann's SAX events.
///
/// nlohmann validates the text and reports values, but not where they start. SAX events arrive in
/// token order and every token between two events is whitespace, ',' or ':' (the parser stops at
/// the first invalid token), so a cursor that skips those and then one token finds the start of
/// each event's token exactly. Only starts matter: a malformed token ends the parse anyway.
class DomBuilder final : public json::json_sax_t {
 public:
  explicit DomBuilder(std::string_view text) : text_(text) {
    // nlohmann skips a UTF-8 byte-order mark; so must the cursor.
    if (text_.substr(0, 3) == "\xEF\xBB\xBF") cursor_ = 3;
  }

  bool null() override { return addValue(json(nullptr), false); }
  bool boolean(bool v) override { return addValue(json(v), false); }
  bool number_integer(number_integer_t v) override { return addValue(json(v), false); }
  bool number_unsigned(number_unsigned_t v) override { return addValue(json(v), false); }
  bool number_float(number_float_t v, const string_t&) override { return addValue(json(v), false); }
  bool string(string_t& v) override { return addValue(json(std::move(v)), false); }
  bool binary(binary_t&) override { return failAt(nextToken(), "binary values are not JSON"); }
  bool start_object(std::size_t) override { return addValue(json::object(), true); }
  bool start_array(std::size_t) override { return addValue(json::array(), true); }
  bool end_object() override { return close(); }
  bool end_array() override { return close(); }

  bool key(string_t& k) override {
    const std::size_t offset = nextToken();
    Frame& top = stack_.back();
    auto& object = top.value->get_ref<json::object_t&>();
    auto [it, inserted] = object.emplace(k, nullptr);
    if (!inserted) return failAt(offset, "duplicate key " + quote(k));
    pendingValue_ = &it->second;
    top.node->members.push_back({std::move(k), JsonSourceNode{}});
    pendingNode_ = &top.node->members.back().node;
    pendingNode_->key = offset;
    return true;
  }

  bool parse_error(std::size_t position, const std::string&, const nlohmann::detail::exception& ex) override {
    // `position` counts the characters read. When the lexer gave up ("... last read: '...'"), the
    // last of them is the offending one. Otherwise a whole token came in the wrong place (or a
    // number overflowed) and ends at `position`: point at its start. (nlohmann's last-token text
    // is no help there: it is not reset for punctuation and literals.)
    const bool lexerError = std::string_view(ex.what()).find("; last read: '") != std::string_view::npos;
    const std::size_t lastRead = std::min(position > 0 ? position - 1 : 0, text_.size());
    error = {lexerError ? lastRead : tokenEndingAt(position, lastRead), shortMessage(ex.what())};
    return false;
  }

  struct Error {
    std::size_t offset;
    std::string message;
  };
  json root;
  JsonSourceNode rootNode;
  std::optional<Error> error;  ///< set when parsing stopped

 private:
  struct Frame {
    json* value;
    JsonSourceNode* node;
  };

  static bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

  /// Offset just past the token that starts at `i` (punctuation, a string, or a number/literal).
  std::size_t tokenEnd(std::size_t i) const {
    const char c = text_[i];
    if (std::string_view("{}[],:").find(c) != std::string_view::npos) return i + 1;
    if (c == '"') {
      for (++i; i < text_.size() && text_[i] != '"'; ++i)
        if (text_[i] == '\\') ++i;
      return std::min(i + 1, text_.size());
    }
    while (i < text_.size() && !isSpace(text_[i]) &&
           std::string_view("{}[],:\"").find(text_[i]) == std::string_view::npos)
      ++i;
    return i;
  }

  /// Skips separators, returns the offset of the next token and moves past it.
  std::size_t nextToken() {
    while (cursor_ < text_.size() && (isSpace(text_[cursor_]) || text_[cursor_] == ',' || text_[cursor_] == ':'))
      ++cursor_;
    const std::size_t start = cursor_;
    if (cursor_ < text_.size()) cursor_ = tokenEnd(cursor_);
    return start;
  }

  /// The start of the first token after the last event's token that reaches `end`, else `fallback`.
  std::size_t tokenEndingAt(std::size_t end, std::size_t fallback) const {
    std::size_t i = cursor_;
    while (true) {
      while (i < text_.size() && isSpace(text_[i])) ++i;
      if (i >= text_.size()) return fallback;
      const std::size_t next = tokenEnd(i);
      if (next >= end) return i;
      i = next;
    }
  }

  bool addValue(json&& v, bool container) {
    const std::size_t offset = nextToken();
    if (container && stack_.size() >= JsonDocument::kMaxDepth)
      return failAt(offset, "nesting deeper than " + std::to_string(JsonDocument::kMaxDepth) + " levels");
    json* slot;
    JsonSourceNode* node;
    if (stack_.empty()) {
      root = std::move(v);
      slot = &root;
      node = &rootNode;
    } else if (stack_.back().value->is_array()) {
      // Only the innermost open container grows, so pointers held in stack_ stay valid.
      auto& array = stack_.back().value->get_ref<json::array_t&>();
      array.push_back(std::move(v));
      slot = &array.back();
      stack_.back().node->elements.emplace_back();
      node = &stack_.back().node->elements.back();
    } else {
      *pendingValue_ = std::move(v);
      slot = pendingValue_;
      node = pendingNode_;
    }
    node->value = offset;
    if (container) stack_.push_back({slot, node});
    return true;
  }

  bool close() {
    nextToken();
    stack_.pop_back();
    return true;
  }

  bool failAt(std::size_t offset, std::string message) {
    error = {offset, std::move(message)};
    return false;
  }

  /// "[json.exception.parse_error.101] parse error at line 1, column 2: syntax error while parsing
  /// value - invalid literal; last read: 'tru,'; expected ..." → "syntax error while parsing value -
  /// invalid literal; expected ..." (our own prefix carries the position; the echo of the last
  /// token can span lines).
  static std::string shortMessage(std::string_view what) {
    std::string_view msg = what;
    if (msg.substr(0, 1) == "[") {
      const std::size_t close = msg.find("] ");
      if (close != std::string_view::npos) msg.remove_prefix(close + 2);
    }
    if (msg.substr(0, 15) == "parse error at ") {
      const std::size_t colon = msg.find(": ");
      if (colon != std::string_view::npos) msg.remove_prefix(colon + 2);
    }
    std::string out(msg);
    const std::size_t lastRead = out.find("; last read: '");
    if (lastRead != std::string::npos) {
      const std::size_t expected = out.rfind("'; expected ");
      out = out.substr(0, lastRead) +
            (expected != std::string::npos && expected > lastRead ? out.substr(expected + 1) : std::string());
    }
    constexpr std::size_t kMaxChars = 160;  // "number overflow parsing '<token>'" echoes the token
    if (out.size() > kMaxChars) out = out.substr(0, kMaxChars - 3) + "...";
    return out;
  }

  std::string_view text_;
  std::size_t cursor_ = 0;
  std::vector<Frame> stack_;
  json* pendingValue_ = nullptr;
  JsonSourceNode* pendingNode_ = nullptr;
};

/// The reference tokens of a JSON pointer, unescaped (~1 → '/', ~0 → '~').
std::vector<std::string> tokens(const JsonDocument::Pointer& ptr) {
  std::vector<std::string> out;
  const std::string s = ptr.to_string();
  std::size_t i = 0;
  while (i < s.size()) {  // s starts with '/' when not empty
    const std::size_t next = s.find('/', i + 1);
    std::string token = s.substr(i + 1, next == std::string::npos ? std::string::npos : next - i - 1);
    std::string unescaped;
    for (std::size_t k = 0; k < token.size(); ++k) {
      if (token[k] == '~' && k + 1 < token.size()) {
        unescaped += token[k + 1] == '1' ? '/' : '~';
        ++k;
      } else {
        unescaped += token[k];
      }
    }
    out.push_back(std::move(unescaped));
    if (next == std::string::npos) break;
    i = next;
  }
  return out;
}

}  // namespace

std::string SourceLoc::str() const {
  return file + ":" + std::to_string(line) + ":" + std::to_string(col);
}

JsonDocument JsonDocument::parse(std::string_view text, std::string fileName) {
  JsonDocument doc;
  doc.fileName_ = std::move(fileName);
  doc.text_ = std::string(text);
  doc.lineStarts_.push_back(0);
  for (std::size_t i = 0; i < doc.text_.size(); ++i)
    if (doc.text_[i] == '\n') doc.lineStarts_.push_back(i + 1);

  DomBuilder builder(doc.text_);
  const bool ok = json::sax_parse(doc.text_.begin(), doc.text_.end(), &builder);
  if (!ok || builder.error) {
    const auto& e = builder.error;
    const std::size_t offset = e ? e->offset : doc.text_.size();
    throw InputError(doc.locateOffset(offset).str() + ": " + (e ? e->message : "invalid JSON"));
  }
  doc.root_ = std::move(builder.root);
  doc.rootNode_ = std::move(builder.rootNode);
  return doc;
}

JsonDocument JsonDocument::load(const std::filesystem::path& file) {
  return parseInputFile(file, [&](const std::string& text) { return parse(text, file.string()); });
}

SourceLoc JsonDocument::locateOffset(std::size_t offset) const {
  offset = std::min(offset, text_.size());
  const auto it = std::upper_bound(lineStarts_.begin(), lineStarts_.end(), offset);
  const std::size_t lineIndex = static_cast<std::size_t>(it - lineStarts_.begin()) - 1;
  int col = 1;
  std::size_t i = lineStarts_[lineIndex];
  if (i == 0 && text_.compare(0, 3, "\xEF\xBB\xBF") == 0) i = std::min<std::size_t>(3, offset);  // no column
  for (; i < offset; ++i)
    if ((static_cast<unsigned char>(text_[i]) & 0xC0) != 0x80) ++col;  // skip UTF-8 continuation bytes
  return {fileName_, static_cast<int>(lineIndex) + 1, col};
}

const JsonSourceNode& JsonDocument::deepest(const Pointer& ptr, bool& exact) const {
  const JsonSourceNode* node = &rootNode_;
  const json* value = &root_;
  exact = true;
  for (const std::string& token : tokens(ptr)) {
    const JsonSourceNode* next = nullptr;
    if (value->is_object()) {
      for (const JsonSourceNode::Member& member : node->members)
        if (member.key == token) next = &member.node;
      if (next) value = &value->find(token).value();
    } else if (value->is_array() && !token.empty() &&
               token.find_first_not_of("0123456789") == std::string::npos && token.size() < 10) {
      const std::size_t index = std::stoul(token);
      if (index < node->elements.size()) {
        next = &node->elements[index];
        value = &(*value)[index];
      }
    }
    if (!next) {
      exact = false;
      break;
    }
    node = next;
  }
  return *node;
}

SourceLoc JsonDocument::locate(const Pointer& ptr) const {
  bool exact;
  return locateOffset(deepest(ptr, exact).value);
}

SourceLoc JsonDocument::locateKey(const Pointer& ptr) const {
  bool exact;
  const JsonSourceNode& node = deepest(ptr, exact);
  return locateOffset(exact && node.key != JsonSourceNode::kNoKey ? node.key : node.value);
}

std::vector<std::string> JsonDocument::keysInOrder(const Pointer& ptr) const {
  bool exact;
  const JsonSourceNode& node = deepest(ptr, exact);
  std::vector<std::string> keys;
  if (!exact) return keys;
  keys.reserve(node.members.size());
  for (const JsonSourceNode::Member& member : node.members) keys.push_back(member.key);
  return keys;
}

void JsonDocument::fail(const Pointer& ptr, std::string_view message) const {
  throw InputError(locate(ptr).str() + ": " + std::string(message));
}

void JsonDocument::failAtKey(const Pointer& ptr, std::string_view message) const {
  throw InputError(locateKey(ptr).str() + ": " + std::string(message));
}

}  // namespace tallow::app
