#!/usr/bin/env python3
"""Issues 6-8's experiments (speed against error, VPLs, peers) and the docs/RESULTS.md sections they become.

  results_bench.py run DIR [--quick]          runs every experiment into DIR (TALLOW: the binary)
  results_bench.py report DIR MD IMAGES       appends the section to MD, copies figures to IMAGES
  results_bench.py gpu FOLDER MD              appends the GPU section (issue 18) from FOLDER/results.md

Called by scripts/results.sh; every number in the section comes from the JSON the runs write.
The experiments follow the radiosity-maps paper: Figs. 6/8 (converged against the reference for
three materials), Fig. 9 (equal time at three scales), Fig. 11 (occupancy at which the maps and the
no-cache gather cost the same), Fig. 13 (coverage against K), and the grazing-incidence and
point-light fixes before and after. Issue 7's VPL experiments (receivers against the reference's
emergent light, shadows, costs, flicker, the paper's candle settings) and issue 8's peers (the four
methods on the bunny at three scales, the blob and the candle holder) follow.
"""
import json
import math
import os
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import results_sections  # noqa: E402

MATERIALS = ["Marble", "White Grapefruit Juice", "Strawberry Shampoo"]
# The bunny lit from low on its left: the grazing case of the paper's §4 / Fig. 8.
GRAZING_LIGHT = "-0.97,0.17,0.17"
OCCUPANCY_FOVS = [35, 28, 22, 17, 13]
COVERAGE_KS = [1, 2, 4, 8, 16, 32]
SCALES = [0.01, 0.1, 1.0]
# presets/bunny.json's camera (position, target) for the 0.1 m bunny; scaled with the bunny.
BUNNY_CAMERA = ((0.05, 0.13, 0.32), (0.0, 0.045, 0.0))


def finished(args):
    """With TALLOW_RESULTS_RESUME=1, a run whose output is already whole (bench.json or stats.json,
    both written by rename) is not run again, so an interrupted or partial regeneration resumes."""
    if os.environ.get("TALLOW_RESULTS_RESUME") != "1" or "--out" not in args:
        return False
    out = args[args.index("--out") + 1]
    return any(results_sections.whole(os.path.join(out, f)) for f in ("bench.json", "stats.json"))


def tallow(*args):
    cmd = [os.environ.get("TALLOW", "tallow")] + [str(a) for a in args]
    if finished(cmd):
        print("results: kept", " ".join(cmd), flush=True)
        return
    print("results:", " ".join(cmd), flush=True)
    subprocess.run(cmd, check=True)


def bench(out, preset, size, extra, ref):
    tallow("bench", "--preset", preset, "--size", size, "--out", out, *ref, *extra)


def run(work, quick):
    os.makedirs(work, exist_ok=True)
    frames = "4" if quick else "16"  # sss.frames: accumulated frames of the maps
    big = "96x72" if quick else "240x180"
    small = "64x48" if quick else "160x120"
    ref_tight = ["--ref-spp", "2"] if quick else ["--ref-rel-error", "0.03"]
    ref_loose = ["--ref-spp", "2"] if quick else ["--ref-rel-error", "0.04"]
    # Figs. 6 and 8; target 1 (marble at 0.1 m, K = 16: set, since sss.maps=auto, the default since
    # issue 17, takes 8 maps on the bunny).
    bench(f"{work}/materials", "bunny", big,
          ["--methods", "radiosity-maps", "--set", f"sss.frames={frames}", "--set", "sss.maps=16",
           "--sweep", "material=" + ",".join(MATERIALS),
           "--sweep", "sss.view_weight=0,2"], ref_tight)
    # Target 1 on its own: the preset's own sss.frames (64) at 320x240 against a tighter reference, so
    # that neither our noise nor the reference's hides the bias.
    bench(f"{work}/target1", "bunny", "96x72" if quick else "320x240",
          ["--methods", "radiosity-maps", "--set", "sss.frames=" + ("4" if quick else "64"), "--set", "material=Marble",
           "--set", "sss.maps=16"],
          ["--ref-spp", "2"] if quick else ["--ref-rel-error", "0.015"])
    # Target 2: grazing incidence. The slab lit at 60 degrees (exact answer known) and the bunny lit
    # from low on its side, with the two corrections off and on. K is held at 16: sss.maps=auto keeps
    # fewer maps on the flat slab, whose 16 frames then average fewer independent estimates (8.4%
    # against 5.0% at K = 16), noise that would hide what the corrections change.
    fixes = ["--set", "sss.maps=16", "--sweep", "sss.projected_area=false,true", "--sweep", "sss.texel_plane=false,true"]
    bench(f"{work}/grazing_slab", "slab", "32x32",
          ["--methods", "radiosity-maps", "--set", f"sss.frames={frames}", "--set", "light.direction=0.8660254,0.5,0",
           "--set", "sss.map_size=128", *fixes], ["--ref-spp", "2" if quick else "12"])
    bench(f"{work}/grazing_bunny", "bunny", small,
          ["--methods", "radiosity-maps", "--set", f"sss.frames={frames}", "--set", f"light.direction={GRAZING_LIGHT}",
           *fixes], ref_loose)
    # The point light in the candle's cup, with and without the area ratio.
    bench(f"{work}/candle", "candle", small,
          ["--time", "5", "--methods", "radiosity-maps", "--set", f"sss.frames={frames}",
           "--sweep", "sss.projected_area=false,true"], ["--ref-spp", "2" if quick else "16"])
    run_scales(work, quick)
    # Fig. 11 and target 4: cost against screen occupancy at 1024x1024 (the chocolate-milk blob,
    # animated, the maps restarted every frame as in the paper: sss.history=0), K = 10 maps.
    size = "256x256" if quick else "1024x1024"
    for method in ("radiosity-maps", "no-cache"):
        for fov in OCCUPANCY_FOVS[:2] if quick else OCCUPANCY_FOVS:
            tallow("capture", "--preset", "blob-chocolate", "--size", size, "--frames", "2" if quick else "5",
                   "--set", f"method={method}", "--set", "sss.maps=10", "--set", "sss.history=0",
                   "--set", f"camera.fov_deg={fov}",
                   "--out", f"{work}/occupancy/{method}_{fov}")
    # Fig. 13: share of the bunny's visible pixels no map sees, against K.
    for k in COVERAGE_KS:
        tallow("capture", "--preset", "bunny", "--size", "320x240", "--frames", "1", "--set", f"sss.maps={k}",
               "--set", "sss.samples=1", "--out", f"{work}/coverage/k{k}")
    run_vpl(work, quick)
    run_peers(work, quick)


# Issue 8: every method on the shared scenes. The bunny's three scales are the equal-time runs above;
# the blob (frozen at one time, so the progressive methods converge) and the candle holder (a point light
# inside a hollow cylinder) are run here.
PEER_METHODS = ["radiosity-maps", "no-cache", "sslpv", "image-space", "burley"]
# Issue 41: the bunny lit from the camera's side (what a screen-space profile handles best), at the
# size of the bound (96x72, relative RMSE at most 0.30 for burley), and the default candle.
FRONT_LIGHT = "0.15,0.37,0.92"
# (label, preset, size, quick size, options)
PEER_SCENES = [("blob", "blob", "160x120", "64x48", ["--time", "2.5"]),
               ("candle-holder", "candle-holder", "160x120", "64x48", []),
               ("bunny front-lit", "bunny", "96x72", "64x48", ["--set", f"light.direction={FRONT_LIGHT}"]),
               ("candle", "candle", "160x90", "64x36", ["--time", "16"])]


