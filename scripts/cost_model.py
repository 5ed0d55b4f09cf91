#!/usr/bin/env python3
"""Turns a stats.json's per-pass pipeline statistics into projected milliseconds (issue 39, point 6).

Usage:

    python3 scripts/cost_model.py CALIBRATION.json [--check T.json]... \\
        [--project T.json]... [--device h200|h100|rtx4090]... [--skip N] [--cpu-ghz GHZ] [--cpu-cores N] \\
        [--json OUT]

CALIBRATION.json and every --check target are stats.json files of `tallow capture` on llvmpipe, e.g.

    build/tallow capture --preset candle --size 160x90    --frames 5 --fps 8 --time 10 --out /tmp/cmA
    build/tallow capture --preset candle --size 320x180   --frames 5 --fps 8 --time 10 --out /tmp/cmB
    build/tallow capture --preset candle --size 1920x1080 --frames 4 --fps 8 --time 10 --out /tmp/cmC
    python3 scripts/cost_model.py /tmp/cmA/stats.json --check /tmp/cmB/stats.json \\
        --project /tmp/cmC/stats.json --device h200 --device rtx4090

The model (docs/device-bench.md, "Cost model"):

- Steady frames: every frame after the first --skip (default 2: the first frame compiles shaders and
  fills caches; the candle's second frame on llvmpipe still spends 10 to 30 times the third's time
  in sss.light_gbuffer at the same counts, and its sss.maps counts fewer invocations than the frames
  after it); a pass's time is the median of its GPU times (`gpu_ms`) over the steady frames, its
  count of each stage the median of its counts (`invocations`).
  A file with no frame beyond --skip uses its last frame (said on stderr).
- llvmpipe's throughput, in lane-cycles per second: cores x fp32 SIMD lanes x clock. Lanes = the
  vector width in GL_RENDERER ("llvmpipe (LLVM 15.0.6, 256 bits)": 256 / 32 = 8); cores = --cpu-cores,
  else stats.json's provenance.cpu.hardware_threads, else this machine's; clock = --cpu-ghz, else the
  first "cpu MHz" of /proc/cpuinfo, else 2.5 GHz.
- Calibration: a pass p's steady GPU time T_p on llvmpipe is L_p = T_p x throughput lane-cycles.
  A pure pass (only raster invocations, vertex/geometry/fragment, or only compute ones) costs
  c_p = L_p / N_p per invocation, N_p its invocations of every stage. A mixed pass (both kinds)
  is split by MIXED_PASSES below: its lighter stage (raster or compute) is charged at the cost per
  invocation c_r of a named pure reference pass r of the same calibration (work of the same kind),
  n_light x c_r, and the rest of L_p goes to its other stage, spread over that stage's
  invocations. If n_light x c_r exceeds L_p, the charge is clamped: all of L_p on the lighter stage,
  nothing on the other (said in the output). A mixed pass not in the table (or whose reference is
  missing or not pure in the calibration) keeps the equal split, c_p = L_p / N_p for every
  invocation, with a warning line naming it. Primitives are not a stage and are not counted.
- Check (--check T.json, llvmpipe): predicted T'_p = sum_s n'_{p,s} c_{p,s} / throughput (c_{p,s} the
  cost of s's kind, raster or compute), against T's measured steady times; the frame total's
  relative error is (predicted - measured) / measured.
- Projection (--project T.json --device D): ms_p = sum_s n_{p,s} c_{p,s} / (lanes_{D,s} x clock_D),
  with the lanes of the device table below: on Hopper the raster stages (vertex, geometry, fragment)
  run on the graphics-capable TPCs only, compute on every SM. The frame total is the sum over passes
  (the passes run one after another). "all raster" / "all compute" bound a pass that has both kinds of
  invocation: its projected lane-cycles sum_s n_{p,s} c_{p,s} run entirely at the raster lanes' or
  entirely at the compute lanes' rate.

Limitations: ALU throughput only. No memory-bandwidth or latency floor, no fixed-function limits
(rasteriser, ROPs, texture units: llvmpipe does in shader code what a GPU does in hardware), no
launch overhead, no occupancy (a small dispatch is assumed to fill every lane), llvmpipe's vertex
shading taken as spread over all cores like the rest, a mixed pass's lighter stage taken to cost
what its reference pass's invocations cost, and the equal weighting of the stages of a pass with
no reference. The calibration's times are whatever the machine gave (a shared machine: upper bounds).

Bad input (a missing or unreadable file, no frames, no invocations, no GPU times, a calibration or
check that is not llvmpipe) prints one error line and exits 1.
"""
import argparse
import json
import os
import re
import statistics
import sys

