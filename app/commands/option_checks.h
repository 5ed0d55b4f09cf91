#pragma once
// Checks of command-line values that the commands share, made before any file is read for
// rendering, any GL context opens or anything is written: each throws InputError with one line
// that names the option and what is wrong with its value.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "app/config/config.h"
#include "app/config/registry.h"

namespace tallow::app {

/// Longest animation time a command accepts, the range of a preset's start_s and duration_s.
inline constexpr double kMaxTimeS = 1e6;

/// An animation time (--time): finite and within [0, kMaxTimeS] seconds, as a preset's start_s.
void checkTime(std::string_view option, double seconds);

/// The range of --fps (capture, view): below it one frame would step the clock past kMaxTimeS in
/// a few frames; above it frames would be closer than a clock of doubles keeps apart over kMaxTimeS.
inline constexpr double kMinFps = 1e-3, kMaxFps = 1e4;
/// --fps within [kMinFps, kMaxFps].
void checkFps(std::string_view option, double fps);

/// An output's name (a file, a folder or a file written beside another, REF_stderr.exr): valid
/// UTF-8 (it goes into the run's JSON), and no longer than the file system takes, each name and the
/// whole path (pathconf(3)), so that no output of a pair fails after its partner was written.
void checkOutputName(std::string_view option, const std::filesystem::path& path);

/// An output folder (--out DIR of capture, bench, probe profile): checkOutputName; a link to a
/// missing folder is refused (never removed); its nearest existing ancestor
/// must be a folder in which the rest can be created and written. Tried for real — the missing
/// folders are created and removed again, a probe file is created and removed — since access(2)
/// answers yes to root on read-only or virtual file systems (/proc), whose refusal would otherwise
/// come only when the outputs are written, after the rendering.
void checkWritableFolder(const std::filesystem::path& dir, std::string_view option = "--out");

/// An output file: checkOutputName; its folder must exist and take a new file (tried, as above), the path must
/// not be a folder, and with `extensions` given (".png", ".exr") its extension must be one of them.
void checkOutputFile(std::string_view option, const std::filesystem::path& file,
                     const std::vector<std::string>& extensions = {});

/// checkOutputFile for a file whose folder is created when it is written, as --out's (view's
/// screenshots): the folder is checked as checkWritableFolder checks --out.
void checkOutputFileInNewFolder(std::string_view option, const std::filesystem::path& file,
                                const std::vector<std::string>& extensions = {});

/// bench --methods: each a value of the registry's `method`, refused as
/// `--methods: unknown method "radiosity-map" (did you mean "radiosity-maps"?)`.
void checkMethods(const Registry& registry, const std::vector<std::string>& methods);

/// One value of a bench --sweep (the option's text `sweepText`, "key=v1,v2"): the key and value
/// through the registry on a copy of `config`, refused under the option the user typed, e.g.
/// `--sweep sss.mpas=1,2: unknown parameter "sss.mpas" (did you mean "sss.maps"?)`.
void checkSweepValue(const Registry& registry, const Config& config, std::string_view sweepText, std::string_view key,
                     std::string_view value);

}  // namespace tallow::app