def peer_folder(work, label):
    return f"{work}/peers_{label.replace(' ', '_')}"


def run_scales(work, quick):
    """Fig. 9 and target 3: equal time at three scales, the camera moved with the bunny so that it
    frames it the same; every peer method beside the maps."""
    frames = "4" if quick else "16"
    for scale in SCALES:
        f = scale / 0.1
        bench(f"{work}/scale_{scale}", "bunny", "64x48" if quick else "160x120",
              ["--methods", ",".join(PEER_METHODS), "--set", f"sss.frames={frames}", "--set", f"scale={scale}",
               "--set", "camera.position=%g,%g,%g" % tuple(f * c for c in BUNNY_CAMERA[0]),
               "--set", "camera.target=%g,%g,%g" % tuple(f * c for c in BUNNY_CAMERA[1]), "--equal-time"],
              ["--ref-spp", "2"] if quick else ["--ref-rel-error", "0.04"])


def run_peers(work, quick):
    """Issues 8 and 41: every method side by side on the shared scenes."""
    for label, preset, size, quick_size, extra in PEER_SCENES:
        bench(peer_folder(work, label), preset, quick_size if quick else size,
              ["--methods", ",".join(PEER_METHODS), "--set", "sss.frames=" + ("4" if quick else "16"), *extra],
              ["--ref-spp", "2"] if quick else ["--ref-rel-error", "0.04"])


VPL_COUNTS = [50, 80, 200]
VPL_COST_COUNTS = [0, 50, 200, 800]
VPL_COST_SIZES = ["160x120", "320x240"]
# [s] the default candle's receivers against the reference at these times (16: its start_s, with a puddle)
CANDLE_VPL_TIMES = [12.0, 16.0]


def candle_vpl_folder(work, t):
    return f"{work}/vpl_receivers_candle" + ("" if t == 12.0 else "_%g" % t)


def run_vpl(work, quick):
    """Issue 7: the receivers against the reference's emergent light, the VPL costs, flicker, and the
    candle at the paper's settings."""
    # The candle holder with its fill light: the table's VPL term against `tallow reference --emergent`.
    tallow("bench", "--preset", "candle-holder", "--size", "64x48" if quick else "160x120", "--methods",
           "radiosity-maps", "--set", "sss.frames=" + ("2" if quick else "16"),
           "--sweep", "vpl.count=" + ",".join(str(n) for n in [0] + VPL_COUNTS), "--receivers",
           "--ref-spp", "4" if quick else "64", "--out", f"{work}/vpl_receivers")
    # The default candle at t = 12 s (issue 36: receivers within 10% at 80 VPLs on the candle too).
    for t in CANDLE_VPL_TIMES:
        tallow("bench", "--preset", "candle", "--time", str(t), "--size", "64x36" if quick else "160x90", "--methods",
               "radiosity-maps", "--set", "sss.frames=" + ("2" if quick else "16"), "--sweep", "vpl.count=0,80",
               "--receivers", "--ref-spp", "4" if quick else "64", "--out", candle_vpl_folder(work, t))
    # VPL shadows: an opaque block beside the holder, shadows off and on.
    tallow("bench", "--preset", "candle-holder-block", "--size", "64x48" if quick else "96x72", "--methods",
           "radiosity-maps", "--set", "sss.frames=" + ("2" if quick else "8"), "--sweep", "vpl.shadows=false,true",
           "--receivers", "--ref-spp", "8" if quick else "256", "--out", f"{work}/vpl_shadows")
    run_vpl_pictures(work, quick)
    # Costs: the vpl pass (frames while the maps accumulate) and the receivers' share of the surface
    # pass (converged frames: only the surface pass runs) against N_vpl and the receiver pixels.
    for size in VPL_COST_SIZES[:1] if quick else VPL_COST_SIZES:
        for n in VPL_COST_COUNTS:
            tallow("capture", "--preset", "candle-holder", "--size", size, "--frames", "7", "--set", "sss.frames=2",
                   "--set", f"vpl.count={n}", "--out", f"{work}/vpl_cost/{size}_{n}")
    # Flicker: the candle melting under a steady flame (flame.flicker=0) fixed where it is at t = 12 s,
    # VPLs stable or re-drawn every frame; 30 frames per second.
    tallow("capture", "--preset", "candle", "--size", "64x48", "--frames", "1", "--out", f"{work}/flicker/flame")
    flame = load(f"{work}/flicker/flame/stats.json")["frames"][0]["point_lights"][0]
    for stable in ("true", "false"):
        tallow("capture", "--preset", "candle", "--size", "96x72" if quick else "160x120", "--frames",
               "4" if quick else "16", "--fps", "30", "--set", "light.position=%.6g,%.6g,%.6g" % tuple(flame),
               "--set", "flame.flicker=0", "--set", f"vpl.stable={stable}", "--out", f"{work}/flicker/stable_{stable}")
    # The candle at the paper's Fig. 1 settings: K = 28, N = 45, 80 VPLs (every frame recomputes all).
    tallow("capture", "--preset", "candle", "--size", "160x120" if quick else "640x480", "--frames", "3",
           "--set", "sss.maps=28", "--set", "sss.samples=45", "--set", "vpl.count=80", "--set", "sss.history=0",
           "--out", f"{work}/candle_paper")


def run_vpl_pictures(work, quick):
    """Pictures of the VPL shadows' effect, large enough to see it: the same scene captured at 320x240
    with the maps accumulated, shadows off and on, and their difference in false colour (tallow compare)."""
    pictures = f"{work}/vpl_pictures"
    for shadows, name in (("false", "off"), ("true", "on")):
        tallow("capture", "--preset", "candle-holder-block", "--size", "160x120" if quick else "320x240", "--frames", "1",
               "--accumulate", "4" if quick else "16", "--set", "sss.frames=" + ("4" if quick else "16"),
               "--set", f"vpl.shadows={shadows}", "--out", f"{pictures}/{name}")
    tallow("compare", f"{pictures}/off/frame_0000.exr", f"{pictures}/on/frame_0000.exr",
           "--caption", "VPL shadows off", "--caption", "VPL shadows on",
           "--title", "candle holder beside a block", "--out", f"{pictures}/vpl_shadows.png")


def report_vpl_pictures(work, add, images, rel_images):
    """The VPL shadows off and on, captioned (run_vpl_pictures)."""
    if not copy_figure(f"{work}/vpl_pictures/vpl_shadows.png", images, "vpl_shadows.png"):
        return
    pic = load(f"{work}/vpl_pictures/on/stats.json")
    add("![VPL shadows off and on](%s/vpl_shadows.png)" % rel_images)
    add("")
    add("*The same scene rendered at %dx%d (`tallow capture`, the maps accumulated over %d renders), VPL shadows"
        " off and on; below, where they differ (`tallow compare`: |off − on| per pixel relative to the RMS radiance of"
        " the picture with shadows, in false colour with the scale bar on the right): the block's shadow of the"
        " holder's emergent light on the table.*" % (pic["resolution"][0], pic["resolution"][1], pic["accumulate"]))
    add("")