STAGES = ["vertex", "geometry", "fragment", "compute"]
RASTER = ["vertex", "geometry", "fragment"]

# Device table: FP32 lanes available to the raster stages and to compute, and the clock [GHz].
DEVICES = {
    # NVIDIA H100 Tensor Core GPU Architecture whitepaper (2022): H100 SXM5 has 132 SMs of 128 FP32
    # lanes; "only two TPCs in both the SXM5 and PCIe H100 GPUs are graphics-capable (that is, they can
    # run vertex, geometry, and pixel shaders)": 2 TPCs = 4 SMs. Clock: 1.98 GHz, the boost clock of
    # the H100 SXM datasheet's FP32 peak (67 TFLOPS = 132 x 128 x 2 x 1.98 GHz).
    "h100": {"name": "NVIDIA H100 SXM5", "raster_lanes": 4 * 128, "compute_lanes": 132 * 128, "ghz": 1.98},
    # NVIDIA H200 datasheet: the same GH100 configuration as H100 SXM5 (FP32 67 TFLOPS, 132 SMs),
    # with HBM3e memory; the same graphics-capable share (2 TPCs = 4 SMs).
    "h200": {"name": "NVIDIA H200 SXM", "raster_lanes": 4 * 128, "compute_lanes": 132 * 128, "ghz": 1.98},
    # NVIDIA Ada GPU Architecture whitepaper: GeForce RTX 4090 has 128 SMs of 128 FP32 lanes (16,384
    # CUDA cores), boost clock 2520 MHz (82.6 TFLOPS FP32); every SM runs every stage.
    "rtx4090": {"name": "NVIDIA GeForce RTX 4090", "raster_lanes": 128 * 128, "compute_lanes": 128 * 128,
                "ghz": 2.52},
}


# Mixed passes (raster and compute invocations in one pass): the lighter stage, charged at the cost
# per invocation of a pure reference pass of the same calibration; the rest of the pass's time goes
# to its other stage. pass: (lighter stage, reference pass, why).
MIXED_PASSES = {
    "sss.maps": ("raster", "sss.light_gbuffer",
                 "the maps' G-buffer (map_gbuffer.frag; map_depth.frag's depth pre-pass instead when the "
                 "gather runs in fragments) and their mip chain (glGenerateTextureMipmap, fragment blits on "
                 "llvmpipe) against the light's G-buffer (light_gbuffer.frag), a pure raster pass writing a "
                 "G-buffer of the same kind; the rest is the gather (radiosity_map.comp) and the history "
                 "passes"),
    "surface": ("compute", "camera.still",
                "the coverage histogram (coverage_histogram.comp), one small invocation per pixel, against "
                "the still's average, one small compute invocation per pixel too; the rest is the camera "
                "pass's shading (surface.vert, surface.frag)"),
    "camera.bloom": ("raster", "camera.still",
                     "bloom.cpp's glGenerateTextureMipmap, a box filter of the bright part's mip chain that "
                     "llvmpipe runs as fragment-shader blits (one light read and write per texel), against "
                     "the cheapest per-pixel reference; the rest is bloom.comp's two steps"),
    "vpl": ("raster", "sss.light_gbuffer",
            "its cube G-buffer (map_gbuffer.frag) against the light's G-buffer (light_gbuffer.frag); the "
            "rest is vpl.comp"),
}


class InputError(Exception):
    pass


