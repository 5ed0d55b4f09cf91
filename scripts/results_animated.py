#!/usr/bin/env python3
"""Issue 17, point 5: the animated candle (the default preset) before and after issue 17. The candle
played from t0 at a fixed frame rate, every frame at a new time (the field and the flame's light
move; the before build restarts the maps every frame, the after build's defaults keep each texel's
history, sss.history), each frame against `tallow reference` at its own time: relative RMSE, the
bias of the wax's upper and lower half, fireflies (and the reference's own), wall time per frame;
then the new build again with N raised until a frame costs what the old build's did, for the error
at equal wall time. The docs/RESULTS.md section they become.

"Before" is the build of BEFORE_COMMIT, the last commit before issue 17's first change (the
paper's estimator per colour band, no second density for point lights, K = 16, 512² maps): the run
step builds it in DIR/before (a git worktree and a build of the `tallow` target; minutes, and once:
the build is kept) unless TALLOW_BEFORE names such a binary. Every frame of every row is measured
the same way, by this build's `tallow compare --json` against the frame's reference.

  results_animated.py run DIR [--quick]   references, builds and captures into DIR (TALLOW: this build's binary)
  results_animated.py report DIR MD       appends the section to MD
  results_animated.py splice DIR MD       replaces the section in MD (or adds it before the GPU section)

Called by scripts/results.sh (run, report). Every number comes from the captures' stats.json and
the compare JSON files.
"""
import json
import os
import statistics
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import results_sections  # noqa: E402
from results_sections import fmt, pct  # noqa: E402

HEADING = "## The animated candle before and after (issue 17, point 5)"
BEFORE_COMMIT = "8b53692"
PRESET, T0, FPS, FRAMES = "candle", 12.0, 8.0, 8
SIZE = "320x180"
# The references' relative standard error: their own noise adds to every row's error in quadrature, so
# it is kept well under the after rows' (4-5% against 2%-references on 2026-12-03).
REF_REL_ERROR = "0.01"
SAMPLES = 8  # sss.samples, the default, of the first after rows
FIREFLY_FACTOR = 4  # gpu::kFireflyFactor: a channel above 4× its 5×5 median
# Rows: (name, binary "before"/"after", extra settings). The equal-time row is added by run().
ROWS = (("before", "before", []),
        ("after, K = 16", "after", ["sss.maps=16"]),
        ("after, restart (sss.history = 0)", "after", ["sss.history=0"]),
        ("after (defaults)", "after", []))


def times(frames):
    return [T0 + i / FPS for i in range(frames)]


def root():
    return os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def before_binary(work):
    given = os.environ.get("TALLOW_BEFORE")
    if given:
        return given
    src, build = os.path.join(work, "before", "src"), os.path.join(work, "before", "build")
    binary = os.path.join(build, "tallow")
    if os.path.exists(binary):
        return binary
    if not os.path.exists(src):
        subprocess.run(["git", "-C", root(), "worktree", "add", "--detach", "-f", src, BEFORE_COMMIT], check=True)
    env = dict(os.environ, TALLOW_BUILD_DIR=build, TALLOW_BUILD_TARGETS="tallow")
    subprocess.run(["bash", os.path.join(src, "scripts", "build.sh")], check=True, env=env, stdout=subprocess.DEVNULL)
    return binary


def row_dir(work, name):
    return os.path.join(work, "rows", name.replace(" ", "_").replace(",", "").replace("(", "").replace(")", "").replace("=", ""))


def capture(binary, work, name, sets, size, frames):
    """Captures a row; the before build, in its own worktree, is pointed at this checkout's data."""
    out = row_dir(work, name)
    args = [binary, "capture", "--preset", PRESET, "--size", size, "--time", repr(T0), "--fps", repr(FPS),
            "--frames", str(frames), "--set", "render.flame=false", "--exr-float", "--out", out]
    for s in sets:
        args += ["--set", s]
    os.environ.setdefault("TALLOW_DATA_DIR", os.path.join(os.path.dirname(root()), "shared", "data"))
    results_sections.run_once(args, os.path.join(out, "stats.json"), quiet=True)
    return out


def compare_frames(binary, work, out, frames):
    for i in range(frames):
        ref = os.path.join(work, "ref_%d.exr" % i)
        result = os.path.join(out, "error_%04d.json" % i)
        results_sections.run_once([binary, "compare", os.path.join(out, "frame_%04d.exr" % i), ref,
                                   "--mask", os.path.join(work, "ref_%d_stderr.exr" % i), "--json", result],
                                  result, quiet=True)


def wall_per_frame(out):
    with open(os.path.join(out, "stats.json")) as f:
        frames = json.load(f)["frames"]
    # The first frame also compiles and allocates; the others are what playing costs.
    return statistics.median(f["wall_ms"] for f in frames[1:])


