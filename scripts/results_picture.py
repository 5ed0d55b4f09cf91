#!/usr/bin/env python3
"""Issue 36: the clean picture measured. Three kinds of runs:

- `tallow capture` of the default candle at 480x270 as the README's still (16 renders a frame), once
  as it is (render.aa=16, the glare and the local exposure on) and once with render.aa=1,
  render.bloom=0 and render.local_exposure=0: the cost of the still's average (camera.still), of the
  glare (camera.bloom) and of the local exposure (camera.local_exposure) per frame, as the ratio of
  the frame to the frame without that pass in the same run (medians over the frames), the two
  radiances' difference in false colour (`tallow compare`) and the two PNGs as shown;
- the GL tests that measure against independent answers (tests/still_average_gltest.cpp: the
  sphere's edges against the analytic box filter, the reference's box filter, the candle's edges
  against the 4x4-supersampled frame; tests/bloom_gltest.cpp: the flux and the flame's ring;
  tests/output_dither_test.cpp: the dithered mean; tests/local_exposure_gltest.cpp: the lift of
  uniform and textured regions against their analytic answer; tests/default_picture_gltest.cpp: the
  default PNG's hue, white and dark pixels and the table's glow), whose printed figures the section
  quotes;
- the speckles at the defaults: `tallow reference` of the candle at 160x90, t = 16 s, 1024 passes,
  against a capture of the same frame as the README's still (16 renders), both without the flame's
  sheet and the VPLs (as results_animated.py's references: the reference draws neither); `tallow
  compare --json` counts the fireflies of each on the wax (a channel above 4x its 5x5 median) and
  names those where the reference has none.

  results_picture.py run DIR [--quick]     runs into DIR (TALLOW: the binary; TALLOW_GLTESTS,
                                           TALLOW_TESTS: the test binaries); --quick: 1 frame
  results_picture.py report DIR MD         appends the section to MD
  results_picture.py splice DIR MD         replaces the section in MD (or adds it before the GPU section)

Called by scripts/results.sh (run, report). Standard library only (and gnuplot, through compare).
"""
import json
import os
import re
import shutil
import statistics
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import results_sections  # noqa: E402
from results_sections import fmt  # noqa: E402

HEADING = "## The clean picture (issue 36)"
CHANNELS = ("red", "green", "blue")
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SIZE = "480x270"
FRAMES, QUICK_FRAMES = 3, 1
CASES = {"on": [], "off": ["--set", "render.aa=1", "--set", "render.bloom=0", "--set", "render.local_exposure=0"]}
TESTS = {"gltests": ("TALLOW_GLTESTS", "build/tests/tallow_gltests",
                     "StillAverage.*:Bloom.*:LocalExposureGL.*:DefaultPicture.*"),
         "tests": ("TALLOW_TESTS", "build/tests/tallow_tests", "OutputDither.*")}
# The speckles' frame (issue 36: 160x90 against a 1024-pass reference).
SPECKLE_SIZE, SPECKLE_TIME, SPECKLE_PASSES, QUICK_SPECKLE_PASSES = "160x90", "16", "1024", "16"
SPECKLE_SETS = ["--set", "render.flame=false", "--set", "vpl.count=0"]
FIGURE = "picture_aa_bloom.png"
SHOWN = {"off": "picture_shown_before.png", "on": "picture_shown_after.png"}


