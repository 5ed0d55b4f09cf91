// bench --sweep's text, apart from the bench itself so that the fuzz target of the command-line
// values (tests/fuzz/fuzz_cli_values.cpp) links it alone.
#include <algorithm>
#include <sstream>

#include "app/commands/bench_command.h"
#include "app/config/input_error.h"

namespace tallow::app {

Sweep parseSweep(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos) throw InputError("--sweep: expected key=v1,v2,... but got " + quote(text));
  Sweep s;
  s.key = text.substr(0, eq);
  if (s.key.empty()) throw InputError("--sweep: no key before '=' in " + quote(text));
  std::stringstream values(text.substr(eq + 1));
  std::string v;
  while (std::getline(values, v, ',')) s.values.push_back(v);
  if (!text.empty() && text.back() == ',') s.values.push_back("");
  if (s.values.empty() || std::any_of(s.values.begin(), s.values.end(), [](const std::string& x) { return x.empty(); }))
    throw InputError("--sweep: " + s.key + ": give one or more values, separated by commas");
  if (s.key == "method") throw InputError("--sweep: method: list the methods with --methods");
  s.knob = (s.key.rfind("sss.", 0) == 0 && s.key != "sss.model") || s.key.rfind("vpl.", 0) == 0 ||
           s.key.rfind("image_space.", 0) == 0 || s.key.rfind("sslpv.", 0) == 0;
  return s;
}

}  // namespace tallow::app
