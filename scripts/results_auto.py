#!/usr/bin/env python3
"""Issue 17, point 4: "only what the scene needs". The marble bunny at 0.01, 0.1 and 1 m (the camera
moved with it, as in the equal-time section) with the map and light G-buffer sizes fixed at the
paper's 512 and chosen by `auto` (sss/maps/map_resolution.h), and with K fixed at 16 and chosen by
`sss.maps=auto` (sss/maps/map_count.h), against `tallow reference` of each scale: error, bias per
half, fireflies, time; the docs/RESULTS.md section they become.

  results_auto.py run DIR [--quick]   renders the references and the benches into DIR (TALLOW: the binary)
  results_auto.py report DIR MD       appends the section to MD
  results_auto.py splice DIR MD       replaces the section in MD (or adds it before the GPU section)

Called by scripts/results.sh (run, report). Every number comes from the benches' bench.json and the
references' logs.
"""
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import results_sections  # noqa: E402
from results_sections import fmt, pct  # noqa: E402

HEADING = "## Map sizes from the scene (issue 17, point 4)"
SIZE = "160x120"
SCALES = (0.01, 0.1, 1.0)
# presets/bunny.json's camera (position, target) for the 0.1 m bunny; scaled with the bunny.
BUNNY_CAMERA = ((0.05, 0.13, 0.32), (0.0, 0.045, 0.0))
REF_REL_ERROR = "0.04"
FRAMES = 16  # sss.frames: the maps converge; the bench's last frame is the converged one


def scene_args(scale):
    f = scale / 0.1
    return ["--preset", "bunny", "--set", "scale=%g" % scale,
            "--set", "camera.position=%g,%g,%g" % tuple(f * c for c in BUNNY_CAMERA[0]),
            "--set", "camera.target=%g,%g,%g" % tuple(f * c for c in BUNNY_CAMERA[1])]


def run(work, quick):
    binary = os.environ.get("TALLOW", "tallow")
    size = "64x48" if quick else SIZE
    frames = 3 if quick else FRAMES  # bench --frames (frames + 2) is at least 5
    for scale in SCALES:
        d = os.path.join(work, "scale_%g" % scale)
        os.makedirs(d, exist_ok=True)
        ref = os.path.join(d, "ref.exr")
        results_sections.run_once([binary, "reference", *scene_args(scale), "--size", size,
              *(["--spp", "2"] if quick else ["--rel-error", REF_REL_ERROR]), "--out", ref], ref)
        results_sections.run_once([binary, "bench", *scene_args(scale), "--size", size, "--reference", ref, "--methods", "radiosity-maps",
              "--set", "sss.frames=%d" % frames, "--frames", str(frames + 2),
              "--set", "sss.maps=16", "--sweep", "sss.map_size=512,auto", "--sweep", "sss.light_map_size=512,auto",
              "--out", os.path.join(d, "bench")], os.path.join(d, "bench", "bench.json"))
        # K: 16 against auto, both with the sizes auto chooses.
        results_sections.run_once([binary, "bench", *scene_args(scale), "--size", size, "--reference", ref, "--methods", "radiosity-maps",
              "--set", "sss.frames=%d" % frames, "--frames", str(frames + 2), "--sweep", "sss.maps=16,auto",
              "--out", os.path.join(d, "bench_k")], os.path.join(d, "bench_k", "bench.json"))




def load(work, bench="bench"):
    out = {}
    for scale in SCALES:
        with open(os.path.join(work, "scale_%g" % scale, bench, "bench.json")) as f:
            out[scale] = json.load(f)
    return out


def label(row):
    p = row["parameters"]
    return "map %s, light %s" % (p["sss.map_size"], p["sss.light_map_size"])