def explain_crossover(pts, crossover, add):
    """Target 4's why: the maps' cost, which the screen does not change, in screen pixels of no-cache work."""
    cached = dict((fov, st) for _, _, fov, st in pts["radiosity-maps"])
    direct = dict((fov, st) for _, _, fov, st in pts["no-cache"])
    fov = max(set(cached) & set(direct), default=None)  # the widest view: the smallest occupancy
    if fov is None:
        return
    def gpu(st, name):
        return median([f["gpu_ms"].get(name, 0.0) for f in st["frames"][1:]] or [st["frames"][0]["gpu_ms"].get(name, 0.0)])
    c, d = cached[fov], direct[fov]
    pixels = d["sss"]["translucent_pixels"]
    per_pixel = (gpu(d, "surface") - gpu(c, "surface")) / pixels  # the no-cache gather's ms per translucent pixel
    maps = gpu(c, "sss.maps")
    if per_pixel <= 0:
        return
    screen = d["resolution"][0] * d["resolution"][1]
    equivalent = maps / per_pixel
    add("- why there: the maps' cost does not depend on the screen. At %g° (%s occupancy) the maps pass took %s ms"
        % (fov, pct(pixels / screen), fmt(maps, 1)))
    add("  (GPU timer, K maps' shaded texels × N samples), and the no-cache gather %s µs per translucent pixel (its"
        % fmt(1000.0 * per_pixel, 2))
    add("  surface pass minus the cached one's, over %d pixels): the maps cost as much as the gather of %d pixels, %s of"
        % (pixels, equivalent, pct(equivalent / screen)))
    add("  the %dx%d screen (the wall-time lines above meet at %s: they also hold the work outside these two GPU"
        % (d["resolution"][0], d["resolution"][1], pct(crossover)))
    add("  timers). Cached wins once the screen holds more translucent pixels than the maps' texel work is worth;")
    add("  the paper's 5.8% means its maps' work was worth fewer screen")
    add("  pixels than ours (it gives neither its maps' coverage nor per-pass times, so the difference cannot be")
    add("  located further). Our K = 10 maps of 512² shade every texel the blob covers in each of them.")


def maps_used(rows):
    """K as the rows' bench measured it (maps_used: what sss.maps=auto chose, or the set value), as 'k'
    or 'lo–hi'."""
    ks = sorted({r["maps_used"] for r in rows if r.get("maps_used") is not None})
    if not ks:
        return "—"
    return str(ks[0]) if len(ks) == 1 else "%d–%d" % (ks[0], ks[-1])


def load(path):
    with open(path) as f:
        return json.load(f)


def fmt(x, d=3):
    return "—" if x is None else "%.*f" % (d, x)


def pct(x):
    return "—" if x is None else "%.1f%%" % (100.0 * x)


