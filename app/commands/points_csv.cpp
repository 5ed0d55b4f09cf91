#include "app/commands/points_csv.h"

#include <cmath>
#include <cstdio>
#include <optional>
#include <stdexcept>

#include "app/commands/csv_reader.h"
#include "app/config/input_error.h"

namespace tallow::app {

std::vector<glm::dvec3> parsePoints(std::string_view text, const std::string& name) {
  const std::vector<std::string_view> header = splitCsvColumns(kPointColumns);
  std::vector<glm::dvec3> points;
  CsvLines lines(text, name);
  if (!lines.next()) throw InputError(name + ":1:1: empty file; expected the header " + std::string(kPointColumns));
  const auto& head = lines.cells();
  for (std::size_t c = 0; c < head.size() || c < header.size(); ++c) {
    if (c < head.size() && c < header.size() && head[c].text == header[c]) continue;
    const int column = c < head.size() ? head[c].column : lines.endColumn();
    throw InputError(lines.where(column) + "expected the header " + std::string(kPointColumns));
  }
  while (lines.next()) {
    const auto& cells = lines.cells();
    if (cells.size() != header.size()) {
      const int column = cells.size() > header.size() ? cells[header.size()].column : lines.endColumn();
      throw InputError(lines.where(column) + "expected " + std::to_string(header.size()) + " columns, found " +
                       std::to_string(cells.size()));
    }
    if (points.size() == kMaxPoints)
      throw InputError(lines.where(1) + "more than " + std::to_string(kMaxPoints) + " points (the limit per file)");
    glm::dvec3 p(0.0);
    for (std::size_t c = 0; c < header.size(); ++c) {
      const std::optional<double> v = parseFiniteNumber(cells[c].text);
      if (!v)
        throw InputError(lines.where(cells[c]) + std::string(header[c]) + ": " + quote(cells[c].text) +
                         " is not a finite number");
      if (std::abs(*v) > kMaxCoordinateM)
        throw InputError(lines.where(cells[c]) + std::string(header[c]) + ": " + quote(cells[c].text) +
                         " is out of range (|" + std::string(header[c]) + "| <= 1e6 m)");
      p[static_cast<int>(c)] = *v;
    }
    points.push_back(p);
  }
  return points;
}

std::string formatFieldValues(const std::vector<glm::dvec3>& points, const std::vector<FieldSample>& samples) {
  if (points.size() != samples.size()) throw std::invalid_argument("formatFieldValues: one sample per point");
  std::string out(kFieldValueColumns);
  out += '\n';
  char buffer[7 * 32];
  for (std::size_t i = 0; i < points.size(); ++i) {
    const glm::dvec3& p = points[i];
    const FieldSample& s = samples[i];
    const int n = std::snprintf(buffer, sizeof buffer, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", p.x, p.y, p.z,
                                s.value, s.gradient.x, s.gradient.y, s.gradient.z);
    out.append(buffer, static_cast<std::size_t>(n));
  }
  return out;
}

}  // namespace tallow::app
