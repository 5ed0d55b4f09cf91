#include "sss/debug_view.h"

#include <charconv>
#include <stdexcept>

namespace tallow::sss {

namespace {
/// Largest light or layer index the text accepts (above any scene's lights or K).
constexpr int kMaxIndex = 4096;

int parseIndex(std::string_view text, std::string_view what) {
  int v = -1;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
  if (text.empty() || r.ec != std::errc() || r.ptr != text.data() + text.size() || v < 0 || v > kMaxIndex)
    throw std::invalid_argument(std::string(what) + ": expected an integer in [0, " + std::to_string(kMaxIndex) +
                                "], got \"" + std::string(text.substr(0, 40)) + "\"");
  return v;
}
}  // namespace

const std::vector<std::string>& debugViewNames() {
  static const std::vector<std::string> names = {"final",    "gbuffer-position", "gbuffer-normal", "map",
                                                 "coverage", "vpl",              "wireframe",      "difference"};
  return names;
}

DebugView parseDebugView(std::string_view text) {
  std::vector<std::string_view> parts;
  for (std::size_t start = 0;;) {
    const std::size_t colon = text.find(':', start);
    parts.push_back(text.substr(start, colon == std::string_view::npos ? std::string_view::npos : colon - start));
    if (colon == std::string_view::npos) break;
    start = colon + 1;
  }
  const auto& names = debugViewNames();
  std::size_t kind = 0;
  while (kind < names.size() && names[kind] != parts[0]) ++kind;
  if (kind == names.size()) {
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
    throw std::invalid_argument("unknown debug view \"" + std::string(parts[0].substr(0, 40)) + "\"; views: " + list);
  }
  DebugView view;
  view.kind = static_cast<DebugViewKind>(kind);
  const bool gbuffer = view.kind == DebugViewKind::GBufferPosition || view.kind == DebugViewKind::GBufferNormal;
  const std::size_t maxParts = gbuffer ? 3 : view.kind == DebugViewKind::Map ? 2 : 1;
  if (parts.size() > maxParts)
    throw std::invalid_argument("debug view " + names[kind] + " takes " +
                                (maxParts == 1 ? std::string("no index")
                                 : maxParts == 2 ? std::string("one index (the map k)")
                                                 : std::string("at most a light and a cube face")));
  if (gbuffer) {
    if (parts.size() > 1) view.light = parseIndex(parts[1], "light");
    if (parts.size() > 2) {
      view.layer = parseIndex(parts[2], "cube face");
      if (view.layer > 5) throw std::invalid_argument("cube face: expected 0 to 5, got " + std::to_string(view.layer));
    }
  } else if (view.kind == DebugViewKind::Map && parts.size() > 1) {
    view.layer = parseIndex(parts[1], "map");
  }
  return view;
}

std::string formatDebugView(const DebugView& view) {
  // Appended piece by piece: `":" + std::string&&` trips GCC 12's false -Wrestrict (bug 105651).
  std::string text = debugViewNames()[static_cast<std::size_t>(view.kind)];
  const auto index = [&text](int i) {
    text += ':';
    text += std::to_string(i);
  };
  if (view.kind == DebugViewKind::GBufferPosition || view.kind == DebugViewKind::GBufferNormal) {
    index(view.light);
    index(view.layer);
  } else if (view.kind == DebugViewKind::Map) {
    index(view.layer);
  }
  return text;
}

}  // namespace tallow::sss
