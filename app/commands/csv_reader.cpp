#include "app/commands/csv_reader.h"

#include <charconv>
#include <cmath>

namespace tallow::app {
namespace {

bool blank(char c) { return c == ' ' || c == '\t'; }

}  // namespace

CsvLines::CsvLines(std::string_view text, std::string name) : text_(text), name_(std::move(name)) {}

bool CsvLines::next() {
  while (pos_ < text_.size()) {
    const std::size_t end = text_.find('\n', pos_);
    std::string_view raw = text_.substr(pos_, end == std::string_view::npos ? std::string_view::npos : end - pos_);
    pos_ = end == std::string_view::npos ? text_.size() : end + 1;
    ++lineNumber_;
    std::size_t first = 0, last = raw.size();
    while (first < last && blank(raw[first])) ++first;
    while (last > first && (blank(raw[last - 1]) || raw[last - 1] == '\r')) --last;
    if (first == last) continue;
    trimmed_ = raw.substr(first, last - first);
    endColumn_ = static_cast<int>(last) + 1;
    cells_.clear();
    std::size_t start = first;
    for (const std::string_view cell : splitCsvColumns(trimmed_)) {
      std::size_t b = 0, e = cell.size();
      while (b < e && blank(cell[b])) ++b;
      while (e > b && blank(cell[e - 1])) --e;
      cells_.push_back({cell.substr(b, e - b), static_cast<int>(start + b) + 1});
      start += cell.size() + 1;  // past the comma
    }
    return true;
  }
  return false;
}

std::string CsvLines::where() const {
  return lineNumber_ == 0 ? name_ + ": " : name_ + ":" + std::to_string(lineNumber_) + ": ";
}

std::string CsvLines::where(const CsvCell& cell) const { return where(cell.column); }

std::string CsvLines::where(int column) const {
  return name_ + ":" + std::to_string(lineNumber_ < 1 ? 1 : lineNumber_) + ":" + std::to_string(column) + ": ";
}

std::vector<std::string_view> splitCsvColumns(std::string_view text) {
  std::vector<std::string_view> out;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    out.push_back(text.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return out;
}

std::optional<double> parseFiniteNumber(std::string_view text) {
  double v = 0.0;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
  if (text.empty() || r.ec != std::errc() || r.ptr != text.data() + text.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

}  // namespace tallow::app
