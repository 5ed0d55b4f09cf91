#include "app/command_line_errors.h"

#include <algorithm>
#include <set>
#include <string_view>
#include <vector>

#include "app/config/input_error.h"

namespace tallow::app {
namespace {

/// The deepest subcommand the parse selected (the app itself when none).
const CLI::App* selectedCommand(const CLI::App& app) {
  const CLI::App* cmd = &app;
  for (;;) {
    const std::vector<CLI::App*> parsed = cmd->get_subcommands();
    if (parsed.empty()) return cmd;
    cmd = parsed.front();
  }
}

/// "capture" or "probe bssrdf": the words the user typed to reach `cmd`.
std::string commandPath(const CLI::App* cmd) {
  std::string path;
  for (; cmd && cmd->get_parent(); cmd = cmd->get_parent())
    path = cmd->get_name() + (path.empty() ? "" : " " + path);
  return path;
}

std::vector<std::string> optionNames(const CLI::App* cmd) {
  std::vector<std::string> names;
  for (const CLI::Option* o : cmd->get_options()) {
    for (const std::string& l : o->get_lnames()) names.push_back("--" + l);
    for (const std::string& s : o->get_snames()) names.push_back("-" + s);
  }
  return names;
}

std::vector<std::string> subcommandNames(const CLI::App* cmd) {
  std::vector<std::string> names;
  for (const CLI::App* sub : cmd->get_subcommands([](const CLI::App*) { return true; }))
    names.push_back(sub->get_name());
  return names;
}

/// The arguments the parse left over, in the order the user typed them (CLI11 collects them per
/// command, not in order).
std::vector<std::string> leftOver(const CLI::App& app, int argc, char** argv) {
  const std::vector<std::string> rest = app.remaining(true);
  std::multiset<std::string> pending(rest.begin(), rest.end());
  std::vector<std::string> ordered;
  for (int i = 1; i < argc; ++i) {
    const auto it = pending.find(argv[i]);
    if (it == pending.end()) continue;
    ordered.push_back(*it);
    pending.erase(it);
  }
  return ordered;
}

std::string unknownOption(const CLI::App& app, const CLI::App* cmd, const std::string& arg) {
  const std::string name = arg.substr(0, arg.find('='));
  std::string line = commandPath(cmd);
  line += line.empty() ? "" : ": ";
  line += "unknown option " + quote(name);
  const std::string match = closestMatch(name, optionNames(cmd));
  if (!match.empty()) return line + " (did you mean " + quote(match) + "?)";
  if (cmd == &app) {
    // Options follow a command: `tallow --preset bunny` means `tallow view --preset bunny`.
    for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
      if (closestMatch(name, optionNames(sub)) == name)
        return line + " (options follow the command, e.g. \"tallow view " + name + "\")";
  }
  return line + (cmd == &app ? "" : " (`tallow " + commandPath(cmd) + " --help` lists them)");
}

}  // namespace

std::string describeParseError(const CLI::App& app, const CLI::ParseError& error, int argc, char** argv) {
  // By type: CLI11 names an ExtrasError after the command it arose in, not after its kind.
  const bool unexpected = dynamic_cast<const CLI::ExtrasError*>(&error) != nullptr;
  const bool missing = dynamic_cast<const CLI::RequiredError*>(&error) != nullptr;
  if (!unexpected && !missing) return error.what();
  const CLI::App* cmd = selectedCommand(app);
  const std::vector<std::string> extras = leftOver(app, argc, argv);
  if (missing) {
    // `--modle standard` leaves --model missing; the misspelling is what to report.
    for (const std::string& arg : extras)
      if (arg.size() > 1 && arg[0] == '-') return unknownOption(app, cmd, arg);
    return error.what();
  }
  // A word where a command is expected: a mistyped subcommand (before any option it would take).
  const std::vector<std::string> commands = subcommandNames(cmd);
  if (!commands.empty() && !extras.empty() && extras.front().rfind('-', 0) != 0) {
    const std::string& word = extras.front();
    std::string line = commandPath(cmd);
    line += line.empty() ? "" : ": ";
    line += "unknown command " + quote(word);
    const std::string match = closestMatch(word, commands);
    if (!match.empty()) return line + " (did you mean " + quote(match) + "?)";
    std::string list;
    for (const std::string& c : commands) list += (list.empty() ? "" : ", ") + c;
    return line + "; commands: " + list;
  }
  // An unknown option; the values after it are its own, so they are not reported.
  for (const std::string& arg : extras)
    if (arg.size() > 1 && arg[0] == '-') return unknownOption(app, cmd, arg);
  if (!extras.empty()) {
    std::string line = commandPath(cmd);
    return line + (line.empty() ? "" : ": ") + "unexpected argument " + quote(extras.front()) +
           " (values follow their option, e.g. --preset bunny)";
  }
  return error.what();
}

std::string selectedCommandName(const CLI::App& app) {
  const std::string path = commandPath(selectedCommand(app));
  return path.empty() ? "view" : path;
}

CLI::Validator nonEmpty(const std::string& what) {
  return CLI::Validator(
      [what](std::string& value) { return value.empty() ? "empty; " + what : std::string(); }, "NONEMPTY");
}

}  // namespace tallow::app
