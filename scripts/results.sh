#!/usr/bin/env bash
# Regenerates docs/RESULTS.md from fresh runs of `tallow probe extraction` (issue 4, point 8):
# GPU dual contouring against OpenVDB's CPU mesher at 64³, 128³ and 256³ for the blob and the candle;
# and of `tallow probe maps` (issue 5, point 9): the cost of the scattered radiosity maps against
# K (maps) and N (samples) on the bunny; and of the issue-6 experiments (scripts/results_bench.py:
# `tallow bench` against `tallow reference`, `tallow capture` for occupancy and coverage) and the
# issue-7 experiments (VPLs against the reference's emergent light, their cost, flicker) and the
# issue-8 comparison of the four methods (radiosity maps, no-cache, SSLPV, image-space); and of
# `tallow probe placement` (issue 16, point 4: dual contouring's vertex placements against the exact
# surface, scripts/results_placement.py) and of `tallow capture` on the animated candle and blob with
# the fields evaluated on the CPU and on the GPU (issue 16, point 7, scripts/results_fields.py) and
# with the maps restarted or kept while they move (issue 17, point 3, scripts/results_history.py), and
# the bunny at three scales with the map sizes and K fixed and chosen (issue 17, point 4,
# scripts/results_auto.py), and the animated default candle, the melting one (issues 17 and 35,
# scripts/results_animated.py), and a 10 000-frame capture's
# bytes, time and memory per frame (issue 37, point 6, scripts/results_soak.py), and the melting
# candle measured on its meshes (issue 35, point 6, scripts/results_melt.py), and the clean picture
# (issue 36: anti-aliasing, glare, dither; scripts/results_picture.py), and dual contouring in
# compute against geometry shaders (issue 39, point 1; scripts/results_extraction.py) and the default
# candle counted per pass and projected onto GPUs (issue 39, points 6-7; scripts/results_passes.py), and
# the default candle by the engines' diffusion profile beside the radiosity maps (issue 41, point 3;
# scripts/results_candle_peers.py). Every
# number in the file comes from those runs; nothing is typed by hand.
# Usage: bash scripts/results.sh [--quick]   (--quick: 1 repeat, for a smoke run)
# The build folder is scripts/build.sh's: build/ unless TALLOW_BUILD_DIR is set.
# TALLOW_RESULTS_WORK=DIR keeps every run's output in DIR (a temporary folder, removed, otherwise);
# with TALLOW_RESULTS_RESUME=1 as well, runs whose output is already whole in DIR are not repeated,
# so an interrupted regeneration resumes and one experiment can be rerun by deleting its folder.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$(bash "$root/scripts/build.sh" | tail -n 1)"
tallow="$build/tallow"
repeats=5
maps_repeats=3
quick=""
if [ "${1:-}" = "--quick" ]; then repeats=1; maps_repeats=1; quick=1; fi
if [ -n "${TALLOW_RESULTS_WORK:-}" ]; then
  work="$TALLOW_RESULTS_WORK"
  mkdir -p "$work"
else
  work="$(mktemp -d)"
  trap 'rm -rf "$work"' EXIT
fi
# kept FILE: true when resuming and FILE is already whole (every output is written by rename).
kept() { [ "${TALLOW_RESULTS_RESUME:-0}" = "1" ] && [ -s "$1" ]; }

echo "results: tallow probe extraction (blob, candle; 64, 128, 256; $repeats repeats)"
kept "$work/extraction.json" || "$tallow" probe extraction --fields blob,candle --res 64,128,256 --repeats "$repeats" --out "$work/extraction.json"
echo "results: tallow probe placement (cube, candle, sphere, blob; 32, 64, 128; $maps_repeats repeats)"
kept "$work/placement.json" || "$tallow" probe placement --shapes cube,candle,sphere,blob --res 32,64,128 --repeats "$maps_repeats" --out "$work/placement.json"
echo "results: tallow probe maps (bunny; K 4, 8, 16; N 1, 4, 8; 256² maps; $maps_repeats repeats)"
kept "$work/maps.json" || "$tallow" probe maps --preset bunny --k 4,8,16 --n 1,4,8 --map-size 256 --repeats "$maps_repeats" --out "$work/maps.json"
for gather in fragment compute; do
  echo "results: tallow probe maps (bunny; K 8, N 4; 256² maps; sss.gather=$gather)"
  kept "$work/gather_$gather.json" || "$tallow" probe maps --preset bunny --k 8 --n 4 --map-size 256 --repeats "$maps_repeats" --gather "$gather" \
    --out "$work/gather_$gather.json"
