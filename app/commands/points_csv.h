#pragma once
// The CSV files of `tallow field`: points in (header x,y,z, world units, metres), field samples out
// (x,y,z,value,grad_x,grad_y,grad_z).
#include <glm/glm.hpp>

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace tallow::app {

inline constexpr std::string_view kPointColumns = "x,y,z";
inline constexpr std::string_view kFieldValueColumns = "x,y,z,value,grad_x,grad_y,grad_z";
/// Rows accepted in one file: 10 million points is ~0.5 GB of CSV, far beyond any test or plot.
inline constexpr std::size_t kMaxPoints = 10'000'000;
/// Largest |coordinate| accepted, metres: scenes are a few metres across; beyond this, the
/// level-set grids' integer voxel coordinates would overflow.
inline constexpr double kMaxCoordinateM = 1e6;

/// Parses the header and every row. Blank lines and trailing CRs are accepted. Errors throw
/// InputError with one line `name:line:col: message` (wrong header, wrong column count, a cell that
/// is not a finite number or is out of range, more than kMaxPoints rows).
std::vector<glm::dvec3> parsePoints(std::string_view text, const std::string& name);

struct FieldSample {
  double value = 0.0;         ///< < 0 inside, 0 on the surface
  glm::dvec3 gradient{0.0};   ///< ∇value, world units (1/m for signed distances)
};

/// The output CSV: kFieldValueColumns, each number with 17 significant digits (doubles read back
/// exactly). `samples` has one entry per point.
std::string formatFieldValues(const std::vector<glm::dvec3>& points, const std::vector<FieldSample>& samples);

}  // namespace tallow::app
