#pragma once
// Plots through gnuplot when it is installed (`probe profile`, `bench`, `compare`), safely: gnuplot
// is started without a shell (app/commands/subprocess.h) in the plots' folder, and the script names
// no path of the user's — data and drawings live under names of ours, in that folder or in a private
// temporary folder inside it (gpu::PrivateFolder: random name, mode 0700) — while every text of the
// user's (a caption, a title, a preset's name) is a single-quoted literal, in which gnuplot expands
// nothing (no `command`, no @macro, no backslash escape). gnuplot draws into the private folder and
// each picture is renamed onto its name only when gnuplot succeeded, so a reader never sees a partial
// PNG; the private folder is removed on every way out.
#include <cstdio>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "gpu/atomic_file.h"

namespace tallow::app {

/// Whether `gnuplot` is on PATH.
bool gnuplotAvailable();

/// `text` as a gnuplot string literal in single quotes, in which gnuplot performs no substitution
/// (its manual, "quote marks" and "substitution"): a quote is doubled, and each control character
/// (a newline would end the command and start another) becomes a space.
std::string gnuplotString(std::string_view text);

/// One gnuplot run drawing into `folder`.
class GnuplotRun {
 public:
  /// Creates the private folder in `folder` (which must exist). Throws std::runtime_error.
  explicit GnuplotRun(const std::filesystem::path& folder);
  ~GnuplotRun();
  GnuplotRun(const GnuplotRun&) = delete;
  GnuplotRun& operator=(const GnuplotRun&) = delete;

  /// A data file of ours in the private folder (`name` of [a-z0-9_.] only): where to write it.
  std::filesystem::path dataPath(std::string_view name) const;
  /// The same file as the script names it: a literal relative to the plots' folder.
  std::string dataLiteral(std::string_view name) const;

  /// The script's body; for each output the name of the gnuplot variable that holds the file to
  /// draw it into (`set output output_0`).
  using ScriptWriter = std::function<void(std::FILE*, const std::vector<std::string>& outputVariables)>;

  /// Writes the script (a preamble that reads comma-separated data and draws 900x600 PNGs, a line
  /// per output that sets its variable to the output's own name unless it is set already, then the
  /// lines `writeScript` prints), runs gnuplot on it in the plots' folder with each variable set to a
  /// file of the private folder, and renames those onto `outputs` (file names in the plots' folder).
  /// With `keptScript` ("speed_error.gp") the script is kept beside them: `gnuplot speed_error.gp`
  /// run in that folder redraws the plots. Returns true; without gnuplot on PATH, prints one note
  /// ("wrote the CSV files without plots"), writes nothing and returns false. Throws
  /// std::runtime_error("gnuplot failed to draw " + what + ": " + gnuplot's last message) when gnuplot
  /// fails (nothing is renamed).
  bool draw(const ScriptWriter& writeScript, const std::vector<std::string>& outputs, const std::string& what,
            const std::string& keptScript = "");

 private:
  std::filesystem::path folder_;
  std::unique_ptr<gpu::PrivateFolder> private_;
};

}  // namespace tallow::app