def run(work, quick):
    os.makedirs(work, exist_ok=True)
    tallow = os.environ.get("TALLOW", "build/tallow")
    frames = QUICK_FRAMES if quick else FRAMES
    for name, sets in CASES.items():
        out = os.path.join(work, name)
        # Frames 1 ms apart: each a new time, so each restarts the maps and the still (16 renders).
        results_sections.run_once([tallow, "capture", "--preset", "candle", "--size", SIZE, "--accumulate", "16",
                                   "--frames", str(frames), "--fps", "1000", "--out", out] + sets,
                                  os.path.join(out, "stats.json"), quiet=True)
    figure = os.path.join(work, FIGURE)
    results_sections.run_once([tallow, "compare", os.path.join(work, "off", "frame_0000.exr"),
                               os.path.join(work, "on", "frame_0000.exr"), "--out", figure, "--exposure-ev", "-1",
                               "--caption", "render.aa=1, render.bloom=0", "--caption", "the candle preset (aa 16, bloom 0.6)",
                               "--title", "The default candle, a still of 16 renders at 480x270"], figure, quiet=True)
    speckles = os.path.join(work, "speckles")
    os.makedirs(speckles, exist_ok=True)
    ref = os.path.join(speckles, "reference.exr")
    results_sections.run_once([tallow, "reference", "--preset", "candle", "--size", SPECKLE_SIZE, "--time", SPECKLE_TIME,
                               "--spp", QUICK_SPECKLE_PASSES if quick else SPECKLE_PASSES, "--out", ref] + SPECKLE_SETS,
                              ref, quiet=True)
    still = os.path.join(speckles, "still")
    results_sections.run_once([tallow, "capture", "--preset", "candle", "--size", SPECKLE_SIZE, "--time", SPECKLE_TIME,
                               "--accumulate", "16", "--exr-float", "--out", still] + SPECKLE_SETS,
                              os.path.join(still, "stats.json"), quiet=True)
    errors = os.path.join(speckles, "error.json")
    results_sections.run_once([tallow, "compare", os.path.join(still, "frame_0000.exr"), ref, "--mask",
                               os.path.join(speckles, "reference_stderr.exr"), "--json", errors], errors, quiet=True)
    for name, (variable, default, pattern) in TESTS.items():
        log = os.path.join(work, name + ".log")
        if os.environ.get("TALLOW_RESULTS_RESUME") == "1" and os.path.exists(log):
            continue
        binary = os.environ.get(variable, default)
        print("results:", binary, "--gtest_filter=" + pattern, flush=True)
        result = subprocess.run([binary, "--gtest_filter=" + pattern], capture_output=True, text=True)
        if result.returncode != 0:
            sys.exit("results_picture: %s failed:\n%s" % (binary, result.stdout[-2000:]))
        with open(log + ".tmp", "w") as f:
            f.write(result.stdout)
        os.replace(log + ".tmp", log)


def pass_ratio(stats, name):
    """Median over frames of the frame's GPU time over the same frame without pass `name`."""
    ratios = []
    for frame in stats["frames"]:
        total, part = frame["gpu_total_ms"], frame["gpu_ms"].get(name)
        if total and part is not None and total > part:
            ratios.append(total / (total - part))
    return statistics.median(ratios) if ratios else None


def ratio(value):
    """'1.23x', or 'above' for a ratio to 0 (JSON null)."""
    return "%.2fx" % value if value is not None else "above"


def printed(log, pattern):
    """The numbers of the first line of a test log that matches `pattern` (a regex with groups)."""
    with open(log) as f:
        for line in f:
            m = re.search(pattern, line)
            if m:
                return [float(g) for g in m.groups()]
    raise ValueError("%s: no line matches %s" % (log, pattern))