def run(work, quick):
    os.makedirs(work, exist_ok=True)
    binary = os.environ.get("TALLOW", "tallow")
    frames = 3 if quick else FRAMES
    size = "96x54" if quick else SIZE
    for i, t in enumerate(times(frames)):
        ref = os.path.join(work, "ref_%d.exr" % i)
        results_sections.run_once([binary, "reference", "--preset", PRESET, "--size", size, "--time", repr(t),
                                   *(["--spp", "2"] if quick else ["--rel-error", REF_REL_ERROR]), "--out", ref],
                                  ref, quiet=True)
    before = before_binary(work)
    walls = {}
    for name, which, sets in ROWS:
        out = capture(before if which == "before" else binary, work, name, sets, size, frames)
        compare_frames(binary, work, out, frames)
        walls[name] = wall_per_frame(out)
    n, guess = equal_time_samples(binary, work, walls, size, frames)
    name = "after, N = %d (equal time)" % n
    out = capture(binary, work, name, ["sss.samples=%d" % n], size, frames)
    compare_frames(binary, work, out, frames)
    with open(os.path.join(work, "equal_time.json"), "w") as f:
        json.dump({"name": name, "samples": n, "first_guess": guess}, f)


def equal_time_samples(binary, work, walls, size, frames):
    """N at which a frame with the defaults costs what a frame before did. The time per frame is about
    a fixed part plus one proportional to N: a first guess scales N by the time ratio as if all of it
    were proportional (too few samples, since the fixed part does not grow), then the line through the
    defaults' time and the guess's gives N, rounded down so that the after row never has more time.
    Returns (N, first guess)."""
    base = walls["after (defaults)"]
    guess = max(SAMPLES + 1, round(SAMPLES * walls["before"] / base))
    probe = capture(binary, work, "equal time, first guess", ["sss.samples=%d" % guess], size, frames)
    per_sample = (wall_per_frame(probe) - base) / (guess - SAMPLES)
    if per_sample <= 0.0:
        return guess, guess
    return max(1, int(SAMPLES + (walls["before"] - base) / per_sample)), guess




def load_row(work, name):
    out = row_dir(work, name)
    with open(os.path.join(out, "stats.json")) as f:
        stats = json.load(f)
    errors = []
    for i in range(len(stats["frames"])):
        with open(os.path.join(out, "error_%04d.json" % i)) as f:
            errors.append(json.load(f)["error"])
    return stats, errors


CHANNELS = ("red", "green", "blue")


def span(values, digits):
    """'a' or 'a–b' for the range of values, at the given digits."""
    lo, hi = "%.*f" % (digits, min(values)), "%.*f" % (digits, max(values))
    return lo if lo == hi else "%s–%s" % (lo, hi)


def add_extra_fireflies(stats, errors, add):
    """The row's fireflies at pixels where the reference has none (`tallow compare --json`'s
    fireflies_not_in_reference), by pixel and channel: in which frames (with their K), how far over the
    reference it is there, and how near the reference itself came to the threshold there (noise, or a
    feature at it)."""
    maps = [(f.get("sss") or {}).get("maps", "?") for f in stats["frames"]]
    by_pixel = {}
    for frame, e in enumerate(errors):
        for f in e.get("fireflies_not_in_reference") or []:
            by_pixel.setdefault((f["x"], f["y"], f["channel"]), []).append((frame, f))
    if not by_pixel:
        return
    for (x, y, c), seen in sorted(by_pixel.items(), key=lambda item: (-len(item[1]), item[0])):
        refs = [f["reference_over_median"] for _, f in seen if f.get("reference_over_median") is not None]
        overs = [f["over_reference"] for _, f in seen if f.get("over_reference") is not None]
        add("  - defaults, pixel (%d, %d), %s, frame(s) %s (K %s): %s× the reference there; the reference's own ratio"
            " to its 5×5 median there %s (a firefly above %g)." % (
                x, y, CHANNELS[c], ", ".join(str(i) for i, _ in seen),
                ", ".join(str(maps[i]) if i < len(maps) else "?" for i, _ in seen), span(overs, 2) if overs else "—",
                span(refs, 2) if refs else "—", FIREFLY_FACTOR))