def load(path, skip):
    try:
        with open(path) as f:
            stats = json.load(f)
    except OSError as e:
        raise InputError(f"{path}: cannot read: {e.strerror}")
    except json.JSONDecodeError as e:
        raise InputError(f"{path}: not JSON: {e}")
    if not isinstance(stats, dict):
        raise InputError(f"{path}: not a stats.json (no object at the top)")
    frames = stats.get("frames")
    if not isinstance(frames, list) or not frames:
        raise InputError(f"{path}: no frames")
    steady = frames[skip:]
    if not steady:
        steady = frames[-1:]
        print(f"cost_model.py: {path}: {len(frames)} frame(s), none after --skip {skip}: using the last",
              file=sys.stderr)
    if not all(isinstance(f, dict) and f.get("invocations") for f in steady):
        raise InputError(f"{path}: no invocations (pipeline statistics) in its frames")
    if not all(f.get("gpu_ms") for f in steady):
        raise InputError(f"{path}: no gpu_ms (GPU times) in its frames")
    passes = sorted({p for f in steady for p in f["invocations"]} | {p for f in steady for p in f["gpu_ms"]})
    counts, ms = {}, {}
    for p in passes:
        counts[p] = {s: statistics.median([float(f["invocations"].get(p, {}).get(s, 0)) for f in steady])
                     for s in STAGES}
        times = [float(f["gpu_ms"][p]) for f in steady if p in f["gpu_ms"]]
        ms[p] = statistics.median(times) if times else None
    gl = stats.get("gl", {}) or {}
    return {"path": path, "stats": stats, "steady_frames": [f.get("index") for f in steady],
            "renderer": gl.get("GL_RENDERER", ""), "counts": counts, "ms": ms}


def llvmpipe_lanes(data):
    m = re.search(r"llvmpipe.*?(\d+) bits", data["renderer"])
    if not m:
        raise InputError(f"{data['path']}: GL_RENDERER is {data['renderer']!r}, not llvmpipe with its vector width")
    return int(m.group(1)) // 32


def default_ghz():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("cpu MHz"):
                    return float(line.split(":")[1]) / 1000.0
    except (OSError, ValueError, IndexError):
        pass
    return 2.5


def fmt(x):
    if x is None:
        return "–"
    if x >= 10:
        return f"{x:,.1f}"
    if x >= 0.1:
        return f"{x:.3f}"
    return f"{x:.3g}"


def kinds(n):
    """Invocations of a pass's raster stages and of its compute stage."""
    return {"raster": sum(n[s] for s in RASTER), "compute": n["compute"]}


def calibrate(data, cores, ghz):
    lanes = llvmpipe_lanes(data)
    per_ms = cores * lanes * ghz * 1e6  # lane-cycles per millisecond
    c, split, unmodelled, warnings = {}, {}, [], []
    pure = {}  # a pure pass's lane-cycles per invocation, the references' costs
    for p, n in data["counts"].items():
        total = sum(n.values())
        if total == 0 or data["ms"][p] is None:
            unmodelled.append(p)
            continue
        k = kinds(n)
        if not (k["raster"] and k["compute"]):
            pure[p] = data["ms"][p] * per_ms / total
    for p, n in data["counts"].items():
        if p in unmodelled:
            continue
        cycles, k = data["ms"][p] * per_ms, kinds(n)
        if p in pure:
            c[p] = {"raster": pure[p], "compute": pure[p]}
            split[p] = "pure"
            continue
        light, ref, _ = MIXED_PASSES.get(p, (None, None, None))
        if ref is None or ref not in pure:
            why = "is not in MIXED_PASSES" if ref is None else f"its reference {ref} is not a pure pass of the calibration"
            warnings.append(f"{p} has raster and compute invocations and {why}: every invocation weighted equally")
            c[p] = {"raster": cycles / sum(n.values()), "compute": cycles / sum(n.values())}
            split[p] = "equal (no reference)"
            continue
        heavy = "compute" if light == "raster" else "raster"
        charge = k[light] * pure[ref]
        if charge >= cycles:
            c[p] = {light: cycles / k[light], heavy: 0.0}
            split[p] = f"{light} at {ref}'s, clamped: all on {light}"
            warnings.append(f"{p}: its {light} invocations at {ref}'s cost ({charge / per_ms:.4g} ms) exceed its "
                            f"measured {data['ms'][p]:.4g} ms: clamped, all of it on {light}")
        else:
            c[p] = {light: pure[ref], heavy: (cycles - charge) / k[heavy]}
            split[p] = f"{light} at {ref}'s"
    return {"lanes": lanes, "cores": cores, "ghz": ghz, "lane_cycles_per_ms": per_ms, "c": c, "split": split,
            "unmodelled": unmodelled, "warnings": warnings}


