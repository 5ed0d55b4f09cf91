#include "app/bssrdf_csv.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "app/input_error.h"

namespace tallow::app {
namespace {

constexpr int kColumns = 19;

std::vector<std::string_view> splitColumns(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    out.push_back(line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return out;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

}  // namespace

std::vector<sss::BssrdfConfig> parseBssrdfConfigs(std::string_view text, const std::string& name) {
  const std::vector<std::string_view> header = splitColumns(kBssrdfConfigColumns);
  std::vector<sss::BssrdfConfig> configs;
  std::size_t pos = 0;
  int lineNo = 0;
  bool sawHeader = false;
  while (pos < text.size()) {
    const std::size_t end = text.find('\n', pos);
    const std::string_view line = trim(text.substr(pos, end == std::string_view::npos ? std::string_view::npos : end - pos));
    pos = end == std::string_view::npos ? text.size() : end + 1;
    ++lineNo;
    if (line.empty()) continue;
    const auto where = name + ":" + std::to_string(lineNo) + ": ";
    if (!sawHeader) {
      if (line != kBssrdfConfigColumns)
        throw InputError(where + "expected the header " + std::string(kBssrdfConfigColumns));
      sawHeader = true;
      continue;
    }
    const auto cells = splitColumns(line);
    if (cells.size() != kColumns)
      throw InputError(where + "expected " + std::to_string(kColumns) + " columns, found " + std::to_string(cells.size()));
    double v[kColumns];
    for (int c = 0; c < kColumns; ++c) {
      const std::string_view cell = trim(cells[static_cast<std::size_t>(c)]);
      const auto r = std::from_chars(cell.data(), cell.data() + cell.size(), v[c]);
      if (r.ec != std::errc() || r.ptr != cell.data() + cell.size() || !std::isfinite(v[c]))
        throw InputError(where + std::string(header[static_cast<std::size_t>(c)]) + ": \"" +
                         std::string(cell.substr(0, 40)) + "\" is not a finite number");
    }
    sss::BssrdfConfig config;
    config.xi = {v[0], v[1], v[2]};
    config.ni = {v[3], v[4], v[5]};
    config.wi = {v[6], v[7], v[8]};
    config.xo = {v[9], v[10], v[11]};
    config.no = {v[12], v[13], v[14]};
    config.sigma_a = v[15];
    config.sigma_s = v[16];
    config.g = v[17];
    config.eta = v[18];
    try {
      sss::validateBssrdfConfig(config);
    } catch (const std::invalid_argument& e) {
      throw InputError(where + e.what());
    }
    configs.push_back(config);
  }
  if (!sawHeader) throw InputError(name + ": empty file; expected the header " + std::string(kBssrdfConfigColumns));
  return configs;
}

std::string formatBssrdfValues(const std::vector<sss::BssrdfConfig>& configs,
                               const std::vector<sss::BssrdfValue>& values) {
  std::string out(kBssrdfConfigColumns);
  out += ",sd,sd_clamped\n";
  char buffer[40];
  auto add = [&](double x, char sep) {
    std::snprintf(buffer, sizeof buffer, "%.17g%c", x, sep);
    out += buffer;
  };
  for (std::size_t i = 0; i < configs.size(); ++i) {
    const auto& c = configs[i];
    for (const glm::dvec3* v : {&c.xi, &c.ni, &c.wi, &c.xo, &c.no})
      for (int k = 0; k < 3; ++k) add((*v)[k], ',');
    add(c.sigma_a, ',');
    add(c.sigma_s, ',');
    add(c.g, ',');
    add(c.eta, ',');
    add(values[i].sd, ',');
    add(values[i].sdClamped, '\n');
  }
  return out;
}

}  // namespace tallow::app
