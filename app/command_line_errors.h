#pragma once
// The line `tallow` prints for a command line CLI11 cannot parse: a mistyped subcommand or option
// gets the closest existing name (`unknown command "captur" (did you mean "capture"?)`,
// `capture: unknown option "--presets" (did you mean "--preset"?)`) instead of CLI11's list of
// arguments "not expected"; every other parse error keeps CLI11's own line.
#include <CLI/CLI.hpp>

#include <string>

namespace tallow::app {

/// One line (without "tallow: ") for `error`, thrown by app.parse(argc, argv).
std::string describeParseError(const CLI::App& app, const CLI::ParseError& error, int argc, char** argv);

/// The subcommand the parse selected, as typed ("capture", "probe bssrdf"); "view" when none.
std::string selectedCommandName(const CLI::App& app);

/// A CLI11 check that refuses an empty value (`--preset ""` would otherwise mean the default
/// preset, silently): `--preset: empty; give a name from presets/ or a JSON file, or leave
/// --preset out for the default`.
CLI::Validator nonEmpty(const std::string& what);

}  // namespace tallow::app