def section(work):
    with open(os.path.join(work, "on", "stats.json")) as f:
        on = json.load(f)
    with open(os.path.join(work, "off", "stats.json")) as f:
        off = json.load(f)
    gl = os.path.join(work, "gltests.log")
    sphere = printed(gl, r"sphere, (\d+) edge pixels: mean \|error\| vs the box filter ([\d.]+) at the centres, ([\d.]+)")
    reference = printed(gl, r"reference, (\d+) edge pixels: mean \|error\| vs the box filter ([\d.]+) \(centre\), ([\d.]+)")
    candle = printed(gl, r"candle \(albedo\) at 240x135, (\d+) edge pixels: mean error vs 960x540 boxed 4x4 ([\d.]+) at the "
                         r"centres, ([\d.]+)")
    ring = printed(gl, r"(\d+) flame pixels; the (\d+) pixels 2-8 px outside brighten by ([\d.]+) with the preset's "
                       r"render.bloom, ([\d.]+) without")
    dither = [printed(os.path.join(work, "tests.log"), r"level ([\d.]+): mean byte ([\d.]+)")]
    lift = printed(gl, r"s ([\d.]+): the dark side ([\d.]+) stops under mid grey lifted ([\d.]+) stops \(worst interior "
                       r"error ([\d.e+-]+)\), within 3 px of the edge at least ([\d.]+); the bright side changed by at "
                       r"most ([\d.e+-]+)")
    texture = printed(gl, r"checkerboard 8 stops down, s ([\d.]+): lifted ([\d.]+) stops on average, neighbours "
                          r"([\d.]+) to ([\d.]+) stops apart after \(a global curve of that strength: ([\d.]+)\)")
    edge = printed(gl, r"an anti-aliased edge, 10 stops, s ([\d.]+): the blended column within ([\d.]+) of the blend "
                       r"of its two sides as shown; (\d+) pixels outside them")
    picture = printed(gl, r"default candle (\d+)x(\d+): (\d+) wax pixels, (\d+) lit: median hue ([\d.]+) deg, value "
                          r"([\d.]+), (\d+) white; (\d+) dark dots; the table under it: brightest tenth from ([\d.]+) "
                          r"\((\d+) pixels\)")
    with open(os.path.join(work, "speckles", "error.json")) as f:
        speckles = json.load(f)["error"]
    still = pass_ratio(on, "camera.still")
    bloom = pass_ratio(on, "camera.bloom")
    local = pass_ratio(on, "camera.local_exposure")
    frame_on = statistics.median(f["gpu_total_ms"] for f in on["frames"])
    frame_off = statistics.median(f["gpu_total_ms"] for f in off["frames"])
    renderer = on.get("gl", {}).get("GL_RENDERER", "?")
    images = os.path.join(ROOT, "docs", "images", "results")
    os.makedirs(images, exist_ok=True)
    shutil.copyfile(os.path.join(work, FIGURE), os.path.join(images, FIGURE))
    for name, figure in SHOWN.items():
        shutil.copyfile(os.path.join(work, name, "frame_0000.png"), os.path.join(images, figure))

    lines = [HEADING, ""]
    lines.append(results_sections.generated_line("results_picture.py", "`tallow capture` and GL-test", [on, off]))
    lines.append("")
    lines.append("**Anti-aliased stills** (`render.aa`, docs/presets.md). Mean |error| over the edge pixels against "
                 "an independent box filter, a pixel centre against a still:")
    lines.append("")
    lines.append("| measurement | edge pixels | at the pixel centres | as a still | ratio |")
    lines.append("|---|---:|---:|---:|---:|")
    lines.append("| the Lambertian sphere, 32x32, 16 jittered frames, against the analytic box filter (linear) | %d | %s | %s | %.2fx |"
                 % (sphere[0], fmt(sphere[1], 4), fmt(sphere[2], 4), sphere[2] / sphere[1]))
    lines.append("| `tallow reference` on the sphere, 64 passes, `--pixel-filter centre` / `box` (linear) | %d | %s | %s | %.2fx |"
                 % (reference[0], fmt(reference[1], 4), fmt(reference[2], 4), reference[2] / reference[1]))
    lines.append("| the default candle (method=albedo, no flame), 240x135 against 960x540 box-filtered 4x4 in linear light (sRGB units; issue 36's bound 0.047) | %d | %s | %s | %.2fx |"
                 % (candle[0], fmt(candle[1], 4), fmt(candle[2], 4), candle[2] / candle[1]))
    lines.append("")
    lines.append("**Speckles** at the defaults: the candle at %s, t = %s s, as the README's still (16 renders), "
                 "against `tallow reference` with %s passes (both without the flame's sheet and the VPLs): %d "
                 "fireflies on the wax against the reference's own %d (issue 36's bound: the reference's + 2), "
                 "relative RMSE %s%%."
                 % (SPECKLE_SIZE, SPECKLE_TIME, SPECKLE_PASSES, speckles["fireflies"], speckles["reference_fireflies"],
                    fmt(100 * speckles["rel_rmse"], 2)))
    extra = speckles.get("fireflies_not_in_reference") or []
    if extra:
        lines.append("Where the reference has none: " + "; ".join(
            "(%d, %d) %s, %s its 5x5 median and %s the reference there (the reference's own ratio to its "
            "median %s)" % (f["x"], f["y"], CHANNELS[f["channel"]], ratio(f["over_median"]), ratio(f["over_reference"]),
                            ratio(f["reference_over_median"]))
            for f in extra) + ".")
    lines.append("")
    lines.append("**Cost** on %s, the README's still (16 renders a frame) of the default candle at %s, medians over "
                 "%d frame(s) of one run: the frame takes %.4fx the frame without its `camera.still` pass, %.4fx "
                 "the frame without its `camera.bloom` pass and %.4fx the frame without its `camera.local_exposure` "
                 "pass (GPU time, per-pass timer queries). The run without the three (render.aa=1, render.bloom=0, "
                 "render.local_exposure=0) took %.0f ms a frame against %.0f ms: the two "
                 "runs differ by more than the passes (the maps' noise and their K chosen from the coverage), so "
                 "the ratio within one run is the cost."
                 % (renderer, SIZE, len(on["frames"]), still or float("nan"), bloom or float("nan"),
                    local or float("nan"), frame_off, frame_on))
    lines.append("")
    lines.append("**Glare** (`render.bloom`, the candle 0.6 of the light above white): the %d pixels 2–8 px outside the "
                 "flame's own %d (640x360) brighten by %s in sRGB with the flame lit, against %s without the glare "
                 "(issue 36's bound: 0.02); the flux of the picture is kept within 1%% (the test's bound)."
                 % (ring[1], ring[0], fmt(ring[2], 4), fmt(ring[3], 4)))
    lines.append("")
    lines.append("**Dither** of 8-bit output: a uniform image between two levels is written with the mean level "
                 "%s for %s (undithered rounding: %d)." % (fmt(dither[0][1], 4), fmt(dither[0][0], 2), round(dither[0][0])))
    lines.append("")
    lines.append("**Local exposure** (`render.local_exposure`, the candle 0.85): a uniform region %s stops under mid "
                 "grey is lifted by s times that, %s stops at s = %s (worst error inside %s, analytic), %s stops "
                 "or more within 3 px of a 10-stop edge (no halo: the bright side's base is kept out), the bright "
                 "side unchanged (at most %s); a 1-stop checkerboard 8 stops down is lifted %s stops on average "
                 "(expected s x 8 = %s) and neighbours stay %s to %s stops apart (a global curve of that strength "
                 "would leave %s); a column blended from both sides of a 10-stop edge, as the still's anti-aliasing "
                 "blends the wax's silhouette with the table, shows the blend of what its two sides show within %s "
                 "(relative), %d of its pixels darker or brighter than both sides."
                 % (fmt(lift[1], 3), fmt(lift[2], 4), fmt(lift[0], 2), "%.1e" % lift[3], fmt(lift[4], 4),
                    "%.1e" % lift[5], fmt(texture[1], 3), fmt(8 * texture[0], 3), fmt(texture[2], 3),
                    fmt(texture[3], 3), fmt(texture[4], 2), fmt(edge[1], 4), edge[2]))
    lines.append("")
    lines.append("**The default PNG** (%dx%d, tests/default_picture_gltest.cpp): of %d wax pixels %d are lit, their "
                 "median hue %s° (issue 36: 22–38°), value %s, %d white; %d dark single-pixel dots on the wax (bound "
                 "2); the brightest tenth of the table under the candle at %s (%d pixels; issue 36's bound 0.25, "
                 "0.076 when the issue was filed, before the local exposure)."
                 % (picture[0], picture[1], picture[2], picture[3], fmt(picture[4], 1), fmt(picture[5], 2),
                    picture[6], picture[7], fmt(picture[8], 3), picture[9]))
    lines.append("")
    lines.append("| render.aa=1, render.bloom=0, render.local_exposure=0 | the candle preset |")
    lines.append("|---|---|")
    lines.append("| ![before](images/results/%s) | ![after](images/results/%s) |" % (SHOWN["off"], SHOWN["on"]))
    lines.append("")
    lines.append("![the default candle without and with render.aa](images/results/%s)" % FIGURE)
    lines.append("")
    lines.append("Compared on the EXRs (the radiance, which holds no glare), in false colour: what the still's "
                 "average changes: the silhouettes, the rim and the table's far edge (anti-aliasing) and the maps' "
                 "noise, which differs from run to run and which the still's average of 16 frames lowers.")
    lines.append("")
    lines.append(results_sections.rerun("results_picture.py"))
    lines.append("")
    return lines


if __name__ == "__main__":
    results_sections.main(sys.argv[1:], __doc__, run, section, HEADING)
