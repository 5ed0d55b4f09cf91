#include "sss/bssrdf/material.h"

#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <new>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <unordered_map>

#include "gpu/file_bytes.h"
#include "gpu/utf8.h"

namespace tallow::sss {

namespace {

/// The columns of materials.csv, in order (../shared/data/README.md).
constexpr std::array<std::string_view, 13> kColumns = {
    "name",    "source",  "sigma_s_r", "sigma_s_g", "sigma_s_b", "sigma_a_r", "sigma_a_g",
    "sigma_a_b", "g_r",   "g_g",       "g_b",       "eta",       "unit"};
constexpr std::string_view kUnit = "mm^-1";
constexpr std::array<char, 3> kBands = {'r', 'g', 'b'};

std::string formatValue(float v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

/// "sigma_s_r", the column naming band `band` of coefficient `what` in materials.csv.
std::string bandName(std::string_view what, int band) {
  return std::string(what) + "_" + kBands[static_cast<std::size_t>(band)];
}

std::vector<std::string_view> splitFields(std::string_view line) {
  std::vector<std::string_view> fields;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    fields.push_back(line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return fields;
}

}  // namespace

void validateMaterial(const Material& m) {
  for (int b = 0; b < 3; ++b) {
    const struct {
      std::string_view name;
      float value;
    } coefficients[] = {{"sigma_s", m.sigma_s[b]}, {"sigma_a", m.sigma_a[b]}, {"g", m.g[b]}};
    for (const auto& [name, value] : coefficients) {
      if (!std::isfinite(value))
        throw std::invalid_argument(bandName(name, b) + " is not finite (" + formatValue(value) + ")");
    }
    if (m.sigma_s[b] < 0.0f)
      throw std::invalid_argument(bandName("sigma_s", b) + " is negative (" + formatValue(m.sigma_s[b]) + ")");
    if (m.sigma_a[b] < 0.0f)
      throw std::invalid_argument(bandName("sigma_a", b) + " is negative (" + formatValue(m.sigma_a[b]) + ")");
    if (!(std::abs(m.g[b]) < 1.0f))
      throw std::invalid_argument(bandName("g", b) + " = " + formatValue(m.g[b]) + " is not in (-1, 1)");
    // σ_s = 0 with σ_a > 0 is a valid (purely absorbing) band, e.g. several Narasimhan liquids;
    // σ_t = 0 leaves nothing to scatter and makes the mean free path infinite.
    if (m.sigma_s[b] + m.sigma_a[b] == 0.0f)
      throw std::invalid_argument("sigma_s_" + std::string(1, kBands[static_cast<std::size_t>(b)]) + " + sigma_a_" +
                                  kBands[static_cast<std::size_t>(b)] + " is 0 (nothing scatters or absorbs)");
  }
  if (!std::isfinite(m.eta) || !(m.eta > 0.0f))
    throw std::invalid_argument("eta must be a positive number (" + formatValue(m.eta) + ")");
}

MaterialTable MaterialTable::load(const std::filesystem::path& csv) {
  gpu::checkInputFile(csv, gpu::kMaxTextFileBytes, "a materials table");
  std::ifstream in(csv, std::ios::binary);
  if (!in) throw std::runtime_error(csv.string() + ": cannot open");
  try {
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad()) throw std::runtime_error(csv.string() + ": read error");
    return parse(text.str(), csv.string());
  } catch (const std::bad_alloc&) {
    gpu::throwOutOfMemoryReading(csv);
  }
}

MaterialTable MaterialTable::parse(std::string_view text, const std::string& name) {
  MaterialTable table;
  std::unordered_map<std::string, int> firstLine;  // material name → line it was defined on
  int lineNo = 0;
  bool sawHeader = false;
  std::size_t pos = 0;
  while (pos < text.size()) {
    const std::size_t eol = text.find('\n', pos);
    std::string_view line = text.substr(pos, eol == std::string_view::npos ? std::string_view::npos : eol - pos);
    pos = eol == std::string_view::npos ? text.size() : eol + 1;
    ++lineNo;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);  // CRLF files
    const auto fail = [&](const std::string& message) {
      throw std::runtime_error(name + ":" + std::to_string(lineNo) + ": " + message);
    };

    if (!sawHeader) {
      std::string expected;
      for (std::string_view c : kColumns) {
        if (!expected.empty()) expected += ',';
        expected += c;
      }
      if (line != expected) fail("expected the header \"" + expected + "\"");
      sawHeader = true;
      continue;
    }
    if (line.empty()) continue;

    const std::vector<std::string_view> fields = splitFields(line);
    if (fields.size() != kColumns.size())
      fail("expected " + std::to_string(kColumns.size()) + " columns, found " + std::to_string(fields.size()));

    Material m;
    m.name = std::string(fields[0]);
    m.source = std::string(fields[1]);
    if (m.name.empty()) fail("name: empty");
    for (const std::string* text : {&m.name, &m.source})
      for (const char c : *text)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7F)
          fail(std::string(text == &m.name ? "name" : "source") + ": contains a control character");
    // Names go into JSON (stats.json, presets), which must be UTF-8: refused here, not after a render.
    for (const std::string* text : {&m.name, &m.source})
      if (const std::size_t bad = gpu::firstInvalidUtf8(*text); bad != std::string::npos)
        fail(std::string(text == &m.name ? "name" : "source") + ": not valid UTF-8 (byte " + std::to_string(bad + 1) +
             ")");
    if (m.name.front() == ' ' || m.name.back() == ' ') fail("name: leading or trailing space in \"" + m.name + "\"");

    float numbers[10];
    for (std::size_t i = 0; i < 10; ++i) {
      const std::string_view field = fields[2 + i];
      const std::string_view column = kColumns[2 + i];
      const char* end = field.data() + field.size();
      const auto [ptr, ec] = std::from_chars(field.data(), end, numbers[i]);
      if (ec == std::errc::result_out_of_range) fail(std::string(column) + ": \"" + std::string(field) + "\" is out of range");
      if (ec != std::errc() || ptr != end || field.empty())
        fail(std::string(column) + ": \"" + std::string(field) + "\" is not a number");
    }
    m.sigma_s = {numbers[0], numbers[1], numbers[2]};
    m.sigma_a = {numbers[3], numbers[4], numbers[5]};
    m.g = {numbers[6], numbers[7], numbers[8]};
    m.eta = numbers[9];
    if (fields[12] != kUnit) fail("unit: \"" + std::string(fields[12]) + "\" (expected \"" + std::string(kUnit) + "\")");

    try {
      validateMaterial(m);
    } catch (const std::invalid_argument& e) {
      fail(std::string(m.name) + ": " + e.what());
    }
    const auto [it, inserted] = firstLine.emplace(m.name, lineNo);
    if (!inserted) fail("duplicate material \"" + m.name + "\" (first on line " + std::to_string(it->second) + ")");
    table.materials_.push_back(std::move(m));
  }
  if (!sawHeader) throw std::runtime_error(name + ":1: empty file (expected the header)");
  if (table.materials_.empty()) throw std::runtime_error(name + ":" + std::to_string(lineNo) + ": no materials");
  return table;
}

std::optional<Material> MaterialTable::find(std::string_view name) const {
  for (const Material& m : materials_)
    if (m.name == name) return m;
  return std::nullopt;
}

}  // namespace tallow::sss