def cycles_of(cal, p, n):
    """Lane-cycles of a pass with counts n: each invocation at its kind's cost."""
    k = kinds(n)
    return k["raster"] * cal["c"][p]["raster"] + k["compute"] * cal["c"][p]["compute"]


def check(cal, data):
    llvmpipe_lanes(data)
    rows, pred_total, meas_total = [], 0.0, 0.0
    for p, n in data["counts"].items():
        measured = data["ms"][p]
        predicted = None
        if p in cal["c"]:
            predicted = cycles_of(cal, p, n) / cal["lane_cycles_per_ms"]
            if measured is not None:
                pred_total += predicted
                meas_total += measured
        rows.append({"pass": p, "invocations": sum(n.values()), "predicted_ms": predicted, "measured_ms": measured})
    err = (pred_total - meas_total) / meas_total if meas_total > 0 else None
    return {"target": data["path"], "steady_frames": data["steady_frames"], "passes": rows,
            "predicted_total_ms": pred_total, "measured_total_ms": meas_total, "relative_error": err}


def project(cal, data, device):
    d = DEVICES[device]
    per_ms = {s: (d["raster_lanes"] if s in RASTER else d["compute_lanes"]) * d["ghz"] * 1e6 for s in STAGES}
    rows, total, lo_total, hi_total = [], 0.0, 0.0, 0.0
    for p, n in data["counts"].items():
        row = {"pass": p, "counts": n, "invocations": sum(n.values()), "ms": None, "all_raster_ms": None,
               "all_compute_ms": None}
        if p in cal["c"]:
            cp = cal["c"][p]
            row["ms"] = sum(n[s] * cp["raster" if s in RASTER else "compute"] / per_ms[s] for s in STAGES)
            if sum(n[s] for s in RASTER) and n["compute"]:
                cycles = cycles_of(cal, p, n)
                row["all_raster_ms"] = cycles / per_ms["fragment"]
                row["all_compute_ms"] = cycles / per_ms["compute"]
            total += row["ms"]
            lo_total += min(row["ms"], row["all_compute_ms"] or row["ms"])
            hi_total += max(row["ms"], row["all_raster_ms"] or row["ms"])
        rows.append(row)
    return {"target": data["path"], "device": device, "device_name": d["name"], "device_constants": d,
            "steady_frames": data["steady_frames"], "passes": rows, "total_ms": total,
            "total_all_compute_ms": lo_total, "total_all_raster_ms": hi_total}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("calibration", help="stats.json of a llvmpipe capture")
    ap.add_argument("--check", action="append", default=[], metavar="T.json",
                    help="predict this llvmpipe capture's per-pass times and compare")
    ap.add_argument("--project", action="append", default=[], metavar="T.json",
                    help="project this capture's counts onto each --device")
    ap.add_argument("--device", action="append", choices=sorted(DEVICES), help="device (repeatable; default h200)")
    ap.add_argument("--skip", type=int, default=2, help="frames left out at the start (default 2)")
    ap.add_argument("--cpu-ghz", type=float, help="llvmpipe's CPU clock [GHz] (default: /proc/cpuinfo, else 2.5)")
    ap.add_argument("--cpu-cores", type=int, help="llvmpipe's threads (default: the calibration's provenance)")
    ap.add_argument("--json", metavar="OUT", help="also write the results as JSON")
    args = ap.parse_args()
    try:
        if args.skip < 0:
            raise InputError("--skip must not be negative")
        cal_data = load(args.calibration, args.skip)
        prov_cores = ((cal_data["stats"].get("provenance") or {}).get("cpu") or {}).get("hardware_threads")
        cores = args.cpu_cores or prov_cores or os.cpu_count() or 1
        ghz = args.cpu_ghz or default_ghz()
        if cores <= 0 or ghz <= 0:
            raise InputError("--cpu-cores and --cpu-ghz must be positive")
        cal = calibrate(cal_data, cores, ghz)
        checks = [check(cal, load(t, args.skip)) for t in args.check]
        devices = args.device or ["h200"]
        projections = [project(cal, load(t, args.skip), dev) for t in args.project for dev in devices]
    except InputError as e:
        print(f"cost_model.py: error: {e}", file=sys.stderr)
        return 1

    print(f"Calibration: {args.calibration} ({cal_data['renderer']}; steady frames {cal_data['steady_frames']}): "
          f"{cal['cores']} cores x {cal['lanes']} lanes x {cal['ghz']:.3f} GHz")
    print()
    print("| pass | raster invocations | compute invocations | llvmpipe ms | lane-cycles / raster invocation | "
          "lane-cycles / compute invocation | split |")
    print("|---|---:|---:|---:|---:|---:|---|")
    for p, n in cal_data["counts"].items():
        k, c = kinds(n), cal["c"].get(p)
        cost = (lambda x: "–" if c is None or not k[x] else f"{c[x]:,.1f}")
        print(f"| {p} | {k['raster']:,.0f} | {k['compute']:,.0f} | {fmt(cal_data['ms'][p])} | {cost('raster')} | "
              f"{cost('compute')} | {cal['split'].get(p, '–')} |")
    if cal["unmodelled"]:
        print(f"\nNot modelled (no invocations or no time): {', '.join(cal['unmodelled'])}")
    for w in cal["warnings"]:
        print(f"\nWarning: {w}")
    for r in checks:
        print(f"\nCheck on llvmpipe: {r['target']} (steady frames {r['steady_frames']})\n")
        print("| pass | invocations | predicted ms | measured ms |")
        print("|---|---:|---:|---:|")
        for row in r["passes"]:
            print(f"| {row['pass']} | {row['invocations']:,.0f} | {fmt(row['predicted_ms'])} | "
                  f"{fmt(row['measured_ms'])} |")
        err = "–" if r["relative_error"] is None else f"{100 * r['relative_error']:+.1f}%"
        print(f"| **total** | | **{fmt(r['predicted_total_ms'])}** | **{fmt(r['measured_total_ms'])}** |")
        print(f"\nTotal: predicted {fmt(r['predicted_total_ms'])} ms, measured {fmt(r['measured_total_ms'])} ms, "
              f"relative error {err}")
    for r in projections:
        d = r["device_constants"]
        print(f"\nProjection onto {r['device_name']} ({d['raster_lanes']:,} raster lanes, "
              f"{d['compute_lanes']:,} compute lanes, {d['ghz']} GHz): {r['target']} "
              f"(steady frames {r['steady_frames']})\n")
        split = d["raster_lanes"] != d["compute_lanes"]  # else the split over stages changes nothing
        extra = " all raster | all compute |" if split else ""
        print("| pass | vertex | geometry | fragment | compute | projected ms |" + extra)
        print("|---|---:|---:|---:|---:|---:|" + ("---:|---:|" if split else ""))
        for row in r["passes"]:
            n = row["counts"]
            cells = f" {fmt(row['all_raster_ms'])} | {fmt(row['all_compute_ms'])} |" if split else ""
            print(f"| {row['pass']} | " + " | ".join(f"{n[s]:,.0f}" for s in STAGES) +
                  f" | {fmt(row['ms'])} |" + cells)
        cells = f" {fmt(r['total_all_raster_ms'])} | {fmt(r['total_all_compute_ms'])} |" if split else ""
        print(f"| **frame total** | | | | | **{fmt(r['total_ms'])}** |" + cells)
        print(f"\nFrame total on {r['device_name']}: {fmt(r['total_ms'])} ms projected" +
              (f" ({fmt(r['total_all_compute_ms'])} to {fmt(r['total_all_raster_ms'])} ms with the mixed passes' "
               f"lane-cycles all on compute or all on raster)" if split else ""))
    if args.json:
        out = {"calibration": {"path": args.calibration, "renderer": cal_data["renderer"],
                               "steady_frames": cal_data["steady_frames"], "ms": cal_data["ms"],
                               "counts": cal_data["counts"], **cal},
               "checks": checks, "projections": projections}
        try:
            with open(args.json, "w") as f:
                json.dump(out, f, indent=1)
        except OSError as e:
            print(f"cost_model.py: error: {args.json}: cannot write: {e.strerror}", file=sys.stderr)
            return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
