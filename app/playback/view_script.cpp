#include "app/playback/view_script.h"

#include <charconv>
#include <cmath>
#include <stdexcept>

#include "app/config/input_error.h"

namespace tallow::app {

namespace {

using json = nlohmann::json;

struct ActionName {
  std::string_view word;
  ScriptAction action;
};
constexpr ActionName kActions[] = {
    {"set", ScriptAction::Set},     {"play", ScriptAction::Play},       {"pause", ScriptAction::Pause},
    {"loop", ScriptAction::Loop},   {"speed", ScriptAction::Speed},     {"seek", ScriptAction::Seek},
    {"orbit", ScriptAction::Orbit}, {"pan", ScriptAction::Pan},         {"zoom", ScriptAction::Zoom},
    {"debug", ScriptAction::Debug}, {"screenshot", ScriptAction::Screenshot}, {"save-preset", ScriptAction::SavePreset},
    {"key", ScriptAction::Key},     {"quit", ScriptAction::Quit},
};

// Bounds of the numeric arguments: generous, finite, so nothing downstream overflows.
constexpr double kMaxSpeed = 1e3;     ///< animation seconds per second, either sign
constexpr double kMaxSeekS = 1e6;     ///< as a preset's animation times
constexpr double kMaxAngleDeg = 1e4;  ///< orbit steps
constexpr double kMaxPan = 1e3;       ///< view heights
constexpr double kMinZoom = 1e-3, kMaxZoom = 1e3;

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r'; }

/// One line being read: its text and where each piece starts, for messages.
class LineReader {
 public:
  LineReader(std::string_view line, const std::string& file, int lineNo) : line_(line), file_(file), lineNo_(lineNo) {}

  /// "FILE:LINE:COL" of byte `offset` (columns count UTF-8 characters, 1-based).
  std::string where(std::size_t offset) const {
    int col = 1;
    for (std::size_t i = 0; i < offset && i < line_.size(); ++i)
      if ((static_cast<unsigned char>(line_[i]) & 0xC0) != 0x80) ++col;
    return file_ + ":" + std::to_string(lineNo_) + ":" + std::to_string(col);
  }
  [[noreturn]] void fail(std::size_t offset, const std::string& message) const {
    throw InputError(where(offset) + ": " + message);
  }

  void skipSpaces() {
    while (pos_ < line_.size() && isSpace(line_[pos_])) ++pos_;
  }
  bool atEnd() {
    skipSpaces();
    return pos_ >= line_.size();
  }
  std::size_t pos() const { return pos_; }
  /// The next word (up to a space); empty at the end.
  std::string_view word() {
    skipSpaces();
    const std::size_t start = pos_;
    while (pos_ < line_.size() && !isSpace(line_[pos_])) ++pos_;
    return line_.substr(start, pos_ - start);
  }
  /// Everything left, without surrounding spaces and one pair of double quotes around it.
  std::string_view rest() {
    skipSpaces();
    std::string_view r = line_.substr(pos_);
    while (!r.empty() && isSpace(r.back())) r.remove_suffix(1);
    pos_ = line_.size();
    if (r.size() >= 2 && r.front() == '"' && r.back() == '"') r = r.substr(1, r.size() - 2);
    return r;
  }

  double number(std::string_view what, double min, double max) {
    skipSpaces();
    const std::size_t at = pos_;
    const std::string_view w = word();
    if (w.empty()) fail(at, "expected " + std::string(what));
    double v = 0.0;
    const auto r = std::from_chars(w.data(), w.data() + w.size(), v);
    if (r.ec != std::errc() || r.ptr != w.data() + w.size() || !std::isfinite(v))
      fail(at, std::string(what) + ": " + quote(w) + " is not a number");
    if (!(v >= min && v <= max))
      fail(at, std::string(what) + ": " + formatNumber(v) + " is out of range [" + formatNumber(min) + ", " +
                   formatNumber(max) + "]");
    return v;
  }

  void expectEnd(std::string_view after) {
    skipSpaces();
    if (pos_ < line_.size()) fail(pos_, "unexpected " + quote(line_.substr(pos_)) + " after " + std::string(after));
  }