def section(work):
    with open(os.path.join(work, "equal_time.json")) as f:
        equal = json.load(f)
    names = [r[0] for r in ROWS] + [equal["name"]]
    rows = {name: load_row(work, name) for name in names}
    lines = []
    add = lines.append
    add(HEADING)
    add("")
    stats0 = rows[names[1]][0]
    add("The default preset, the candle, played from t₀ = %g s at %g frames per second for %d frames at %s, every"
        % (T0, FPS, len(stats0["frames"]), "×".join(SIZE.split("x"))))
    add("frame at a new time (the field and the flame's light move: the before build restarts the maps at every")
    add("frame, the after build keeps each texel's history by default, `sss.history` = 8 rescaled on one diffusion")
    add("length, `sss.history_rescale` = 1, and restarts them in the row with `sss.history = 0`), the flame")
    add("itself not drawn (the reference has none); each frame against `tallow reference` at its own time (ε %s)."
        % pct(float(REF_REL_ERROR)))
    add("Before: the build of `%s`, the last commit before issue 17 (the paper's estimator per colour band, no"
        % BEFORE_COMMIT)
    add("second density for point lights, K = 16, 512² maps). After: this build, with K = 16 and with its")
    add("defaults (`sss.maps=auto`, sizes `auto`, `sss.point_share` 0.25), then with N raised until a frame costs")
    add("what a frame before did (equal wall time: a first guess N = %d scaled by the time ratio, then the N on the"
        % equal["first_guess"])
    add("line through the defaults' and the guess's time per frame, rounded down). Every frame is measured by this")
    add("build's `tallow compare --json`.")
    add("Medians over the frames; the wall time leaves out the first frame (compiling, allocating). Device `%s`."
        % stats0.get("gl", {}).get("GL_RENDERER", "?"))
    add("Upper / lower: the mean over the upper or lower half of the wax's pixels against the reference's (the")
    add("lower wall is lit only through the cup); fireflies: wax pixels with a channel above 4× its 5×5 median.")
    add("")
    add("| row | N | K | rel. RMSE | upper / lower | fireflies (reference) | wall per frame [ms] |")
    add("|---|---:|---:|---:|---:|---:|---:|")
    summary = {}
    for name in names:
        stats, errors = rows[name]
        med = lambda key: statistics.median(e[key] for e in errors if e.get(key) is not None)
        wall = statistics.median(f["wall_ms"] for f in stats["frames"][1:])
        k = statistics.median((f.get("sss") or {}).get("maps", 16) for f in stats["frames"])
        n = stats.get("parameters", {}).get("sss.samples", SAMPLES)
        summary[name] = {"rel": med("rel_rmse"), "upper": med("upper_mean_ratio"), "lower": med("lower_mean_ratio"),
                         "ff": med("fireflies"), "rff": med("reference_fireflies"), "wall": wall}
        s = summary[name]
        add("| %s | %s | %g | %s | %s / %s | %g (%g) | %.0f |" % (name, n, k, pct(s["rel"]), fmt(s["upper"]),
                                                                 fmt(s["lower"]), s["ff"], s["rff"], s["wall"]))
    add("")
    before, after, eq = summary["before"], summary["after (defaults)"], summary[equal["name"]]
    add("- Lower-wall bias within 5%% of the reference: before %s, after %s (%s)." % (
        fmt(before["lower"]), fmt(after["lower"]), "met" if abs(after["lower"] - 1.0) <= 0.05 else "not met"))
    add("- No more fireflies than the reference's own: after %g against %g (%s)." % (
        after["ff"], after["rff"], "met" if after["ff"] <= after["rff"] else "not met"))
    add_extra_fireflies(*rows["after (defaults)"], add)
    restart = summary["after, restart (sss.history = 0)"]
    add("- The maps kept while the candle melts (issue 17, point 3): relative RMSE %s with the defaults against %s"
        " restarting at every frame (%.2f×), lower wall %s against %s, at %.0f against %.0f ms a frame." % (
            pct(after["rel"]), pct(restart["rel"]), restart["rel"] / after["rel"], fmt(after["lower"]),
            fmt(restart["lower"]), after["wall"], restart["wall"]))
    add("- With the defaults alone (N = %d): %s against %s before, %.2f× lower in %.0f%% of the wall time." % (
        SAMPLES, pct(after["rel"]), pct(before["rel"]), before["rel"] / after["rel"], 100.0 * after["wall"] / before["wall"]))
    ratio = before["rel"] / eq["rel"]
    add("- At equal wall time (%.0f ms before, %.0f ms after with N = %d), relative RMSE %s before against %s after:"
        " %.2f× lower (target 3×: %s)." % (before["wall"], eq["wall"], equal["samples"], pct(before["rel"]),
                                           pct(eq["rel"]), ratio, "met" if ratio >= 3.0 - 1e-9 else "not met"))
    add("")
    add(results_sections.rerun("results_animated.py"))
    add("")
    return lines


if __name__ == "__main__":
    results_sections.main(sys.argv[1:], __doc__, run, section, HEADING)
