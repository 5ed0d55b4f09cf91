#!/usr/bin/env python3
"""Issue 17, point 3: the radiosity maps while the geometry deforms. Frame k of an animation of the
blob and of the candle against `tallow reference` at t_k, with the maps restarted at every frame
(`sss.history=0`, the paper) and kept per texel (`sss.history` > 0), and the flicker of both
(`translucent_change`, `receiver_change`); the docs/RESULTS.md section they become.

  results_history.py run DIR [--quick]     renders the references and the captures into DIR (TALLOW: the binary)
  results_history.py report DIR MD         appends the section to MD
  results_history.py splice DIR MD         replaces the section in MD (or adds it before the GPU section)

Called by scripts/results.sh (run, report). Every number comes from the stats.json of `tallow capture
--reference` runs and the references' EXR headers.
"""
import json
import os
import statistics
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import results_sections  # noqa: E402
from results_sections import fmt, pct  # noqa: E402

HEADING = "## The maps while the geometry deforms (issue 17, point 3)"
SIZE = "160x90"
FRAMES = 8
# (sss.history, sss.history_move, sss.samples, sss.history_rescale): the paper's restart; the history
# kept as it was (rescale 0, the first version, which lagged); the defaults (8 frames rescaled on one
# diffusion length); the rescale's footprint and the history's length about the defaults; then
# restart, unrescaled and default at N = 1, where one frame alone is noisy.
DEFAULT = (8, 0.5, 8, 1.0)
VARIANTS = ((0, 0.5, 8, 0.0), (8, 0.5, 8, 0.0), DEFAULT, (8, 0.5, 8, 0.5), (8, 0.5, 8, 2.0), (4, 0.5, 8, 1.0),
            (16, 0.5, 8, 1.0), (0, 0.5, 1, 0.0), (8, 0.5, 1, 0.0), (8, 0.5, 1, 1.0))
# At an interactive rate the surface and the light move less per frame, so a history lags less.
FAST_VARIANTS = ((0, 0.5, 8, 0.0), (8, 0.5, 8, 0.0), DEFAULT, (0, 0.5, 1, 0.0), (8, 0.5, 1, 1.0))
# preset, first frame's time [s], frames per second (every frame at a new time, k frames), variants.
ANIMATIONS = (("blob", 2.0, 8.0, VARIANTS), ("candle", 12.0, 4.0, VARIANTS),
              ("blob", 2.0, 30.0, FAST_VARIANTS), ("candle", 12.0, 30.0, FAST_VARIANTS))
REF_REL_ERROR = "0.02"
# K fixed: with sss.maps=auto every change of the chosen K restarts the maps (their views change), which
# on these moving scenes happened every few frames and cut the history short at random.
FIXED = ("--set", "sss.maps=16")


def times(t0, fps, frames):
    return [t0 + i / fps for i in range(frames)]


def run_dir(work, preset, fps, history, move, samples, rescale):
    name = "%s_%gfps_history_%d_move_%g" % (preset, fps, history, move)
    if history > 0:
        name += "_rescale_%g" % rescale
    return os.path.join(work, name if samples == 8 else name + "_n%d" % samples)


def reference_path(work, preset, fps):
    return os.path.join(work, "%s_%gfps_ref.exr" % (preset, fps))


def restart_of(rows, r):
    """The restarting row (sss.history 0) of r's preset, frame rate and N, or None."""
    return next((b for b in rows if b["preset"] == r["preset"] and b["fps"] == r["fps"] and b["history"] == 0 and
                 b["samples"] == r["samples"]), None)


def run(work, quick):
    os.makedirs(work, exist_ok=True)
    binary = os.environ.get("TALLOW", "tallow")
    frames = 3 if quick else FRAMES
    size = "64x36" if quick else SIZE
    for preset, t0, fps, variants in ANIMATIONS:
        tk = times(t0, fps, frames)[-1]
        ref = reference_path(work, preset, fps)
        # render.flame=false as in the captures (the reference would add the flame's reflection on the pool).
        results_sections.run_once([binary, "reference", "--preset", preset, "--size", size, "--time", repr(tk),
              "--set", "render.flame=false",
              *(["--spp", "2"] if quick else ["--rel-error", REF_REL_ERROR]), "--out", ref], ref, quiet=True)
        for history, move, samples, rescale in (variants[:3] if quick else variants):
            out = run_dir(work, preset, fps, history, move, samples, rescale)
            results_sections.run_once([binary, "capture", "--preset", preset, "--size", size, "--time", repr(t0), "--fps", repr(fps),
                  "--frames", str(frames), "--reference", ref, "--set", "sss.history=%d" % history,
                  "--set", "sss.history_move=%g" % move, "--set", "sss.samples=%d" % samples,
                  "--set", "sss.history_rescale=%g" % rescale,
                  "--set", "render.flame=false", *FIXED, "--out", out],
                 os.path.join(out, "stats.json"), quiet=True)


