#!/usr/bin/env python3
"""Issue 41, point 3: the picture that explains the project. The default candle (t = 16 s, its start)
by the engines' screen-space diffusion profile (`method=burley`, docs/burley.md, both of its kernels)
and by the scattered radiosity maps, each against the same `tallow reference` (its emergent light on
the table included): one `tallow bench` run, its table and its comparison pictures. Then the
kernel's choice (burley.kernel: importance-sampled discs or two separable passes) measured on the
front-lit marble bunny at the issue's 96x72 as well.

  results_candle_peers.py run DIR [--quick]     benches into DIR (TALLOW: the binary); --quick: 64x36, 4 spp
  results_candle_peers.py report DIR MD         appends the section to MD
  results_candle_peers.py splice DIR MD         replaces the section in MD (or adds it before the GPU section)

Called by scripts/results.sh (run, report).
"""
import json
import os
import shutil
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import results_sections  # noqa: E402

HEADING = "## The default candle by the engines' method and by the radiosity maps (issue 41)"
METHODS = ["radiosity-maps", "burley"]
KERNELS = "burley.kernel=disc,separable"
FRONT_LIGHT = "0.15,0.37,0.92"  # results_bench.py's front-lit bunny
IMAGES = "images/results"


def run(work, quick):
    os.makedirs(work, exist_ok=True)
    tallow = os.environ.get("TALLOW", "build/tallow")
    out = os.path.join(work, "bench")
    size = "64x36" if quick else "160x90"
    with open(os.path.join(work, "size.txt"), "w") as f:
        f.write(size + "\n")
    results_sections.run_once(
        [tallow, "bench", "--preset", "candle", "--time", "16", "--size", size,
         "--methods", ",".join(METHODS), "--set", "sss.frames=" + ("2" if quick else "16"), "--sweep", KERNELS,
         "--receivers", "--ref-spp", "4" if quick else "64", "--out", out],
        os.path.join(out, "bench.json"))
    kernels = os.path.join(work, "kernels")
    results_sections.run_once(
        [tallow, "bench", "--preset", "bunny", "--size", "64x48" if quick else "96x72", "--set",
         f"light.direction={FRONT_LIGHT}", "--methods", "burley", "--sweep", KERNELS, "--ref-spp", "4" if quick else "64",
         "--out", kernels],
        os.path.join(kernels, "bench.json"))