def section(work):
    benches = load(work)
    lines = []
    add = lines.append
    first = benches[SCALES[0]]
    add(HEADING)
    add("")
    add("`sss.map_size=auto` and `sss.light_map_size=auto` (the defaults) choose the sizes from the scene")
    add("(`sss/maps/map_resolution.h`): a map texel no wider than half a pixel of the objects' bounding sphere")
    add("on screen (the screen asking at most 512) nor than the shortest diffusion length 1/σ_tr; a light")
    add("G-buffer texel of a quarter of the")
    add("shortest 1/σ_tr; powers of two, maps in [128, 2048], light G-buffers in [512, 4096]. And Algorithm 1")
    add("filters a map over a pixel's footprint only up to half the shortest 1/σ_tr (`uMaxFootprint`,")
    add("`shaders/maps/algorithm1.glsl`): before, a pixel wider than that, as on the 1 m bunny, took the mean of")
    add("B over its whole footprint (more on a map seeing x_o at a grazing angle) where the reference takes B at")
    add("the pixel's centre; that blur and the light G-buffer's 2.7 mm texels, under one 1/σ_tr of blue marble")
    add("(4.0 mm), made the 1 m bunny's 18.3% in the equal-time section (measured before both changes; that")
    add("section is regenerated only with the whole file). The fixed rows below have the footprint cap too,")
    add("and, like every row, the footprint's shrinking as the frames accumulate (F^(−1/4), `uNarrowFootprint`;")
    add("docs/radiosity-maps.md): the converged rows take B nearer the pixel's centre than the first.")
    add("With fewer texels each pixel averages fewer texels' samples, so a first frame of the smaller auto maps")
    add("is noisier; each frame costs less, and the converged error is what the sizes decide.")
    add("")
    add("Marble bunny, %s, the camera moved with it; K = 16, N = 8, `sss.frames` = %d; each scale against its"
        % (SIZE, FRAMES))
    prov = first.get("provenance", {})
    add("own `tallow reference` (ε below). Device `%s`, %s hardware threads: compare wall times within a scale."
        % (prov.get("gl", {}).get("GL_RENDERER", "?"), prov.get("cpu", {}).get("hardware_threads", "?")))
    add("`upper`/`lower`: the mean over the upper or lower half of the object's pixels against the reference's;")
    add("fireflies: object pixels with a channel above 4× its 5×5 median (the reference's own count beside).")
    add("")
    add("| scale [m] | sizes | chosen map / light | first frame rel. RMSE | converged rel. RMSE | upper / lower | fireflies (ref.) | median wall per accumulating frame [ms] | reference ε |")
    add("|---|---|---|---:|---:|---:|---:|---:|---:|")
    verdict = {}
    for scale in SCALES:
        for row in benches[scale]["rows"]:
            add("| %g | %s | %s / %s | %s | %s | %s / %s | %s (%s) | %s | %s |" % (
                scale, label(row), row.get("map_size_used", "—"), row.get("light_map_size_used", "—"),
                pct(row["first_rel_rmse"]), pct(row["last_rel_rmse"]), fmt(row.get("last_upper_mean_ratio")), fmt(row.get("last_lower_mean_ratio")),
                row.get("last_fireflies", "—"), row.get("reference_fireflies", "—"),
                fmt(row.get("median_accumulating_wall_ms"), 0), pct(row.get("reference_rel_error"))))
            verdict[(scale, row["parameters"]["sss.map_size"], row["parameters"]["sss.light_map_size"])] = row
    add("")
    fixed = {s: verdict.get((s, 512, 512)) for s in SCALES}
    auto = {s: verdict.get((s, "auto", "auto")) for s in SCALES}
    for s in SCALES:
        if fixed[s] and auto[s]:
            add("- %g m: fixed 512 / 512 %s in %s ms per frame; auto (%s / %s) %s in %s ms per frame (%.2f× the time)."
                % (s, pct(fixed[s]["last_rel_rmse"]), fmt(fixed[s]["median_accumulating_wall_ms"], 0),
                   auto[s].get("map_size_used"), auto[s].get("light_map_size_used"), pct(auto[s]["last_rel_rmse"]),
                   fmt(auto[s]["median_accumulating_wall_ms"], 0),
                   auto[s]["median_accumulating_wall_ms"] / fixed[s]["median_accumulating_wall_ms"]))
    big, small = auto.get(1.0), (auto.get(0.01), fixed.get(0.01))
    if big:
        add("- Target: the 1 m bunny under 10%%: **%s** (%s)." % (pct(big["last_rel_rmse"]),
                                                              "met" if big["last_rel_rmse"] < 0.10 else "not met"))
    if all(small):
        faster = small[0]["median_accumulating_wall_ms"] <= small[1]["median_accumulating_wall_ms"]
        add("- Target: the 0.01 m bunny not slower: auto %s ms against fixed %s ms per frame (%s)." % (
            fmt(small[0]["median_accumulating_wall_ms"], 0), fmt(small[1]["median_accumulating_wall_ms"], 0),
            "met" if faster else "not met"))
    add("")
    lines += k_section(work)
    return lines


def k_section(work):
    benches = load(work, "bench_k")
    lines = []
    add = lines.append
    add("K from coverage (`sss.maps=auto`, the default; `sss/maps/map_count.h`). The GPU counts, for every")
    add("visible pixel of the object and every VPL, the first map that sees it and, for the pixels, the second")
    add("that sees it within 60° of its normal; the renderer reads the counts back behind a fence (no frame")
    add("waits) and takes the fewest of the nested Halton directions that leave at most 0.1% more of the pixels")
    add("or VPLs with no map, and 2% more of the pixels with fewer than two facing maps, than the most maps it")
    add("tried (16 at first, doubled up to 32 while either is exceeded 1.5 times). A change of K restarts the maps that are new (the nested directions keep theirs). Sizes `auto` in")
    add("both rows; the first frame of a bench is the one after the warm-up, with what the chooser knew then.")
    add("")
    add("| scale [m] | sss.maps | K used | first frame rel. RMSE | converged rel. RMSE | upper / lower | fireflies (ref.) | median wall per accumulating frame [ms] | reference ε |")
    add("|---|---|---:|---:|---:|---:|---:|---:|---:|")
    by = {}
    for scale in SCALES:
        for row in benches[scale]["rows"]:
            k = row["parameters"]["sss.maps"]
            by[(scale, str(k))] = row
            add("| %g | %s | %s | %s | %s | %s / %s | %s (%s) | %s | %s |" % (
                scale, k, row.get("maps_used", "—"), pct(row["first_rel_rmse"]), pct(row["last_rel_rmse"]),
                fmt(row.get("last_upper_mean_ratio")), fmt(row.get("last_lower_mean_ratio")),
                row.get("last_fireflies", "—"), row.get("reference_fireflies", "—"),
                fmt(row.get("median_accumulating_wall_ms"), 0), pct(row.get("reference_rel_error"))))
    add("")
    for s in SCALES:
        fixed, auto = by.get((s, "16")), by.get((s, "auto"))
        if fixed and auto:
            add("- %g m: K = 16 %s in %s ms per frame; auto (K = %s) %s in %s ms per frame (%.2f× the time)."
                % (s, pct(fixed["last_rel_rmse"]), fmt(fixed["median_accumulating_wall_ms"], 0), auto.get("maps_used"),
                   pct(auto["last_rel_rmse"]), fmt(auto["median_accumulating_wall_ms"], 0),
                   auto["median_accumulating_wall_ms"] / fixed["median_accumulating_wall_ms"]))
    add("")
    return lines


if __name__ == "__main__":
    results_sections.main(sys.argv[1:], __doc__, run, section, HEADING)