def median(values):
    values = [v for v in values if v is not None]
    return statistics.median(values) if values else None




def eps(text):
    try:
        return pct(float(text))
    except (TypeError, ValueError):
        return "?"


def reference_info(path):
    """spp and ε from the reference's EXR header, read by the stats' provenance-free route: the
    capture records nothing of it, so the header's text attributes are scanned."""
    info = {}
    try:
        with open(path, "rb") as f:
            head = f.read(1 << 16)
        for key in (b"tallow.spp", b"tallow.rel_error"):
            i = head.find(key + b"\0")
            if i >= 0:
                j = i + len(key) + 1
                kind_end = head.index(b"\0", j)
                size = int.from_bytes(head[kind_end + 1:kind_end + 5], "little")
                info[key.decode()] = head[kind_end + 5:kind_end + 5 + size].decode(errors="replace")
    except (OSError, ValueError):
        pass
    return info


def verdict(compared):
    """The verdict lines over (history row, its restart row) pairs: how often a kept history wins,
    by sss.history_rescale, and whether the defaults (DEFAULT) win at N = 8 in most animations."""
    if not compared:
        return []
    wins = lambda pairs: sum(1 for r, b in pairs if r["rel_rmse"] < b["rel_rmse"])
    parts = []
    for rescale in sorted({r["rescale"] for r, _ in compared}):
        pairs = [(r, b) for r, b in compared if r["rescale"] == rescale]
        parts.append("with `sss.history_rescale` = %g in %d of %d" % (rescale, wins(pairs), len(pairs)))
    default_pairs = [(r, b) for r, b in compared
                     if (r["history"], r["move"], r["samples"], r["rescale"]) == DEFAULT]
    keep = default_pairs and wins(default_pairs) * 2 > len(default_pairs)
    ratios = ", ".join("%s at %g fps %s against %s" % (r["preset"], r["fps"], pct(r["rel_rmse"]), pct(b["rel_rmse"]))
                       for r, b in default_pairs)
    return ["", "Verdict: a kept history has the lower error at frame k %s. The defaults (`sss.history` = %d, "
            "`sss.history_rescale` = %g, N = %d) against restarting: %s; they %s." % (
                "; ".join(parts), DEFAULT[0], DEFAULT[3], DEFAULT[2], ratios,
                "win in %d of %d animations, so the maps are not restarted by default" % (wins(default_pairs), len(default_pairs))
                if keep else "do not win in most animations: the default should be a restart (`sss.history` = 0)")]