done

# Issue 6: speed against error, every figure from `tallow bench` / `tallow capture` runs (see
# scripts/results_bench.py for the experiments and the section they become).
TALLOW="$tallow" python3 "$root/scripts/results_bench.py" run "$work/bench" ${quick:+--quick}
# Issue 16, point 7: the animated candle and blob, CPU-evaluated (the path before) against GPU fields.
TALLOW="$tallow" python3 "$root/scripts/results_fields.py" run "$work/fields" ${quick:+--quick}
# Issue 17, point 3: frame k of the animated blob and candle against the reference at t_k, the maps
# restarted at every frame against kept per texel (sss.history).
TALLOW="$tallow" python3 "$root/scripts/results_history.py" run "$work/history" ${quick:+--quick}
# Issue 17, point 4: the map and light G-buffer sizes chosen from the scene (auto) against the fixed
# 512, the marble bunny at 0.01, 0.1 and 1 m.
TALLOW="$tallow" python3 "$root/scripts/results_auto.py" run "$work/auto" ${quick:+--quick}
# Issues 17 (point 5) and 35 (point 6): the animated default candle against the references at each
# frame's time, restarted, with the defaults and with K = 16.
TALLOW="$tallow" python3 "$root/scripts/results_animated.py" run "$work/animated" ${quick:+--quick}
# Issue 37, point 6: a 10 000-frame capture's bytes written, time between frames and memory.
TALLOW="$tallow" python3 "$root/scripts/results_soak.py" run "$work/soak" ${quick:+--quick}
TALLOW="$tallow" python3 "$root/scripts/results_melt.py" run "$work/melt" ${quick:+--quick}
# Issue 39, points 6 and 7: the default candle counted per pass, dual contouring before and after it
# moved to compute, projected onto GPUs by the cost model (scripts/results_passes.py).
TALLOW="$tallow" python3 "$root/scripts/results_passes.py" run "$work/passes" ${quick:+--quick}
# Issue 41, point 3: the default candle by method=burley and by the radiosity maps against the reference.
TALLOW="$tallow" python3 "$root/scripts/results_candle_peers.py" run "$work/candle_peers" ${quick:+--quick}
# Issue 36: the clean picture: anti-aliased stills, the glare, the dither (captures and the GL tests
# that measure against independent answers).
TALLOW="$tallow" TALLOW_GLTESTS="$build/tests/tallow_gltests" TALLOW_TESTS="$build/tests/tallow_tests" \
  python3 "$root/scripts/results_picture.py" run "$work/picture" ${quick:+--quick}

python3 - "$work/extraction.json" "$root/docs/RESULTS.md.tmp" "$repeats" "$(nproc 2>/dev/null || echo '?')" "$work/maps.json" "$work/gather_fragment.json" "$work/gather_compute.json" <<'PY'
import json, sys, datetime, platform
src, dst, repeats, cores, maps_src = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4], sys.argv[5]
gathers = {}
for name, path in (("fragment", sys.argv[6]), ("compute", sys.argv[7])):
    with open(path) as f:
        gathers[name] = json.load(f)["rows"][0]
with open(src) as f:
    r = json.load(f)
with open(maps_src) as f:
    m = json.load(f)
