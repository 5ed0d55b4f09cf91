#pragma once
// Plots through gnuplot when it is installed (`probe profile`, `bench`): the script is written
// into the output folder, gnuplot draws into temporary files, and each is renamed onto its final
// name only when gnuplot succeeded, so a reader never sees a partial PNG.
#include <cstdio>
#include <filesystem>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace tallow::app {

/// Whether `gnuplot` is on PATH.
bool gnuplotAvailable();

/// A plot gnuplot writes to `temporary`, renamed to `final` on success.
struct PlotOutput {
  std::filesystem::path temporary, final;
};

/// Writes the script with `writeScript` to `script`, runs gnuplot on it, removes the script unless
/// `keepScript` (to redraw the plots by hand), and renames every output. Throws
/// std::runtime_error("gnuplot failed to draw " + what) when gnuplot fails (the temporary outputs
/// removed).
void runGnuplot(const std::filesystem::path& script, const std::function<void(std::FILE*)>& writeScript,
                const std::vector<PlotOutput>& outputs, const std::string& what, bool keepScript = false);

}  // namespace tallow::app
