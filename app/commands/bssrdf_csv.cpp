#include "app/commands/bssrdf_csv.h"

#include <cstdio>
#include <optional>
#include <stdexcept>

#include "app/commands/csv_reader.h"
#include "app/config/input_error.h"

namespace tallow::app {
namespace {
constexpr int kColumns = 19;
}  // namespace

std::vector<sss::BssrdfConfig> parseBssrdfConfigs(std::string_view text, const std::string& name) {
  const std::vector<std::string_view> header = splitCsvColumns(kBssrdfConfigColumns);
  std::vector<sss::BssrdfConfig> configs;
  CsvLines lines(text, name);
  bool sawHeader = false;
  while (lines.next()) {
    const std::string where = lines.where();
    if (!sawHeader) {
      if (lines.line() != kBssrdfConfigColumns)
        throw InputError(where + "expected the header " + std::string(kBssrdfConfigColumns));
      sawHeader = true;
      continue;
    }
    const auto& cells = lines.cells();
    if (cells.size() != kColumns)
      throw InputError(where + "expected " + std::to_string(kColumns) + " columns, found " + std::to_string(cells.size()));
    double v[kColumns];
    for (int c = 0; c < kColumns; ++c) {
      const std::string_view cell = cells[static_cast<std::size_t>(c)].text;
      const std::optional<double> number = parseFiniteNumber(cell);
      if (!number)
        throw InputError(where + std::string(header[static_cast<std::size_t>(c)]) + ": \"" +
                         std::string(cell.substr(0, 40)) + "\" is not a finite number");
      v[c] = *number;
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
