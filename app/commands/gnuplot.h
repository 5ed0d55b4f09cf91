#pragma once
// Plots through gnuplot when it is installed (`probe profile`, `bench`): the script is written
// into the output folder, gnuplot draws into temporary files, and each is renamed onto its final
// name only when gnuplot succeeded, so a reader never sees a partial PNG.
#include <cstdio>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace tallow::app {

/// Whether `gnuplot` is on PATH.
bool gnuplotAvailable();

/// `text` as a gnuplot string literal in double quotes (quotes and backslashes escaped).
std::string gnuplotString(const std::string& text);

/// Writes the script (a preamble that reads comma-separated data and draws 900x600 PNGs, then the
/// lines `writeScript` prints; it gets, for each of `outputs`, the temporary file gnuplot must draw
/// into, `.NAME.tmp` beside it) to `script`, runs gnuplot on it, removes the script unless
/// `keepScript` (to redraw the plots by hand), and renames every temporary file onto its output;
/// returns true. Without gnuplot on PATH, prints one note ("wrote the CSV files without plots"),
/// writes nothing and returns false. Throws std::runtime_error("gnuplot failed to draw " + what +
/// ": " + gnuplot's last message) when gnuplot fails (the temporary files removed).
using PlotScriptWriter = std::function<void(std::FILE*, const std::vector<std::filesystem::path>& temporaries)>;
bool runGnuplot(const std::filesystem::path& script, const PlotScriptWriter& writeScript,
                const std::vector<std::filesystem::path>& outputs, const std::string& what, bool keepScript = false);

}  // namespace tallow::app
