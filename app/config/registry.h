#pragma once
// The parameter registry: every tunable declared once — key, type, range, default, units, help —
// with a getter and setter on Config. `--set`, the preset's "settings", the ImGui panel and
// stats.json all go through it (STYLE 7, 9), so ranges and defaults cannot drift apart.
#include <nlohmann/json.hpp>

#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "app/config/config.h"

namespace tallow::app {

class Registry {
 public:
  struct Param {
    std::string key;    ///< e.g. "render.width"; dots group keys in the panel
    std::string type;   ///< "bool", "int", "float", "enum" or "vec3"
    std::string units;  ///< e.g. "px", "m", "W/m²"; empty when dimensionless
    std::string help;   ///< one sentence
    double min = 0.0;   ///< int, float: inclusive range; vec3: per component; unused otherwise
    double max = 0.0;
    std::vector<std::string> choices;  ///< enum only
    /// int only: the string "auto" is a value too, and the renderer chooses (sss.map_size=auto).
    bool acceptsAuto = false;
    /// With acceptsAuto: the number the view's panel sets when its auto checkbox is cleared.
    double autoOffValue = 0.0;
    /// int only: a frame's work in the passes it feeds grows as value^costPower (the view panel's
    /// hint while the value is dragged); 0: no such law.
    int costPower = 0;
    /// Absent for scene-bound parameters, whose value comes from the preset.
    std::optional<nlohmann::json> defaultValue;

    /// Reads the value from a Config; null when the parameter does not apply to its scene (e.g.
    /// `light.direction` with no light). Returns vec3 as [x, y, z], enum as its string.
    std::function<nlohmann::json(const Config&)> getter;
    /// Writes a value that Registry::set has already checked against type, range and choices.
    /// May throw InputError("<message>") (no key prefix) when the value cannot apply to this
    /// Config, e.g. no object to give a material to, or a zero direction.
    std::function<void(Config&, const nlohmann::json&)> setter;

    bool sceneBound() const { return !defaultValue.has_value(); }
  };

  /// Declares a parameter. Throws std::logic_error on a duplicate key, an unknown type, or a
  /// default outside the declared type or range (a programming error, caught by the tests).
  void add(Param param);

  const std::vector<Param>& params() const { return params_; }
  const Param* find(std::string_view key) const;

  /// Sets every parameter that has a default to that default.
  void applyDefaults(Config& config) const;

  /// Checks `value` against the parameter's type and range, then stores it. Throws InputError
  /// "<key>: <message>", e.g. `render.pcf_radius: 9 is out of range [0, 4]`; an unknown key gives
  /// `unknown parameter "foo" (did you mean "bar"?)`.
  void set(Config& config, std::string_view key, const nlohmann::json& value) const;
  /// `key=value` as given to --set; the value is read by the parameter's type: bool
  /// true/false/1/0/on/off, int and float as numbers, enum as the bare choice, vec3 as "x,y,z".
  void setFromString(Config& config, std::string_view assignment) const;
  /// The value text of `key=value` read by the parameter's type as setFromString reads it, not yet
  /// checked against range or choices (checkParamValue does that). Throws InputError "<key>: …" for
  /// an unknown key or text that is not of the type.
  nlohmann::json parseValue(std::string_view key, std::string_view valueText) const;

  /// The current value (see Param::getter). Throws InputError on an unknown key.
  nlohmann::json get(const Config& config, std::string_view key) const;
  /// {key: value} for every parameter (null where one does not apply), for stats.json.
  nlohmann::json snapshot(const Config& config) const;

  /// The registry's keys, for suggestions and listings.
  std::vector<std::string> keys() const;

 private:
  const Param& require(std::string_view key) const;

  std::vector<Param> params_;
};

/// Checks `value` against `param`'s type, range and choices and returns it normalised (an int as
/// an integer, a float as a number). Throws InputError with the message alone (no key prefix).
nlohmann::json checkParamValue(const Registry::Param& param, const nlohmann::json& value);

/// Shortest text that reads back as the same double: 1e-05, 0.1, 2048.
std::string formatNumber(double v);
/// A float as JSON without float-to-double noise (0.1f → 0.1, not 0.10000000149011612).
nlohmann::json floatToJson(float v);

}  // namespace tallow::app