def section(work):
    with open(os.path.join(work, "bench", "bench.json")) as f:
        bench = json.load(f)
    lines = []
    add = lines.append
    add(HEADING)
    add("")
    add(results_sections.generated_line("results_candle_peers.py", "`tallow bench`", [bench]))
    add("")
    # burley.kernel is swept for burley's sake; the maps' rows do not read it, so one of them stands
    # for the maps (the other is the same run again).
    rows = []
    for r in bench["rows"]:
        if r["method"] not in METHODS or (r["method"] != "burley" and any(x["method"] == r["method"] for x in rows)):
            continue
        rows.append(r)
    first = rows[0]
    add("The default candle at its start (t = 16 s: the pool, the rim, the frozen drips, the flame in the hollow),")
    with open(os.path.join(work, "size.txt")) as f:
        size = f.read().strip()
    add("%s, by the engines' method — Christensen and Burley's diffusion profile in screen space with" % size)
    add("transmission from the shadow maps (`method=burley`, docs/burley.md) — and by the scattered radiosity")
    add("maps, each against the same `tallow reference` (reference ε %s). `first` is a frame after a restart"
        % results_sections.pct(first.get("reference_rel_error")))
    add("(what the melting candle pays every frame), `converged` the last of the run; errors are relative")
    add("RMSE over the candle's pixels; the table's glow (the light the wax gives its surroundings) is the")
    add("receivers' error against the reference's emergent light (`--receivers`). Device: `%s`; compare"
        % bench["gpu"]["GL_RENDERER"])
    add("times as ratios.")
    add("")
    add("| method | first frame [ms] | first rel. RMSE | converged [ms] | converged rel. RMSE | mean L / reference (upper, lower half) | table's glow rel. RMSE | table's glow / reference |")
    add("|---|---:|---:|---:|---:|---:|---:|---:|")
    for r in rows:
        conv = r.get("median_converged_wall_ms") or r.get("median_wall_ms")
        glow = r.get("receiver_error") or {}
        add("| %s | %s | %s | %s | %s | %s, %s | %s | %s |" % (
            label(r), results_sections.fmt(r["first_wall_ms"], 1), results_sections.pct(r["first_rel_rmse"]),
            results_sections.fmt(conv, 1), results_sections.pct(r["last_rel_rmse"]),
            results_sections.fmt(r.get("last_upper_mean_ratio")), results_sections.fmt(r.get("last_lower_mean_ratio")),
            results_sections.pct(glow.get("rel_rmse")), results_sections.fmt(glow.get("mean_ratio"))))
    add("")
    disc = next((r for r in rows if r["method"] == "burley" and "separable" not in r["row"]), None)
    maps = next((r for r in rows if r["method"] == "radiosity-maps"), None)
    if disc and maps:
        b, m = disc, maps
        add("What the table says: the engines' method draws its first frame %.1fx as fast as the maps' restart"
            % (m["first_wall_ms"] / b["first_wall_ms"]))
        add("(a melting candle restarts the maps every frame), with %.1fx their error; the flame sits inside the"
            % (b["last_rel_rmse"] / max(m["last_rel_rmse"], 1e-9)))
        add("hollow, so the wax below the rim gets its light through more wax than the profile's transmittance")
        add("carries (mean L / reference %s in the lower half, %s in the upper), and nothing reaches the table"
            % (results_sections.fmt(b.get("last_lower_mean_ratio")), results_sections.fmt(b.get("last_upper_mean_ratio"))))
        add("(its glow %s of the reference's): a screen-space profile has no light for the surroundings." %
            results_sections.fmt((b.get("receiver_error") or {}).get("mean_ratio")))
        add("")
    images = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "docs", IMAGES)
    os.makedirs(images, exist_ok=True)
    for r in rows:
        if "separable" in r["row"]:
            continue  # the kernel's choice below; the pictures show the default
        src = os.path.join(work, "bench", r.get("folder", "rows/" + r["row"]), "comparison.png")
        name = "candle_peers_%s.png" % r["method"]
        if os.path.exists(src):
            shutil.copyfile(src, os.path.join(images, name))
            add("![the candle by %s](%s/%s)" % (r["method"], IMAGES, name))
            add("")
            add("*%s: first frame %s, last frame %s against the reference.*" % (
                r["method"], results_sections.pct(r["first_rel_rmse"]), results_sections.pct(r["last_rel_rmse"])))
            add("")
    kernel_choice(work, add, rows)
    add(results_sections.rerun("results_candle_peers.py"))
    add("")
    return lines


def label(row):
    """A row's name in the tables: the method, and for burley its kernel."""
    if row["method"] != "burley":
        return row["method"]
    return "burley (%s)" % ("separable" if "separable" in row["row"] else "disc")


def kernel_choice(work, add, candle_rows):
    """burley.kernel's default, chosen by the error against the reference on the front-lit bunny and
    the candle (the disc kernel unless the separable one is closer on both)."""
    with open(os.path.join(work, "kernels", "bench.json")) as f:
        bunny = json.load(f)
    add("### The kernel of `burley`, measured")
    add("")
    add("The same profile applied by importance-sampled discs facing the camera (`burley.kernel=disc`, Unreal's")
    add("way, 32 samples a pixel) or by a horizontal then a vertical pass of 33 taps (`separable`, Jimenez et")
    add("al. 2015's structure), against the reference, converged frames:")
    add("")
    add("| scene | kernel | converged [ms] | converged rel. RMSE |")
    add("|---|---|---:|---:|")
    errors = {"disc": [], "separable": []}
    for label, rows in (("bunny front-lit (%dx%d)" % (bunny["width"], bunny["height"]), bunny["rows"]),
                        ("candle", [r for r in candle_rows if r["method"] == "burley"])):
        for r in rows:
            kernel = "separable" if "separable" in r["row"] else "disc"
            errors[kernel].append(r["last_rel_rmse"])
            add("| %s | %s | %s | %s |" % (label, kernel, results_sections.fmt(
                r.get("median_converged_wall_ms") or r.get("median_wall_ms"), 1), results_sections.pct(r["last_rel_rmse"])))
    add("")
    better = all(s < d for s, d in zip(errors["separable"], errors["disc"])) and errors["separable"]
    add("The default is `disc`; %s" % ("the separable passes are closer to the reference in both scenes, so the"
                                       " default should change." if better else
                                       "the separable passes are not closer to the reference in both scenes."))
    add("")


if __name__ == "__main__":
    results_sections.main(sys.argv[1:], __doc__, run, section, HEADING)