lines = []
add = lines.append
gpu = r["gpu"]
renderer = gpu["GL_RENDERER"]
software = any(s in renderer.lower() for s in ("llvmpipe", "softpipe", "swrast", "lavapipe"))
cpu_model = "unknown CPU"
try:
    with open("/proc/cpuinfo") as f:
        for line in f:
            if line.startswith("model name"):
                cpu_model = line.split(":", 1)[1].strip()
                break
except OSError:
    pass

add("# Results")
add("")
add("Generated by `scripts/results.sh` on %s UTC from fresh runs of `tallow probe extraction` and"
    % datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M"))
add("`tallow probe maps`; do not edit by hand. Figures measured on a GPU, if any, are in the last section,")
add("*On a GPU*.")
add("")
add("## Isosurface extraction (issue 4, point 8)")
add("")
add("Device: `%s` (%s, %s), OpenGL context `%s`; CPU: %s, %s hardware threads visible." %
    (renderer, gpu["GL_VERSION"], platform.machine(), gpu["backend"], cpu_model, cores))
add("")
if software:
    add("**The GPU figures below come from a software rasteriser (%s) running on this CPU. They say" % renderer)
    add("nothing about a real GPU**; they only show how the GPU path's cost scales and that it runs.")
    add("")
add("Timings are medians of %d runs after one warm-up, on a machine shared with other builds, so they" % r["repeats"])
add("are noisy. Each field is sampled once on the CPU per resolution (`sample`); the GPU path and")
add("OpenVDB's `volumeToMesh` then contour exactly the same lattice. `GPU` is the span between")
add("GL_TIMESTAMP queries around `extract()` (four passes, %d³-cell blocks, vertices placed by `field.placement=%s`)," % (r["block_cells"], r.get("placement", "mass")))
add("`GPU wall` is `extract()` +")
add("`glFinish()` on the CPU clock; the upload of the lattice into the 3D texture is excluded from both and")
add("listed on its own. `CPU` is OpenVDB's mesher plus per-vertex gradient normals. Triangles per second")
add("use the GPU timestamp span and the CPU time respectively. Buffer memory is everything the GPU path")
add("allocates: lattice texture, index map, vertex and mesh buffers, block list.")
add("")

def fmt(x, d=2):
    return "—" if x is None else ("%.*f" % (d, x))

def mega(x):
    return "%.2f M" % (x / 1e6)

for field in r["fields"]:
    add("### %s (t = %g s)" % (field["field"], field["time_s"]))
    add("")
    add("| res | sample [ms] | upload [ms] | GPU [ms] | GPU wall [ms] | CPU OpenVDB [ms] | triangles GPU / CPU | triangles/s GPU / CPU | active / all blocks | GPU buffers [MiB] |")
    add("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for row in field["rows"]:
        add("| %d³ | %s | %s | %s | %s | %s | %d / %d | %s / %s | %d / %d (%.1f%%) | %.1f |" % (
            row["res"], fmt(row["sample_cpu_ms"]), fmt(row["gpu_upload_ms"]), fmt(row["gpu_extract_ms"]),
            fmt(row["gpu_extract_wall_ms"]), fmt(row["cpu_mesh_ms"]), row["gpu_triangles"], row["cpu_triangles"],
            mega(row["gpu_triangles_per_s"]), mega(row["cpu_triangles_per_s"]), row["active_blocks"], row["blocks"],
            100.0 * row["active_blocks"] / row["blocks"], row["gpu_buffer_bytes"] / 2**20))
    add("")
    ratios = field["ratio_256_128"]
    def verdict(x):
        if x is None:
            return "not measured (needs both 128³ and 256³)"
        return "%.2f — %s the bound of 5" % (x, "under" if x < 5.0 else "**over**")
    add("time(256³) / time(128³), against the issue's bound of 5 (the surface grows about 4×, the volume 8×;")
    add("the bound is on the GPU path, OpenVDB is the reference):")
    add("")
    add("- GPU (timestamps): %s" % verdict(ratios["gpu_extract"]))
    add("- GPU (wall, glFinish): %s" % verdict(ratios["gpu_extract_wall"]))
    add("- CPU (OpenVDB): %s" % verdict(ratios["cpu_mesh"]))
    add("")

add("### Rerun")
add("")
add("`bash scripts/results.sh` (builds with `scripts/build.sh`, honours `TALLOW_BUILD_DIR`), or directly")
add("`tallow probe extraction --fields blob,candle --res 64,128,256 --repeats %d --out extraction.json`." % repeats)
add("")
add("## Scattered radiosity maps: cost against K and N")
add("")
mg = m["gpu"]
ms = m["settings"]
mrenderer = mg["GL_RENDERER"]
add("Device: `%s` (%s), OpenGL context `%s`; CPU: %s, %s hardware threads visible." %
    (mrenderer, mg["GL_VERSION"], mg["backend"], cpu_model, cores))
add("")
if any(s in mrenderer.lower() for s in ("llvmpipe", "softpipe", "swrast", "lavapipe")):
    add("**The GPU figures below come from a software rasteriser (%s) running on this CPU. They say" % mrenderer)
    add("nothing about a real GPU**; they only show how the maps' cost scales with K and N and that they run.")
    add("")
def squared(size):
    """A map size as the probe recorded it: a number of texels a side, or `auto` (sized from the scene)."""
    return "%d²" % size if isinstance(size, int) else "`%s`-sized" % size

add("Preset `%s` at %d×%d, %s maps, %s light G-buffers, %s dipole, `sss.gather` = %s, %d light(s)."
    % (m["preset"], ms["width"], ms["height"], squared(ms["map_size"]), squared(ms["light_map_size"]), ms["model"],
       ms.get("gather") or "—", m["rows"][0]["lights"]))
add("For each K (`sss.maps`)")
add("and N (`sss.samples`) the renderer renders one warm-up frame, which restarts the maps (light")
add("G-buffers, the maps' depth pre-pass, the first N samples), then %d frames in which nothing changes and" % ms["repeats"])
add("`sss.frames` is raised so that the maps keep accumulating: each of them runs `sss.maps` alone (N")
add("more samples per shaded texel, map and colour band) on the warm-up frame's light G-buffers, which")
add("are kept since nothing their pass reads changed. Times are medians of GL timestamp spans over those")
add("frames, on a machine shared with other builds, so they are noisy; the light G-buffer column and")
add("`first frame` are the warm-up frame's passes. Memory is the maps (RGBA32F with mipmaps) and their depth (32-bit float);")
add("the light G-buffers come on top (`sss_bytes` in the JSON). Shaded texels are the level-0 map texels")
add("whose alpha (frames accumulated) is above 0, over all K maps, read back after the run.")
add("Evaluations per second = shaded texels × 3 bands × N × lights / `sss.maps` time: an upper bound,")
add("since every sample is counted as a BSSRDF evaluation, samples that miss the object included, and")
add("the pass's time also holds its fixed per-map costs (drawing the maps' texels, mipmaps).")
add("")
add("| K | N | K·N | light G-buffer [ms] | maps [ms] | surface [ms] | first frame G-buffer / maps [ms] | shaded texels | maps memory [MiB] | evaluations/s |")
add("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
for row in m["rows"]:
    ff = row["first_frame"]
    add("| %d | %d | %d | %s | %s | %s | %s / %s | %d (%.1f%%) | %.2f | %s |" % (
        row["k"], row["n"], row["k_times_n"], fmt(row["light_gbuffer_ms"], 3), fmt(row["maps_ms"]),
        fmt(row["surface_ms"]), fmt(ff["light_gbuffer_ms"]), fmt(ff["maps_ms"]), row["shaded_texels"],
        100.0 * row["shaded_share"], row["map_bytes"] / 2**20, mega(row["evaluations_per_s"])))
add("")
fit, fk, fkn = m["fit"], m["fit_k"], m["fit_k_kn"]
add("Least-squares fits of the `sss.maps` time over the %d rows (the paper's Fig. 13 finds the cost" % len(m["rows"]))
add("linear in K):")
add("")
add("- time = a + b·K·N: a = %.3f ms, b = %.4f ms per map and sample, R² = %.3f" % (fit["intercept_ms"], fit["slope_ms"], fit["r2"]))
add("- time = a + b·K: a = %.3f ms, b = %.3f ms per map, R² = %.3f" % (fk["intercept_ms"], fk["slope_ms"], fk["r2"]))
add("- time = a + c·K + b·K·N: a = %.3f ms, c = %.3f ms per map, b = %.4f ms per map and sample, R² = %.3f" % (
    fkn["intercept_ms"], fkn["per_map_ms"], fkn["per_sample_ms"], fkn["r2"]))
add("")
add("Rerun: `tallow probe maps --preset bunny --k 4,8,16 --n 1,4,8 --map-size 256 --repeats %d --out maps.json`." % ms["repeats"])
add("")
add("### The two gathers (`sss.gather`)")
add("")
add("The same maps (bit for bit, `tests/radiosity_maps_gltest.cpp`) by the paper's layered fragment pass")
add("and by the compute pass over the maps' G-buffer, bunny, K = 8, N = 4, 256² maps, in one run:")
add("")
add("| gather | maps [ms] | evaluations/s | shaded texels |")
add("|---|---:|---:|---:|")
for name in ("fragment", "compute"):
    g = gathers[name]
    add("| %s | %s | %s | %d |" % (name, fmt(g["maps_ms"]), mega(g["evaluations_per_s"]), g["shaded_texels"]))
add("")
add("Time ratio fragment / compute: %.2f on this device." % (gathers["fragment"]["maps_ms"] / gathers["compute"]["maps_ms"]))
add("")
add("## BSSRDF models")
add("")
add("Profiles against the Monte Carlo reference, the models' errors and their evaluation cost are in")
add("[bssrdf.md](bssrdf.md), generated by `scripts/bssrdf_docs.sh`.")
with open(dst, "w") as f:
    f.write("\n".join(lines) + "\n")
PY
python3 "$root/scripts/results_bench.py" report "$work/bench" "$root/docs/RESULTS.md.tmp" "$root/docs/images/results"
python3 "$root/scripts/results_placement.py" "$work/placement.json" "$root/docs/RESULTS.md.tmp"
python3 "$root/scripts/results_extraction.py" "$work/extraction.json" "$root/docs/RESULTS.md.tmp"
python3 "$root/scripts/results_fields.py" report "$work/fields" "$root/docs/RESULTS.md.tmp"
python3 "$root/scripts/results_history.py" report "$work/history" "$root/docs/RESULTS.md.tmp"
python3 "$root/scripts/results_auto.py" report "$work/auto" "$root/docs/RESULTS.md.tmp"
python3 "$root/scripts/results_animated.py" report "$work/animated" "$root/docs/RESULTS.md.tmp"
python3 "$root/scripts/results_soak.py" report "$work/soak" "$root/docs/RESULTS.md.tmp"
python3 "$root/scripts/results_melt.py" report "$work/melt" "$root/docs/RESULTS.md.tmp"
python3 "$root/scripts/results_passes.py" report "$work/passes" "$root/docs/RESULTS.md.tmp"
python3 "$root/scripts/results_picture.py" report "$work/picture" "$root/docs/RESULTS.md.tmp"
python3 "$root/scripts/results_candle_peers.py" report "$work/candle_peers" "$root/docs/RESULTS.md.tmp"
# Issue 18: a GPU run of the device bench, copied into docs/gpu/, or the statement that none exists.
python3 "$root/scripts/results_bench.py" gpu "$root/docs/gpu" "$root/docs/RESULTS.md.tmp"
mv "$root/docs/RESULTS.md.tmp" "$root/docs/RESULTS.md"
# Pictures of earlier runs that this RESULTS.md no longer shows go.
for f in "$root/docs/images/results"/*; do
  grep -qF "images/results/$(basename "$f")" "$root/docs/RESULTS.md" || rm -f "$f"
done
echo "results: wrote docs/RESULTS.md"