def section(work):
    lines = []
    add = lines.append
    add(HEADING)
    add("")
    generated = len(lines)
    add(None)  # the "Generated" line, once the runs' dates are known
    gl = None
    rows = []
    runs = []
    for preset, t0, fps, variants in ANIMATIONS:
        ref = reference_path(work, preset, fps)
        for history, move, samples, rescale in variants:
            path = os.path.join(run_dir(work, preset, fps, history, move, samples, rescale), "stats.json")
            if not os.path.exists(path):
                continue
            with open(path) as f:
                stats = json.load(f)
            runs.append(stats)
            gl = gl or stats["gl"]
            frames = stats["frames"]
            last = frames[-1]
            err = last.get("reference_error") or {}
            rows.append({
                "preset": preset, "history": history, "move": move, "samples": samples, "rescale": rescale,
                "frames": len(frames), "t0": frames[0]["time_s"],
                "tk": last["time_s"], "fps": fps, "rel_rmse": err.get("rel_rmse"), "mean": err.get("mean_ratio"),
                "upper": err.get("upper_mean_ratio"), "lower": err.get("lower_mean_ratio"),
                "pixels": err.get("pixels"),
                "first_rel_rmse": (frames[0].get("reference_error") or {}).get("rel_rmse"),
                "translucent_change": median([f.get("translucent_change") for f in frames[1:]]),
                "receiver_change": median([f.get("receiver_change") for f in frames[1:]]),
                "wall": median([f["wall_ms"] for f in frames[1:]]),
                "maps_frames": (last.get("sss") or {}).get("frames_accumulated"),
                "ref": reference_info(ref), "size": stats["resolution"],
            })
    lines[generated] = results_sections.generated_line(
        "results_history.py", "`tallow reference` and `tallow capture --reference`", runs)
    renderer = gl.get("GL_RENDERER", "?") if gl else "?"
    add("Device: `%s`." % renderer)
    add("")
    add("Each preset is played from t₀ at a fixed frame rate, every frame at a new time (the field and, for the")
    add("candle, the flame's light move), one render per frame as in the window, the flame itself not drawn (the")
    add("reference has none, as in `tallow bench`); frame k's image is compared with")
    add("`tallow reference` at t_k (object pixels the reference marks; ε its relative standard error). `history 0`")
    add("is the paper: the maps restart at every change, so each frame is a first frame. Otherwise each map texel")
    add("keeps at most `sss.history` frames where its surface point and normal still hold")
    add("([radiosity-maps.md](radiosity-maps.md#history-while-the-geometry-moves-ssshistory-issue-17)), and with")
    add("`sss.history_rescale` > 0 what it keeps is rescaled band by band to this frame's estimate on a footprint of")
    add("that many diffusion lengths (at least 8×8 texels), so that it follows a light that moves. Flicker:")
    add("the median over frames 2…k of the translucent pixels' and the receivers' mean absolute frame-to-frame")
    add("change relative to their mean (part of it is the motion itself, the same for every row of a preset).")
    add("K is fixed at 16 (`sss.maps=16`): with `auto`, every change of the chosen K restarts the maps, which on")
    add("these moving scenes cut the history short every few frames. F at k: the frames the maps held at frame k.")
    add("")
    add("| preset | size | fps | t₀ → t_k [s] | k | N | sss.history | sss.history_move | sss.history_rescale | F at k | frame k rel. RMSE | frame 1 rel. RMSE | mean ratio (upper / lower) | translucent change | receiver change | wall [ms] | reference |")
    add("|---|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---|---:|---:|---:|---|")
    for r in rows:
        ref = r["ref"]
        add("| %s | %d×%d | %g | %.3g → %.3g | %d | %d | %d | %s | %s | %s | %s | %s | %s (%s / %s) | %s | %s | %s | %s spp, ε %s |" % (
            r["preset"], r["size"][0], r["size"][1], r["fps"], r["t0"], r["tk"], r["frames"], r["samples"], r["history"],
            "—" if r["history"] == 0 else "%g" % r["move"], "—" if r["history"] == 0 else "%g" % r["rescale"],
            r["maps_frames"] if r["maps_frames"] is not None else "—", pct(r["rel_rmse"]), pct(r["first_rel_rmse"]),
            fmt(r["mean"]), fmt(r["upper"]), fmt(r["lower"]), pct(r["translucent_change"]), pct(r["receiver_change"]),
            fmt(r["wall"], 0), ref.get("tallow.spp", "?"), eps(ref.get("tallow.rel_error"))))
    add("")
    compared = [(r, restart_of(rows, r)) for r in rows if r["history"] > 0]
    compared = [(r, b) for r, b in compared if b and r["rel_rmse"] and b["rel_rmse"]]
    for r, b in compared:
        add("- %s at %g fps, N = %d, sss.history = %d, sss.history_rescale = %g: frame k's relative RMSE %s against %s"
            " restarting (restart / history = %s); translucent change %s against %s." % (
                r["preset"], r["fps"], r["samples"], r["history"], r["rescale"], pct(r["rel_rmse"]), pct(b["rel_rmse"]),
                fmt(b["rel_rmse"] / r["rel_rmse"], 2), pct(r["translucent_change"]), pct(b["translucent_change"])))
    lines.extend(verdict(compared))
    add("")
    add(results_sections.rerun("results_history.py"))
    add("")
    return lines


if __name__ == "__main__":
    results_sections.main(sys.argv[1:], __doc__, run, section, HEADING)