 private:
  std::string_view line_;
  const std::string& file_;
  int lineNo_;
  std::size_t pos_ = 0;
};

/// The line without its comment: '#' at the start or after a space begins one.
std::string_view stripComment(std::string_view line) {
  for (std::size_t i = 0; i < line.size(); ++i)
    if (line[i] == '#' && (i == 0 || isSpace(line[i - 1]))) return line.substr(0, i);
  return line;
}

}  // namespace

std::string_view scriptActionName(ScriptAction action) {
  for (const ActionName& a : kActions)
    if (a.action == action) return a.word;
  return "?";
}

std::vector<const ScriptCommand*> Script::at(int frame) const {
  std::vector<const ScriptCommand*> out;
  for (const ScriptCommand& c : commands)
    if (c.frame == frame) out.push_back(&c);
  return out;
}

Script parseScript(std::string_view text, const std::string& fileName, const Registry& registry) {
  Script script;
  script.fileName = fileName;
  if (text.size() >= 3 && text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);  // UTF-8 byte-order mark
  int lineNo = 0;
  for (std::size_t start = 0; start <= text.size();) {
    const std::size_t newline = text.find('\n', start);
    const std::string_view raw =
        text.substr(start, newline == std::string_view::npos ? std::string_view::npos : newline - start);
    start = newline == std::string_view::npos ? text.size() + 1 : newline + 1;
    ++lineNo;
    const std::string_view line = stripComment(raw);
    LineReader in(line, fileName, lineNo);
    if (raw.size() > kMaxScriptLine)
      in.fail(0, "line longer than " + std::to_string(kMaxScriptLine) + " characters");
    if (raw.find('\0') != std::string_view::npos) in.fail(raw.find('\0'), "NUL character (not a text file?)");
    if (in.atEnd()) continue;

    ScriptCommand c;
    const std::size_t frameAt = in.pos();
    const std::string_view frameWord = in.word();
    if (frameWord != "frame") in.fail(frameAt, "expected \"frame N <command>\", got " + quote(frameWord));
    in.skipSpaces();
    const std::size_t numberAt = in.pos();
    const double frame = in.number("frame number", 0, kMaxScriptFrame);
    if (frame != std::floor(frame)) in.fail(numberAt, "frame number: expected an integer");
    c.frame = static_cast<int>(frame);
    if (!script.commands.empty() && c.frame < script.commands.back().frame)
      in.fail(numberAt, "frame " + std::to_string(c.frame) + " comes after frame " +
                            std::to_string(script.commands.back().frame) + " (frames must not decrease)");
    in.skipSpaces();
    const std::size_t actionAt = in.pos();
    const std::string_view word = in.word();
    if (word.empty()) in.fail(actionAt, "expected a command after the frame number");
    const ActionName* found = nullptr;
    for (const ActionName& a : kActions)
      if (a.word == word) found = &a;
    if (!found) {
      std::vector<std::string> names;
      for (const ActionName& a : kActions) names.emplace_back(a.word);
      in.fail(actionAt, "unknown command " + quote(word) + didYouMean(word, names));
    }
    c.action = found->action;
    c.where = in.where(actionAt);
    switch (c.action) {
      case ScriptAction::Set: {
        in.skipSpaces();
        const std::size_t keyAt = in.pos();
        const std::string_view assignment = in.rest();
        const std::size_t eq = assignment.find('=');
        if (eq == std::string_view::npos) in.fail(keyAt, "expected key=value after set");
        std::string_view key = assignment.substr(0, eq);
        while (!key.empty() && isSpace(key.back())) key.remove_suffix(1);
        const Registry::Param* param = registry.find(key);
        if (!param) in.fail(keyAt, "unknown parameter " + quote(key) + didYouMean(key, registry.keys()));
        // Past '=' and its spaces: where the value starts.
        std::size_t valueAt = static_cast<std::size_t>(assignment.data() - line.data()) + eq + 1;
        std::string_view valueText = assignment.substr(eq + 1);
        while (!valueText.empty() && isSpace(valueText.front())) {
          valueText.remove_prefix(1);
          ++valueAt;
        }
        if (valueText.size() >= 2 && valueText.front() == '"' && valueText.back() == '"')
          valueText = valueText.substr(1, valueText.size() - 2);
        try {
          c.value = checkParamValue(*param, registry.parseValue(param->key, valueText));
        } catch (const InputError& e) {
          const std::string message = e.what();
          // parseValue's messages start with the key already; checkParamValue's do not.
          in.fail(valueAt, message.rfind(param->key + ": ", 0) == 0 ? message : param->key + ": " + message);
        }
        c.key = param->key;
        break;
      }
      case ScriptAction::Play:
      case ScriptAction::Pause:
      case ScriptAction::Quit:
        break;
      case ScriptAction::Loop: {
        in.skipSpaces();
        const std::size_t at = in.pos();
        const std::string_view w = in.word();
        if (w == "on" || w == "true" || w == "1") c.on = true;
        else if (w == "off" || w == "false" || w == "0") c.on = false;
        else in.fail(at, "loop: expected on or off, got " + quote(w));
        break;
      }
      case ScriptAction::Speed:
        c.a = in.number("speed", -kMaxSpeed, kMaxSpeed);
        break;
      case ScriptAction::Seek:
        c.a = in.number("seek time [s]", 0.0, kMaxSeekS);  // the range of --time and a preset's start_s
        break;
      case ScriptAction::Orbit:
        c.a = in.number("orbit yaw [deg]", -kMaxAngleDeg, kMaxAngleDeg);
        c.b = in.number("orbit pitch [deg]", -kMaxAngleDeg, kMaxAngleDeg);
        break;
      case ScriptAction::Pan:
        c.a = in.number("pan right [view heights]", -kMaxPan, kMaxPan);
        c.b = in.number("pan up [view heights]", -kMaxPan, kMaxPan);
        break;
      case ScriptAction::Zoom:
        c.a = in.number("zoom factor", kMinZoom, kMaxZoom);
        break;
      case ScriptAction::Debug: {
        in.skipSpaces();
        const std::size_t at = in.pos();
        const std::string_view spec = in.word();
        if (spec.empty()) in.fail(at, "debug: expected a view, e.g. map:3");
        try {
          c.debug = sss::parseDebugView(spec);
        } catch (const std::invalid_argument& e) {
          in.fail(at, std::string("debug: ") + e.what());
        }
        break;
      }
      case ScriptAction::Key: {
        in.skipSpaces();
        const std::size_t at = in.pos();
        const std::string_view name = in.word();
        if (name.empty()) in.fail(at, "key: expected a hotkey, e.g. space or ctrl+z");
        const std::optional<Hotkey> key = parseHotkey(name);
        if (!key) {
          std::vector<std::string> names;
          for (const std::string_view n : hotkeyNames()) names.emplace_back(n);
          in.fail(at, "key: unknown hotkey " + quote(name) + didYouMean(name, names));
        }
        c.hotkey = *key;
        break;
      }
      case ScriptAction::Screenshot:
      case ScriptAction::SavePreset: {
        in.skipSpaces();
        const std::size_t at = in.pos();
        const std::string_view path = in.rest();
        const std::string name(scriptActionName(c.action));
        if (path.empty()) in.fail(at, name + ": expected a file name");
        if (c.action == ScriptAction::Screenshot) {
          const std::string ext = std::filesystem::path(path).extension().string();
          if (ext != ".png" && ext != ".exr") in.fail(at, "screenshot: expected a .png or .exr file, got " + quote(path));
        }
        c.path = std::string(path);
        break;
      }
    }
    in.expectEnd(std::string(word));
    script.commands.push_back(std::move(c));
  }
  return script;
}

Script loadScript(const std::filesystem::path& file, const Registry& registry) {
  return parseInputFile(file, [&](const std::string& text) { return parseScript(text, file.string(), registry); });
}

}  // namespace tallow::app