def median(values):
    v = sorted(values)
    n = len(v)
    if n == 0:
        return None
    return v[n // 2] if n % 2 else 0.5 * (v[n // 2 - 1] + v[n // 2])


def reference_error(b, row):
    """The relative standard error of the reference a bench row was measured against."""
    name = row["reference"]
    for ref in b["references"]:
        if ref.get("file") == name or os.path.basename(ref.get("file", "")) == name:
            if "rel_error" in ref:
                return ref["rel_error"]
            return float(ref.get("attributes", {}).get("tallow.rel_error", "nan"))
    return None


def without_reference_noise(rel, eps):
    """E[rmse²] = our error² + the reference's own ε²: the part that is ours."""
    if rel is None or eps is None or not math.isfinite(eps):
        return None
    return math.sqrt(max(rel * rel - eps * eps, 0.0))


# What the false-colour panels show (app/commands/comparison_figure.h); RESULTS says it under each figure.
DIFFERENCE_NOTE = ("in false colour: |Δ| per pixel relative to the RMS radiance of the reference over the object's"
                   " pixels, the bench's relative-RMSE metric pixel by pixel, with the scale bar on the right.")


def row_figure(work, bench_dir, row):
    """A bench row's captioned comparison picture (tallow bench: rows/<row>/comparison.png)."""
    return os.path.join(work, bench_dir, row.get("folder", "rows/" + row["row"]), "comparison.png")


def copy_figure(src, images, name):
    if os.path.exists(src):
        shutil.copyfile(src, os.path.join(images, name))
        return True
    return False


def fit_line(xs, ys):
    n = len(xs)
    mx, my = sum(xs) / n, sum(ys) / n
    sxx = sum((x - mx) ** 2 for x in xs)
    b = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx if sxx > 0 else 0.0
    return my - b * mx, b


def settings_table(add, b, keys):
    """One row per swept setting of a bench: its converged error, without the reference's noise, and
    the bias of the mean; then the reference's ε."""
    add("| " + " | ".join(k.split(".", 1)[-1] for k in keys) + " | converged rel. RMSE | without ε | mean L / reference |")
    add("|" + "---|" * len(keys) + "---:|---:|---:|")
    for row in b["rows"]:
        eps = reference_error(b, row)
        cells = [row["settings"][k] for k in keys]
        cells += [pct(row["last_rel_rmse"]), pct(without_reference_noise(row["last_rel_rmse"], eps)),
                  fmt(row["last_error"].get("mean_ratio"))]
        add("| " + " | ".join(cells) + " |")
    add("")
    add("(reference ε = %s)" % pct(reference_error(b, b["rows"][0])))
    add("")


def report(work, md, images):
    os.makedirs(images, exist_ok=True)
    rel_images = os.path.relpath(images, os.path.dirname(md))
    L = []
    add = L.append
    mat = load(f"{work}/materials/bench.json")
    add("")
    add("## Speed against error (issue 6)")
    add("")
    add("Device: `%s` (%s, `%s` context); CPU: %s, %d hardware threads. The reference is `tallow reference`"
        % (mat["gpu"]["GL_RENDERER"], mat["gpu"]["GL_VERSION"], mat["gpu"]["backend"], mat["cpu"]["model"],
           mat["cpu"]["hardware_threads"]))
    add("(CPU, Embree + TBB, all threads) on the same scene; errors are over the pixels where the camera sees a")
    add("translucent object: relative RMSE = √(mean_p Σ_c Δ²) / √(mean_p Σ_c L_ref²) (docs/commands.md, `tallow bench`).")
    add("Every error includes the reference's own noise ε (its relative standard error, same statistic):")
    add("E[RMSE²] = ours² + ε², so tables also give √(rel² − ε²), the part that is ours. Times are medians of")
    add("frames after a warm-up frame on a machine shared with other work. **llvmpipe runs on this CPU: its")
    add("times say nothing about a real GPU**, so speed claims below are ratios measured in one run.")
    add("")

    # --- Figs. 6 and 8 ---------------------------------------------------------------------------
    add("### Converged maps against the reference: three materials (the paper's Figs. 6 and 8)")
    add("")
    add("Bunny, 0.1 m, directional light, %dx%d, K = %s, N = 8, `sss.frames` = %s; each material has its own"
        % (mat["width"], mat["height"], maps_used(mat["rows"]), mat["rows"][0]["parameters"]["sss.frames"]))
    add("reference. `first` is the first frame after a restart, `converged` the last. `view_weight` p weights")
    add("Algorithm 1's maps by cos^p θ (0: the paper's equal weights; 2: the default, docs/radiosity-maps.md).")
    add("")
    add("| material | view_weight | reference ε | first frame rel. RMSE | converged rel. RMSE | converged, without ε | mean L / reference | max error | frame [ms] |")
    add("|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    marble = {}
    for row in mat["rows"]:
        eps = reference_error(mat, row)
        ours = without_reference_noise(row["last_rel_rmse"], eps)
        weight = row["settings"]["sss.view_weight"]
        add("| %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
            row["settings"]["material"], weight, pct(eps), pct(row["first_rel_rmse"]), pct(row["last_rel_rmse"]),
            pct(ours), fmt(row["last_error"].get("mean_ratio")), fmt(row["last_max_error"]),
            fmt(row["median_accumulating_wall_ms"] or row["median_wall_ms"], 1)))
        if row["settings"]["material"] == "Marble":
            marble[weight] = (row, eps, ours)
        if weight == "2":
            copy_figure(row_figure(work, "materials", row), images, f"materials_{row['row']}.png")
    add("")
    add("Per material (view_weight 2): the reference, our first and converged frames (top) and their differences")
    add("to the reference (bottom), " + DIFFERENCE_NOTE)
    add("")
    for row in mat["rows"]:
        if row["settings"]["sss.view_weight"] == "2":
            add("![%s](%s/materials_%s.png)" % (row["settings"]["material"], rel_images, row["row"]))
            add("")
            add("*%s: converged rel. RMSE %s (reference ε %s).*" % (
                row["settings"]["material"], pct(row["last_rel_rmse"]), pct(reference_error(mat, row))))
            add("")

    # --- Grazing incidence -------------------------------------------------------------------------
    slab = load(f"{work}/grazing_slab/bench.json")
    graz = load(f"{work}/grazing_bunny/bench.json")
    add("### Grazing incidence: where the light went, before and after (target 2)")
    add("")
    add("Two causes, both in the estimator of Eq. 9 (docs/radiosity-maps.md): the samples lie on the light's view")
    add("plane, not on the surface (`sss.projected_area`: weight by the surface's area per plane area; the paper's")
    add("Eq. 9 as printed loses a factor cos θ_ℓ), and x_i took the light G-buffer texel's depth, which puts it off a")
    add("tilted surface by up to half a texel × tan θ_ℓ so that r never reaches the peak of S_d at 0")
    add("(`sss.texel_plane`: intersect the texel's tangent plane). Both on is the default; `false,false` is the")
    add("estimator as the paper prints it.")
    add("")
    for title, b in (("slab lit at 60° (%dx%d; Eq. 7 is exact far from the edges)" % (slab["width"], slab["height"]), slab),
                     ("bunny lit from low on its side, light direction (%s) (%dx%d)" % (GRAZING_LIGHT, graz["width"], graz["height"]), graz)):
        add("*%s*" % title)
        add("")
        settings_table(add, b, ["sss.projected_area", "sss.texel_plane"])

    # --- Point light -----------------------------------------------------------------------------
    cand = load(f"{work}/candle/bench.json")
    add("### The point light in the candle's cup, before and after")
    add("")
    add("Candle at t = %g s, %dx%d: the flame a few mm from the wax. The stereographic look-up (Eqs. 13–14) moves"
        % (cand["time_s"], cand["width"], cand["height"]))
    add("samples from x_o's tangent plane to the surface; `sss.projected_area` weights each by dA_i/dA_j.")
    add("The reference meshes the field with OpenVDB, the GPU with its own surface nets (up to a cell apart).")
    add("")
    settings_table(add, cand, ["sss.projected_area"])

    # --- Fig. 9 ----------------------------------------------------------------------------------
    report_scales(work, add, images, rel_images)

    # --- Fig. 11 ---------------------------------------------------------------------------------
    add("### Cached against no-cache by screen occupancy (the paper's Fig. 11; target 4)")
    add("")
    pts = {"radiosity-maps": [], "no-cache": []}
    occ_dir = f"{work}/occupancy"
    for name in sorted(os.listdir(occ_dir)):
        method, fov = name.rsplit("_", 1)
        st = load(f"{occ_dir}/{name}/stats.json")
        total = st["resolution"][0] * st["resolution"][1]
        occupancy = st["sss"]["translucent_pixels"] / total
        wall = median([f["wall_ms"] for f in st["frames"][1:]] or [st["frames"][0]["wall_ms"]])
        pts[method].append((occupancy, wall, float(fov), st))
    st0 = pts["radiosity-maps"][0][3]
    add("Chocolate-milk blob, animated (the maps restart every frame, as in the paper: `sss.history=0`), %dx%d, K = %s maps of %s²,"
        % (st0["resolution"][0], st0["resolution"][1], st0["parameters"]["sss.maps"], st0["parameters"]["sss.map_size"]))
    add("N = %s samples per texel (maps) or per pixel (no cache) and band; the paper used N = 1000, which llvmpipe"
        % st0["parameters"]["sss.samples"])
    add("cannot run at this size. Occupancy is changed by the camera's field of view; each time is the median")
    add("wall time of the frames after the first (`tallow capture`, stats.json).")
    add("")
    add("| fov [°] | occupancy | radiosity maps [ms] | no cache [ms] |")
    add("|---:|---:|---:|---:|")
    by_fov = {}
    for m, items in pts.items():
        for occ, wall, fov, _ in items:
            by_fov.setdefault(fov, {})["occ"] = occ
            by_fov[fov][m] = wall
    for fov in sorted(by_fov, reverse=True):
        v = by_fov[fov]
        add("| %g | %s | %s | %s |" % (fov, pct(v["occ"]), fmt(v.get("radiosity-maps"), 1), fmt(v.get("no-cache"), 1)))
    add("")
    fits = {m: fit_line([p[0] for p in items], [p[1] for p in items]) for m, items in pts.items() if len(items) >= 2}
    crossover = None
    if len(fits) == 2:
        (a1, b1), (a2, b2) = fits["radiosity-maps"], fits["no-cache"]
        for m, (a, b) in fits.items():
            add("- %s: time ≈ %.1f ms + %.1f ms per 1%% of occupancy" % (m, a, b / 100.0))
        if b2 != b1:
            crossover = (a1 - a2) / (b2 - b1)
        add("- equal cost at **%s** occupancy (least-squares lines above; the paper: 5.8%% at 1024², 12 fps on a"
            % pct(crossover))
        add("  GTX 780 Ti).")
        explain_crossover(pts, crossover, add)
    add("")

    # --- Fig. 13 ---------------------------------------------------------------------------------
    add("### Coverage against K (the paper's Fig. 13)")
    add("")
    add("Bunny, 320x240: the share of the visible translucent pixels that no map sees (Algorithm 1's n = 0, shaded")
    add("B = 0), after one frame. Time against K is the table of `tallow probe maps` above.")
    add("")
    add("| K | translucent pixels | unseen | unseen share |")
    add("|---:|---:|---:|---:|")
    for k in COVERAGE_KS:
        st = load(f"{work}/coverage/k{k}/stats.json")["sss"]
        add("| %d | %d | %d | %s |" % (k, st["translucent_pixels"], st["unseen_pixels"], "%.2f%%" % (100 * st["unseen_share"])))
    add("")

    # --- Targets ---------------------------------------------------------------------------------
    add("### The targets, measured")
    add("")
    t1 = load(f"{work}/target1/bench.json")
    row = t1["rows"][0]
    eps = reference_error(t1, row)
    ours = without_reference_noise(row["last_rel_rmse"], eps)
    verdict = ("met" if row["last_rel_rmse"] <= 0.05 else
               "met once the reference's own noise is removed" if ours is not None and ours <= 0.05 else "**not met**")
    add("1. Converged maps within 5%% relative RMSE, marble bunny 0.1 m, K = 16 (measured: K = %s, %dx%d, `sss.frames` = %s,"
        " view_weight 2): **%s** against a reference with ε = %s, %s without the reference's noise — %s (first frame %s)."
        " In the materials table above (%dx%d, 16 frames, ε = 3%%): %s, with the paper's equal weights %s." % (
            maps_used([row]), t1["width"], t1["height"], row["parameters"]["sss.frames"], pct(row["last_rel_rmse"]),
            pct(eps), pct(ours),
            verdict, pct(row["first_rel_rmse"]), mat["width"], mat["height"],
            pct(marble["2"][0]["last_rel_rmse"]) if "2" in marble else "—",
            pct(marble["0"][0]["last_rel_rmse"]) if "0" in marble else "—"))
    s_rows = {(r["settings"]["sss.projected_area"], r["settings"]["sss.texel_plane"]): r for r in slab["rows"]}
    g_rows = {(r["settings"]["sss.projected_area"], r["settings"]["sss.texel_plane"]): r for r in graz["rows"]}
    before, after = ("false", "false"), ("true", "true")
    add("2. Grazing incidence: slab at 60°, mean L / reference %s → %s and rel. RMSE %s → %s; bunny lit from low, %s → %s"
        " and %s → %s (the paper's estimator → ours)." % (
            fmt(s_rows[before]["last_error"].get("mean_ratio")), fmt(s_rows[after]["last_error"].get("mean_ratio")),
            pct(s_rows[before]["last_rel_rmse"]), pct(s_rows[after]["last_rel_rmse"]),
            fmt(g_rows[before]["last_error"].get("mean_ratio")), fmt(g_rows[after]["last_error"].get("mean_ratio")),
            pct(g_rows[before]["last_rel_rmse"]), pct(g_rows[after]["last_rel_rmse"])))
    parts = []
    for scale in ("0.1", "1"):
        r = equal.get(scale)
        if r and r.get("equal_time_rel_rmse") is not None:
            won = r["first_rel_rmse"] < r["equal_time_rel_rmse"]
            parts.append("%s m: ours %s in %s ms against the reference's %s in %s ms (%d pass(es)) — %s" % (
                scale, pct(r["first_rel_rmse"]), fmt(r["first_wall_ms"], 0), pct(r["equal_time_rel_rmse"]),
                fmt(r["equal_time_ms"], 0), r["equal_time_passes"], "lower" if won else "**higher**"))
    add("3. Equal time, first interactive frame against the reference: " + "; ".join(parts) + ".")
    if crossover is not None:
        add("4. Cached against no-cache: equal cost at %s occupancy (paper: 5.8%%) — cached wins from %s." % (
            pct(crossover), "a smaller occupancy than the paper's" if crossover < 0.058 else "**a larger occupancy than the paper's** (why: the occupancy section above)"))
    add("")
    report_vpl(work, add, images, rel_images)
    report_peers(work, add, images, rel_images)
    add("Rerun: `bash scripts/results.sh`; the experiments and their commands are in `scripts/results_bench.py`.")
    with open(md, "a") as f:
        f.write("\n".join(L) + "\n")


def report_scales(work, add, images, rel_images):
    """Fig. 9 and target 3: the equal-time runs at three scales (a ### part of the issue-6 section)."""
    scale_runs = [(scale, load(f"{work}/scale_{scale}/bench.json")) for scale in SCALES]
    sc = scale_runs[1][1]
    add("### Equal time against the reference at three scales (the paper's Fig. 9; target 3)")
    add("")
    add("Bunny in marble at %dx%d, the camera moved with it so that it frames it the same. For each row,"
        % (sc["width"], sc["height"]))
    add("`tallow bench --equal-time` runs the reference with another seed")
    add("for as long as our first frame took (at least one pass, so it often runs longer) and measures it against")
    add("the converged reference like our frame. The no-cache gather (the paper's Fig. 11 variant) renders one")
    add("independent estimate per frame.")
    add("")
    add("| scale [m] | method | first frame [ms] | first frame rel. RMSE | reference at equal time: [ms], passes, rel. RMSE | converged rel. RMSE | reference ε |")
    add("|---|---|---:|---:|---:|---:|---:|")
    equal = {}
    for scale, b in scale_runs:
        for row in b["rows"]:
            eps = reference_error(b, row)
            add("| %g | %s | %s | %s | %s, %d, %s | %s | %s |" % (
                scale, row["method"], fmt(row["first_wall_ms"], 1), pct(row["first_rel_rmse"]),
                fmt(row.get("equal_time_ms"), 1), row.get("equal_time_passes", 0), pct(row.get("equal_time_rel_rmse")),
                pct(row["last_rel_rmse"]), pct(eps)))
            if row["method"] == "radiosity-maps":
                equal["%g" % scale] = row
    add("")
    copy_figure(f"{work}/scale_0.1/speed_error.png", images, "scales_speed_error.png")
    copy_figure(f"{work}/scale_0.1/convergence.png", images, "scales_convergence.png")
    for scale, b in scale_runs:
        for row in b["rows"]:
            copy_figure(row_figure(work, f"scale_{scale}", row), images, f"scales_{row['row']}_{scale:g}.png")
    add("Speed against error (one colour and marker per method; dashed: the reference's own ε) and convergence")
    add("with frames (0.1 m):")
    add("")
    add("![speed against error](%s/scales_speed_error.png) ![convergence](%s/scales_convergence.png)" % (rel_images, rel_images))
    add("")
    add("Radiosity maps at each scale: the reference, our first and last frames and the reference run for as long")
    add("as our first frame (top), their differences to the converged reference (bottom), " + DIFFERENCE_NOTE)
    add("")
    for scale, b in scale_runs:
        for row in b["rows"]:
            if row["method"] == "radiosity-maps":
                add("![scale %g](%s/scales_%s_%g.png)" % (scale, rel_images, row["row"], scale))
                add("")
                add("*Bunny at %g m: first frame %s in %s ms; the reference at equal time %s.*" % (
                    scale, pct(row["first_rel_rmse"]), fmt(row["first_wall_ms"], 0), pct(row.get("equal_time_rel_rmse"))))
                add("")


def report_vpl(work, add, images, rel_images):
    add("## Emergent light: virtual point lights (issue 7)")
    add("")
    b = load(f"{work}/vpl_receivers/bench.json")
    ref = b["references"][0]
    em = ref.get("emergent", {})
    add("Candle holder (grapefruit juice, point light in the cavity, dim directional fill), %dx%d, maps converged"
        " over %s frames. The table's VPL term (the frame minus the same frame with `vpl.count=0`) against"
        " `tallow reference --emergent` (%s emitter points per pass, %s passes; its own relative standard error"
        " over the receiver pixels %s), over the %s receiver pixels with emergent light (docs/vpl.md)."
        % (b["width"], b["height"], b["rows"][0]["parameters"]["sss.frames"], em.get("emitter_points"),
           ref.get("passes"), pct(em.get("rel_error")), em.get("receiver_pixels")))
    add("")
    add("| N_vpl | receivers' rel. RMSE | without the reference's ε | mean / reference | vpl pass [ms] | surface pass [ms] |")
    add("|---:|---:|---:|---:|---:|---:|")
    for row in b["rows"]:
        e = row.get("receiver_error", {})
        add("| %s | %s | %s | %s | %s | %s |" % (
            row["settings"]["vpl.count"], pct(e.get("rel_rmse")),
            pct(without_reference_noise(e.get("rel_rmse"), em.get("rel_error"))), fmt(e.get("mean_ratio")),
            fmt(row["gpu_ms_median"].get("vpl"), 1), fmt(row["gpu_ms_median"].get("surface"), 1)))
    add("")
    candles = [(t, load(candle_vpl_folder(work, t) + "/bench.json")) for t in CANDLE_VPL_TIMES]
    c = candles[0][1]
    add("The default candle (`presets/candle.json`, the flame in its cup), %dx%d, maps converged over %s frames, against"
        " the same kind of reference (%s emitter points per pass, %s passes), at two times:"
        % (c["width"], c["height"], c["rows"][0]["parameters"]["sss.frames"],
           c["references"][0].get("emergent", {}).get("emitter_points"), c["references"][0].get("passes")))
    add("")
    add("| t [s] | N_vpl | receiver pixels | reference ε | receivers' rel. RMSE | without the reference's ε | mean / reference | vpl pass [ms] | surface pass [ms] |")
    add("|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for t, c in candles:
        cem = c["references"][0].get("emergent", {})
        for row in c["rows"]:
            e = row.get("receiver_error", {})
            add("| %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
                fmt(t, 0), row["settings"]["vpl.count"], cem.get("receiver_pixels"), pct(cem.get("rel_error")),
                pct(e.get("rel_rmse")), pct(without_reference_noise(e.get("rel_rmse"), cem.get("rel_error"))),
                fmt(e.get("mean_ratio")), fmt(row["gpu_ms_median"].get("vpl"), 1),
                fmt(row["gpu_ms_median"].get("surface"), 1)))
    add("")
    s = load(f"{work}/vpl_shadows/bench.json")
    sem = s["references"][0].get("emergent", {})
    add("VPL shadows (`vpl.shadows`, clustered cube shadow maps, docs/vpl.md) on `candle-holder-block`, an opaque block")
    add("beside the holder, %dx%d, %s VPLs, %s clusters (reference ε over the receivers %s):" % (
        s["width"], s["height"], s["rows"][0]["parameters"]["vpl.count"],
        s["rows"][0]["parameters"]["vpl.shadow_clusters"], pct(sem.get("rel_error"))))
    add("")
    add("| vpl.shadows | receivers' rel. RMSE | without ε | mean / reference | vpl pass [ms] |")
    add("|---|---:|---:|---:|---:|")
    for row in s["rows"]:
        e = row.get("receiver_error", {})
        add("| %s | %s | %s | %s | %s |" % (row["settings"]["vpl.shadows"], pct(e.get("rel_rmse")),
                                            pct(without_reference_noise(e.get("rel_rmse"), sem.get("rel_error"))),
                                            fmt(e.get("mean_ratio")), fmt(row["gpu_ms_median"].get("vpl"), 1)))
    add("")
    report_vpl_pictures(work, add, images, rel_images)
    # Costs.
    add("Cost against N_vpl and receiver pixels (candle holder; llvmpipe, so the ratios matter, not the ms): the `vpl`")
    add("pass (cube of the outermost surface + one compute invocation per VPL; medians over the frames that ran it)")
    add("and the `surface` pass once the maps are converged (the receivers loop over every VPL, and those within 3")
    add("sides of a VPL over its cell's 9 parts as well, docs/vpl.md, so the cost per VPL and pixel falls as N_vpl grows).")
    add("")
    add("| size | N_vpl | receiver pixels | vpl pass [ms] | surface pass [ms] | surface − surface(N=0) per 1000 VPL·Mpixel [ms] |")
    add("|---|---:|---:|---:|---:|---:|")
    spreads = []
    for size in VPL_COST_SIZES:
        base = spread = None
        for n in VPL_COST_COUNTS:
            path = f"{work}/vpl_cost/{size}_{n}/stats.json"
            if not os.path.exists(path):
                continue
            st = load(path)
            frames = st["frames"]
            vpl = median([f["gpu_ms"]["vpl"] for f in frames if "vpl" in f["gpu_ms"]])
            surfaces = [f["gpu_ms"]["surface"] for f in frames[3:]]
            surface = median(surfaces)
            w, h = st["resolution"]
            if n == 0:
                # Half the range of the N = 0 frames' times: a difference within it is the timer's noise.
                base, spread = surface, 0.5 * (max(surfaces) - min(surfaces))
                spreads.append("±%s ms at %s" % (fmt(spread, 1), size))
            per = "—"
            if base is not None and n > 0:
                per = (fmt((surface - base) / (n / 1000.0 * w * h / 1e6), 1) if surface - base > spread
                       else "— (within noise)")
            add("| %s | %d | %d | %s | %s | %s |" % (size, n, w * h, fmt(vpl, 2), fmt(surface, 2), per))
    add("")
    add("(receiver pixels: the image size; the table fills most of it. Within noise: the surface pass took no more"
        " than at N = 0 by half the range of the N = 0 frames' times, %s.)" % ", ".join(spreads))
    add("")
    # Flicker.
    add("Temporal stability: the candle melting from t = 12 s at 30 frames per second under a steady flame")
    add("(`flame.flicker=0`) fixed where it is at 12 s; the mean absolute frame-to-frame change of the receivers' radiance relative to their mean")
    add("(stats.json `receiver_change`), with the paper's fixed directions and with VPLs re-drawn every frame. The")
    add("maps keep each texel's history while the candle deforms (`sss.history`, the default), rescaled to this frame's")
    add("estimate, so part of their noise changes from frame to frame too.")
    add("")
    add("| VPL directions | mean frame-to-frame change | frames |")
    add("|---|---:|---:|")
    for stable, label in (("true", "fixed (`vpl.stable=true`)"), ("false", "re-drawn every frame")):
        st = load(f"{work}/flicker/stable_{stable}/stats.json")
        add("| %s | %s | %d |" % (label, pct(st["summary"]["receiver_change_mean"]), len(st["frames"])))
    add("")
    # The paper's candle settings.
    st = load(f"{work}/candle_paper/stats.json")
    walls = [f["wall_ms"] for f in st["frames"]]
    add("The candle at the paper's Fig. 1 settings (K = 28, N = 45, 80 VPLs), %dx%d, every frame recomputed (`sss.history=0`) as the"
        % tuple(st["resolution"]))
    add("candle melts: median frame %s ms on `%s` (the paper: 6 fps on a GTX 780 Ti; no GPU was available"
        % (fmt(median(walls), 0), st["gl"]["GL_RENDERER"]))
    add("for this run). Passes (median GPU ms): " + ", ".join(
        "%s %s" % (k, fmt(v, 1)) for k, v in st["summary"]["gpu_ms_median"].items()) + ".")
    add("")


def peer_runs(work):
    """(scene label, bench.json) of every scene that ran all methods."""
    runs = [("bunny %g m" % scale, load(f"{work}/scale_{scale}/bench.json")) for scale in SCALES]
    runs += [(label, load(f"{peer_folder(work, label)}/bench.json")) for label, *_ in PEER_SCENES]
    return runs


def peers_plot(runs, images, name):
    """One plot of speed against error: every method on every scene, first frame (filled) and converged
    frame (open), through gnuplot (a note instead when gnuplot is missing)."""
    if shutil.which("gnuplot") is None:
        return False
    data = os.path.join(images, name + ".csv")
    with open(data, "w") as f:
        for label, b in runs:
            for row in b["rows"]:
                conv = row.get("median_converged_wall_ms") or row.get("median_wall_ms")
                f.write("%s,%s,%.6g,%.6g,%.6g,%.6g\n" % (label, row["method"], row["first_wall_ms"],
                                                         row["first_rel_rmse"], conv, row["last_rel_rmse"]))
    styles = {"radiosity-maps": 7, "no-cache": 5, "sslpv": 9, "image-space": 13, "burley": 11}
    plots = []
    for i, method in enumerate(PEER_METHODS):
        sel = "(strcol(2) eq '%s' ? $%%d : NaN)" % method
        plots.append("'%s' using 3:%s with points pt %d ps 1.6 lc %d title '%s, first frame'"
                     % (data, sel % 4, styles[method], i + 1, method))
        plots.append("'%s' using 5:%s with points pt %d ps 1.6 lc %d title '%s, converged'"
                     % (data, sel % 6, styles[method] - 1, i + 1, method))
    script = "\n".join([
        "set datafile separator ','",
        "set terminal pngcairo size 900,600 font ',11'",
        "set output '%s.tmp.png'" % os.path.join(images, name),
        "set logscale xy", "set grid",
        "set xlabel 'frame time [ms] (llvmpipe)'", "set ylabel 'relative RMSE against the reference'",
        "set key outside right top",
        "plot " + ", ".join(plots), ""])
    subprocess.run(["gnuplot"], input=script, text=True, check=True)
    os.replace(os.path.join(images, name + ".tmp.png"), os.path.join(images, name + ".png"))
    os.remove(data)
    return True


def report_burley(runs, add):
    """Issue 41: where the engines' method wins and where it fails, from the peers' table."""
    pairs = []
    for label, b in runs:
        by = {r["method"]: r for r in b["rows"]}
        if "burley" in by and "radiosity-maps" in by:
            pairs.append((label, by["burley"], by["radiosity-maps"], by))
    if not pairs:
        return
    add("The engines' method (`burley`) against the radiosity maps, scene by scene (first frame: time ratio maps /")
    add("burley, error ratio burley / maps; converged: error ratio):")
    add("")
    for label, bu, m, by in pairs:
        rank = 1 + sum(1 for r in by.values() if r["method"] in PEER_METHODS and r["first_wall_ms"] < bu["first_wall_ms"])
        add("- **%s**: first frame %.1fx as fast (rank %d of %d by time), %s against %s (%.1fx the error); converged %s"
            " against %s; mean L / reference %s." % (
                label, m["first_wall_ms"] / bu["first_wall_ms"], rank,
                sum(1 for r in by.values() if r["method"] in PEER_METHODS), pct(bu["first_rel_rmse"]),
                pct(m["first_rel_rmse"]), bu["first_rel_rmse"] / max(m["first_rel_rmse"], 1e-9),
                pct(bu["last_rel_rmse"]), pct(m["last_rel_rmse"]), fmt(bu["last_error"].get("mean_ratio"))))
    side = next((bu for label, bu, _, _ in pairs if label == "bunny 0.1 m"), None)
    front = next((bu for label, bu, _, _ in pairs if label == "bunny front-lit"), None)
    if side and front:
        add("")
        worse = side["last_rel_rmse"] > 1.1 * front["last_rel_rmse"]
        add("The 0.1 m bunny lit from the camera's side and from its left (the preset): `burley` %s and %s (the"
            " issue's bound for the front-lit bunny: 30%%); %s" % (
                pct(front["last_rel_rmse"]), pct(side["last_rel_rmse"]),
                "worse from the side: a radial profile has no direction, so light entering at a grazing angle"
                " scatters as if it had come straight in." if worse else
                "about the same: on the bunny its error does not come from the light's direction but from"
                " what both lightings share (the mean L / reference above)."))
    add("")


def report_peers(work, add, images, rel_images):
    """Issues 8 and 41: every method on the same scenes, one table and one plot, and where each wins."""
    runs = peer_runs(work)
    add("## The peers side by side (issue 8)")
    add("")
    add("Every method on the same scenes, lights and materials, each against the same `tallow reference`: the")
    add("scattered radiosity maps (`radiosity-maps`), their gather per camera pixel without a cache (`no-cache`,")
    add("the paper's Fig. 11 variant), subsurface light propagation volumes (`sslpv`, docs/sslpv.md),")
    add("image-space importance sampling of the dipole (`image-space`, docs/image-space.md) and what engines")
    add("ship, Christensen and Burley's diffusion profile in screen space with shadow-map transmission (`burley`,")
    add("docs/burley.md). The bunny runs at three scales are the equal-time runs above (lit from the side, as the")
    add("preset); `bunny front-lit` is the 0.1 m bunny at 96x72 lit from the camera's side (light direction")
    add("%s); the blob is frozen at t = 2.5 s; the candle is the default one at its start (t = 16 s). `first` is the first frame after a" % FRONT_LIGHT)
    add("restart (what an animated scene pays every frame), `converged` the last frame of the run (a still")
    add("scene, after the progressive methods have accumulated). Device: `%s`; times are llvmpipe's, so compare"
        % runs[0][1]["gpu"]["GL_RENDERER"])
    add("them as ratios within a scene.")
    add("")
    add("| scene | method | first frame [ms] | first frame rel. RMSE | converged frame [ms] | converged rel. RMSE | mean L / reference | reference ε |")
    add("|---|---|---:|---:|---:|---:|---:|---:|")
    wins = []
    for label, b in runs:
        rows = [r for r in b["rows"] if r["method"] in PEER_METHODS]
        for row in rows:
            add("| %s | %s | %s | %s | %s | %s | %s | %s |" % (
                label, row["method"], fmt(row["first_wall_ms"], 1), pct(row["first_rel_rmse"]),
                fmt(row.get("median_converged_wall_ms") or row.get("median_wall_ms"), 1), pct(row["last_rel_rmse"]),
                fmt(row["last_error"].get("mean_ratio")), pct(reference_error(b, row))))
        if rows:
            fastest = min(rows, key=lambda r: r["first_wall_ms"])
            first = min(rows, key=lambda r: r["first_rel_rmse"])
            conv = min(rows, key=lambda r: r["last_rel_rmse"])
            # Pareto front of (first-frame time, first-frame error): no other method is both faster and closer.
            front = [r["method"] for r in rows if not any(
                o is not r and o["first_wall_ms"] <= r["first_wall_ms"] and o["first_rel_rmse"] <= r["first_rel_rmse"]
                for o in rows)]
            wins.append("- **%s**: fastest first frame %s (%s ms); lowest first-frame error %s (%s); lowest converged"
                        " error %s (%s); not beaten on both time and error by another method: %s." % (
                            label, fastest["method"], fmt(fastest["first_wall_ms"], 0), first["method"],
                            pct(first["first_rel_rmse"]), conv["method"], pct(conv["last_rel_rmse"]), ", ".join(front)))
    add("")
    add("Where each method wins (from the table):")
    add("")
    for w in wins:
        add(w)
    add("")
    report_burley(runs, add)
    add("The 0.1 m bunny, each method: the reference, the method's first and last frames and the reference run for")
    add("as long as its first frame (top), their differences to the reference (bottom), " + DIFFERENCE_NOTE)
    add("")
    for row in load(f"{work}/scale_0.1/bench.json")["rows"]:
        if row["method"] in PEER_METHODS:
            add("![%s](%s/scales_%s_0.1.png)" % (row["method"], rel_images, row["row"]))
            add("")
            add("*%s: first frame %s, last frame %s.*" % (row["method"], pct(row["first_rel_rmse"]),
                                                         pct(row["last_rel_rmse"])))
            add("")
    if peers_plot(runs, images, "peers_speed_error"):
        add("Speed against error, every scene (filled: first frame; open: converged):")
        add("")
        add("![speed against error, all methods](%s/peers_speed_error.png)" % rel_images)
    else:
        add("(gnuplot was not installed when this was generated: no plot.)")
    add("")


def report_gpu(folder, md):
    """Issue 18: the section of a GPU run of the device bench (docs/device-bench.md). FOLDER holds the
    results.md and results.json that bench.sh wrote on the GPU machine, copied here as they are; the
    section includes that results.md under a heading naming the device. Without them, or when they
    come from a software renderer, it says that no GPU figures exist yet."""
    L = []
    add = L.append
    add("")
    add("## On a GPU (issue 18)")
    add("")
    results_md = os.path.join(folder, "results.md")
    results_json = os.path.join(folder, "results.json")
    gpu = None
    if os.path.exists(results_md) and os.path.exists(results_json):
        gpu = load(results_json)
        if gpu["device"].get("software"):
            gpu = None
    rel = os.path.relpath(folder, os.path.dirname(os.path.abspath(md)))
    if gpu is None:
        add("**No GPU figures exist yet: every time in this file is llvmpipe's**, a software rasteriser on this CPU.")
        add("The device bench measures a real GPU in one run of at most 8 minutes: `scripts/device_bundle.sh` packs")
        add("Tallow with its libraries, and its `bench.sh` writes `results.md` and `results.json` there")
        add("(docs/device-bench.md). Copied into `%s/` beside this file, they become this section when RESULTS is" % rel)
        add("regenerated.")
    else:
        dev = gpu["device"]
        name = dev.get("nvidia_smi_name") or dev.get("GL_RENDERER")
        add("Measured on **%s** (`%s`, OpenGL %s, driver %s) by the device bench (docs/device-bench.md), mode `%s`,"
            % (name, dev.get("GL_RENDERER"), dev.get("GL_VERSION"), dev.get("nvidia_smi_driver") or "—",
               gpu["meta"].get("mode")))
        add("Tallow %s; its `results.md` and `results.json` are in `%s/` beside this file. The run's report follows, headings"
            % ((gpu.get("bundle") or {}).get("commit", "—"), rel))
        add("two levels down.")
        add("")
        with open(results_md) as f:
            for line in f.read().splitlines():
                add("##" + line if line.startswith("#") else line)
    with open(md, "a") as f:
        f.write("\n".join(L) + "\n")


def splice_vpl(work, md, images):
    """Only the VPL section, regenerated from run_vpl's runs and put in place in MD."""
    os.makedirs(images, exist_ok=True)
    lines = []
    report_vpl(work, lines.append, images, os.path.relpath(images, os.path.dirname(md)))
    results_sections.splice(md, lines[0], lines)


def splice_peers(work, md, images):
    """Only the equal-time runs at three scales (Fig. 9, a ### part of the issue-6 section) and the
    peers' section, regenerated from run-peers' runs and put in place in MD."""
    os.makedirs(images, exist_ok=True)
    rel_images = os.path.relpath(images, os.path.dirname(md))
    for report_part in (report_scales, report_peers):
        lines = []
        report_part(work, lines.append, images, rel_images)
        results_sections.splice(md, lines[0], lines)


def main(argv):
    if len(argv) >= 2 and argv[0] == "run":
        run(argv[1], "--quick" in argv[2:])
    elif len(argv) >= 2 and argv[0] == "run-vpl":
        os.makedirs(argv[1], exist_ok=True)
        run_vpl(argv[1], "--quick" in argv[2:])
    elif len(argv) == 4 and argv[0] == "splice-vpl":
        splice_vpl(argv[1], argv[2], argv[3])
    elif len(argv) >= 2 and argv[0] == "run-peers":
        os.makedirs(argv[1], exist_ok=True)
        run_scales(argv[1], "--quick" in argv[2:])
        run_peers(argv[1], "--quick" in argv[2:])
    elif len(argv) == 4 and argv[0] == "splice-peers":
        splice_peers(argv[1], argv[2], argv[3])
    elif len(argv) == 4 and argv[0] == "report":
        report(argv[1], argv[2], argv[3])
    elif len(argv) == 3 and argv[0] == "gpu":
        report_gpu(argv[1], argv[2])
    else:
        sys.exit("usage: results_bench.py run DIR [--quick] | run-vpl DIR [--quick] | report DIR MD IMAGES |"
                 " splice-vpl DIR MD IMAGES | run-peers DIR [--quick] | splice-peers DIR MD IMAGES | gpu FOLDER MD")


if __name__ == "__main__":
    main(sys.argv[1:])
