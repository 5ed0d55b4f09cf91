#pragma once
// Optical coefficients of a translucent material, per colour band (r, g, b), in mm⁻¹.
#include <glm/glm.hpp>

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace tallow::sss {

struct Material {
  std::string name;    ///< as in materials.csv, or "custom"
  std::string source;  ///< citation of the measurement, empty for custom coefficients
  glm::vec3 sigma_s{0.0f};  ///< scattering coefficient [mm⁻¹]
  glm::vec3 sigma_a{0.0f};  ///< absorption coefficient [mm⁻¹]
  glm::vec3 g{0.0f};        ///< Henyey–Greenstein mean cosine, |g| < 1
  float eta = 1.3f;         ///< relative index of refraction (inside / outside), > 0
};

/// Throws std::invalid_argument with one line naming the offending coefficient when a value is
/// negative, non-finite, |g| ≥ 1, η ≤ 0, or σ_t = 0 in some band (nothing to scatter).
void validateMaterial(const Material& m);

/// The rows of a materials table (the format of ../shared/data/materials.csv).
class MaterialTable {
 public:
  /// Reads and validates the CSV; errors name file:line. Throws std::runtime_error.
  static MaterialTable load(const std::filesystem::path& csv);
  /// Same, from text already in memory; `name` is used in error messages.
  static MaterialTable parse(std::string_view text, const std::string& name);

  const std::vector<Material>& materials() const { return materials_; }
  /// Case-sensitive exact name match.
  std::optional<Material> find(std::string_view name) const;

 private:
  std::vector<Material> materials_;
};

}  // namespace tallow::sss
