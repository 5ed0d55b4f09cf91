#include "app/config/registry.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <system_error>

#include "app/config/input_error.h"

namespace tallow::app {

namespace {

using json = nlohmann::json;

/// A short rendering of a JSON value for messages.
std::string describe(const json& value) {
  constexpr std::size_t kMaxChars = 40;
  std::string text = value.dump(-1, ' ', true, json::error_handler_t::replace);
  if (text.size() > kMaxChars) text = text.substr(0, kMaxChars - 3) + "...";
  return text;
}

std::string rangeText(const Registry::Param& p) {
  return "[" + formatNumber(p.min) + ", " + formatNumber(p.max) + "]";
}

/// Throws unless min <= v <= max (NaN fails too).
void checkRange(const Registry::Param& p, double v, std::string_view suffix = {}) {
  if (!std::isfinite(v)) throw InputError(formatNumber(v) + " is not a finite number" + std::string(suffix));
  if (!(v >= p.min && v <= p.max))
    throw InputError(formatNumber(v) + " is out of range " + rangeText(p) + std::string(suffix));
}

std::string_view trim(std::string_view s) {
  const auto isSpace = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; };
  while (!s.empty() && isSpace(s.front())) s.remove_prefix(1);
  while (!s.empty() && isSpace(s.back())) s.remove_suffix(1);
  return s;
}

template <typename T>
std::optional<T> parseWhole(std::string_view text) {
  T value{};
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (text.empty() || ec != std::errc() || ptr != end) return std::nullopt;
  return value;
}

[[noreturn]] void failParam(const Registry::Param& p, const std::string& message) {
  throw InputError(p.key + ": " + message);
}

bool isKnownType(std::string_view type) {
  return type == "bool" || type == "int" || type == "float" || type == "enum" || type == "vec3";
}

}  // namespace

std::string formatNumber(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

json floatToJson(float v) {
  if (!std::isfinite(v)) return json(nullptr);
  // The shortest decimal that reads back as this float, read as a double.
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  double d = v;
  std::from_chars(buf, r.ptr, d);
  return json(d);
}

json checkParamValue(const Registry::Param& p, const json& value) {
  if (p.type == "bool") {
    if (!value.is_boolean()) throw InputError("expected true or false, got " + describe(value));
    return value;
  }
  if (p.type == "int") {
    if (p.acceptsAuto && value.is_string() && value.get_ref<const std::string&>() == "auto") return value;
    if (!value.is_number_integer())
      throw InputError(std::string(p.acceptsAuto ? "expected an integer or \"auto\"" : "expected an integer") +
                       ", got " + describe(value));
    const double v = value.is_number_unsigned() ? static_cast<double>(value.get<std::uint64_t>())
                                                : static_cast<double>(value.get<std::int64_t>());
    checkRange(p, v);
    return json(value.get<std::int64_t>());  // in range, so it fits
  }
  if (p.type == "float") {
    if (!value.is_number()) throw InputError("expected a number, got " + describe(value));
    const double v = value.get<double>();
    checkRange(p, v);
    return json(v);
  }
  if (p.type == "enum") {
    if (!value.is_string()) throw InputError("expected a string, got " + describe(value));
    const std::string& s = value.get_ref<const std::string&>();
    if (std::find(p.choices.begin(), p.choices.end(), s) == p.choices.end()) {
      std::string message = "unknown value " + quote(s) + didYouMean(s, p.choices);
      constexpr std::size_t kMaxListed = 8;  // a material table is too long to list in one line
      if (p.choices.size() <= kMaxListed) {
        message += "; choices:";
        for (std::size_t i = 0; i < p.choices.size(); ++i) message += (i ? ", " : " ") + p.choices[i];
      }
      throw InputError(message);
    }
    return value;
  }
  if (p.type == "vec3") {
    if (!value.is_array() || value.size() != 3 ||
        !std::all_of(value.begin(), value.end(), [](const json& c) { return c.is_number(); }))
      throw InputError("expected an array of 3 numbers, got " + describe(value));
    json out = json::array();
    for (std::size_t i = 0; i < 3; ++i) {
      const double v = value[i].get<double>();
      checkRange(p, v, std::string(" (component ") + "xyz"[i] + ")");
      out.push_back(v);
    }
    return out;
  }
  throw std::logic_error("parameter " + p.key + " has unknown type " + p.type);
}

void Registry::add(Param param) {
  if (find(param.key)) throw std::logic_error("parameter declared twice: " + param.key);
  if (!isKnownType(param.type)) throw std::logic_error("parameter " + param.key + ": unknown type " + param.type);
  if (!param.getter || !param.setter) throw std::logic_error("parameter " + param.key + ": missing getter or setter");
  if (param.type == "int" || param.type == "float" || param.type == "vec3") {
    // Values pass through float; a range beyond it would let a cast overflow.
    constexpr double kFloatMax = std::numeric_limits<float>::max();
    if (!(param.min <= param.max) || std::abs(param.min) > kFloatMax || std::abs(param.max) > kFloatMax)
      throw std::logic_error("parameter " + param.key + ": bad range");
  }
  if (param.type == "enum" && param.choices.empty()) throw std::logic_error("parameter " + param.key + ": no choices");
  if (param.defaultValue) {
    try {
      checkParamValue(param, *param.defaultValue);
    } catch (const InputError& e) {
      throw std::logic_error("parameter " + param.key + ": default " + e.what());
    }
  }
  params_.push_back(std::move(param));
}

const Registry::Param* Registry::find(std::string_view key) const {
  for (const Param& p : params_)
    if (p.key == key) return &p;
  return nullptr;
}

std::vector<std::string> Registry::keys() const {
  std::vector<std::string> out;
  out.reserve(params_.size());
  for (const Param& p : params_) out.push_back(p.key);
  return out;
}

const Registry::Param& Registry::require(std::string_view key) const {
  if (const Param* p = find(key)) return *p;
  throw InputError("unknown parameter " + quote(key) + didYouMean(key, keys()));
}

void Registry::applyDefaults(Config& config) const {
  for (const Param& p : params_)
    if (p.defaultValue) p.setter(config, checkParamValue(p, *p.defaultValue));
}

void Registry::set(Config& config, std::string_view key, const json& value) const {
  const Param& p = require(key);
  try {
    p.setter(config, checkParamValue(p, value));
  } catch (const InputError& e) {
    throw InputError(p.key + ": " + e.what());
  }
}

void Registry::setFromString(Config& config, std::string_view assignment) const {
  const std::size_t eq = assignment.find('=');
  if (eq == std::string_view::npos)
    throw InputError("expected key=value, got " + quote(assignment));
  const std::string_view key = trim(assignment.substr(0, eq));
  set(config, key, parseValue(key, assignment.substr(eq + 1)));
}

json Registry::parseValue(std::string_view key, std::string_view valueText) const {
  const Param& p = require(key);
  const std::string_view text = trim(valueText);
  json value;
  if (p.type == "bool") {
    if (text == "true" || text == "1" || text == "on") value = true;
    else if (text == "false" || text == "0" || text == "off") value = false;
    else failParam(p, "expected true/false, 1/0 or on/off, got " + quote(text));
  } else if (p.type == "int") {
    const auto v = parseWhole<std::int64_t>(text);
    if (p.acceptsAuto && text == "auto") value = "auto";
    else if (!v) failParam(p, quote(text) + (p.acceptsAuto ? " is neither an integer nor auto" : " is not an integer"));
    else value = *v;
  } else if (p.type == "float") {
    const auto v = parseWhole<double>(text);
    if (!v) failParam(p, quote(text) + " is not a number");
    value = *v;
  } else if (p.type == "enum") {
    value = std::string(text);
  } else {  // vec3
    value = json::array();
    std::string_view rest = text;
    for (int i = 0; i < 3; ++i) {
      const std::size_t comma = rest.find(',');
      const std::string_view part = trim(rest.substr(0, comma));
      const auto v = parseWhole<double>(part);
      if (!v || (i < 2) == (comma == std::string_view::npos))
        failParam(p, "expected three numbers x,y,z, got " + quote(text));
      value.push_back(*v);
      rest = comma == std::string_view::npos ? std::string_view() : rest.substr(comma + 1);
    }
  }
  return value;
}

json Registry::get(const Config& config, std::string_view key) const { return require(key).getter(config); }

json Registry::snapshot(const Config& config) const {
  json out = json::object();
  for (const Param& p : params_) out[p.key] = p.getter(config);
  return out;
}

}  // namespace tallow::app
